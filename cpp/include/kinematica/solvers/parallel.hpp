// Three-parallel 6R arms (UR type), second half: every solution of one target.
//
// For each pair (q1, q5) of parallel_pairs.hpp:
//
// * q6 by subproblem 1: R(h6, -q6) R5ᵀ k = R_Gᵀ k1 (R1ᵀ R_G = R234 R5 R6 and R234
//   keeps k);
// * θ234, the angle of R234 = R1ᵀ R_G R6ᵀ R5ᵀ about k;
// * H = E1⁻¹ G E6⁻¹ E5⁻¹ = E2 E3 E4 takes axis 4 (p4) where the planar triangle
//   axis 2 -> axis 3 -> axis 4 must put it: q2 and q3 (two elbows), then
//   q4 = σ4 (θ234 - q2 - σ3 q3).
//
// Up to 8 solutions. Singular sets, all continua of solutions (info marks them and
// names the free joints; the candidates are representatives; a wrist within
// NEAR_ALIGNED_TOL of aligned is marked near):
//
// * the wrist aligned, axis 6 along k (sine below CONTINUUM_TOL): q6 turns with q2, q3,
//   q4 (axes 2, 3, 4, 6 all parallel). The representative q6 puts axis 4 at mid-reach
//   of the triangle;
// * axis 4 on axis 2 with equal links (the folded elbow): q2 turns with q4;
// * an equation independent of q1 (axes 5 and 6 meeting: (2), the wrist point on axis 1
//   and no shoulder offset; parallel: (1), axis 6 parallel to axis 1; apart: both
//   together, axis 6 along axis 1 through it, and the offsets such that q5 can meet
//   both): q1 turns, the other joints following it over an arc of q1 (where q5 has a
//   root and the triangle closes), a pair's continuum in one or more arcs of q1. Each arc
//   of each pair is represented (free_q1_arcs: at q1rep when the arc holds it, else at
//   its middle on a grid of FREE_Q1_SAMPLES).
//
// Elbow labels: "up" when the elbow (axis 3) lies on the side of the line
// axis 2 -> axis 4 toward which h1 points.
#pragma once

#include <cmath>

#include "../geometry.hpp"
#include "../so3.hpp"
#include "parallel_pairs.hpp"
#include "parallel_params.hpp"

namespace km {
namespace parallel {

//! G = T M⁻¹: R_G = R_T R_Mᵀ, t_G = t_T - R_G t_M.
KM_HD inline Pose goal(const ParallelParams& P, const Pose& T) {
    double r[3][3];
    for (int i = 0; i < 3; ++i) {
        const Vec3 ti = T.row(i);
        for (int j = 0; j < 3; ++j) r[i][j] = dot(ti, P.home.row(j));
    }
    const Vec3& tm = P.home.p;
    Pose G;
    G.x = {r[0][0], r[1][0], r[2][0]};
    G.y = {r[0][1], r[1][1], r[2][1]};
    G.z = {r[0][2], r[1][2], r[2][2]};
    G.p = {T.p.x - (r[0][0] * tm.x + r[0][1] * tm.y + r[0][2] * tm.z),
           T.p.y - (r[1][0] * tm.x + r[1][1] * tm.y + r[1][2] * tm.z),
           T.p.z - (r[2][0] * tm.x + r[2][1] * tm.y + r[2][2] * tm.z)};
    return G;
}

//! The coordinates of x across k (along e1, e2).
struct Plane {
    double u, v;
};
KM_HD inline Plane plane(const ParallelParams& P, const Vec3& x) {
    return {dot(P.e1, x), dot(P.e2, x)};
}

//! R1ᵀ R_G x: a direction of the target seen from link 1.
KM_HD inline Vec3 back(const ParallelParams& P, const Pose& G, double c1, double s1,
                       const Vec3& x) {
    return rotate_about(P.h1, c1, -s1, G.rotate(x));
}

//! E1⁻¹(G(x)) - p2 in plane coordinates.
KM_HD inline Plane moved(const ParallelParams& P, const Pose& G, double c1, double s1,
                         const Vec3& x) {
    const Vec3 g = G.rotate(x) + (G.p - P.p1);
    return plane(P, rotate_about(P.h1, c1, -s1, g) + (P.p1 - P.p2));
}

//! The representative q6 of an aligned wrist: axis 4 at mid-reach of the triangle.
//!
//! With axis 6 along k, axis 4 (E1⁻¹ G (p6 + R(h6, -q6) v) - p2, v = E5⁻¹(p4) - p6)
//! runs on the circle Z0 + cos q6 Z1 - sin q6 Z2 of radius |v across h6|: take the point
//! at distance max(|A|, |B|) from axis 2 (clamped to the circle's range).
KM_HD inline double free_q6(const ParallelParams& P, const Pose& G, double c1, double s1,
                            const Vec3& v) {
    const Vec3& h6 = P.h6;
    const double along = dot(h6, v);
    const Vec3 on = along * h6;
    const Plane z0 = moved(P, G, c1, s1, P.p6 + on);
    const Plane z1 = plane(P, back(P, G, c1, s1, v - on));
    const Plane z2 = plane(P, back(P, G, c1, s1, cross(h6, v)));
    const double r0 = std::hypot(z0.u, z0.v);
    const double rad = 0.5 * (std::hypot(z1.u, z1.v) + std::hypot(z2.u, z2.v));
    const double want =
        smaller(larger(larger(P.len_a, P.len_b), std::fabs(r0 - rad)), r0 + rad);
    // |Z0|² + rad² + 2 cos q6 Z0·Z1 - 2 sin q6 Z0·Z2 = want²
    double out[2];
    trig_linear(2.0 * (z0.u * z1.u + z0.v * z1.v), -2.0 * (z0.u * z2.u + z0.v * z2.v),
                want * want - r0 * r0 - rad * rad, out);
    return out[0];
}

//! What triangle() found: no solution, or flags.
constexpr int TRIANGLE_NONE = -1;
//! Axis 4 on axis 2 with equal links: q2 free, the first elbow a representative and the
//! second NaN.
constexpr int TRIANGLE_FOLD = 1;
//! Stretched or folded to round-off, or missed by less than NEAR_TOL: the least-squares
//! elbow, once for both (the elbows merge: the target is near).
constexpr int TRIANGLE_NEAR = 2;

//! The elbows of the triangle: flags, then (q2, ψ) of elbow up and of elbow down.
struct Elbows {
    int flags;
    double q2_up, psi_up, q2_down, psi_down;
};

//! q2 and ψ = σ3 q3 putting axis 4 at tx (plane, from axis 2): two elbows.
//!
//! tx = e^{i q2} (A + e^{iψ} B); with γ = ψ + arg B - arg A, 1 ∓ cos γ are formed as
//! products of sums and differences of lengths (exact at the folded and stretched elbow).
//! TRIANGLE_NONE: no solution (angles NaN).
//!
//! A near-degenerate arm (P.slack > 0, m: how far the real arm may put axis 4 from this
//! one's) knows 1 ∓ cos γ only to within slack (2 |tx| + slack) / (2 |A| |B|) (|tx|² moves
//! by at most slack (2 |tx| + slack)):
//! where the stretched (or folded) side is below that, the real arm's two elbows may lie
//! either side of the fold however this triangle sees them, so that side is raised by
//! it, the elbows one on each side and at least as far from the fold as the real arm's
//! (the repair carries each to the solution on its side; triangle.hpp's two_link, the
//! same for the small arms). The flags are this triangle's.
KM_HD inline Elbows triangle(const ParallelParams& P, const Plane& tx) {
    const double a = P.len_a, b = P.len_b;
    const double arg_a = P.arg_a, arg_b = P.arg_b;
    const double span = a + b;
    const double d = std::fabs(a - b);
    // within reach (the gap check): no overflow
    const double n = std::sqrt(tx.u * tx.u + tx.v * tx.v);
    if (n <= CONTINUUM_TOL * span && d <= CONTINUUM_TOL * span) {
        return {TRIANGLE_FOLD, P.q2rep, wrap(PI + arg_a - arg_b), NaN, NaN};
    }
    const double miss = larger(n - span, d - n);
    int flags = 0;
    if (miss > 0.0) {  // past the stretched or folded elbow: the elbows merge there
        if (miss > NEAR_TOL * span) return {TRIANGLE_NONE, NaN, NaN, NaN, NaN};
        flags = TRIANGLE_NEAR;
    }
    const double omc0 = (span - n) * (span + n) / (2.0 * a * b);  // 1 - cos γ
    const double opc0 = (n - d) * (n + d) / (2.0 * a * b);        // 1 + cos γ
    double omc = larger(omc0, 0.0), opc = larger(opc0, 0.0);
    const double margin = P.slack * (2.0 * n + P.slack) / (2.0 * a * b);
    if (margin > 0.0 && omc0 < margin) {  // straddle the stretched elbow (beyond the
        omc = smaller(larger(omc0 + margin, 0.0), 2.0);  // reach by more: stretched)
        opc = 2.0 - omc;
    } else if (margin > 0.0 && opc0 < margin) {  // ... or the folded one
        opc = smaller(larger(opc0 + margin, 0.0), 2.0);
        omc = 2.0 - opc;
    }
    const double sg = std::sqrt(omc * opc);  // sin γ >= 0
    const double gamma = std::atan2(sg, 0.5 * (opc - omc));
    const double arg_t = std::atan2(tx.v, tx.u);
    const double turn = std::atan2(b * sg, (a - b) + b * opc);  // arg(A + e^{iψ} B) - arg A
    // With γ >= 0 the elbow e^{i q2} A is clockwise of t about k: "up" (on the side of
    // h1 × k from the line axis 2 -> axis 4) when t·zup < 0.
    const double cw_q2 = arg_t - arg_a - turn, cw_psi = gamma + arg_a - arg_b;
    const double ccw_q2 = arg_t - arg_a + turn, ccw_psi = -gamma + arg_a - arg_b;
    if (tx.u * P.zup[0] + tx.v * P.zup[1] < 0.0) return {flags, cw_q2, cw_psi, ccw_q2, ccw_psi};
    return {flags, ccw_q2, ccw_psi, cw_q2, cw_psi};
}

//! The solutions of pair j into rows 2 j (elbow up) and 2 j + 1 of Q (8, 6); how many
//! were written (0, 1 or 2).
KM_HD inline int finish(const ParallelParams& P, const Pose& G, const Pair& pair,
                        PairKind kind, int j, double* Q, SolverInfo& info) {
    const double q1 = pair.q1, q5 = pair.q5;
    const double c1 = pair.c1, s1 = pair.s1, c5 = pair.c5, s5 = pair.s5;
    const Vec3& h5 = P.h5;
    const Vec3& h6 = P.h6;
    const Vec3& k = P.k;
    const Vec3 b = G.unrotate(rotate_about(P.h1, c1, s1, k));  // R_Gᵀ k1
    const Vec3 a = rotate_about(h5, c5, -s5, k);               // R5ᵀ k
    // v = E5⁻¹(p4) - p6 = p5 - p6 + R5ᵀ (p4 - p5)
    const Vec3& p5 = P.p5;
    const Vec3 v = rotate_about(h5, c5, -s5, P.p4 - p5) + (p5 - P.p6);
    const double tilt2 = cross2(a, h6);  // sin² of the angle of axis 6 and k
    const bool aligned = tilt2 <= CONTINUUM_TOL * CONTINUUM_TOL;  // axis 6 along k
    const double q6 = aligned ? free_q6(P, G, c1, s1, v) : -subproblem1(a, b, h6);
    double s6, c6;
    sincos(q6, s6, c6);
    // θ234: R234 e1 = R1ᵀ R_G R6ᵀ R5ᵀ e1
    const Vec3 y =
        back(P, G, c1, s1, rotate_about(h6, c6, -s6, rotate_about(h5, c5, -s5, P.e1)));
    const double th234 = std::atan2(dot(P.e2, y), dot(P.e1, y));
    // axis 4: E1⁻¹ G E6⁻¹ (p6 + v) - p2 = E1⁻¹ G (p6 + R6ᵀ v) - p2
    const Plane t = moved(P, G, c1, s1, P.p6 + rotate_about(h6, c6, -s6, v));
    const Elbows el = triangle(P, t);
    if (el.flags < 0) return 0;
    int count = 0;
    for (int e = 0; e < 2; ++e) {
        const double q2 = e == 0 ? el.q2_up : el.q2_down;
        const double psi = e == 0 ? el.psi_up : el.psi_down;
        if (std::isnan(q2)) continue;
        double* row = Q + 6 * (2 * j + e);
        row[0] = q1;
        row[1] = q2;
        row[2] = P.sign3 * psi;
        row[3] = P.sign4 * (th234 - q2 - psi);
        row[4] = q5;
        row[5] = q6;
        count += 1;
    }
    const bool fold = (el.flags & TRIANGLE_FOLD) != 0;
    if ((el.flags & TRIANGLE_NEAR) != 0) info.near = true;
    if (!aligned && count > 0 && tilt2 <= NEAR_ALIGNED_TOL * NEAR_ALIGNED_TOL) info.near = true;
    if (aligned) {
        info.set_free(1);
        info.set_free(2);
        info.set_free(3);
        info.set_free(5);
    }
    if (fold) {
        info.set_free(1);
        info.set_free(3);
    }
    const bool free_q1 = kind == PairKind::free_q1;
    if (free_q1) info.set_free(0);
    if (aligned || fold || free_q1) info.singular = true;
    return count;
}

//! How close the pairs of one target and their elbows (rows of Q) lie to the family's
//! singular sets (rad): the smallest sine of the wrist's tilt (axis 6 from k) over the
//! pairs found, whether or not their triangle closes; half the largest joint difference
//! of two pairs (q1, q5), which merge at a fold; half the difference of q3 of elbow up
//! and down (the stretched or folded elbow). +inf with no pair.
KM_HD inline double pair_margin(const ParallelParams& P, const Pairs& pairs, const double* Q) {
    double out = INF;
    for (int m = 0; m < 4; ++m) {
        if (pairs.kind[m] == PairKind::none) continue;
        const Pair& x = pairs.pair[m];
        out = smaller(out, std::sqrt(cross2(rotate_about(P.h5, x.c5, -x.s5, P.k), P.h6)));
        const double* up = Q + 12 * m;
        out = smaller(out, 0.5 * std::fabs(wrap(up[2] - up[8])));  // NaN: kept
        for (int j = 0; j < m; ++j) {
            if (pairs.kind[j] == PairKind::none) continue;
            const Pair& y = pairs.pair[j];
            out = smaller(out, 0.5 * larger(std::fabs(wrap(x.q1 - y.q1)),
                                            std::fabs(wrap(x.q5 - y.q5))));
        }
    }
    return out;
}

//! Where q1 turns freely: one representative on each arc of q1 of each pair, into Q
//! (8, 6); how many rows were written. info as on entry (entry), then each written
//! representative's.
//!
//! The pairs' existence is read at FREE_Q1_SAMPLES values of q1 around the circle
//! (free_q1_sample's, in circular order here): a maximal run of samples at which the
//! other joints can follow pair m is an arc, represented at q1rep when the run holds it,
//! else at its middle sample. A pair's first arc (the nearest q1rep) takes its own slots;
//! any other arc takes the slots of a pair found at no sample (the meet and parallel
//! modes give two pairs where q1 is free, the general mode one), while any remain: an arc
//! left without one marks the target near, as does no arc at all.
KM_HD inline int free_q1_arcs(const ParallelParams& P, const Pose& G, const Vec3& x6,
                              const Vec3& w6, const SolverInfo& entry, double* Q,
                              SolverInfo& info) {
    constexpr int N = FREE_Q1_SAMPLES;
    const double step = TWO_PI / N;
    unsigned found[N];
    unsigned ever = 0;
    double scratch[8 * 6];
    for (int j = 0; j < N; ++j) {
        SolverInfo tmp = entry;
        Pairs pairs;
        find_pairs(P, x6, w6, wrap(P.q1rep + j * step), pairs, tmp);
        found[j] = 0;
        for (int m = 0; m < 4; ++m) {
            if (pairs.kind[m] != PairKind::none &&
                finish(P, G, pairs.pair[m], pairs.kind[m], m, scratch, tmp) > 0) {
                found[j] |= 1u << m;
            }
        }
        ever |= found[j];
    }
    info = entry;
    int spare = 0;  // the next pair index found at no sample
    int count = 0;
    for (int m = 0; m < 4; ++m) {
        if ((ever & (1u << m)) == 0) continue;
        // the arcs' representative samples, nearest q1rep first
        int reps[N];
        int arcs = 0;
        for (int j = 0; j < N; ++j) {
            const bool on = (found[j] >> m) & 1u;
            const bool before = (found[(j + N - 1) % N] >> m) & 1u;
            if (!on || before) continue;  // not the first sample of a run
            int len = 1;
            while (len < N && ((found[(j + len) % N] >> m) & 1u)) ++len;
            reps[arcs++] = (j == 0 || j + len > N) ? 0 : (j + (len - 1) / 2) % N;
        }
        if (arcs == 0) reps[arcs++] = 0;  // every sample: the whole turn
        for (int a = 1; a < arcs; ++a) {  // by circular distance from sample 0
            for (int b = a; b > 0; --b) {
                const int x = reps[b] < N - reps[b] ? reps[b] : N - reps[b];
                const int y = reps[b - 1] < N - reps[b - 1] ? reps[b - 1] : N - reps[b - 1];
                if (x >= y) break;
                const int t = reps[b];
                reps[b] = reps[b - 1];
                reps[b - 1] = t;
            }
        }
        for (int a = 0; a < arcs; ++a) {
            int slot = m;
            if (a > 0) {
                while (spare < 4 && (ever & (1u << spare)) != 0) ++spare;
                if (spare == 4) {  // no slot left for this arc
                    info.near = true;
                    break;
                }
                slot = spare++;
            }
            Pairs pairs;
            find_pairs(P, x6, w6, wrap(P.q1rep + reps[a] * step), pairs, info);
            count += finish(P, G, pairs.pair[m], pairs.kind[m], slot, Q, info);
        }
    }
    // on a continuum none of whose sampled q1 the other joints can follow: not proven
    // unreachable (an arc shorter than the step)
    if (count == 0) info.near = true;
    return count;
}

}  // namespace parallel

KM_HD inline void ParallelParams::solve(const Pose& T, double* Q, SolverInfo& info) const {
    double margin;
    solve(T, Q, info, margin);
}

KM_HD inline void ParallelParams::solve(const Pose& T, double* Q, SolverInfo& info,
                                        double& margin) const {
    using namespace parallel;
    margin = INF;
    for (int i = 0; i < 8 * 6; ++i) Q[i] = NaN;
    info.gap = NaN;
    bool ok = true;
    for (int i = 0; i < 3; ++i) {
        ok = ok && std::isfinite(T.x[i]) && std::isfinite(T.y[i]) && std::isfinite(T.z[i]) &&
             std::isfinite(T.p[i]);
    }
    if (!ok) return;
    const Pose G = goal(*this, T);
    const double size = scale;
    // |G(a6) - p1s| beyond the reach bound proves the target out of reach (and keeps
    // huge targets out of the maths: no overflow).
    const Vec3 x = G.rotate(a6) + (G.p - p1s);
    double gap = std::hypot(std::hypot(x.x, x.y), x.z) - bound;  // no overflow
    if (gap > NEAR_TOL * size) {
        info.gap = gap;
        return;
    }
    const Vec3 x6 = G.rotate(h6);
    const Vec3 w6 = G.rotate(p6) + (G.p - p1);
    // (2) cannot hold when its sides' ranges do not meet: a proven gap too.
    const double sk = dot(kperp, w6), sh = dot(hk, w6);
    const double miss = std::fabs(F2 - dot(kpar, w6)) - std::sqrt(sk * sk + sh * sh) -
                        std::sqrt(D2 * D2 + E2 * E2);
    gap = larger(larger(gap, miss / lip), 0.0);
    int count = 0;
    if (miss <= NEAR_TOL * size) {
        const SolverInfo entry = info;
        Pairs pairs;
        find_pairs(*this, x6, w6, q1rep, pairs, info);
        if (pairs.free_q1) {
            count = free_q1_arcs(*this, G, x6, w6, entry, Q, info);
            margin = 0.0;  // on the singular set
        } else {
            for (int m = 0; m < 4; ++m) {
                if (pairs.kind[m] != PairKind::none) {
                    count += finish(*this, G, pairs.pair[m], pairs.kind[m], m, Q, info);
                }
            }
            margin = pair_margin(*this, pairs, Q);
        }
    }
    if (count == 0) {
        info.gap = gap;
        info.free = 0;
        info.singular = false;
    }
}

}  // namespace km
