// Three-parallel 6R arms whose axes 5 and 6 are apart: the pairs (q1, q5) of a quartic.
//
// With (cos q5, sin q5) = P (cos q1, sin q1, 1) (equations (1) and (2) of
// parallel_pairs.hpp, solved for the wrist's side), |P x|² = 1 is a quartic in
// t = tan((q1 - φ0) / 2) (IK-Geo's subproblem 6), with φ0 putting t = ∞ where
// |P x|² - 1 is largest (a leading coefficient far from 0). Each root is polished by
// Newton steps on (1) and (2) themselves.
//
// Near the aligned wrist (axis 6 along k) both sides of (1) sit at an extremum and two
// roots merge: 1 - k·u for unit u loses every digit to cancellation, so (1) is
// evaluated as |k × u|² / (1 + k·u) instead, which resolves the two roots however close
// they are; two seeds that polish to one root send the second across their midpoint
// (the sum of a near-double root is well conditioned).
#pragma once

#include <cmath>

#include "../check.hpp"
#include "../geometry.hpp"
#include "../polynomial.hpp"
#include "../so3.hpp"
#include "parallel_params.hpp"

namespace km {
namespace parallel {

//! Newton steps at most polishing a quartic root on equations (1) and (2): quadratic
//! convergence takes 2-3, but at a double root (the wrist aligned) it is linear, halving
//! the error per step from the quartic's ~1e-8.
constexpr int NEWTON_STEPS = 50;
//! A Newton step of at most this (|Δq1| + |Δq5|, rad) is the last: the error it leaves
//! is about its square while convergence is quadratic, about its size while it is linear
//! (merging roots), both far below the 1e-10 the check asks. Without it each root took
//! one more step, to find that steps had stopped shrinking (two sine-cosine pairs per
//! root).
constexpr double NEWTON_QUIET = 1e-14;

//! cos and sin of m π/4, m = 0..7, as the C library rounds them (cos π/2 = 6.1e-17):
//! where |P x|² - 1 is sampled.
constexpr double SAMPLES[8][2] = {
    {0x1.0000000000000p+0, 0.0},
    {0x1.6a09e667f3bcdp-1, 0x1.6a09e667f3bccp-1},
    {0x1.1a62633145c07p-54, 0x1.0000000000000p+0},
    {-0x1.6a09e667f3bccp-1, 0x1.6a09e667f3bcdp-1},
    {-0x1.0000000000000p+0, 0x1.1a62633145c07p-53},
    {-0x1.6a09e667f3bcep-1, -0x1.6a09e667f3bccp-1},
    {-0x1.a79394c9e8a0ap-53, -0x1.0000000000000p+0},
    {0x1.6a09e667f3bcbp-1, -0x1.6a09e667f3bcep-1},
};

//! d - e for d = k·u, e = k·v (unit u, v), m2 = |k × u|², n2 = |k × v|².
//!
//! 1 ∓ d = m2 / (1 ± d): exact however close u and v are to ±k.
KM_HD inline double unit_gap(double d, double m2, double e, double n2) {
    if (d + e >= 0.0) return n2 / (1.0 + e) - m2 / (1.0 + d);
    return m2 / (1.0 - d) - n2 / (1.0 - e);
}

//! Where Newton steps on (1) and (2) end.
struct NewtonEnd {
    double q1, q5;     //!< the last q1, q5
    double res;        //!< |f1| + |f2| / scale where the last step was computed
    int evaluations;   //!< how many times (1) and (2) were evaluated
    double c1, s1, c5, s5;  //!< cos q1, sin q1, cos q5, sin q5 at (q1, q5)
};

//! Newton steps on (1) and (2) from (q1, q5).
//!
//! Steps stop after one of at most NEWTON_QUIET, or when they no longer shrink
//! (round-off reached, or no root nearby); stopped so, they end at the point of least
//! residual they evaluated: at a double root (a fold of (1) and (2), where the Jacobian
//! of the pair loses rank) a seed that round-off put where the pair has no real root
//! takes a first step of any length, and the point it leaps to is no root (a target made
//! by FK was called unreachable: issue 34 item 2), while the seed met (1) and (2) to
//! round-off. (1) is evaluated as unit_gap: its error stays
//! at round-off of its (small) terms near the aligned wrist, where two roots merge, so
//! the roots are resolved however close they are. After a step of at most NEWTON_QUIET
//! the last cosines and sines are turned by it to first order: exact (d² < 1e-28), and
//! no sine-cosine pairs to evaluate again.
KM_HD inline NewtonEnd newton(const ParallelParams& P, const Vec3& x6, const Sides& L1,
                              const Sides& L2, double q1, double q5) {
    const double D1 = P.D1, E1 = P.E1, D2 = P.D2, E2 = P.E2;
    const double size = P.scale;
    const Vec3& h6par = P.h6par;
    const Vec3& h6perp = P.h6perp;
    const Vec3& h5xh6 = P.h5xh6;
    const Vec3& k = P.k;
    double res = INF;
    double last = INF;
    int evaluations = 0;
    bool moved = false;
    bool quiet = false;  // ended by a step of at most NEWTON_QUIET
    double c1 = NaN, s1 = NaN, c5 = NaN, s5 = NaN;
    NewtonEnd best{q1, q5, INF, 0, NaN, NaN, NaN, NaN};  // the least residual evaluated
    for (int step_index = 0; step_index < NEWTON_STEPS; ++step_index) {
        evaluations += 1;
        sincos(q1, s1, c1);
        sincos(q5, s5, c5);
        moved = false;
        const Vec3 k1 = axis2_now(P, c1, s1);
        const Vec3 r{h6par.x + c5 * h6perp.x + s5 * h5xh6.x,  // R5 h6
                     h6par.y + c5 * h6perp.y + s5 * h5xh6.y,
                     h6par.z + c5 * h6perp.z + s5 * h5xh6.z};
        const double f1 = unit_gap(dot(k1, x6), cross2(k1, x6), dot(k, r), cross2(k, r));
        const double f2 = L2.a * c1 + L2.b * s1 + L2.c - (D2 * c5 + E2 * s5 + P.F2);
        res = std::fabs(f1) + std::fabs(f2) / size;
        if (res < best.res) best = {q1, q5, res, 0, c1, s1, c5, s5};
        const double j11 = L1.b * c1 - L1.a * s1;
        const double j12 = D1 * s5 - E1 * c5;
        const double j21 = L2.b * c1 - L2.a * s1;
        const double j22 = D2 * s5 - E2 * c5;
        const double det = j11 * j22 - j12 * j21;
        if (det == 0.0 || !std::isfinite(det)) break;
        const double d1 = (f1 * j22 - f2 * j12) / det;
        const double d5 = (j11 * f2 - j21 * f1) / det;
        const double step = std::fabs(d1) + std::fabs(d5);
        if (!(step < last)) break;  // no longer contracting: round-off (or no root here)
        last = step;
        q1 -= d1;
        q5 -= d5;
        moved = true;
        if (step <= NEWTON_QUIET) {
            const double c1n = c1 + s1 * d1, s1n = s1 - c1 * d1;
            const double c5n = c5 + s5 * d5, s5n = s5 - c5 * d5;
            c1 = c1n;
            s1 = s1n;
            c5 = c5n;
            s5 = s5n;
            moved = false;
            quiet = true;
            break;
        }
    }
    if (quiet) return {q1, q5, res, evaluations, c1, s1, c5, s5};
    if (moved) {  // NEWTON_STEPS used up, every step contracting: where the last one led
        sincos(q1, s1, c1);
        sincos(q5, s5, c5);
        return {q1, q5, res, evaluations, c1, s1, c5, s5};
    }
    best.evaluations = evaluations;
    return best;
}

//! Newton from the seed of pair m into pair m and its kind.
//!
//! A root meets (1) and (2) to TRIG_TOL; one that meets them to NEAR_TOL only is
//! proposed too, and the target marked near.
KM_HD inline void polish(const ParallelParams& P, const Vec3& x6, const Sides& L1,
                         const Sides& L2, Pairs& pairs, int m, SolverInfo& info) {
    Pair& pair = pairs.pair[m];
    const NewtonEnd end = newton(P, x6, L1, L2, pair.seed1, pair.seed5);
    pairs.kind[m] = PairKind::none;
    if (end.res <= NEAR_TOL) {
        pairs.kind[m] = PairKind::root;
        if (end.res > TRIG_TOL) info.near = true;
    }
    pair.q1 = wrap(end.q1);
    pair.q5 = wrap(end.q5);
    pair.c1 = end.c1;
    pair.s1 = end.s1;
    pair.c5 = end.c5;
    pair.s5 = end.s5;
}

//! Axes 5 and 6 apart: the quartic of subproblem 6, its roots polished by Newton.
//!
//! (1) and (2) read k1·y = a cos q1 + b sin q1 + c with L1, L2 = (a, b, c); rep is the q1
//! given where every q1 solves.
KM_HD inline void pairs_general(const ParallelParams& P, const Vec3& x6, const Sides& L1,
                                const Sides& L2, double rep, Pairs& pairs, SolverInfo& info) {
    const double m0 = P.minv[0], m1 = P.minv[1], m2 = P.minv[2], m3 = P.minv[3];
    const double P00 = m0 * L1.a + m1 * L2.a;
    const double P01 = m0 * L1.b + m1 * L2.b;
    const double P02 = m0 * L1.c + m1 * L2.c - (m0 * P.F1 + m1 * P.F2);
    const double P10 = m2 * L1.a + m3 * L2.a;
    const double P11 = m2 * L1.b + m3 * L2.b;
    const double P12 = m2 * L1.c + m3 * L2.c - (m2 * P.F1 + m3 * P.F2);
    // φ0 puts t = ∞ where |P x|² - 1 is largest: the leading coefficient is then large.
    double worst = -1.0;
    double far = 0.0;
    const double size =
        1.0 + P00 * P00 + P01 * P01 + P02 * P02 + P10 * P10 + P11 * P11 + P12 * P12;
    for (int m = 0; m < 8; ++m) {
        const double u = P00 * SAMPLES[m][0] + P01 * SAMPLES[m][1] + P02;
        const double v = P10 * SAMPLES[m][0] + P11 * SAMPLES[m][1] + P12;
        const double f = std::fabs(u * u + v * v - 1.0);
        if (f > worst) {
            worst = f;
            far = 0.25 * PI * m;
        }
    }
    if (worst <= CONTINUUM_TOL * size) {  // every q1 solves, each with one q5
        const double q1 = rep;
        const double u = P00 * std::cos(q1) + P01 * std::sin(q1) + P02;
        const double v = P10 * std::cos(q1) + P11 * std::sin(q1) + P12;
        store_pair(pairs.pair[0], q1, std::atan2(v, u));
        pairs.kind[0] = PairKind::free_q1;
        pairs.free_q1 = true;
        return;
    }
    const double phi0 = far - PI;
    double sp, cp;
    sincos(phi0, sp, cp);
    // rows i = 0, 1 of P x at q1 = φ0 + 2 atan t, times (1 + t²): u0 + u1 t + u2 t²
    const double a0 = P00 * cp + P01 * sp;
    const double b0 = P10 * cp + P11 * sp;
    const double u00 = a0 + P02, u01 = b0 + P12;
    const double u10 = 2.0 * (P01 * cp - P00 * sp), u11 = 2.0 * (P11 * cp - P10 * sp);
    const double u20 = P02 - a0, u21 = P12 - b0;
    const double coef[5] = {
        u20 * u20 + u21 * u21 - 1.0,
        2.0 * (u10 * u20 + u11 * u21),
        u10 * u10 + u11 * u11 + 2.0 * (u00 * u20 + u01 * u21) - 2.0,
        2.0 * (u00 * u10 + u01 * u11),
        u00 * u00 + u01 * u01 - 1.0,
    };
    Complex roots[4];
    quartic_roots(coef, roots);
    const double root_imag = std::sqrt(NEAR_TOL);
    for (int m = 0; m < 4; ++m) {
        const double re = roots[m].real(), im = roots[m].imag();
        const double modulus = std::sqrt(re * re + im * im);  // roots are O(1): no overflow
        if (!(std::fabs(im) <= root_imag * (1.0 + modulus))) continue;
        // a merging pair a ± bi: start from a + b and a - b, on either side
        const double q1 = phi0 + 2.0 * std::atan(re + im);
        double s1, c1;
        sincos(q1, s1, c1);
        pairs.pair[m].seed1 = q1;
        pairs.pair[m].seed5 = std::atan2(P10 * c1 + P11 * s1 + P12, P00 * c1 + P01 * s1 + P02);
        polish(P, x6, L1, L2, pairs, m, info);
    }
    // Two seeds of a merging pair may polish to one root; the other then lies across
    // their midpoint (the sum of a near-double root is well conditioned).
    for (int j = 0; j < 4; ++j) {
        for (int i = 0; i < j; ++i) {
            if (pairs.kind[i] == PairKind::none || pairs.kind[j] == PairKind::none) continue;
            const Pair& a = pairs.pair[i];
            Pair& b = pairs.pair[j];
            if (larger(std::fabs(wrap(a.q1 - b.q1)), std::fabs(wrap(a.q5 - b.q5))) >= DEDUP_TOL) {
                continue;
            }
            b.seed1 = a.q1 + wrap(a.seed1 - a.q1) + wrap(b.seed1 - a.q1);
            b.seed5 = a.q5 + wrap(a.seed5 - a.q5) + wrap(b.seed5 - a.q5);
            polish(P, x6, L1, L2, pairs, j, info);
        }
    }
    // Two pairs still one root: a merging pair's other root is lost to round-off (at a
    // double root Newton's first step may go anywhere, onto another root): the pair
    // system is at a fold there, and the target is near (issue 34: an "ok" without the
    // flag lacked the configuration that made the target).
    for (int j = 0; j < 4; ++j) {
        for (int i = 0; i < j; ++i) {
            if (pairs.kind[i] == PairKind::none || pairs.kind[j] == PairKind::none) continue;
            const Pair& a = pairs.pair[i];
            const Pair& b = pairs.pair[j];
            if (larger(std::fabs(wrap(a.q1 - b.q1)), std::fabs(wrap(a.q5 - b.q5))) < DEDUP_TOL) {
                info.near = true;
            }
        }
    }
}

}  // namespace parallel
}  // namespace km
