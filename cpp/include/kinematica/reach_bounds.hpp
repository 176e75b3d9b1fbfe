// Targets a 6R arm cannot reach, proved: two points each fixed on an axis, their distance
// and height bounded over the middle joints once per arm (kinematica.ik.reach_bounds makes
// the bounds and says why they hold; this is the check of one target, a few flops).
#pragma once

#include <algorithm>
#include <cmath>

#include "kinematica/types.hpp"

namespace km::reach {

//! Where each number of an arm's bounds is, in the flat array kinematica.ik.reach_bounds
//! lays out: vectors (3 numbers), ranges (2: low, high) and arcs (2: the joint's limits,
//! widened by the check's LIMIT_TOL).
enum Slot : int {
    A6 = 0,         //!< axis 6's direction, tool frame
    XC = 3,         //!< x (on axis 5) is XC + XU cos q6 + XV sin q6, tool frame
    XU = 6,
    XV = 9,
    SHOULDER = 12,  //!< the point S on axis 1, base frame
    A1 = 15,        //!< axis 1's direction, base frame
    REACH = 18,     //!< |x - S| (m)
    HEIGHT = 20,    //!< (x - S)·a1 (m)
    X_RADIUS = 22,  //!< the farthest a point of x's circle is from the tool frame's origin (m)
    ARC6 = 23,      //!< q6's limits
    YC = 25,        //!< y (on axis 2) is YC + YU cos q1 + YV sin q1, base frame
    YU = 28,
    YV = 31,
    ARC1 = 34,      //!< q1's limits
    Z = 36,         //!< the point Z on axis 6, tool frame
    REACH2 = 39,    //!< |y - Z| (m)
    HEIGHT2 = 41,   //!< (y - Z)·a6 (m)
    SIZE = 43
};

inline Vec3 at(const double* b, int i) { return {b[i], b[i + 1], b[i + 2]}; }

//! The least and greatest of A + B cos θ + C sin θ over θ in arc[0] .. arc[1] (every θ
//! without limits, or when the arc spans a turn).
inline void arc_range(double A, double B, double C, const double* arc, bool limits, double& least,
                      double& most) {
    constexpr double TWO_PI = 6.283185307179586;
    const double rho = std::hypot(B, C);
    least = A - rho;
    most = A + rho;
    const double span = arc[1] - arc[0];
    if (!limits || !(span < TWO_PI)) return;
    const double f0 = A + B * std::cos(arc[0]) + C * std::sin(arc[0]);
    const double f1 = A + B * std::cos(arc[1]) + C * std::sin(arc[1]);
    const auto inside = [&](double t) {
        double d = std::fmod(t - arc[0], TWO_PI);
        if (d < 0.0) d += TWO_PI;
        return d <= span;
    };
    const double top = std::atan2(C, B);  // where the greatest is; the least half a turn on
    if (!inside(top)) most = std::max(f0, f1);
    if (!inside(top + 0.5 * TWO_PI)) least = std::min(f0, f1);
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

//! How far (m) the target T (the arm's tool frame in its base frame) misses the bounds b
//! beyond the slack of the acceptance tolerance (P m, R rad): positive where no solution
//! within the tolerance (and q1, q6 within their limits, with `limits`) reaches T. NaN for
//! a T with a non-finite entry.
inline double violation(const double* b, const Pose& T, double P, double R, bool limits) {
    const double entries[12] = {T.x.x, T.x.y, T.x.z, T.y.x, T.y.y, T.y.z, T.z.x, T.z.y, T.z.z, T.p.x, T.p.y, T.p.z};
    for (const double e : entries) {
        if (!std::isfinite(e)) return std::nan("");
    }
    // forward: x's circle about axis 6 (q6) against S on axis 1
    const Vec3 cs = T.apply(at(b, XC)) - at(b, SHOULDER);
    const Vec3 u = T.rotate(at(b, XU)), v = T.rotate(at(b, XV));
    double slack = P + R * b[X_RADIUS];
    const double forward = std::max(circle_gap(cs, u, v, b + ARC6, limits, b + REACH, slack),
                                    height_gap(cs, u, v, b + ARC6, limits, at(b, A1), b + HEIGHT, slack));
    // reverse: y's circle about axis 1 (q1) against Z on axis 6 (a6 turned by at most R)
    const Vec3 a6 = T.rotate(at(b, A6));
    const Vec3 cz = at(b, YC) - T.apply(at(b, Z)), U = at(b, YU), V = at(b, YV);
    slack = P + R * norm(at(b, Z));
    const double lean = slack + R * b[REACH2 + 1];
    const double reverse = std::max(circle_gap(cz, U, V, b + ARC1, limits, b + REACH2, slack),
                                    height_gap(cz, U, V, b + ARC1, limits, a6, b + HEIGHT2, lean));
    return std::max(forward, reverse);
}

}  // namespace km::reach
