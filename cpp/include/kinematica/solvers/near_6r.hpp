// A 6R arm that a family of closed forms holds only within the line geometry's tolerance
// (axes 2 and 3 of a UR type 5e-10 rad off parallel): the family's candidates, then the
// general 6R's.
//
// The family's closed form solves the nearby arm whose relations hold exactly, and the
// check's repair carries each candidate to the real arm's solution beside it. That fails
// near the family's singular sets: where the real arm's Jacobian has σmin ≈ β (β the
// distance to the set, rad), its solutions lie up to about slack / β from the nearby
// arm's (slack: lines::near_degenerate_slack, m), beyond the repair's reach once β is
// below about √slack, and the nearby arm's continuum (the aligned wrist of a UR type) is
// broken into the real arm's isolated solutions anywhere along it. Measured on
// three-parallel arms with α2 = 5e-10 and q5 within 1e-12..1e-2 rad of the aligned wrist
// (640 poses, 40 arms): the family's candidates alone, repaired, missed a solution of a
// 200-start numeric search at 302 poses and the generating configuration at 405. The
// general 6R's elimination knows the real arm (it reads no relation as exact), so its
// candidates are the real arm's solutions to the eigenproblem's accuracy, which the
// repair takes to round-off; the family's stay for poses where the eigenproblem is
// ill-conditioned (roots merging, β about 1e-6). One check judges both sets: a solution
// both give is kept once, in the family's slot (its branch label).
//
// Where the general 6R runs. Its solve and check cost about ten times the family's (60 µs
// a target against 6 on an idle core, the near UR5), and its builder 13 ms once, so it
// runs only where the family's candidates cannot be enough, which the family can tell.
// FK of the two arms differs by at most about ε = slack / size (relative) at any q. A
// solution q* of the real arm therefore meets the family's equations in (q1, q5) (which
// hold no other joint) to within ε, and the family finds a pair (q1, q5) within ε / c
// of q*'s, c the pair system's conditioning (or calls the target near: a root missed by
// less than NEAR_TOL). Given the pair, q6 moves by ε / τ (τ the sine of the wrist's tilt
// from aligned) and the elbows by ε / (τ sγ) (sγ: the elbow's sine from stretched or
// folded). The real arm's σmin at q* is of the order of the smallest of c, τ, sγ, and
// Newton on the real arm from the family's candidate (the repair) reaches q* while that
// distance, about ε / σmin, is below its basin's radius, about σmin: while σmin is above
// about √ε. Each of c, τ, sγ the family reads off its own pairs and elbows
// (ParallelParams::solve's margin: the tilt at every pair found, whether or not its
// triangle then closes, and half the distance of two pairs, or of elbow up and down,
// which merge where c or sγ vanish). So at a target where that margin is WATCH_FACTOR √ε
// or more (and the family calls it neither near nor singular) every real solution lies
// beside one of the family's candidates, and the general 6R is not run. Elsewhere its
// candidates join: the margin below that, or near, or singular (the family's continuum
// is the real arm's broken into isolated solutions anywhere along it), or nothing found
// without a gap beyond NEAR_GAP. WATCH_FACTOR stands for the constants of order 1 above,
// with room: benchmarks/ik_parallel_near.py counts the solutions lost near the aligned
// wrist with the watch at 0, 1, 10 and WATCH_FACTOR times √ε, and at every target.
//
// What each says of the target is joined: a gap either proves (the check weighs it against
// the slack), near where either is near, singular and the free joints where either finds
// a continuum (the family's is the nearby arm's: within the tolerances, a continuum of the
// real arm too).
#pragma once

#include <cmath>

#include "../ik_types.hpp"
#include "../types.hpp"
#include "general_6r.hpp"
#include "parallel.hpp"  // the family joined so far: three-parallel (UR type)

namespace km {

//! A family that finds no candidate proves the target out of reach of the real arm only
//! with a gap beyond this fraction of the arm's size (its own NEAR_TOL: what it calls a
//! near miss); closer, the general 6R's candidates are tried.
constexpr double NEAR_GAP = 1e-6;
//! The general 6R runs where the family's candidates lie within WATCH_FACTOR √(slack /
//! size) rad of its singular sets (Near6RParams::watch; the header says why).
constexpr double WATCH_FACTOR = 100.0;

//! A near-degenerate 6R arm: its family's Params and the general 6R's, for one check.
//!
//! Family's solve(T, Q, info, margin) also says how close to its singular sets the
//! target's candidates lie (rad).
template <class Family>
struct Near6RParams {
    Family family;                      //!< the family's closed form (the nearby exact arm)
    general6r::General6RParams general; //!< the general 6R's (this arm)
    //! The general 6R runs where the family's candidates lie within this of its singular
    //! sets (rad: WATCH_FACTOR √(slack / size)), or the family says near or singular or
    //! finds nothing without a gap beyond NEAR_GAP of the size; +inf: everywhere.
    double watch = INF;

    int slots() const { return family.slots() + general.slots(); }
    int dof() const { return 6; }
    //! Why these fields cannot be solved with (nullptr when they can): the general 6R's.
    const char* invalid() const { return general.invalid(); }

    //! Candidates of one target T (base frame): the family's slots, then the general 6R's
    //! (NaN rows where the family's candidates are far from its singular sets).
    void solve(const Pose& T, double* Q, SolverInfo& info) const {
        SolverInfo a = info, b = info;
        double margin = INF;
        family.solve(T, Q, a, margin);
        double* rest = Q + 6 * family.slots();
        bool any = false;
        for (int i = 0; i < family.slots(); ++i) any = any || !std::isnan(Q[6 * i]);
        const bool proven = !any && a.gap > NEAR_GAP * family.scale;
        if (!(a.near || a.singular || margin < watch || (!any && !proven))) {
            for (int i = 0; i < 6 * general.slots(); ++i) rest[i] = NaN;
            info = a;
            return;
        }
        general.solve(T, rest, b);
        // a gap either proves: the larger (NaN where unknown)
        info.gap = std::isnan(a.gap) ? b.gap : (b.gap > a.gap ? b.gap : a.gap);
        info.near = a.near || b.near;
        info.singular = a.singular || b.singular;
        info.free = a.free | b.free;
    }
};

}  // namespace km
