// Arms the C++ tests build from DH rows (standard convention, m and rad), the IK round
// trip they share (FK of a configuration, every solution of that pose checked by FK, the
// configuration found among them), and a small deterministic generator.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "check.hpp"
#include "kinematica/chain.hpp"
#include "kinematica/ik.hpp"

namespace kmtest {

//! A revolute arm of n joints from standard DH rows (theta offsets 0, no limits).
inline km::Chain revolute_arm(int n, const double* d, const double* a, const double* alpha) {
    const size_t size = static_cast<size_t>(n);
    std::vector<double> theta(size, 0.0), lo(size, -INFINITY), hi(size, INFINITY);
    bool prismatic[16] = {};
    return km::Chain::from_dh(n, prismatic, theta.data(), d, a, alpha, lo.data(), hi.data(), false,
                              km::Pose{}, km::Pose{});
}

//! Uniform in [-π, π) from a 64-bit linear congruential generator (the same numbers on
//! every machine).
struct Uniform {
    std::uint64_t state;
    double operator()() {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        return (static_cast<double>(state >> 11) * 0x1.0p-53 - 0.5) * 2.0 * M_PI;
    }
};

//! The pose of q (the chain's FK).
inline km::Pose pose_of(const km::Chain& chain, const double* q) {
    double c[16], s[16];
    return km::fk(chain.view(), q, c, s);
}

//! Solves FK(q) with `solver` (slots m) through the shared check; returns how many
//! solutions came, after checking each reaches the pose (FK_TOL) and q is among them.
//! (find_q false: an arm solved at a parameter q need not have, e.g. the SRS arm angle.)
template <class Solver>
int round_trip(const char* name, const Solver& solver, const km::Chain& chain, const double* q,
               bool find_q = true) {
    constexpr double FK_TOL = 1e-9, FOUND_TOL = 1e-7;
    const km::ChainView ch = chain.view();
    const int n = ch.n, m = solver.slots();
    const km::Pose T = pose_of(chain, q);
    km::IKWork<Solver> work(solver, n);
    km::CheckOptions options;
    options.complete = true;
    std::vector<double> Q(static_cast<size_t>(m * n)), res(static_cast<size_t>(2 * m));
    std::vector<int> slot(static_cast<size_t>(m));
    const km::CheckReport r =
        km::solve_ik(solver, ch, T, options, nullptr, work, km::CheckOut{Q.data(), slot.data(), res.data()});
    CHECK(r.count > 0, "%s: no solution of FK(q)", name);
    double nearest = INFINITY;
    for (int k = 0; k < r.count; ++k) {
        const km::Pose S = pose_of(chain, &Q[static_cast<size_t>(k * n)]);
        double miss = 0.0, dq = 0.0;
        for (int i = 0; i < 3; ++i) {
            miss = std::fmax(miss, std::fabs(S.p[i] - T.p[i]));
            miss = std::fmax(miss, std::fabs(S.x[i] - T.x[i]) + std::fabs(S.y[i] - T.y[i]) + std::fabs(S.z[i] - T.z[i]));
        }
        CHECK(miss <= FK_TOL, "%s: solution %d misses the pose by %.3g", name, k, miss);
        for (int j = 0; j < n; ++j) dq = std::fmax(dq, angle_distance(Q[static_cast<size_t>(k * n + j)], q[j]));
        nearest = std::fmin(nearest, dq);
    }
    CHECK(!find_q || nearest <= FOUND_TOL, "%s: the generating q is %.3g rad from every solution", name, nearest);
    return r.count;
}

}  // namespace kmtest
