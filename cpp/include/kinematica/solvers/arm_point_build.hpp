// Where the first three joints put a point: the ArmPoint of arm_point.hpp, from the axes.
//
// Joints 1 and 2 are revolute (lines (h1, p1), (h2, p2) at q = 0); joint 3 is revolute or
// prismatic. A point c fixed after joint 3 (a wrist centre, or the tool origin with the later
// joints at 0) must reach a target. arm_geometry() reads which of three shoulders it is (axes
// 1 and 2 meet, are parallel, or are skew), the motion u(q3) of the point as seen from axis
// 2, its expression on a frame of axis 2, the bounds of the reachable shell; places_point()
// whether joints 1-3 move the point in three directions at all. The spherical-wrist,
// spherical-shoulder and position builders start here.
#pragma once

#include <cmath>
#include <optional>

#include "../chain.hpp"
#include "../lines.hpp"
#include "../point_rank.hpp"
#include "arm_point.hpp"

namespace km::decoupled {

//! Joints 1-3 place the point when, at one of PLACE_PROBES, the smallest singular value of
//! the point's 3 x 3 Jacobian exceeds this times the largest.
constexpr double PLACE_RANK_TOL = 1e-6;
//! Configurations of joints 1-3 at which that rank is tested (fixed, so that the decision
//! depends on the geometry alone).
constexpr double PLACE_PROBES[3][3] = {{0.3, -0.7, 1.1}, {-1.3, 0.4, -0.6}, {2.1, 1.7, 0.2}};

//! True when joints 1-3 of the chain (n >= 3) move a point, fixed in the tool frame at c_tool
//! (joints 4..n at 0), in three independent directions.
inline bool places_point(const Chain& chain, const Vec3& c_tool) {
    const ChainView ch = chain.view();
    const auto N = static_cast<size_t>(ch.n);
    std::vector<double> q(N, 0.0), c(N), s(N), J(6 * N);
    for (const auto& probe : PLACE_PROBES) {
        for (int j = 0; j < 3; ++j) q[static_cast<size_t>(j)] = probe[j];
        if (point_rank_ratio(ch, q.data(), c_tool, c.data(), s.data(), J.data()) > PLACE_RANK_TOL) {
            return true;
        }
    }
    return false;
}

namespace build_detail {

inline Vec3 divided(const Vec3& v, double r) { return {v.x / r, v.y / r, v.z / r}; }

//! A unit vector normal to the unit vector h.
inline Vec3 unit_normal(const Vec3& h) {
    Vec3 n = cross(h, {1.0, 0.0, 0.0});
    if (norm(n) < 0.5) n = cross(h, {0.0, 1.0, 0.0});
    return divided(n, norm(n));
}

//! Python's max(a, b): b only when b > a.
inline double larger(double a, double b) { return b > a ? b : a; }

//! Fourier coefficients [g0, a1, b1, a2, b2] of (x0 + xc cos + xs sin)².
inline void trig_square(double x0, double xc, double xs, double (&out)[5]) {
    out[0] = x0 * x0 + (xc * xc + xs * xs) / 2;
    out[1] = 2 * x0 * xc;
    out[2] = 2 * x0 * xs;
    out[3] = (xc * xc - xs * xs) / 2;
    out[4] = xc * xs;
}

//! (5, 5): rows turn [X0², X0, Y0², Y0, 1] into the Fourier coefficients of Pieper's
//! F(q3) = sin²α X² + 4a² Y² - 4a² sin²α (L - H²) (arm_quartic.hpp), X = X0 - L1 cos - L2 sin
//! (X0 = |d|² - a² - L0), Y = Y0 - cα (H1 cos + H2 sin) (Y0 = ζ - cα H0).
inline void fourier_matrix(double a, double sa, double ca, const double (&L)[3],
                           const double (&H)[3], double (&F)[5][5]) {
    const double sa2 = sa * sa, a2 = a * a;
    for (auto& row : F)
        for (double& v : row) v = 0.0;
    F[0][0] = sa2;
    F[1][1] = -2 * sa2 * L[1];
    F[1][2] = -2 * sa2 * L[2];
    F[2][0] = 4 * a2;
    F[3][1] = -8 * a2 * ca * H[1];
    F[3][2] = -8 * a2 * ca * H[2];
    double A[5], B[5], C[5];
    trig_square(0.0, -L[1], -L[2], A);
    trig_square(0.0, -ca * H[1], -ca * H[2], B);
    trig_square(H[0], H[1], H[2], C);
    const double Lv[5] = {L[0], L[1], L[2], 0.0, 0.0};
    for (int j = 0; j < 5; ++j) {
        F[4][j] = sa2 * A[j] + 4 * a2 * B[j] - 4 * a2 * sa2 * (Lv[j] - C[j]);
    }
}

}  // namespace build_detail

//! The geometry of joints 1-3 placing c, or nullopt when they cannot: axes 1 and 2
//! coincide, the point lies on axis 3 (or axis 3 passes p2 where |u| would not depend on
//! q3), or three parallel axes keep the point in a plane.
//!
//! h, p: unit directions and points of axes 1..3 at q = 0 (base frame); prismatic: joint 3
//! slides; c: the point at q = 0; size: the arm's size (m; lines.hpp's tolerances).
inline std::optional<ArmPoint> arm_geometry(const Vec3* h, const Vec3* p, bool prismatic,
                                            const Vec3& c, double size) {
    using namespace build_detail;
    const Vec3 h1 = divided(h[0], norm(h[0])), h2 = divided(h[1], norm(h[1])),
               h3 = divided(h[2], norm(h[2]));
    Vec3 p1 = p[0], p2 = p[1];
    const Vec3 p3 = p[2];
    const double tol = lines::length_tol(size);
    // the lengths the solver's own tolerances scale with (its double roots, its polish)
    const double scale = 1.0 + (norm(c - p1) + norm(p2 - p1));
    const double ca = dot(h1, h2), sa = norm(cross(h1, h2));
    Shoulder kind;
    double a;
    Vec3 e1, e2;
    if (sa <= lines::AXIS_ANGLE_TOL) {
        const Vec3 delta = (p2 - p1) - dot(p2 - p1, h1) * h1;
        a = norm(delta);
        if (a <= tol) return std::nullopt;  // axes 1 and 2 coincide
        kind = Shoulder::parallel;
        p2 = p1 + delta;
        e1 = divided(delta, a);
        e2 = cross(h2, e1);
    } else {
        Vec3 f1, f2;
        lines::normal_feet(h1, p1, h2, p2, f1, f2);
        a = norm(f2 - f1);
        if (a <= tol) {  // they meet, or all but (an offset of 1e-10)
            kind = Shoulder::meet;
            p1 = f1, p2 = f2;
            e2 = divided(h1 - ca * h2, sa);
            e1 = cross(e2, h2);
            a = dot(f2 - f1, e1);  // signed: f2 - f1 is along h1 × h2, so along e1
        } else {
            kind = Shoulder::general;
            p1 = f1, p2 = f2;
            e1 = divided(f2 - f1, a);
            e2 = cross(h2, e1);
        }
    }
    Vec3 U[3];
    bool parallel23 = false;
    if (prismatic) {
        U[0] = c - p2, U[1] = h3, U[2] = Vec3{0.0, 0.0, 0.0};
    } else {
        const Vec3 r = c - p3;
        const Vec3 rpar = dot(r, h3) * h3;
        U[0] = (p3 - p2) + rpar, U[1] = r - rpar, U[2] = cross(h3, r - rpar);
        if (norm(U[1]) <= tol) return std::nullopt;  // the point is on axis 3
        parallel23 = lines::lines_parallel(h3, h2);
        if (kind == Shoulder::parallel && parallel23) return std::nullopt;  // in a plane
    }
    ArmPoint arm;
    for (int i = 0; i < 3; ++i) {  // u1, u2, H: U's components along e1, e2, h2
        arm.u1[i] = dot(U[i], e1);
        arm.u2[i] = dot(U[i], e2);
        arm.H[i] = dot(U[i], h2);
    }
    double umin, umax, Hlo, Hhi;
    if (prismatic) {
        arm.L[0] = dot(U[0], U[0]), arm.L[1] = 2 * dot(U[0], U[1]), arm.L[2] = 1.0;
        umin = norm(U[0] - dot(U[0], h3) * h3);
        umax = INF;
        const bool tilted = std::fabs(dot(h2, h3)) > 0;
        Hlo = tilted ? -INF : arm.H[0];
        Hhi = tilted ? INF : arm.H[0];
    } else {
        arm.L[0] = dot(U[0], U[0]) + dot(U[1], U[1]);
        arm.L[1] = 2 * dot(U[0], U[1]), arm.L[2] = 2 * dot(U[0], U[2]);
        const double rL = std::hypot(arm.L[1], arm.L[2]);
        umin = std::sqrt(larger(arm.L[0] - rL, 0.0)), umax = std::sqrt(arm.L[0] + rL);
        const double rH = std::hypot(arm.H[1], arm.H[2]);
        Hlo = arm.H[0] - rH, Hhi = arm.H[0] + rH;
    }
    const double b3 = dot(U[0], h3);
    const double m3 = norm(U[0] - b3 * h3);  // distance of axis 3 from p2
    double beta = 0.0, dmin = 0.0, dmax = 0.0;  // |u(q3)| in half-angle form (revolute)
    if (!prismatic) {
        const double n3 = norm(U[1]);
        if (m3 <= tol && (kind == Shoulder::meet || parallel23)) {
            return std::nullopt;  // axis 3 through p2: |u| does not depend on q3
        }
        beta = std::atan2(dot(U[0], U[2]), dot(U[0], U[1]));
        dmin = std::hypot(b3, m3 - n3), dmax = std::hypot(b3, m3 + n3);
    }
    const double g = dot(h1, e2);
    // |x - p1| = |δ + R2 u| lies in [max(0, umin - a, a - umax), a + umax]; with axes 1 and
    // 2 parallel h1ᵀ(x - p1) = cα H lies in cα [Hmin, Hmax]
    double zlo = -INF, zhi = INF;
    if (kind == Shoulder::parallel) {
        const double u = ca * Hlo, v = ca * Hhi;
        zlo = v < u ? v : u, zhi = v < u ? u : v;
    }
    const Vec3 a1 = unit_normal(h1), b1 = cross(h1, a1);
    const Vec3 rows[4] = {h2, e1, e2, p2 - p1};
    for (int i = 0; i < 4; ++i) arm.xframe[i][0] = dot(rows[i], a1), arm.xframe[i][1] = dot(rows[i], b1);
    // Elbow up: the elbow lies on the side of the shoulder-wrist line that axis 1 points to
    // (arm_point.hpp); the second root of a pair is "up" exactly when g v1 (h2ᵀh3) > 0.
    const double k23 = dot(h2, h3);
    const double elbow = g * (k23 > 0.0 ? 1.0 : (k23 < 0.0 ? -1.0 : 0.0));
    if (kind == Shoulder::meet && parallel23) {
        // axes 1 and 2 meet: sign(g v1) is the shoulder sign (g > 0), so the order is fixed
        const int flipped = elbow > 0 ? 0 : 1;
        arm.upper_root[flipped][0] = false, arm.upper_root[flipped][1] = true;
    }
    // a second pass where the closed form neglects a small coupling: axes 1, 2 meeting but
    // for an offset, or axes 2, 3 parallel but for a twist
    arm.refine = (kind == Shoulder::meet && a != 0.0) ||
                 (parallel23 && std::fabs(arm.H[1]) + std::fabs(arm.H[2]) > DOUBLE_ROOT_TOL * scale);
    if (kind == Shoulder::general && !prismatic) fourier_matrix(a, sa, ca, arm.L, arm.H, arm.fourier);
    arm.kind = kind;
    arm.prismatic = prismatic;
    arm.parallel23 = parallel23;
    arm.p1 = p1;
    arm.h1 = h1, arm.a1 = a1, arm.b1 = b1, arm.h2 = h2, arm.h3 = h3;
    arm.a = a;
    arm.ca = ca;
    arm.g = g;
    arm.elbow = elbow;
    arm.scale = scale;
    arm.r_lo = larger(larger(0.0, umin - std::fabs(a)), std::fabs(a) - umax);
    arm.r_hi = std::fabs(a) + umax;
    arm.z_lo = zlo, arm.z_hi = zhi;
    arm.beta = beta, arm.dmin = dmin, arm.dmax = dmax;
    arm.b3 = b3, arm.m3 = m3;
    return arm;
}

}  // namespace km::decoupled
