// The numeric solver as an IK solver: one candidate per target, from the LM search.
#pragma once

#include <vector>

#include "ik_types.hpp"
#include "lm.hpp"

namespace km {

//! Levenberg-Marquardt over a chain, set up once per arm and settings.
struct NumericSolver {
    int n = 0;
    std::vector<JointBound> bounds;  //!< (n)
    LMSettings settings{};
    double weights[6] = {1.0, 1.0, 1.0, 1.0, 1.0, 1.0};
    std::vector<double> samples;     //!< (R x n) restart configurations, used in order
    std::vector<double> middle;      //!< (n) the first guess when no q0 is given
    //! The first guess was searched alone already (and did not settle the target): the
    //! attempts start at the first restart, and the first guess is not searched again.
    bool skip_first = false;

    using Work = LMWork;
    Work work(int n) const { return LMWork(n); }
    int slots() const { return 1; }
    int dof() const { return n; }
    int restarts() const { return n > 0 ? static_cast<int>(samples.size()) / n : 0; }

    //! The search's one candidate into Q (1 x n); info.gap when proven out of reach.
    //! (Inlined into each instruction-set copy of its caller, as the search is.)
    KM_INLINE void solve(const ChainView& chain, const Pose& T, const double* q0, double* Q,
                         SolverInfo& info, Work& w) const {
        const int R = restarts();
        const bool skip = skip_first && R > 0;
        const double* start = skip ? samples.data() : (q0 != nullptr ? q0 : middle.data());
        const LMStats st = lm_solve(chain, bounds.data(), weights, settings, T, start,
                                    samples.data() + (skip ? n : 0), skip ? R - 1 : R, Q, w);
        info.gap = st.gap;
    }
};

}  // namespace km
