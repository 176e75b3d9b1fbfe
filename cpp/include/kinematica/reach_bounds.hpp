// Targets a 6R arm cannot reach, proved: two points each fixed on an axis, their distance
// and height bounded over the middle joints once per arm (kinematica.ik.reach_bounds makes
// the bounds and says why they hold; this is the check of one target, a few flops). The
// forward point's distance and height are asked of one q6 together (its circle's angles
// meeting each range: arcs; do they share one?), not each over the whole circle alone.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "kinematica/types.hpp"

namespace km::reach {

//! A circle c + u cos θ + v sin θ (u, v orthogonal and as long) as a joint turns a point.
struct Circle {
    Vec3 c, u, v;
};

//! A 6R arm's bounds (reach_bounds_build.hpp makes them): ranges are (low, high), arcs a
//! joint's limits widened by the check's LIMIT_TOL.
struct Bounds {
    Vec3 a6;                          //!< axis 6's direction, tool frame
    Circle x;                         //!< x (on axis 5) as q6 turns it, tool frame
    Vec3 shoulder, a1;                //!< S on axis 1 and axis 1's direction, base frame
    double reach[2] = {0.0, 0.0};     //!< |x - S| (m)
    double height[2] = {0.0, 0.0};    //!< (x - S)·a1 (m)
    double x_radius = 0.0;            //!< the farthest a point of x's circle is from the tool origin (m)
    double arc6[2] = {0.0, 0.0};      //!< q6's limits
    Circle y;                         //!< y (on axis 2) as q1 turns it, base frame
    double arc1[2] = {0.0, 0.0};      //!< q1's limits
    Vec3 z;                           //!< the point Z on axis 6, tool frame
    double reach2[2] = {0.0, 0.0};    //!< |y - Z| (m)
    double height2[2] = {0.0, 0.0};   //!< (y - Z)·a6 (m)
};

//! Angles arc[0] .. arc[1] with their ends' cosines and sines, or every angle (whole:
//! without limits, or when the arc spans a turn).
struct Arc {
    bool whole = true;
    double lo = 0.0, span = 0.0, c0 = 1.0, s0 = 0.0, c1 = 1.0, s1 = 0.0;
};

inline Arc arc_of(const double* arc, bool limits) {
    constexpr double TWO_PI = 6.283185307179586;
    Arc a;
    a.span = arc[1] - arc[0];
    if (!limits || !(a.span < TWO_PI)) return a;
    a.whole = false;
    a.lo = arc[0];
    a.c0 = std::cos(arc[0]), a.s0 = std::sin(arc[0]);
    a.c1 = std::cos(arc[1]), a.s1 = std::sin(arc[1]);
    return a;
}

//! The least and greatest of A + B cos θ + C sin θ over θ in the arc.
inline void arc_range(double A, double B, double C, const Arc& arc, double& least, double& most) {
    constexpr double TWO_PI = 6.283185307179586;
    const double rho = std::hypot(B, C);
    least = A - rho;
    most = A + rho;
    if (arc.whole) return;
    const double f0 = A + B * arc.c0 + C * arc.s0;
    const double f1 = A + B * arc.c1 + C * arc.s1;
    const auto inside = [&](double t) {
        double d = std::fmod(t - arc.lo, TWO_PI);
        if (d < 0.0) d += TWO_PI;
        return d <= arc.span;
    };
    const double top = std::atan2(C, B);  // where the greatest is; the least half a turn on
    if (!inside(top)) most = std::max(f0, f1);
    if (!inside(top + 0.5 * TWO_PI)) least = std::min(f0, f1);
}

//! arc_range over arc[0] .. arc[1] (every θ without limits, or when it spans a turn).
inline void arc_range(double A, double B, double C, const double* arc, bool limits, double& least,
                      double& most) {
    arc_range(A, B, C, arc_of(arc, limits), least, most);
}

//! How far the distances from the origin of cs + u cos θ + v sin θ (u, v orthogonal and
//! as long, to round-off) over the arc miss [span[0], span[1]], less slack (m).
inline double circle_gap(const Vec3& cs, const Vec3& u, const Vec3& v, const double* arc, bool limits,
                         const double* span, double slack) {
    const double uu = dot(u, u), vv = dot(v, v);
    const double off = 0.5 * std::fabs(uu - vv) + std::fabs(dot(u, v));  // a circle's round-off
    double least, most;
    arc_range(dot(cs, cs) + 0.5 * (uu + vv), 2.0 * dot(cs, u), 2.0 * dot(cs, v), arc, limits, least, most);
    const double near = std::sqrt(std::max(least - off, 0.0));
    const double far = std::sqrt(most + off);
    return std::max(near - span[1], span[0] - far) - slack;
}

//! How far the heights along `axis` of the arc miss [span[0], span[1]], less slack (m).
inline double height_gap(const Vec3& cs, const Vec3& u, const Vec3& v, const double* arc, bool limits,
                         const Vec3& axis, const double* span, double slack) {
    double least, most;
    arc_range(dot(cs, axis), dot(u, axis), dot(v, axis), arc, limits, least, most);
    return std::max(least - span[1], span[0] - most) - slack;
}

//! The angles θ where lo <= A + B cos θ + C sin θ <= hi: every θ (all), none, or the arcs
//! [start[k], start[k] + length] (k < 2).
struct Band {
    bool all = false;
    int arcs = 0;
    double start[2] = {0.0, 0.0};
    double length = 0.0;
};

inline Band band(double A, double B, double C, double lo, double hi) {
    Band r;
    const double rho = std::hypot(B, C);
    if (!(rho > 0.0)) {
        r.all = lo <= A && A <= hi;
        return r;
    }
    const double cl = (lo - A) / rho, ch = (hi - A) / rho;
    if (cl <= -1.0 && ch >= 1.0) {
        r.all = true;
        return r;
    }
    if (cl > 1.0 || ch < -1.0 || cl > ch) return r;
    // cos(θ - φ) within [cl, ch]: θ - φ within ±[acos ch, acos cl]
    const double a1 = std::acos(std::min(ch, 1.0)), a2 = std::acos(std::max(cl, -1.0));
    const double phi = std::atan2(C, B);
    r.arcs = 2;
    r.start[0] = phi + a1;
    r.start[1] = phi - a2;
    r.length = a2 - a1;
    return r;
}

//! Whether some θ has lo_f <= A + B cos θ + C sin θ <= hi_f (f) and lo_g <= a + b cos θ +
//! c sin θ <= hi_g (g) at once, within the arc (arc[0] .. arc[1] with `limits` and a span
//! under a turn). Their common θ, where there is one, make arcs, each starting where one
//! of the bands or the arc starts: those starts are tried.
inline bool together(const double* f, const double* flim, const double* g, const double* glim,
                     const double* arc, bool limits) {
    constexpr double TWO_PI = 6.283185307179586;
    const Band bf = band(f[0], f[1], f[2], flim[0], flim[1]);
    const Band bg = band(g[0], g[1], g[2], glim[0], glim[1]);
    if ((!bf.all && bf.arcs == 0) || (!bg.all && bg.arcs == 0)) return false;
    const bool bounded = limits && arc[1] - arc[0] < TWO_PI;
    const auto on = [](const Band& bd, double t) {
        if (bd.all) return true;
        for (int k = 0; k < bd.arcs; ++k) {
            double d = std::fmod(t - bd.start[k], TWO_PI);
            if (d < 0.0) d += TWO_PI;
            if (d <= bd.length) return true;
        }
        return false;
    };
    const auto inside = [&](double t) {
        if (!bounded) return true;
        double d = std::fmod(t - arc[0], TWO_PI);
        if (d < 0.0) d += TWO_PI;
        return d <= arc[1] - arc[0];
    };
    double starts[6];
    int count = 0;
    starts[count++] = bounded ? arc[0] : 0.0;
    for (const Band* bd : {&bf, &bg}) {
        for (int k = 0; k < bd->arcs; ++k) starts[count++] = bd->start[k];
    }
    for (int i = 0; i < count; ++i) {
        if (on(bf, starts[i]) && on(bg, starts[i]) && inside(starts[i])) return true;
    }
    return false;
}

//! How far (m), at least, the distances and heights of the arc cs + u cos θ + v sin θ
//! (forward()'s) miss [reach[0], reach[1]] x [height[0], height[1]] together, less
//! slack: where each alone is met (gap <= 0) but no one θ meets both, the least widening of
//! both ranges that does, found to within a part in 2^-30 of it (the lower end: a
//! widening that still does not); -inf where θ's meet both.
inline double together_gap(const Vec3& cs, const Vec3& u, const Vec3& v, const double* arc,
                           bool limits, const Vec3& axis, const double* reach,
                           const double* height, double slack) {
    const double uu = dot(u, u), vv = dot(v, v);
    const double off = 0.5 * std::fabs(uu - vv) + std::fabs(dot(u, v));
    const double f[3] = {dot(cs, cs) + 0.5 * (uu + vv), 2.0 * dot(cs, u), 2.0 * dot(cs, v)};
    const double g[3] = {dot(cs, axis), dot(u, axis), dot(v, axis)};
    const auto meets = [&](double wide) {
        const double s = slack + wide;
        const double near = std::max(reach[0] - s, 0.0), far = reach[1] + s;
        const double flim[2] = {near * near - off, far * far + off};
        const double glim[2] = {height[0] - s, height[1] + s};
        return together(f, flim, g, glim, arc, limits);
    };
    if (meets(0.0)) return -std::numeric_limits<double>::infinity();
    double lo = 0.0, hi = 1e-6;
    while (!meets(hi)) {
        lo = hi;
        hi *= 2.0;
        if (hi > 1e6) return lo;  // a range over 1000 km: not an arm's
    }
    for (int i = 0; i < 30 && hi - lo > 1e-30; ++i) {
        const double mid = 0.5 * (lo + hi);
        (meets(mid) ? hi : lo) = mid;
    }
    return lo;
}

//! How far (m) the target T (the arm's tool frame in its base frame) misses the bounds b
//! beyond the slack of the acceptance tolerance (P m, R rad): positive where no solution
//! within the tolerance (and q1, q6 within their limits, with `limits`) reaches T. NaN for
//! a T with a non-finite entry.
inline double violation(const Bounds& b, const Pose& T, double P, double R, bool limits) {
    const double entries[12] = {T.x.x, T.x.y, T.x.z, T.y.x, T.y.y, T.y.z, T.z.x, T.z.y, T.z.z, T.p.x, T.p.y, T.p.z};
    for (const double e : entries) {
        if (!std::isfinite(e)) return std::nan("");
    }
    // forward: x's circle about axis 6 (q6) against S on axis 1
    const Vec3 cs = T.apply(b.x.c) - b.shoulder;
    const Vec3 u = T.rotate(b.x.u), v = T.rotate(b.x.v);
    double slack = P + R * b.x_radius;
    double forward = std::max(circle_gap(cs, u, v, b.arc6, limits, b.reach, slack),
                              height_gap(cs, u, v, b.arc6, limits, b.a1, b.height, slack));
    // reverse: y's circle about axis 1 (q1) against Z on axis 6 (a6 turned by at most R)
    const Vec3 a6 = T.rotate(b.a6);
    const Vec3 cz = b.y.c - T.apply(b.z);
    const double slack2 = P + R * norm(b.z);
    const double lean = slack2 + R * b.reach2[1];
    const double reverse = std::max(circle_gap(cz, b.y.u, b.y.v, b.arc1, limits, b.reach2, slack2),
                                    height_gap(cz, b.y.u, b.y.v, b.arc1, limits, a6, b.height2, lean));
    if (forward <= 0.0 && reverse <= 0.0) {  // each range met alone: both at one q6?
        forward = together_gap(cs, u, v, b.arc6, limits, b.a1, b.reach, b.height, slack);
    }
    return std::max(forward, reverse);
}

}  // namespace km::reach
