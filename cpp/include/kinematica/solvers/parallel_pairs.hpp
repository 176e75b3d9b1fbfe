// Three-parallel 6R arms (UR type), first half: the pairs (q1, q5) of one target.
//
// Written as a product of exponentials G = T·M⁻¹ = E1(q1)···E6(q6) (M the tool pose at
// q = 0, Ei the rotation by qi about joint i's axis, unit hi through pi at q = 0), with k
// the direction of axes 2, 3, 4: E2 E3 E4 is a planar motion about k (it keeps heights
// along k), E6 fixes p6 and E5 fixes p5. So, with k1 = R1 k (axis 2 now):
//
//     (1)  k1 · R_G h6        = k · R5 h6                            (orientation)
//     (2)  k1 · (G(p6) - p1)  = k · (p5 - p1) + k · R5 (p6 - p5)     (height)
//
// both a cos q1 + b sin q1 + c = D cos q5 + E sin q5 + F. With p5, p6 the feet of the
// common normal of axes 5 and 6, [[D1, E1], [D2, E2]] is singular exactly when the axes
// meet (row 2 is zero: UR type, ParallelMode::meet) or are parallel (row 1 is zero,
// ParallelMode::parallel): then one equation holds q1 alone and the other gives q5 (two
// and two). Otherwise (ParallelMode::general) (cos q5, sin q5) = P (cos q1, sin q1, 1)
// and |P x|² = 1 is a quartic in tan((q1 - φ0) / 2) (IK-Geo's subproblem 6), whose roots
// are polished by Newton steps on (1) and (2) (parallel_quartic.hpp).
//
// Near the aligned wrist (axis 6 parallel to k) both sides of (1) sit at an extremum
// and 1 - k·u for unit u loses every digit to cancellation; it is formed as
// |k × u|² / (1 + k·u) instead, which keeps q5 accurate to round-off however close to
// alignment the target is.
#pragma once

#include <cmath>

#include "../geometry.hpp"
#include "parallel_params.hpp"
#include "parallel_quartic.hpp"

namespace km {
namespace parallel {

//! What wrist() found.
enum class WristRoots : int { none = -1, near = 0, two = 1 };

//! q5 from (1) when axes 5 and 6 meet: k·R5 h6 = d, m2 = |k1 × R_G h6|².
//!
//! q5 = φ ± δ with cos δ = (d - F1) / ρ; 1 ∓ cos δ is formed from 1 ∓ d
//! (= m2 / (1 ± d)) and the exact constants wlo, whi. Writes q5, cos q5, sin q5 of
//! "no-flip" φ + δ into pair[0] and of "flip" φ - δ into pair[1] (none: no root, both
//! unchanged; near: a double root, or missed by less than NEAR_TOL: the double root
//! twice, the branches merging there).
KM_HD inline WristRoots wrist(const ParallelParams& P, double d, double m2, Pair* pair) {
    const double D1 = P.D1, E1 = P.E1;
    const double rho = std::sqrt(D1 * D1 + E1 * E1);  // lengths of the arm: no overflow (nor below)
    const double omd = d > 0.0 ? m2 / (1.0 + d) : 1.0 - d;
    const double opd = d < 0.0 ? m2 / (1.0 - d) : 1.0 + d;
    double lo = (omd - P.wlo) / rho;  // 1 - cos δ
    double hi = (opd - P.whi) / rho;  // 1 + cos δ
    WristRoots code = WristRoots::two;
    const double worst = smaller(lo, hi) * rho;
    if (worst < 0.0) {  // a double root, or missed: the two q5 merge (near)
        if (worst < -NEAR_TOL) return WristRoots::none;
        code = WristRoots::near;
    }
    lo = larger(lo, 0.0);
    hi = larger(hi, 0.0);
    const double cd = 0.5 * (hi - lo);
    const double sd = std::sqrt(lo * hi);
    const double norm = std::sqrt(cd * cd + sd * sd);  // both within [0, 2]
    const double cf = D1 / (rho * norm);
    const double sf = E1 / (rho * norm);
    for (int i = 0; i < 2; ++i) {
        const double sd_i = i == 0 ? sd : -sd;
        const double c5 = cf * cd - sf * sd_i;
        const double s5 = sf * cd + cf * sd_i;
        pair[i].q5 = std::atan2(s5, c5);
        pair[i].c5 = c5;
        pair[i].s5 = s5;
    }
    return code;
}

//! The two θ of a cos θ + b sin θ = c into out[2]: the rising root, then the falling.
//!
//! A double root within DOUBLE_ROOT_TOL is one angle, twice, and a root missed by less
//! than NEAR_TOL (of size) the least-squares angle twice: both mark the target near.
//! False when there is no root (out then holds trig_linear's angles).
KM_HD inline bool roots(double a, double b, double c, double size, double* out,
                        SolverInfo& info) {
    const double r2 = a * a + b * b;
    if (trig_linear(a, b, c, out) != TrigRoots::two) {
        if (std::fabs(c) - std::sqrt(r2) > NEAR_TOL * size) return false;
        info.near = true;
    } else if (r2 - c * c <= DOUBLE_ROOT_TOL * r2) {  // two branches merge: near
        out[0] = std::atan2(b * c, a * c);
        out[1] = out[0];
        info.near = true;
    } else {
        const double rise = out[1];  // a cos + b sin = r cos(θ - φ): rising at φ - δ
        out[1] = out[0];
        out[0] = rise;
    }
    return true;
}

//! The q1 of a cos q1 + b sin q1 = rhs (size: the equation's scale), into out[2].
//!
//! root: out holds the root where the left side rises, then the one where it falls (see
//! roots()); free_q1: every q1 solves, out holds rep, then NaN; none.
KM_HD inline PairKind first(double a, double b, double rhs, double size, double rep,
                            double* out, SolverInfo& info) {
    if (std::sqrt(a * a + b * b) <= CONTINUUM_TOL * size) {  // bounded by the reach check
        if (std::fabs(rhs) <= CONTINUUM_TOL * size) {
            out[0] = rep;
            out[1] = NaN;
            return PairKind::free_q1;
        }
        return PairKind::none;
    }
    return roots(a, b, rhs, size, out, info) ? PairKind::root : PairKind::none;
}

//! Axes 5 and 6 meet: q1 from (2) (shoulder right, left), q5 from (1) (no-flip, flip);
//! rep is the q1 given where q1 is free.
KM_HD inline void pairs_meet(const ParallelParams& P, const Vec3& x6, const Sides& L2,
                             double rep, Pairs& pairs, SolverInfo& info) {
    const double size = P.scale;
    double q1s[2];
    const PairKind kind = first(L2.a, L2.b, P.F2 - L2.c, size, rep, q1s, info);
    if (kind == PairKind::none) return;
    pairs.free_q1 = kind == PairKind::free_q1;
    for (int i = 0; i < 2; ++i) {
        const double q1 = q1s[i];
        if (std::isnan(q1)) continue;
        double s1, c1;
        sincos(q1, s1, c1);
        const Vec3 k1 = axis2_now(P, c1, s1);
        const WristRoots code = wrist(P, dot(k1, x6), cross2(k1, x6), pairs.pair + 2 * i);
        if (code == WristRoots::none) continue;
        if (code == WristRoots::near) info.near = true;
        for (int m = 2 * i; m < 2 * i + 2; ++m) {
            pairs.pair[m].q1 = q1;
            pairs.pair[m].c1 = c1;
            pairs.pair[m].s1 = s1;
            pairs.kind[m] = kind;
        }
    }
}

//! Axes 5 and 6 parallel: q1 from (1), then q5 from (2); rep is the q1 given where q1
//! is free.
KM_HD inline void pairs_parallel(const ParallelParams& P, const Sides& L1, const Sides& L2,
                                 double rep, Pairs& pairs, SolverInfo& info) {
    double q1s[2];
    double q5s[2];
    const PairKind kind = first(L1.a, L1.b, P.F1 - L1.c, 1.0, rep, q1s, info);
    if (kind == PairKind::none) return;
    pairs.free_q1 = kind == PairKind::free_q1;
    const double D2 = P.D2, E2 = P.E2;
    const double size = P.scale;
    for (int i = 0; i < 2; ++i) {
        const double q1 = q1s[i];
        if (std::isnan(q1)) continue;
        double s1, c1;
        sincos(q1, s1, c1);
        const double lhs = L2.a * c1 + L2.b * s1 + L2.c - P.F2;
        if (!roots(D2, E2, lhs, size, q5s, info)) continue;
        for (int j = 0; j < 2; ++j) {
            store_pair(pairs.pair[2 * i + j], q1, q5s[j]);
            pairs.kind[2 * i + j] = kind;
        }
    }
}

//! Order the pairs by q1 (found ones first): the "root j" labels.
KM_HD inline void sort_pairs(Pairs& pairs) {
    for (int i = 1; i < 4; ++i) {
        int j = i;
        while (j > 0 && pairs.kind[j] != PairKind::none &&
               (pairs.kind[j - 1] == PairKind::none ||
                pairs.pair[j].q1 < pairs.pair[j - 1].q1)) {
            const Pair tmp = pairs.pair[j];
            pairs.pair[j] = pairs.pair[j - 1];
            pairs.pair[j - 1] = tmp;
            const PairKind kk = pairs.kind[j];
            pairs.kind[j] = pairs.kind[j - 1];
            pairs.kind[j - 1] = kk;
            j -= 1;
        }
    }
}

//! Every (q1, q5) of a target, by the arm's mode.
//!
//! x6 = R_G h6 (axis 6's direction in the target), w6 = G(p6) - p1, rep the q1 given
//! where q1 is free. The pairs: q1, q5, their cosines and sines (ParallelMode::meet: pair
//! 2 shoulder + wrist; otherwise by increasing q1), and each one's kind; info.near is set
//! here.
KM_HD inline void find_pairs(const ParallelParams& P, const Vec3& x6, const Vec3& w6,
                             double rep, Pairs& pairs, SolverInfo& info) {
    // a, b, c of (1) and (2): k1·y = a cos q1 + b sin q1 + c
    const Sides L1{dot(P.kperp, x6), dot(P.hk, x6), dot(P.kpar, x6)};
    const Sides L2{dot(P.kperp, w6), dot(P.hk, w6), dot(P.kpar, w6)};
    for (int i = 0; i < 4; ++i) pairs.kind[i] = PairKind::none;
    pairs.free_q1 = false;
    if (P.mode == ParallelMode::meet) {
        pairs_meet(P, x6, L2, rep, pairs, info);
        return;
    }
    if (P.mode == ParallelMode::parallel) {
        pairs_parallel(P, L1, L2, rep, pairs, info);
    } else {
        pairs_general(P, x6, L1, L2, rep, pairs, info);
    }
    sort_pairs(pairs);
}

}  // namespace parallel
}  // namespace km
