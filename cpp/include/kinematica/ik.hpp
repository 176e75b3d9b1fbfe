// Solving one target: a solver's candidates, then the shared check.
//
// A solver is any type with
//     using Work = ...;                           // its scratch, made once per thread
//     Work work(int n) const;
//     int slots() const;                          // candidate slots m
//     int dof() const;                            // the joints n of the chains it solves
//     void solve(const ChainView&, const Pose& T, const double* q0, double* Q, SolverInfo&,
//                Work&) const;
// filling Q (m x n, row-major; NaN rows: no real solution on that branch). A closed form
// (solve(T, Q, info) only) is adapted by ClosedForm<Params>.
#pragma once

#include <vector>

#include "check.hpp"
#include "ik_types.hpp"

namespace km {

//! Scratch of a closed form: none.
struct NoWork {};

//! A closed-form solver's Params (solve(T, Q, info), slots()) as a solver.
template <class Params>
struct ClosedForm {
    const Params& params;
    using Work = NoWork;
    Work work(int) const { return {}; }
    int slots() const { return params.slots(); }
    int dof() const { return params.dof(); }
    KM_HD void solve(const ChainView&, const Pose& T, const double*, double* Q, SolverInfo& info,
                     Work&) const {
        params.solve(T, Q, info);
    }
};

//! Scratch of solving targets with one solver on one chain: made once per thread.
template <class Solver>
struct IKWork {
    typename Solver::Work solver;
    CheckWork check;
    std::vector<double> Q;
    IKWork(const Solver& s, int n)
        : solver(s.work(n)), check(s.slots(), n), Q(static_cast<size_t>(s.slots() * n)) {}
};

//! Every solution of one target T (base frame): candidates, then the check.
//!
//! Inlined, with the check and the solver where that is inlined too (the numeric search
//! is), into its caller: a batch loop compiled for AVX-512 and AVX2 (the binding's target
//! clones) then runs the check's trigonometry of all candidates as SIMD; a call kept out
//! of line is compiled for the baseline x86-64 only, and the check took twice as long
//! (PUMA 560: 1.3 µs a target instead of 0.6).
template <class Solver>
KM_INLINE CheckReport solve_ik(const Solver& solver, const ChainView& ch, const Pose& T,
                               const CheckOptions& opts, const double* q0,
                               IKWork<Solver>& work, const CheckOut& out) {
    SolverInfo info;
    solver.solve(ch, T, q0, work.Q.data(), info, work.solver);
    return check(ch, T, work.Q.data(), solver.slots(), info, opts, q0, work.check, out);
}

}  // namespace km
