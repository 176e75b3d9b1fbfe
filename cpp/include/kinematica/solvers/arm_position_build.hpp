// The arm-position solver's builder (position targets of arms of n > 3 joints whose joints
// 1-3 place the tool origin): from a chain's joint axes at q = 0 and its joints' fixed parts
// to the ArmPositionParams arm_position.hpp solves with.
//
// Arms it declines (nullopt): any chain of 3 joints or fewer or more than MAX_POSITION_DOF,
// whose joints 1 and 2 are not revolute; whose joints 1-3 cannot move the tool origin in
// three directions (places_point) or make no ArmPoint of it (arm_geometry says when).
#pragma once

#include <cmath>
#include <optional>
#include <vector>

#include "../arm_axes.hpp"
#include "../chain.hpp"
#include "arm_point_build.hpp"
#include "arm_position.hpp"
#include "planar_build.hpp"

namespace km::decoupled {

//! Two axes whose sine squared is below this are treated as parallel when a point of one
//! nearest the other is chosen (wrist_chain): the choice decides only how tight the bound
//! is, never whether it holds (any point of an axis would do); nearly parallel axes would
//! put their common perpendicular's feet far away, and the bound out of use.
constexpr double PARALLEL_SIN2 = 1e-12;

//! A bound (m) on how far joints 4..n move the tool origin from where it is at 0.
//!
//! Joint i's factor M_i(q_i) · Rot(z, θi) · Tras(t_i) · Rot(x, αi) (chain.hpp; a DH row's
//! t_i = (ai*, 0, di)) moves the tool origin by at most |t_i| (bounded by the sum of its
//! components) from the origin before it, a slide by that plus max |qi| (infinite without
//! limits); joint 4's own t_z is fixed to link 3 (Rot(z, q4) keeps it). The tool origin at
//! any q and at joints 4..n = 0 both lie within that sum (plus the tool's offset) of one
//! point of link 3: twice it bounds their distance.
inline double reach_after_joint3(const Chain& chain) {
    const ChainView ch = chain.view();
    double half = norm(ch.tool.p);
    for (int i = 3; i < ch.n; ++i) {
        const Joint& J = ch.joint[i];
        half += std::fabs(J.t.x);
        half += std::fabs(J.t.y);
        if (J.prismatic) {
            const double lo = std::fabs(J.qlo), hi = std::fabs(J.qhi);
            half += std::fabs(J.t.z) + (hi > lo ? hi : lo);
        } else if (i > 3) {
            half += std::fabs(J.t.z);
        }
    }
    return 2.0 * half;
}

//! The point of line (p, h) nearest line (q, g); of parallel lines (sine² below
//! PARALLEL_SIN2), the point of the first nearest x.
inline Vec3 nearest_foot(const Vec3& p, const Vec3& h0, const Vec3& q, const Vec3& g0,
                         const Vec3& x) {
    const Vec3 h = build_detail::divided(h0, norm(h0)), g = build_detail::divided(g0, norm(g0));
    const double c = planar::build_detail::dot0(h, g);
    const double det = 1.0 - c * c;
    if (det < PARALLEL_SIN2) return p + planar::build_detail::dot0(h, x - p) * h;  // any point would do: nearest x
    const Vec3 w = q - p;
    return p + ((planar::build_detail::dot0(h, w) - c * planar::build_detail::dot0(g, w)) / det) * h;
}

//! A point C on axis 4 and a bound R (m) on the tool origin's distance from it at every q;
//! false when a joint after the third slides.
//!
//! A point on a revolute joint's axis is fixed to the links before and after it, so the
//! distance of two points on consecutive axes k and k + 1 is the same at every q, as is
//! that of the tool origin from a point on axis n. With B_k on axis k (k = 4..n), the foot
//! of the common perpendicular towards axis k + 1 (axis n: towards axis n - 1; parallel
//! axes: the tool origin's foot), |tool origin - B_4| <= Σ_k |B_(k+1) - B_k| +
//! |tool origin - B_n|. For a spherical wrist every B_k is the wrist centre and the bound
//! is the exact wrist-to-tool distance.
inline bool wrist_chain(const ArmAxes& A, Vec3& C, double& R) {
    const int n = A.n;
    for (int k = 3; k < n; ++k)
        if (A.prismatic[k]) return false;
    const Vec3 tool = A.home.p;
    std::vector<Vec3> feet;
    for (int k = 3; k < n; ++k) {
        const int other = k + 1 < n ? k + 1 : k - 1;
        feet.push_back(nearest_foot(A.p[k], A.h[k], A.p[other], A.h[other], tool));
    }
    double steps = 0.0;
    for (size_t k = 1; k < feet.size(); ++k) steps += norm(feet[k] - feet[k - 1]);
    C = feet.front();
    R = steps + norm(tool - feet.back());
    return true;
}

//! The arm-position solver of a chain whose axes are A (arm_axes), or nullopt.
inline std::optional<ArmPositionParams> build_position(const Chain& chain, const ArmAxes& A) {
    if (A.n <= 3 || A.prismatic[0] || A.prismatic[1]) return std::nullopt;
    if (A.n > MAX_POSITION_DOF || !places_point(chain, Vec3{0.0, 0.0, 0.0})) return std::nullopt;
    const std::optional<ArmPoint> arm =
        arm_geometry(A.h.data(), A.p.data(), A.prismatic[2], A.home.p, A.size);
    if (!arm) return std::nullopt;
    ArmPositionParams P;
    P.arm = *arm;
    P.reach = reach_after_joint3(chain);
    Vec3 C;
    double R = 0.0;
    if (wrist_chain(A, C, R)) {
        const std::optional<ArmPoint> centre =
            arm_geometry(A.h.data(), A.p.data(), A.prismatic[2], C, A.size);
        if (centre) {
            P.centre = *centre;
            P.centre_reach = R;
        }
    }
    P.n = A.n;
    return P;
}

//! The arm-position solver of a chain, or nullopt (the arms the header lists).
inline std::optional<ArmPositionParams> build_position(const Chain& chain) {
    return build_position(chain, arm_axes(chain));
}

}  // namespace km::decoupled
