// The reach bounds of a 6R arm, made once per arm (reach_bounds.hpp checks a target against
// them). Two points each fixed on an axis, and the ranges of their distance and height:
//
// * forward: a point x on axis 5 (where the common normal of axes 4 and 5 meets it) and a
//   point S on axis 1 (likewise with axis 2). The target fixes the last link, so axis 6;
//   x is fixed to axis 6's link but for the turn q6 about it, so it lies on a known
//   circle. Seen from axis 1, |x - S| and the height (x - S)·a1 depend on q2, q3, q4 alone.
// * reverse: the same from the tool's side: a point y on axis 2 (on a fixed circle about
//   axis 1) and a point Z on axis 6 (fixed by the target), joints q3, q4, q5.
//
// The ranges over three joints: exact over the joint nearest S (a circle's or an arc's
// range of distance from a point), sampled on a GRID x GRID grid over the other two (a
// whole turn, or the limits with their ends), widened by a bound of the error: an extremum
// is a critical point along every joint not at a limit, so a grid point is within ½ C |δ|²
// of it (C bounds the Hessian, from the distances of the point from the axes bounded by
// triangle inequalities; |δ|² <= (h2/2)² + (h3/2)², h the steps). An extremum at a limit
// has a zero derivative along the other joints (the limits make a box), and the grid holds
// the limits' ends, so the bound holds there too. Where solutions are held to the joint
// limits, the ranges are over the limits of q2 to q5 (each widened by the check's
// LIMIT_TOL; the check takes an angle or its turn ±2π, and so does a limit spanning less
// than a turn here). Which way each joint turns its link is read from FK.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>

#include "arm_axes.hpp"
#include "check.hpp"
#include "reach_bounds.hpp"

namespace km::reach {

//! Samples per joint of the grid over two joints (the ranges' margin shrinks as 1/GRID²).
constexpr int GRID = 256;
//! A point turned by a joint's FK and by a turn about its axis are the same point within
//! this (m): which way the joint turns its link (signs()); else the arm is not read.
constexpr double TURN_MATCH_TOL = 1e-9;

namespace detail {

constexpr double TWO_PI = 6.283185307179586;

//! The point of line 1 nearest line 2 (of a parallel pair: p2 projected on line 1).
inline Vec3 foot(const Vec3& p1, const Vec3& a1, const Vec3& p2, const Vec3& a2) {
    const Vec3 w = p1 - p2;
    const double b = dot(a1, a2), d = dot(a1, w), e = dot(a2, w);
    const double den = 1.0 - b * b;
    const double s = den > 1e-12 ? (b * e - d) / den : -d;
    return p1 + s * a1;
}

//! v turned about the unit vector a by the angle whose cosine and sine are c, s.
inline Vec3 turned(const Vec3& a, double c, double s, const Vec3& v) {
    return c * v + s * cross(a, v) + ((1.0 - c) * dot(a, v)) * a;
}

//! The angles a joint's range is taken over: its limits (lo, hi) or a whole turn.
struct Box {
    bool whole = true;
    double lo = -PI, hi = PI;
};

//! The turns t with sign·t within the box.
inline Box signed_box(const Box& b, double sign) {
    if (b.whole) return b;
    const double u = sign * b.lo, v = sign * b.hi;
    return {false, std::min(u, v), std::max(u, v)};
}

//! The box as the check's arc (its ends' trigonometry once).
inline Arc arc_of(const Box& b) {
    const double ends[2] = {b.lo, b.hi};
    return reach::arc_of(ends, !b.whole);
}

//! The grid's k-th angle over the box (its ends included) or a whole turn.
inline double grid_at(const Box& b, int k) {
    if (b.whole) return -PI + TWO_PI * k / GRID;
    return k == GRID - 1 ? b.hi : b.lo + (b.hi - b.lo) * k / (GRID - 1);
}

//! The grid's step over the box.
inline double grid_step(const Box& b) { return b.whole ? TWO_PI / GRID : (b.hi - b.lo) / (GRID - 1); }

//! S on axis s, x0 on axis m, and the ranges of |x - S| and (x - S)·a_s over the joints
//! mids (nearest S first): x = exp(t1) exp(t2) exp(t3) x0, turns about the axes at q = 0
//! (P, A: points, directions), each t within its box.
struct Ranges {
    Vec3 S, x0;
    double reach[2] = {0.0, 0.0}, height[2] = {0.0, 0.0};
};

inline Ranges ranges(const Vec3* P, const Vec3* A, int s, int m, const int* mids, const Box* boxes) {
    const int j1 = mids[0], j2 = mids[1], j3 = mids[2];
    Ranges r;
    r.S = foot(P[s], A[s], P[j1], A[j1]);
    r.x0 = foot(P[m], A[m], P[j3], A[j3]);
    double cos2[GRID], sin2[GRID];
    for (int k = 0; k < GRID; ++k) {
        const double t2 = grid_at(boxes[1], k);
        cos2[k] = std::cos(t2), sin2[k] = std::sin(t2);
    }
    const Arc first = arc_of(boxes[0]);
    double g_lo = INF, g_hi = -INF, h_lo = INF, h_hi = -INF;
    for (int k3 = 0; k3 < GRID; ++k3) {
        const double t3 = grid_at(boxes[2], k3);
        const Vec3 y3 = turned(A[j3], std::cos(t3), std::sin(t3), r.x0 - P[j3]) + P[j3];
        for (int k2 = 0; k2 < GRID; ++k2) {
            const Vec3 y = turned(A[j2], cos2[k2], sin2[k2], y3 - P[j2]) + P[j2];
            const Vec3 c = P[j1] + dot(y - P[j1], A[j1]) * A[j1];  // its circle about axis j1
            const Vec3 u = y - c, v = cross(A[j1], u), cs = c - r.S;
            double lo, hi;
            arc_range(dot(cs, cs) + dot(u, u), 2.0 * dot(cs, u), 2.0 * dot(cs, v), first, lo, hi);
            g_lo = std::min(g_lo, lo), g_hi = std::max(g_hi, hi);
            arc_range(dot(cs, A[s]), dot(u, A[s]), dot(v, A[s]), first, lo, hi);
            h_lo = std::min(h_lo, lo), h_hi = std::max(h_hi, hi);
        }
    }
    // the distances of x from S and from the axes j1, j2, j3, bounded by triangle
    // inequalities along points each two of which are fixed in one link
    const Vec3 feet[5] = {r.S, foot(P[j1], A[j1], P[j2], A[j2]), foot(P[j2], A[j2], P[j3], A[j3]),
                          foot(P[j3], A[j3], P[m], A[m]), r.x0};
    double hops[4];
    for (int i = 0; i < 4; ++i) hops[i] = norm(feet[i + 1] - feet[i]);
    const double D = hops[0] + hops[1] + hops[2] + hops[3];
    const double rho[3] = {hops[1] + hops[2] + hops[3], hops[2] + hops[3], hops[3]};
    double c2 = 0.0, ch2 = 0.0;
    for (int i = 0; i < 3; ++i) {
        for (int k = 0; k < 3; ++k) {
            const double most = std::max(rho[i], rho[k]);
            const double term = rho[i] * rho[k] + D * most;
            c2 += term * term;
            ch2 += most * most;
        }
    }
    const double C = 2.0 * std::sqrt(c2), Ch = std::sqrt(ch2);
    const double h2 = grid_step(boxes[1]), h3 = grid_step(boxes[2]);
    const double step = 0.25 * h2 * h2 + 0.25 * h3 * h3;  // |δ|² at most: half a step off each
    const double wide = 0.5 * C * step, hw = 0.5 * Ch * step;
    r.reach[0] = std::sqrt(std::max(g_lo - wide, 0.0));
    r.reach[1] = std::sqrt(g_hi + wide);
    r.height[0] = h_lo - hw;
    r.height[1] = h_hi + hw;
    return r;
}

//! Records every frame of a walk: 0T0 (base), 0T1, ..., 0T6 (with tool).
struct Frames {
    static constexpr bool frames = true;
    static constexpr bool axes = false;
    Pose* F;
    void frame(int i, const Pose& T) { F[i] = T; }
    void axis(int, const Vec3&, const Vec3&) {}
};

//! The frames of the 6R chain at q.
inline void frames_at(const ChainView& ch, const double* q, Pose* F) {
    double c[6], s[6];
    joint_trig(ch, q, c, s);
    walk(ch, q, c, s, Frames{F});
}

//! ±1: joint j turns its link about A[j] by ±q (read from FK); false where neither.
inline bool signs(const ChainView& ch, const Vec3* P, const Vec3* A, double* sign) {
    constexpr double TURN = 0.3;
    const double zero[6] = {};
    Pose F0[7], F[7];
    frames_at(ch, zero, F0);
    for (int j = 0; j < 6; ++j) {
        double q[6] = {};
        q[j] = TURN;
        frames_at(ch, q, F);
        const Vec3 seed = std::fabs(A[j].x) < 0.9 ? Vec3{1.0, 0.0, 0.0} : Vec3{0.0, 1.0, 0.0};
        const Vec3 e = cross(A[j], seed);
        const Vec3 p = P[j] + (1.0 / norm(e)) * e;  // a point of link j off its axis, at q = 0
        const Pose &before = F0[j + 1], &after = F[j + 1];
        const Vec3 moved = after.apply(before.unrotate(p - before.p));
        const double c = std::cos(TURN), s = std::sin(TURN);
        const double plus = norm(turned(A[j], c, s, p - P[j]) + P[j] - moved);
        const double minus = norm(turned(A[j], c, -s, p - P[j]) + P[j] - moved);
        if (!(std::min(plus, minus) < TURN_MATCH_TOL)) return false;
        sign[j] = plus < minus ? 1.0 : -1.0;
    }
    return true;
}

}  // namespace detail

//! The bounds of a chain of 6 revolute joints, of solutions within the joint limits
//! (`limits`) or anywhere; none for any other chain, or one whose joints' turns FK does
//! not show.
inline std::optional<Bounds> build(const Chain& chain, bool limits) {
    const ChainView ch = chain.view();
    if (ch.n != 6) return std::nullopt;
    for (int i = 0; i < 6; ++i)
        if (ch.joint[i].prismatic) return std::nullopt;
    const ArmAxes AX = arm_axes(chain);
    const Vec3* P = AX.p.data();
    const Vec3* A = AX.h.data();
    const Pose& home = AX.home;  // the tool at q = 0
    const auto tool = [&](const Vec3& point) { return home.unrotate(point - home.p); };
    double sign[6];
    if (!detail::signs(ch, P, A, sign)) return std::nullopt;
    // each joint's limits as angles of the turns the ranges take
    detail::Box boxes[6];
    for (int j = 0; j < 6; ++j) {
        const double lo = AX.qlo[static_cast<size_t>(j)] - LIMIT_TOL;
        const double hi = AX.qhi[static_cast<size_t>(j)] + LIMIT_TOL;
        if (limits && hi - lo < detail::TWO_PI) boxes[j] = {false, lo, hi};
    }
    // forward: x = exp(q2) exp(q3) exp(q4) x0, turns by t = sign q; reverse: y seen from
    // link 5, exp(-q5) exp(-q4) exp(-q3) y0, turns by t = -sign q
    const int fwd[3] = {1, 2, 3}, rev[3] = {4, 3, 2};
    detail::Box fb[3], rb[3];
    for (int i = 0; i < 3; ++i) {
        fb[i] = detail::signed_box(boxes[fwd[i]], sign[fwd[i]]);
        rb[i] = detail::signed_box(boxes[rev[i]], -sign[rev[i]]);
    }
    const detail::Ranges forward = detail::ranges(P, A, 0, 4, fwd, fb);
    const detail::Ranges reverse = detail::ranges(P, A, 5, 1, rev, rb);
    // x (fixed to link 5) in the tool frame at q6 = 0 and π/2, the other joints at 0; y
    // (fixed to link 1) at q1 = 0 and π/2: each circle as its joint turns it
    Pose F0[7], F6[7], F1[7];
    const double zero[6] = {}, q6[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.5 * PI},
                 q1[6] = {0.5 * PI, 0.0, 0.0, 0.0, 0.0, 0.0};
    detail::frames_at(ch, zero, F0);
    detail::frames_at(ch, q6, F6);
    detail::frames_at(ch, q1, F1);
    const Vec3 x0 = forward.x0, y0 = reverse.x0;
    const Vec3 xs0 = F0[6].unrotate(x0 - F0[6].p), xs1 = F6[6].unrotate(x0 - F6[6].p);
    const Vec3 a6 = home.unrotate(A[5]), p6 = tool(P[5]);
    const Vec3 xc = p6 + dot(xs0 - p6, a6) * a6;
    const Vec3 y_half = F1[1].apply(F0[1].unrotate(y0 - F0[1].p));
    const Vec3 yc = P[0] + dot(y0 - P[0], A[0]) * A[0];
    Bounds b;
    b.a6 = a6;
    b.x = {xc, xs0 - xc, xs1 - xc};
    b.shoulder = forward.S;
    b.a1 = A[0];
    std::copy(forward.reach, forward.reach + 2, b.reach);
    std::copy(forward.height, forward.height + 2, b.height);
    b.x_radius = norm(xc) + norm(xs0 - xc);
    b.arc6[0] = AX.qlo[5] - LIMIT_TOL, b.arc6[1] = AX.qhi[5] + LIMIT_TOL;
    b.y = {yc, y0 - yc, y_half - yc};
    b.arc1[0] = AX.qlo[0] - LIMIT_TOL, b.arc1[1] = AX.qhi[0] + LIMIT_TOL;
    b.z = tool(reverse.S);
    std::copy(reverse.reach, reverse.reach + 2, b.reach2);
    std::copy(reverse.height, reverse.height + 2, b.height2);
    return b;
}

}  // namespace km::reach
