// Roots of cubics and quartics.
//
// quartic_roots is Ferrari's closed form: the quartic is made monic, scaled so that its
// roots are O(1), depressed (x = y - b/4) and split by the largest root m >= 0 of its
// resolvent cubic into two quadratics y² ∓ √(2m) y + p/2 + m ± w. Ferrari loses small
// roots next to much larger ones; a root whose backward error |P(x)| / Σ|k_i||x|^i
// exceeds QUARTIC_CHECK sends the quartic to Aberth-Ehrlich iterations started from
// Ferrari's roots (simultaneous Newton steps that converge to every root, backward
// stable). A companion-matrix eigensolver would do as well and cost more per call.
#pragma once

#include <cmath>
#include <complex>

#include "config.hpp"

namespace km {

//! A Ferrari root whose backward error exceeds this sends the quartic to Aberth-Ehrlich.
constexpr double QUARTIC_CHECK = 1e-12;
//! Aberth-Ehrlich steps at most (each updates all four roots; a handful suffice).
constexpr int ABERTH_STEPS = 50;

namespace detail {
//! Below this s = sqrt(2m) (roots scaled to O(1)), w = q / 2s is 0/0.
constexpr double SMALL_S = 1e-8;
}  // namespace detail

using Complex = std::complex<double>;

//! Largest real root of m³ + A m² + B m + C, polished by two Newton steps.
KM_HD inline double largest_cubic_root(double A, double B, double C) {
    const double A3 = A / 3.0;
    const double P = B - A * A3;
    const double Q = (2.0 / 27.0) * A * A * A - A3 * B + C;
    const double disc = 0.25 * Q * Q + P * P * P / 27.0;
    double z;
    if (disc > 0.0) {  // one real root (Cardano)
        const double sq = std::sqrt(disc);
        z = std::cbrt(-0.5 * Q + sq) + std::cbrt(-0.5 * Q - sq);
    } else {  // three real roots (trigonometric form): the largest
        const double rho = std::sqrt(std::fmax(P * (-1.0 / 3.0), 0.0));
        double den = rho * rho * rho;
        if (den == 0.0) den = 1.0;
        const double cos3 = std::fmin(std::fmax(-0.5 * Q / den, -1.0), 1.0);
        z = 2.0 * rho * std::cos(std::acos(cos3) / 3.0);
    }
    double m = z - A3;
    for (int i = 0; i < 2; ++i) {
        const double df = (3.0 * m + 2.0 * A) * m + B;
        if (df != 0.0) m -= (((m + A) * m + B) * m + C) / df;
    }
    return m;
}

namespace detail {

// Complex arithmetic written out: std::complex's operator/ and abs take slow paths
// (C99 Annex G scaling) that these well-scaled roots do not need.
struct Cx {
    double re, im;
};
KM_HD inline Cx cmul(Cx a, Cx b) { return {a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re}; }
KM_HD inline Cx cadd(Cx a, Cx b) { return {a.re + b.re, a.im + b.im}; }
KM_HD inline Cx csub(Cx a, Cx b) { return {a.re - b.re, a.im - b.im}; }
//! a / b by Smith's scaling (as CPython's complex division).
KM_HD inline Cx cdiv(Cx a, Cx b) {
    if (std::fabs(b.re) >= std::fabs(b.im)) {
        if (b.re == 0.0) return {0.0, 0.0};
        const double ratio = b.im / b.re;
        const double den = b.re + b.im * ratio;
        return {(a.re + a.im * ratio) / den, (a.im - a.re * ratio) / den};
    }
    if (std::fabs(b.im) >= std::fabs(b.re)) {
        const double ratio = b.re / b.im;
        const double den = b.re * ratio + b.im;
        return {(a.re * ratio + a.im) / den, (a.im * ratio - a.re) / den};
    }
    return {NaN, NaN};  // a NaN in b
}
KM_HD inline double cabs(Cx a) { return std::hypot(a.re, a.im); }
KM_HD inline bool czero(Cx a) { return a.re == 0.0 && a.im == 0.0; }

//! True when every root's backward error is within QUARTIC_CHECK.
KM_HD inline bool backward_ok(const double* k, const Cx* roots) {
    for (int i = 0; i < 4; ++i) {
        const Cx x = roots[i];
        const double size = std::sqrt(x.re * x.re + x.im * x.im);  // |x|² overflows where x⁴ has
        Cx value{k[0], 0.0};
        double bound = std::fabs(k[0]);
        for (int j = 1; j < 5; ++j) {
            value = cadd(cmul(value, x), Cx{k[j], 0.0});
            bound = bound * size + std::fabs(k[j]);
        }
        const double lhs = value.re * value.re + value.im * value.im;
        const double rhs = (QUARTIC_CHECK * bound) * (QUARTIC_CHECK * bound);
        if (!(lhs <= rhs)) return false;
    }
    return true;
}

//! Refine all four roots of k together (Aberth-Ehrlich), in place.
//!
//! Real starting values of a real polynomial would stay real: each start is first moved
//! off the real axis by a different small amount, so that iterates can reach complex pairs.
KM_HD inline void aberth(const double* k, Cx* roots) {
    for (int i = 0; i < 4; ++i) {
        const double e = 1e-3 * (i + 1);
        roots[i] = cadd(cmul(roots[i], Cx{1.0, e}), Cx{0.0, e});
    }
    for (int step = 0; step < ABERTH_STEPS; ++step) {
        double largest = 0.0;
        for (int i = 0; i < 4; ++i) {
            const Cx x = roots[i];
            Cx p{k[0], 0.0};
            Cx dp{0.0, 0.0};
            for (int j = 1; j < 5; ++j) {
                dp = cadd(cmul(dp, x), p);
                p = cadd(cmul(p, x), Cx{k[j], 0.0});
            }
            if (czero(p)) continue;
            const Cx ratio = !czero(dp) ? cdiv(p, dp) : Cx{1e300, 0.0};
            Cx s{0.0, 0.0};
            for (int j = 0; j < 4; ++j) {
                if (j == i) continue;
                const Cx diff = csub(x, roots[j]);
                if (!czero(diff)) s = cadd(s, cdiv(Cx{1.0, 0.0}, diff));
            }
            const Cx den = csub(Cx{1.0, 0.0}, cmul(ratio, s));
            const Cx w = !czero(den) ? cdiv(ratio, den) : ratio;
            roots[i] = csub(x, w);
            largest = std::fmax(largest, cabs(w) / (1.0 + cabs(x)));
        }
        if (largest < 1e-17) return;
    }
}

//! sqrt of a real number as a complex number (i·sqrt(-v) for v < 0).
KM_HD inline Cx csqrt_real(double v) {
    return v >= 0.0 ? Cx{std::sqrt(v), 0.0} : Cx{0.0, std::sqrt(-v)};
}

}  // namespace detail

//! The four complex roots of k[0] x⁴ + k[1] x³ + ... + k[4] (k[0] != 0), in no order;
//! NaN when a coefficient is not finite or k[0] = 0.
KM_HD inline void quartic_roots(const double* k, Complex* out) {
    using detail::Cx;
    bool finite = true;
    for (int j = 0; j < 5; ++j) finite = finite && std::isfinite(k[j]);
    if (!finite || k[0] == 0.0) {
        for (int i = 0; i < 4; ++i) out[i] = Complex(NaN, NaN);
        return;
    }
    const double k0 = k[0];
    // x = λ z with λ the largest |k_i / k_0|^(1/i) (Fujiwara's bound without its factor
    // 2): the roots z are O(1) however large the x are.
    const double r1 = std::fabs(k[1] / k0), r2 = std::fabs(k[2] / k0);
    const double r3 = std::fabs(k[3] / k0), r4 = std::fabs(k[4] / k0);
    double lam = std::fmax(std::fmax(r1, std::sqrt(r2)), std::fmax(std::cbrt(r3), std::sqrt(std::sqrt(r4))));
    if (lam == 0.0) lam = 1.0;
    const double inv = 1.0 / lam;
    const double b = k[1] / k0 * inv;
    const double c = k[2] / k0 * inv * inv;
    const double d = k[3] / k0 * inv * inv * inv;
    const double e = k[4] / k0 * inv * inv * inv * inv;
    const double b4 = 0.25 * b;
    const double b42 = b4 * b4;
    const double p = c - 6.0 * b42;
    const double q = d - 2.0 * b4 * c + 8.0 * b42 * b4;
    const double r = e - b4 * d + b42 * c - 3.0 * b42 * b42;
    const double m = std::fmax(largest_cubic_root(p, 0.25 * p * p - r, -0.125 * q * q), 0.0);
    const double s = std::sqrt(2.0 * m);
    double w;
    if (s > detail::SMALL_S * (1.0 + std::sqrt(std::fabs(p)))) {
        w = 0.5 * q / s;
    } else {  // w = q / 2s is 0/0; w² = m² + m p + p²/4 - r instead
        w = std::copysign(std::sqrt(std::fmax(m * m + m * p + 0.25 * p * p - r, 0.0)), q);
    }
    // y² - s y + (p/2 + m + w) = 0 and y² + s y + (p/2 + m - w) = 0
    const Cx d1 = detail::csqrt_real(s * s - 4.0 * (0.5 * p + m) - 4.0 * w);
    const Cx d2 = detail::csqrt_real(s * s - 4.0 * (0.5 * p + m) + 4.0 * w);
    Cx roots[4] = {
        {(0.5 * (s + d1.re) - b4) * lam, 0.5 * d1.im * lam},
        {(0.5 * (s - d1.re) - b4) * lam, -0.5 * d1.im * lam},
        {(0.5 * (-s + d2.re) - b4) * lam, 0.5 * d2.im * lam},
        {(0.5 * (-s - d2.re) - b4) * lam, -0.5 * d2.im * lam},
    };
    if (!detail::backward_ok(k, roots)) detail::aberth(k, roots);
    for (int i = 0; i < 4; ++i) out[i] = Complex(roots[i].re, roots[i].im);
}

}  // namespace km
