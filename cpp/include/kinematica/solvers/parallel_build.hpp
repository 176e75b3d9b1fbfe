// The three-parallel family's builder: from a chain's joint axes at q = 0 and its tool pose
// to the ParallelParams parallel.hpp solves with (parallel_params.hpp names every field).
//
// Once per arm: the vectors and constants of equations (1) and (2) in (q1, q5), the planar
// triangle axis 2 -> 3 -> 4, a proven reach bound, and the arm's mode (axes 5 and 6
// meeting, parallel, or apart: the quartic).
//
// Arms it declines (nullopt: the numeric solver takes them): any chain but six revolute
// joints with axes 2, 3, 4 parallel (the family's structure); axis 1 or axis 5 parallel to
// axes 2-4 (four parallel axes); axes 5 and 6 on one line; a link of the triangle of length
// zero (axes 2 and 3, or 3 and 4, on one line, within CONTINUUM_TOL of the links' sum).
#pragma once

#include <cmath>
#include <optional>

#include "../arm_axes.hpp"
#include "../chain.hpp"
#include "parallel.hpp"

namespace km::parallel {

namespace detail {

//! v / |v|.
inline Vec3 unit(const Vec3& v) {
    const double r = norm(v);
    return {v.x / r, v.y / r, v.z / r};
}

//! The point of the line p + t h (unit h) closest to x.
inline Vec3 project(const Vec3& x, const Vec3& h, const Vec3& p) {
    return p + dot(x - p, h) * h;
}

//! The angle (rad) between unit vectors u and v, accurate near 0 and π.
inline double angle(const Vec3& u, const Vec3& v) { return std::atan2(norm(cross(u, v)), dot(u, v)); }

//! |(x, y)| as numpy's complex absolute value computes it: larger · √(1 + ratio²), the
//! square added by one fused multiply-add. The builder was numpy's: a port keeps its
//! numbers, and the continua of this family (q1 free on two arcs) are followed
//! numerically from solutions that a last-bit change of a link's length moves.
inline double modulus(double x, double y) {
    const double ax = std::fabs(x), ay = std::fabs(y);
    const double larger = ax < ay ? ay : ax, smaller = ax < ay ? ax : ay;
    if (larger == 0.0) return 0.0;
    const double ratio = smaller / larger;
    return larger * std::sqrt(std::fma(ratio, ratio, 1.0));
}

//! The middle of a joint's limits, 0 where either is infinite.
inline double middle(double lo, double hi) {
    return std::isfinite(lo) && std::isfinite(hi) ? 0.5 * (lo + hi) : 0.0;
}

//! The inverse of [[a, b], [c, d]] (row-major into out), by Gaussian elimination with
//! partial pivoting (the operations of LAPACK's getrf/getrs on a 2x2).
inline void inverse2(double a, double b, double c, double d, double (&out)[4]) {
    const bool swap = std::fabs(c) > std::fabs(a);
    const double u00 = swap ? c : a, u01 = swap ? d : b, r10 = swap ? a : c, r11 = swap ? b : d;
    const double l = r10 / u00, u11 = r11 - l * u01;
    for (int col = 0; col < 2; ++col) {  // solve for column col of the identity
        const double e0 = (col == 0) != swap ? 1.0 : 0.0;  // the rows swapped
        const double e1 = (col == 0) != swap ? 0.0 : 1.0;
        const double y1 = e1 - l * e0;
        const double x1 = y1 / u11;
        const double x0 = (e0 - u01 * x1) / u00;
        out[col] = x0;
        out[2 + col] = x1;
    }
}

}  // namespace detail

//! The closed form of an arm of the family from its axes (arm_axes), or nullopt.
inline std::optional<ParallelParams> build(const ArmAxes& A) {
    if (A.n != 6 || !A.all_revolute() || !A.parallel[1] || !A.parallel[2]) return std::nullopt;
    const Vec3* h = A.h.data();
    const Vec3* p = A.p.data();
    const Vec3 k = detail::unit(h[1]);
    const Vec3 h1 = h[0], h5 = h[4], h6 = h[5];
    if (lines::lines_parallel(h1, k) || lines::lines_parallel(h5, k)) return std::nullopt;
    const Vec3 seed = std::fabs(k.x) < 0.9 ? Vec3{1.0, 0.0, 0.0} : Vec3{0.0, 1.0, 0.0};
    const Vec3 e1 = detail::unit(cross(k, seed));
    const Vec3 e2 = cross(k, e1);
    const Vec3 dA = p[2] - p[1], dB = p[3] - p[2];
    const double xA = dot(dA, e1), yA = dot(dA, e2), xB = dot(dB, e1), yB = dot(dB, e2);
    const double lenA = detail::modulus(xA, yA), lenB = detail::modulus(xB, yB);
    if (std::fmin(lenA, lenB) <= CONTINUUM_TOL * (lenA + lenB)) return std::nullopt;
    const double meet = A.length_tol();
    ParallelParams P;
    Vec3 p5, p6;
    if (lines::lines_parallel(h5, h6)) {
        if (lines::line_distance(h5, p[4], h6, p[5]) <= meet) return std::nullopt;
        P.mode = ParallelMode::parallel;
        p5 = p[4];
        p6 = detail::project(p5, h6, p[5]);
    } else {
        lines::normal_feet(h5, p[4], h6, p[5], p5, p6);
        P.mode = ParallelMode::general;
        if (norm(p6 - p5) <= meet) {
            P.mode = ParallelMode::meet;
            p5 = p6 = 0.5 * (p5 + p6);
        }
    }
    const Vec3 h6par = dot(h5, h6) * h5;
    const Vec3 z = p6 - p5;
    double eq1[3] = {dot(k, h6 - h6par), dot(k, cross(h5, h6)), dot(k, h5) * dot(h5, h6)};
    double eq2[3] = {dot(k, z - dot(h5, z) * h5), dot(k, cross(h5, z)),
                     dot(k, h5) * dot(h5, z) + dot(k, p5 - p[0])};
    if (P.mode == ParallelMode::meet) {
        eq2[0] = eq2[1] = 0.0;
    } else if (P.mode == ParallelMode::parallel) {
        eq1[0] = eq1[1] = 0.0;
        eq1[2] = dot(k, h5) * std::copysign(1.0, dot(h5, h6));
    } else {
        detail::inverse2(eq1[0], eq1[1], eq2[0], eq2[1], P.minv);
    }
    const double alpha = detail::angle(k, h5), beta = detail::angle(h6, h5);
    // reach: |G(a6) - p1s| <= the length of the chain of feet p1s, a2, ..., a6
    Vec3 p1s, a;
    lines::normal_feet(h1, p[0], k, p[1], p1s, a);
    double bound = norm(a - p1s);
    for (int i = 2; i < 6; ++i) {
        const Vec3 next = detail::project(a, h[i], p[i]);
        bound += norm(next - a);
        a = next;
    }
    const Vec3 kpar = dot(h1, k) * h1;
    P.k = k, P.h1 = h1, P.p1 = p[0], P.kpar = kpar, P.kperp = k - kpar, P.hk = cross(h1, k);
    P.h5 = h5, P.p5 = p5, P.h6 = h6, P.p6 = p6;
    P.h6par = h6par, P.h6perp = h6 - h6par, P.h5xh6 = cross(h5, h6);
    P.p2 = p[1], P.p4 = p[3], P.e1 = e1, P.e2 = e2;
    P.home = A.home;
    P.p1s = p1s, P.a6 = a;
    P.D1 = eq1[0], P.E1 = eq1[1], P.F1 = eq1[2];
    P.D2 = eq2[0], P.E2 = eq2[1], P.F2 = eq2[2];
    const double sw = std::sin(0.5 * (alpha - beta)), cw = std::cos(0.5 * (alpha + beta));
    P.wlo = 2.0 * (sw * sw);
    P.whi = 2.0 * (cw * cw);
    P.len_a = lenA, P.len_b = lenB;
    P.arg_a = std::atan2(yA, xA), P.arg_b = std::atan2(yB, xB);
    const Vec3 up = cross(h1, k);
    P.zup[0] = dot(up, e1), P.zup[1] = dot(up, e2);
    P.sign3 = std::copysign(1.0, dot(h[2], k));
    P.sign4 = std::copysign(1.0, dot(h[3], k));
    P.bound = bound;
    P.lip = std::fabs(dot(h1, k)) + norm(k - kpar);
    P.scale = bound;
    P.slack = A.features.slack;  // 0 unless near-degenerate: the triangle straddles its fold
    P.q1rep = detail::middle(A.qlo[0], A.qhi[0]);
    P.q2rep = detail::middle(A.qlo[1], A.qhi[1]);
    return P;
}

//! The closed form of a chain of the family, or nullopt (the arms the header lists).
inline std::optional<ParallelParams> build(const Chain& chain) { return build(arm_axes(chain)); }

}  // namespace km::parallel
