// Pieper's elimination: the roots q3 of a point placed by skew axes 1, 2 and a general joint 3.
//
// When axes 1 and 2 are skew (distance a along their common normal, angle α), joint 1
// keeps |d| and ζ = h1ᵀd of the target, and the two resulting equations are linear in
// (cos q2, sin q2): the part of R2 u normal to axis 2 must be v = (X / 2a, Y / g) in the
// basis (e1, e2) with X = |d|² - a² - L(q3) and Y = ζ - cos α · H(q3). Joint 2 keeps the
// length of that part, so q3 must satisfy (Pieper 1968; Craig, "Introduction to
// Robotics", §4.7)
//
//     F(q3) = sin²α · X² + 4a² · Y² - 4a² sin²α · (L - H²) = 0.
//
// L and H are of degree 1 in (cos q3, sin q3) for a revolute joint 3, so F is a
// trigonometric polynomial of degree 2: a quartic in tan((q3 - θ)/2) (up to four real
// roots), with the shift θ (a multiple of π/4) that makes its leading coefficient
// F(θ + π) largest, so that every root is finite and well scaled (trig_roots). For a
// slide L is quadratic and H linear in q3: a quartic in q3 (slide_roots). The roots
// (quartic_roots) are polished by Newton steps on F; the error the elimination amplifies
// near double roots is removed by the shared check's Gauss-Newton polishing, which works
// on the whole arm. F ≡ 0 is a self-motion of joints 1-3: every q3 reaches the target.
//
// The pieces here are pure functions of their coefficients; ArmPoint (arm_point.hpp)
// forms F from the arm's geometry.
#pragma once

#include <cmath>
#include <complex>

#include "../config.hpp"
#include "../polynomial.hpp"

namespace km::decoupled {

//! A quartic root with |Im t| <= IMAG_TOL (1 + |t|) is taken as real and polished: a
//! double root (target on the workspace boundary) splits into a complex pair of size
//! ~sqrt(ulp).
constexpr double IMAG_TOL = 1e-6;
//! Newton steps on F for each quartic root.
constexpr int NEWTON_STEPS = 2;
//! Newton steps on F longer than this (rad or m) are round-off at a double root
//! (F' ≈ 0) and are skipped: the closed form is far closer than that.
constexpr double MAX_NEWTON_STEP = 1e-4;
//! F is identically 0 (a self-motion of joints 1-3) when its largest leading
//! coefficient is below this fraction of its Fourier coefficients.
constexpr double SELF_MOTION_TOL = 1e-14;
//! A fold's signed distance past 0 by at most this fraction of its scale still gives
//! candidates (mirrored) for the check, and flags the target as near a fold (no real
//! candidate is then no proof). (Declared here: a root just off the real axis by
//! sqrt of it is such a target.)
constexpr double NEAR_TOL = 1e-6;

//! The Newton step f / df, or 0 when it is longer than MAX_NEWTON_STEP (or undefined).
KM_HD inline double bounded_step(double f, double df) {
    const double step = df != 0.0 ? f / df : NaN;
    return std::fabs(step) <= MAX_NEWTON_STEP ? step : 0.0;
}

//! Sort q[4] ascending, NaN last (insertion sort).
KM_HD inline void sort4(double* q) {
    for (int i = 1; i < 4; ++i) {
        const double v = q[i];
        int j = i;
        while (j > 0 && (std::isnan(q[j - 1]) || q[j - 1] > v) && !std::isnan(v)) {
            q[j] = q[j - 1];
            --j;
        }
        q[j] = v;
    }
}

//! t.real where t counts as real (IMAG_TOL), else NaN.
//!
//! A root dropped with |Im t| <= sqrt(NEAR_TOL) (1 + |t|) is a double root split by a
//! target just past a fold (by about Im²): `near` is raised.
KM_HD inline double real_root(const Complex& t, bool& near) {
    const double size = 1.0 + std::hypot(t.real(), t.imag());
    if (std::fabs(t.imag()) <= IMAG_TOL * size) return t.real();
    if (std::fabs(t.imag()) <= std::sqrt(NEAR_TOL) * size) near = true;
    return NaN;
}

//! The real roots of F0 + F1 cos q + F2 sin q + F3 cos 2q + F4 sin 2q in q[4].
//!
//! `size` is the magnitude of the terms F was computed from: F within SELF_MOTION_TOL of
//! it at every sample is 0 to round-off. Returns true for F ≡ 0 (every q is a root: q
//! holds -π/2, 0, π/2, π); otherwise the roots are in (-π, π], sorted, NaN-padded.
//! `near` is raised for a root just off the real axis.
KM_HD inline bool trig_roots(const double* F, double size, double* q, bool& near) {
    constexpr double QUARTER = 0.25 * PI;
    double best = -1.0;
    int kbest = 0;
    for (int k = 0; k < 8; ++k) {
        const double th = k * QUARTER + PI;
        double val = F[0] + F[1] * std::cos(th) + F[2] * std::sin(th);
        val += F[3] * std::cos(2.0 * th) + F[4] * std::sin(2.0 * th);
        if (std::fabs(val) > best) {
            best = std::fabs(val);
            kbest = k;
        }
    }
    if (!(best > SELF_MOTION_TOL * size)) {
        q[0] = -0.5 * PI;
        q[1] = 0.0;
        q[2] = 0.5 * PI;
        q[3] = PI;
        return true;
    }
    const double th = kbest * QUARTER;
    const double c = std::cos(th);
    const double s = std::sin(th);
    const double c2 = std::cos(2.0 * th);
    const double s2 = std::sin(2.0 * th);
    const double g0 = F[0];
    const double a1 = c * F[1] + s * F[2];
    const double b1 = c * F[2] - s * F[1];
    const double a2 = c2 * F[3] + s2 * F[4];
    const double b2 = c2 * F[4] - s2 * F[3];
    // (1 + t²)² F(θ + 2 atan t), highest power first
    const double coef[5] = {g0 - a1 + a2, 2.0 * b1 - 4.0 * b2, 2.0 * g0 - 6.0 * a2,
                            2.0 * b1 + 4.0 * b2, g0 + a1 + a2};
    Complex roots[4];
    quartic_roots(coef, roots);
    for (int i = 0; i < 4; ++i) {
        double x = th + 2.0 * std::atan(real_root(roots[i], near));
        for (int step = 0; step < NEWTON_STEPS; ++step) {
            const double cx = std::cos(x);
            const double sx = std::sin(x);
            const double c2x = cx * cx - sx * sx;
            const double s2x = 2.0 * sx * cx;
            const double f = F[0] + F[1] * cx + F[2] * sx + F[3] * c2x + F[4] * s2x;
            const double df = F[2] * cx - F[1] * sx + 2.0 * (F[4] * c2x - F[3] * s2x);
            x -= bounded_step(f, df);
        }
        q[i] = std::atan2(std::sin(x), std::cos(x));
    }
    sort4(q);
    return false;
}

//! The real roots of the quartic k[5] (highest power first) in q[4], sorted, NaN-padded.
//! `near` is raised for a root just off the real axis (see trig_roots).
KM_HD inline void slide_roots(const double* k, double* q, bool& near) {
    Complex roots[4];
    quartic_roots(k, roots);
    for (int i = 0; i < 4; ++i) {
        double x = real_root(roots[i], near);
        for (int step = 0; step < NEWTON_STEPS; ++step) {
            double f = 0.0;
            double df = 0.0;
            for (int j = 0; j < 5; ++j) {
                df = df * x + f;
                f = f * x + k[j];
            }
            x -= bounded_step(f, df);
        }
        q[i] = x;
    }
    sort4(q);
}

}  // namespace km::decoupled
