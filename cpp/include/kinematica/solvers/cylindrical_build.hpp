// The cylindrical family's builder (a turn, a lift along its axis, a reach across it, an
// optional roll): from a chain's joint axes at q = 0 and its tool pose to the
// CylindricalParams cylindrical.hpp solves with.
//
// Arms it declines (nullopt): any chain but RPP, PRP, RPPR or PRPR whose turn and lift are
// parallel, whose reach is not parallel to the turn, and whose roll (if any) is not either.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>

#include "../arm_axes.hpp"
#include "../chain.hpp"
#include "../lines.hpp"
#include "cylindrical.hpp"
#include "planar_build.hpp"

namespace km::cylindrical {

//! True when the axes make a cylindrical arm (the header's list).
inline bool is_cylindrical(const ArmAxes& A) {
    if (A.n != 3 && A.n != 4) return false;
    const bool* P = A.prismatic.get();
    // the turn and the lift in either order, then the reach (a slide), then a revolute roll
    if (P[0] == P[1] || !P[2] || (A.n == 4 && P[3])) return false;
    const int turn = P[0] ? 1 : 0, lift = 1 - turn;
    const auto par = [&A](int i, int j) { return lines::lines_parallel(A.h[i], A.h[j]); };
    return par(turn, lift) && !par(turn, 2) && (A.n == 3 || !par(turn, 3));
}

//! The cylindrical solver of an arm from its axes (arm_axes), for pose targets or (pose
//! false) for position targets of the tool origin; nullopt for the arms the header lists.
inline std::optional<CylindricalParams> build(const ArmAxes& A, bool pose = true) {
    using namespace planar::build_detail;
    if (!is_cylindrical(A)) return std::nullopt;
    const int n = A.n;
    const Vec3* h = A.h.data();
    const Vec3* p = A.p.data();
    const Pose& M = A.home;
    const Vec3 tool = M.p;
    const int turn = A.prismatic[0] ? 1 : 0, lift = 1 - turn;
    CylindricalParams C;
    const Vec3 k = unit(h[turn]), o = p[turn], s = unit(h[2]);
    const double sk = dot0(k, s);
    const Vec3 sp = s - sk * k;
    const Vec3 nrm = unit(cross(k, sp));
    Vec3 h4 = k, c4 = tool;
    if (n == 4) {
        h4 = unit(h[3]);
        c4 = p[3] + dot0(tool - p[3], h4) * h4;
    }
    Vec3 w4, e1, unused;
    plane_basis(h4, w4, unused);
    plane_basis(k, e1, unused);
    C.n = n;
    C.pose = pose;
    C.turn = turn;
    C.lift = lift;
    C.lift_sign = sign(dot(h[lift], k));
    C.k = k, C.o = o, C.s = s, C.sp = sp, C.sk = sk, C.ss = dot0(sp, sp), C.nrm = nrm;
    C.tool = tool, C.h4 = h4, C.c4 = c4, C.rho = norm(tool - c4), C.w4 = w4;
    C.rh4 = unrotate0(M, h4);
    C.rw4 = unrotate0(M, w4);
    C.e1 = e1;
    C.re1 = unrotate0(M, e1);
    C.offset = std::fabs(dot0(nrm, c4 - o));
    C.scale = A.size;
    // The lift parallel to k within the classification's tolerance only: a travel t along
    // a direction tilted by δ moves the tool δ t across k (no limit: no bound).
    const double tilt = norm(cross(h[lift], k));
    const auto L = static_cast<size_t>(lift);
    const double travel = std::max(std::fabs(A.qlo[L]), std::fabs(A.qhi[L]));
    C.slack = tilt > 0.0 ? tilt * travel : 0.0;
    return C;
}

//! The cylindrical solver of a chain for pose targets, or nullopt (the arms the header lists).
inline std::optional<CylindricalParams> build(const Chain& chain) {
    return build(arm_axes(chain));
}

}  // namespace km::cylindrical
