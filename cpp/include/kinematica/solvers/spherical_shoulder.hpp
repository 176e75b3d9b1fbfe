// Closed-form IK of arms with a spherical shoulder (Pieper's second case): 6R, and the
// spherical shoulder followed by a slide (R R R P R R).
//
// The first three axes meet at the shoulder centre. Read backwards, the arm is a
// spherical-wrist arm: with T(q) = start · Π_i [M_i(q_i) F_i] · tool,
//
//     T(q)⁻¹ = (tool⁻¹ F_6⁻¹) · M_6(-q_6) F_5⁻¹ ··· F_1⁻¹ · M_1(-q_1) · start⁻¹,
//
// a chain (built in Python from the chain's own transforms: Chain.reversed) whose joint
// j moves by q'_j = -q_(7-j) and whose last three axes (this arm's 3, 2, 1) meet. Its
// solver (spherical_wrist.hpp) solves the inverted target; each candidate row is read
// back (order reversed, signs flipped), and so are the joints it says are free. Its q4
// and q6 limits are this arm's q3 and q1 limits mapped the same way ([-hi, -lo]), so a
// singular shoulder's representative lands within this arm's limits.
//
// Slots: the wrist solver's, 2 k + s: k the reversed arm's position branch (joints 6, 5,
// 4 of this arm placing the shoulder centre as the tool sees it), s the reversed arm's
// wrist no-flip or flip (joints 3, 2, 1 of this arm: the shoulder's two ways to bend).
#pragma once

#include "../config.hpp"
#include "../ik_types.hpp"
#include "../types.hpp"
#include "spherical_wrist.hpp"

namespace km::decoupled {

//! A spherical-shoulder arm (6R or RRRPRR): the spherical-wrist solver of its reversed chain.
struct SphericalShoulderParams {
    SphericalWristParams wrist{};  //!< the reversed chain's solver (its q' = -q reversed)

    KM_HD int slots() const { return wrist.slots(); }
    KM_HD int dof() const { return wrist.dof(); }

    //! Candidates for one pose T (base frame) into Q (8 x 6), slot for slot the reversed
    //! arm's: NaN rows where a branch has no real solution.
    KM_HD void solve(const Pose& T, double* Q, SolverInfo& info) const {
        constexpr int n = 6;
        SolverInfo back;
        wrist.solve(inverse(T), Q, back);
        for (int r = 0; r < slots(); ++r) {
            double* row = Q + n * r;
            for (int i = 0; i < n / 2; ++i) {
                const double a = row[i];
                row[i] = -row[n - 1 - i];
                row[n - 1 - i] = -a;
            }
        }
        info.singular = back.singular;
        info.near = back.near;
        // the reversed arm's gap is a distance of its wrist centre, as the tool sees this
        // arm's shoulder centre: the same metres
        info.gap = back.gap;
        for (int j = 0; j < n; ++j) {
            if (back.is_free(j)) info.set_free(n - 1 - j);
        }
    }
};

}  // namespace km::decoupled
