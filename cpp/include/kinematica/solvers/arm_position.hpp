// Position targets of arms with more than three joints: joints 1-3 place the tool origin.
//
// The tool origin with joints 4..n at 0 is a point fixed after joint 3; ArmPoint
// (arm_point.hpp) puts it on the target, up to four ways (the decoupling of the lecture
// notes: shoulder × elbow). Joints 4..n stay free, so every target's solutions form a
// continuum: the candidates are its representatives with those joints at 0, the target
// is singular and joints 4..n are named free.
//
// A target that no branch reaches with joints 4..n at 0 may still be reached with other
// values of them (they move the tool origin by at most `reach`, a bound from the joints'
// translations): the gap is then the arm part's gap less that bound, and the target is
// flagged near (no proof) unless the bound is 0 (the tool origin on every later axis: a
// spherical wrist without tool offset).
//
// A second, tighter bound serves targets no branch reaches: a point C on axis 4 (fixed to
// link 3) whose own shell (`centre`, the shell bounds alone) holds every reachable C, and
// `centre_reach`, a bound on |tool origin - C| over every q (a chain of points on axes
// 4..n whose consecutive distances no joint changes). The target then lies at least the
// distance to C's shell less centre_reach outside the reach; for a spherical wrist C is
// the wrist centre and centre_reach the wrist-to-tool distance, and the bound is exact
// when the shoulder reaches the shell's nearest point. The larger of the two bounds is
// reported.
#pragma once

#include <cmath>

#include "../config.hpp"
#include "../ik_types.hpp"
#include "../types.hpp"
#include "arm_point.hpp"

namespace km::decoupled {

//! Most joints an arm-position solver serves: its free joints are bits of SolverInfo::free.
constexpr int MAX_POSITION_DOF = 32;
static_assert(MAX_POSITION_DOF <= FREE_JOINTS, "every joint's free bit must fit the mask");

//! Position targets of an arm of n > 3 joints whose joints 1-3 place the tool origin.
struct ArmPositionParams {
    ArmPoint arm{};      //!< joints 1-3 placing the tool origin (joints 4..n at 0)
    double reach = 0.0;  //!< bound (m) on how far joints 4..n move the tool origin from the point
    //! Joints 1-3 placing a point C on axis 4: only its shell bounds (r_lo ... z_hi) are read.
    ArmPoint centre{};
    double centre_reach = INF;  //!< bound (m) on |tool origin - C| over every q (INF: none)
    int n = 4;           //!< the chain's joints (4 .. MAX_POSITION_DOF)

    KM_HD int slots() const { return 4; }
    KM_HD int dof() const { return n; }

    //! Candidates for the position of T (its rotation is not read) into Q (4 x n): one
    //! slot per arm branch, joints 4..n at 0.
    KM_HD void solve(const Pose& T, double* Q, SolverInfo& info) const {
        double Q3[4][3];
        ArmState st;
        arm.place(T.p, Q3, st);
        bool real = false;
        for (int k = 0; k < 4; ++k) {
            const bool ok = !std::isnan(Q3[k][0]);
            real |= ok;
            for (int j = 0; j < n; ++j) Q[k * n + j] = ok ? (j < 3 ? Q3[k][j] : 0.0) : NaN;
        }
        info.singular = true;
        for (int j = 0; j < n; ++j) {
            if (j >= 3 || st.free[j]) info.set_free(j);
        }
        info.near = st.near || (!real && reach > 0.0);
        double gap = py_max(0.0, st.gap - reach);
        if (!real) gap = py_max(gap, centre_gap(T.p));
        info.gap = !real || gap > 0.0 ? gap : NaN;
    }

    //! Lower bound (m) of the distance of target p to the reachable tool origins, from C's
    //! shell: negative or NaN when it proves nothing (then not used).
    KM_HD double centre_gap(const Vec3& p) const {
        double zeta = 0.0;
        for (int i = 0; i < 3; ++i) zeta += (p[i] - centre.p1[i]) * centre.h1[i];
        // hypot: no overflow of squares for a target far beyond any arm
        const double r = std::hypot(std::hypot(p[0] - centre.p1[0], p[1] - centre.p1[1]),
                                    p[2] - centre.p1[2]);
        return centre.shell_gap(r, zeta) - centre_reach;
    }
};

}  // namespace km::decoupled
