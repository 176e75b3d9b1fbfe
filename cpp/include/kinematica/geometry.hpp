// Small geometry: rotations about axes and the subproblems they pose.
//
// The building blocks of the closed-form solvers (Paden-Kahan subproblems in
// product-of-exponentials form): rotate a vector about a unit axis, the angle that turns
// one vector onto another about an axis (SP1), and the two angles of a cos θ + b sin θ = c.
#pragma once

#include <cmath>

#include "config.hpp"
#include "types.hpp"

namespace km {

//! a cos θ + b sin θ = c with |c| above hypot(a, b) by at most this fraction is taken as
//! touching (one double root) rather than unreachable: a target on the boundary of the
//! reachable set, computed by forward kinematics, lands a few ulps on either side of it.
constexpr double TRIG_TOL = 1e-10;

//! R(k, θ) v (Rodrigues) for a unit axis k, c = cos θ, s = sin θ.
KM_HD inline Vec3 rotate_about(const Vec3& k, double c, double s, const Vec3& v) {
    const double t = (1.0 - c) * dot(k, v);
    return {c * v.x + s * (k.y * v.z - k.z * v.y) + t * k.x,
            c * v.y + s * (k.z * v.x - k.x * v.z) + t * k.y,
            c * v.z + s * (k.x * v.y - k.y * v.x) + t * k.z};
}

//! SP1: the angle θ with R(k, θ) p1 = p2 (the closest when not exact).
//!
//! If p1 or p2 lies on the axis every angle is as good and 0 comes back (atan2(0, 0)).
//! Both vectors are projected across k first: near the axis their parts along it would
//! swamp the small cross parts.
KM_HD inline double subproblem1(const Vec3& p1, const Vec3& p2, const Vec3& k) {
    const double kp = dot(k, p1);
    const Vec3 a{p1.x - kp * k.x, p1.y - kp * k.y, p1.z - kp * k.z};
    const double kq = dot(k, p2);
    const Vec3 b{p2.x - kq * k.x, p2.y - kq * k.y, p2.z - kq * k.z};
    const Vec3 c = cross(a, b);
    return std::atan2(dot(k, c), dot(a, b));
}

//! What trig_linear says of a cos θ + b sin θ = c.
enum class TrigRoots {
    none = 0,       //!< |c| > r beyond TRIG_TOL: the least-squares angle, twice
    two = 1,        //!< two solutions (possibly a double root)
    any_or_none = -1  //!< a = b = 0: every angle solves c = 0, none c != 0; 0 given
};

//! The angles θ with a cos θ + b sin θ = c, into out[2].
//!
//! With r = hypot(a, b) and s = sqrt(r² - c²): θ = atan2(b c ± a s, a c ∓ b s) (no acos:
//! no loss of accuracy away from the double root). |c| > r by at most TRIG_TOL relative
//! is a double root.
KM_HD inline TrigRoots trig_linear(double a, double b, double c, double* out) {
    const double r2 = a * a + b * b;
    if (r2 == 0.0) {
        out[0] = 0.0;
        out[1] = 0.0;
        return TrigRoots::any_or_none;
    }
    const double disc = r2 - c * c;
    const bool exact = disc >= -2.0 * TRIG_TOL * r2;
    const double s = disc > 0.0 ? std::sqrt(disc) : 0.0;
    out[0] = std::atan2(b * c + a * s, a * c - b * s);
    out[1] = std::atan2(b * c - a * s, a * c + b * s);
    return exact ? TrigRoots::two : TrigRoots::none;
}

}  // namespace km
