// Targets a 6R arm cannot reach, proved: two points each fixed on an axis, their distance
// and height bounded over the middle joints once per arm (kinematica.ik.reach_bounds makes
// the bounds and says why they hold; this is the check of one target, a few flops).
#pragma once

#include <algorithm>
#include <cmath>

#include "kinematica/types.hpp"

namespace km::reach {

//! Where each number of an arm's bounds is, in the flat array kinematica.ik.reach_bounds
//! lays out: vectors (3 numbers) and ranges (2: low, high).
enum Slot : int {
    A6 = 0,         //!< axis 6's direction, tool frame
    P6 = 3,         //!< a point on axis 6, tool frame
    X = 6,          //!< the point x on axis 5 at q6 = 0, tool frame
    SHOULDER = 9,   //!< the point S on axis 1, base frame
    A1 = 12,        //!< axis 1's direction, base frame
    REACH = 15,     //!< |x - S| (m)
    HEIGHT = 17,    //!< (x - S)·a1 (m)
    X_RADIUS = 19,  //!< the farthest a point of x's circle is from the tool frame's origin (m)
    CENTRE = 20,    //!< the circle of the point y on axis 2 about axis 1: centre, base frame
    U = 23,         //!< its two orthogonal radius vectors
    V = 26,
    Z = 29,         //!< the point Z on axis 6, tool frame
    REACH2 = 32,    //!< |y - Z| (m)
    HEIGHT2 = 34,   //!< (y - Z)·a6 (m)
    SIZE = 36
};

inline Vec3 at(const double* b, int i) { return {b[i], b[i + 1], b[i + 2]}; }

//! How far the distances from the origin of the circle cs + u cos θ + v sin θ miss
//! [span[0], span[1]], less slack (m).
inline double circle_gap(const Vec3& cs, const Vec3& u, const Vec3& v, const double* span, double slack) {
    const double mid = dot(cs, cs) + dot(u, u);
    const double swing = 2.0 * std::hypot(dot(cs, u), dot(cs, v));
    const double near = std::sqrt(std::max(mid - swing, 0.0));
    const double far = std::sqrt(mid + swing);
    return std::max(near - span[1], span[0] - far) - slack;
}

//! How far the circle's heights along `axis` miss [span[0], span[1]], less slack (m).
inline double height_gap(const Vec3& cs, const Vec3& u, const Vec3& v, const Vec3& axis, const double* span,
                         double slack) {
    const double mid = dot(cs, axis);
    const double swing = std::hypot(dot(u, axis), dot(v, axis));
    return std::max(mid - swing - span[1], span[0] - mid - swing) - slack;
}

//! How far (m) the target T (the arm's tool frame in its base frame) misses the bounds b
//! beyond the slack of the acceptance tolerance (P m, R rad): positive where no solution
//! within the tolerance reaches T. NaN for a T with a non-finite entry.
inline double violation(const double* b, const Pose& T, double P, double R) {
    const double entries[12] = {T.x.x, T.x.y, T.x.z, T.y.x, T.y.y, T.y.z, T.z.x, T.z.y, T.z.z, T.p.x, T.p.y, T.p.z};
    for (const double e : entries) {
        if (!std::isfinite(e)) return std::nan("");
    }
    const Vec3 a6 = T.rotate(at(b, A6));
    // forward: x's circle about axis 6 against S on axis 1
    const Vec3 p6 = T.apply(at(b, P6)), x = T.apply(at(b, X));
    const Vec3 c = p6 + dot(x - p6, a6) * a6;
    const Vec3 u = x - c, v = cross(a6, u);
    double slack = P + R * b[X_RADIUS];
    const Vec3 cs = c - at(b, SHOULDER);
    const double forward =
        std::max(circle_gap(cs, u, v, b + REACH, slack), height_gap(cs, u, v, at(b, A1), b + HEIGHT, slack));
    // reverse: y's circle about axis 1 against Z on axis 6 (a6 turned by at most R)
    const Vec3 z = T.apply(at(b, Z));
    slack = P + R * norm(at(b, Z));
    const Vec3 cz = at(b, CENTRE) - z, U2 = at(b, U), V2 = at(b, V);
    const double reverse = std::max(circle_gap(cz, U2, V2, b + REACH2, slack),
                                    height_gap(cz, U2, V2, a6, b + HEIGHT2, slack + R * b[REACH2 + 1]));
    return std::max(forward, reverse);
}

//! The target of the arm locked at 0 that is T with its first (before) or last joint at v:
//! Gl Rz(-v) Gr T, or T Gl Rz(-v) Gr (kinematica.ik.moved: Gl, Gr = G, G⁻¹ for the first,
//! G⁻¹, G for the last).
inline Pose moved(const Pose& T, const Pose& Gl, const Pose& Gr, double v, bool before) {
    const double c = std::cos(v), s = std::sin(v);
    Pose M;
    M.x = {c, -s, 0.0};
    M.y = {s, c, 0.0};
    M.z = {0.0, 0.0, 1.0};
    M.p = {0.0, 0.0, 0.0};
    const Pose move = Gl * M * Gr;
    return before ? move * T : T * move;
}

}  // namespace km::reach
