// The spherical-wrist family's builder (6R, and RRP of the Stanford type): from a chain's
// joint axes at q = 0 and its tool pose to the SphericalWristParams spherical_wrist.hpp
// solves with. Joints 1-3 place the wrist centre (arm_point_build.hpp); the wrist's own
// fields (wrist_params) serve the spherical shoulder and the SRS arms too.
//
// Arms it declines (nullopt: the numeric solver takes them): any chain but six joints, the
// third revolute or a slide and the others revolute, whose last three axes meet; joints 1-3
// unable to move the wrist centre in three directions (places_point, arm_geometry); two
// consecutive wrist axes coinciding.
#pragma once

#include <cmath>
#include <optional>

#include "../arm_axes.hpp"
#include "../chain.hpp"
#include "../lines.hpp"
#include "arm_point_build.hpp"
#include "spherical_wrist.hpp"

namespace km::decoupled {

//! Fill the wrist's fields of P from its unit axes h4, h5, h6 at q = 0 (base frame) and the
//! tool's rotation at q = 0 (home's); false for no 3-DOF wrist (consecutive axes coincide).
//! When the wrist is singular at q = 0, "no-flip" is the bend of q5 > 0 (singular_side 1)
//! or of q5 < 0 (-1: the reversed chain of a spherical shoulder, whose q2 is -q5).
inline bool wrist_params(SphericalWristParams& P, const Vec3& h4, const Vec3& h5,
                         const Vec3& h6, const Pose& home, double singular_side = 1.0) {
    const double k45 = dot(h4, h5);
    Vec3 ea = h5 - k45 * h4;
    const double s45 = norm(ea);
    if (s45 <= lines::AXIS_ANGLE_TOL || lines::lines_parallel(h5, h6)) return false;
    ea = build_detail::divided(ea, s45);
    const Vec3 eb = cross(h4, ea);
    const Vec3 x6 = build_detail::unit_normal(h6);
    const double k56 = dot(h5, h6);
    // "no-flip" bends the wrist as at q = 0 (the sign of γ there), or as q5 > 0 bends it
    // from there when γ = 0 at q = 0 (h6 in the plane of h4 and h5, e.g. aligned with h4):
    // (h4 × h5)ᵀ R5(ε) h6 ≈ ε (k45 k56 - h4ᵀh6)
    const double gamma = dot(cross(h4, h5), h6);
    const double bend = k45 * k56 - dot(h4, h6);
    const auto framed = [&](const Vec3& v) { return Vec3{dot(h4, v), dot(ea, v), dot(eb, v)}; };
    P.lh = home.unrotate(h6);  // R_Mᵀ h6
    P.lx = home.unrotate(x6);
    P.h4 = h4, P.h5 = h5, P.x6 = x6, P.y6 = cross(h6, x6), P.ea = ea, P.eb = eb;
    P.n56 = framed(cross(h5, h6));
    P.h6f = framed(h6);
    P.k45 = k45, P.s45 = s45, P.k56 = k56;
    P.flip = std::copysign(1.0, std::fabs(gamma) > lines::AXIS_ANGLE_TOL ? gamma : singular_side * bend);
    const double twin = build_detail::larger(build_detail::larger(std::fabs(k45), std::fabs(k56)),
                                             norm(cross(h4, h6)));
    P.twin = twin <= TWIN_TOL;
    return true;
}

//! The spherical-wrist solver of an arm from its axes (arm_axes), or nullopt. The chain is
//! the axes' (places_point walks it); singular_side: see wrist_params.
inline std::optional<SphericalWristParams> build(const Chain& chain, const ArmAxes& A,
                                                 double singular_side = 1.0) {
    if (A.n != 6 || !A.features.wrist.found) return std::nullopt;
    for (int i = 0; i < 6; ++i)
        if (i != 2 && A.prismatic[i]) return std::nullopt;
    const Pose& M = A.home;
    const Vec3 c = A.features.wrist.at;
    const Vec3 c_tool = M.unrotate(c - M.p);
    if (!places_point(chain, c_tool)) return std::nullopt;
    std::optional<ArmPoint> arm = arm_geometry(A.h.data(), A.p.data(), A.prismatic[2], c, A.size);
    if (!arm) return std::nullopt;
    SphericalWristParams P;
    P.arm = *arm;
    P.c_tool = c_tool;
    if (!wrist_params(P, A.h[3], A.h[4], A.h[5], M, singular_side)) return std::nullopt;
    P.q4_lo = A.qlo[3], P.q4_hi = A.qhi[3];
    P.q6_lo = A.qlo[5], P.q6_hi = A.qhi[5];
    return P;
}

//! The spherical-wrist solver of a chain, or nullopt (the arms the header lists).
inline std::optional<SphericalWristParams> build(const Chain& chain) {
    return build(chain, arm_axes(chain));
}

}  // namespace km::decoupled
