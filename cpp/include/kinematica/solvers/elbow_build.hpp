// The elbow family's builder (3R anthropomorphic and elbow arms): from a chain's joint axes
// at q = 0 and its tool pose to the ElbowParams elbow.hpp solves with.
//
// Arms it declines (nullopt: the numeric solver takes them): any chain but three revolute
// joints with axes 2 and 3 parallel and axis 1 perpendicular to axis 2; one whose link 2
// (axis 2 to axis 3) or link 3 (axis 3 to the tool origin), seen in the plane normal to
// the axes, is no longer than the line geometry's length tolerance (a link that moves
// nothing, or coinciding axes).
#pragma once

#include <cmath>
#include <optional>

#include "../arm_axes.hpp"
#include "../chain.hpp"
#include "../lines.hpp"
#include "elbow.hpp"
#include "planar_build.hpp"

namespace km::elbow {

//! True when the axes make an elbow arm: 3R, axes 2 and 3 parallel, 1 normal to 2.
inline bool is_elbow(const ArmAxes& A) {
    return A.n == 3 && A.all_revolute() && lines::lines_parallel(A.h[1], A.h[2]) &&
           lines::lines_perpendicular(A.h[0], A.h[1]);
}

//! The elbow solver of an arm from its axes (arm_axes), for pose targets or (pose false)
//! for position targets of the tool origin; nullopt for the arms the header lists.
inline std::optional<ElbowParams> build(const ArmAxes& A, bool pose = true) {
    using namespace planar::build_detail;
    if (!is_elbow(A)) return std::nullopt;
    const Vec3* h = A.h.data();
    const Vec3* p = A.p.data();
    const Pose& M = A.home;
    const Vec3 x = M.p;
    const Vec3 h1 = unit(h[0]), k = unit(h[1]);
    Vec3 e1, e2;
    plane_basis(k, e1, e2);
    ElbowParams P;
    const auto plane = [&](const Vec3& v, double* out) {
        out[0] = dot0(v, e1);
        out[1] = dot0(v, e2);
    };
    plane(p[2] - p[1], P.a);
    plane(x - p[2], P.b);
    const double la = length2(P.a[0], P.a[1]), lb = length2(P.b[0], P.b[1]);
    // a link that moves nothing, or coinciding axes: degenerate
    if ((la < lb ? la : lb) <= A.length_tol()) return std::nullopt;
    const Vec3 hk = cross(h1, k);
    Vec3 foot1, foot2;
    lines::normal_feet(h1, p[0], k, p[1], foot1, foot2);
    // The tool turns about axis 3 on a circle (centre c3, radius rho3); its distance from
    // foot2 (on axis 2, which turns about itself) spans [rmin, rmax].
    const Vec3 c3 = p[2] + dot0(x - p[2], k) * k;
    const double rho3 = norm(x - c3);
    const double dh = dot0(k, foot2 - c3);
    const double dr = norm(foot2 - c3 - dh * k);
    const double offset = norm(foot2 - foot1);
    const double height = dot0(k, x - p[0]);
    P.pose = pose;
    P.h1 = h1, P.p1 = p[0], P.k = k, P.e1 = e1, P.e2 = e2, P.hk = hk, P.p2 = p[1];
    plane(hk, P.up);
    P.s2 = 1.0;  // k is axis 2's own direction
    P.s3 = dot(h[2], k) > 0.0 ? 1.0 : -1.0;
    P.height = height;
    P.rk = unrotate0(M, k);
    P.re1 = unrotate0(M, e1);
    P.foot = foot1;
    P.offset = offset;
    P.rmin = std::hypot(dh, std::fabs(dr - rho3));
    P.rmax = std::hypot(dh, dr + rho3);
    P.scale = la + lb + std::fabs(height) + offset;
    // Axis 3 is parallel to axis 2 within the classification's tolerance: a turn about it
    // moves the tool (within `length`) by at most 2 δ length off the ideal.
    const double length = norm(p[1] - p[0]) + norm(p[2] - p[1]) + norm(x - p[2]);
    P.slack = 2.0 * norm(cross(h[2], k)) * length;
    return P;
}

//! The elbow solver of a chain for pose targets, or nullopt (the arms the header lists).
inline std::optional<ElbowParams> build(const Chain& chain) { return build(arm_axes(chain)); }

}  // namespace km::elbow
