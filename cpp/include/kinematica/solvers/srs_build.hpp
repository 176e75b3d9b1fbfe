// The SRS 7R family's builder: from a chain's joint axes at q = 0 and its tool pose to the
// SRSParams srs.hpp solves with (at the arm angle in its field psi, 0 as built).
//
// Arms it declines (nullopt): any chain but seven revolute joints with axes 1-3 meeting at
// S, axes 5-7 at W, and axis 4 through neither (within the line geometry's length
// tolerance: |S - W| would not depend on q4); two consecutive axes of the shoulder or the
// wrist coinciding.
#pragma once

#include <cmath>
#include <optional>

#include "../arm_axes.hpp"
#include "../chain.hpp"
#include "spherical_wrist_build.hpp"
#include "srs.hpp"

namespace km::srs {

//! The shoulder centre S, the elbow point E0 (the foot of the perpendicular from S onto
//! axis 4) and the wrist centre W0 at q = 0 (base frame, m); false for no SRS arm.
inline bool srs_points(const ArmAxes& A, Vec3& S, Vec3& E, Vec3& W) {
    if (A.n != 7 || !A.all_revolute() || !A.features.wrist.found || !A.features.shoulder.found) {
        return false;
    }
    const Vec3 h4 = A.h[3], p4 = A.p[3];
    S = A.features.shoulder.at;
    W = A.features.wrist.at;
    E = p4 + dot(S - p4, h4) * h4;
    for (const Vec3& point : {S, W}) {
        const Vec3 r = point - p4;
        if (norm(r - dot(r, h4) * h4) <= A.length_tol()) return false;  // axis 4 through it
    }
    return true;
}

namespace detail {

//! v turned by `angle` about the unit axis h (Rodrigues).
inline Vec3 turn(const Vec3& h, double angle, const Vec3& v) {
    const double c = std::cos(angle), s = std::sin(angle);
    return c * v + s * cross(h, v) + ((1.0 - c) * dot(h, v)) * h;
}

}  // namespace detail

//! The SRS solver of an arm from its axes (arm_axes), or nullopt.
inline std::optional<SRSParams> build(const ArmAxes& A) {
    Vec3 S, E, W;
    if (!srs_points(A, S, E, W)) return std::nullopt;
    const Vec3* h = A.h.data();
    const Pose& M = A.home;
    SRSParams P;
    if (!(decoupled::wrist_params(P.shoulder, h[0], h[1], h[2], Pose{}) &&
          decoupled::wrist_params(P.wrist, h[4], h[5], h[6], M))) {
        return std::nullopt;  // two consecutive axes of the shoulder or the wrist coincide
    }
    P.shoulder.q4_lo = A.qlo[0], P.shoulder.q4_hi = A.qhi[0];
    P.shoulder.q6_lo = A.qlo[2], P.shoulder.q6_hi = A.qhi[2];
    P.wrist.q4_lo = A.qlo[4], P.wrist.q4_hi = A.qhi[4];
    P.wrist.q6_lo = A.qlo[6], P.wrist.q6_hi = A.qhi[6];
    const Vec3 se = E - S, ew = W - E, h4 = h[3];
    // |se + R4(q4) ew|² = |se|² + |ew|² + 2 (C + A cos q4 + B sin q4): largest at atan2(B, A)
    const Vec3 ew_across = ew - dot(ew, h4) * h4;
    const Vec3 se_across = se - dot(se, h4) * h4;
    const double stretched = std::atan2(dot(h4, cross(ew, se)), dot(se_across, ew_across));
    P.s = S;
    P.w_tool = M.unrotate(W - M.p);
    P.se = se, P.ew = ew, P.h4 = h4;
    P.ref = h[0];
    P.ref_alt = decoupled::build_detail::unit_normal(h[0]);
    P.stretched = stretched;
    // the extremes as norms of vectors (no cancellation in |se|² + |ew|² - 2r at a fold)
    P.d_max = norm(se + detail::turn(h4, stretched, ew));
    P.d_min = norm(se + detail::turn(h4, stretched + PI, ew));
    P.scale = A.size;
    return P;
}

//! The SRS solver of a chain, or nullopt (the arms the header lists).
inline std::optional<SRSParams> build(const Chain& chain) { return build(arm_axes(chain)); }

}  // namespace km::srs
