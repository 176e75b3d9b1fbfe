// From raw IK candidates to checked, distinct, limit-aware solutions: one target.
//
// Every candidate a solver proposes is judged here by forward kinematics against the
// target, never by the solver's own word. Candidates a little off (round-off near a
// double root) get a few Gauss-Newton steps first and count only if they then meet the
// tolerances. Solutions are wrapped to (-π, π] (or moved by 2π into their limit window),
// duplicates modulo 2π dropped, split by the joint limits, sorted (by distance to q0 when
// given, else in the solver's slot order), and the target gets an honest status.
#pragma once

#include <cmath>
#include <cstring>
#include <vector>

#include "chain.hpp"
#include "ik_types.hpp"
#include "jacobian.hpp"
#include "linalg.hpp"
#include "so3.hpp"

namespace km {

//! Candidates whose residual is below this (m or rad) but above the tolerance are
//! polished by Gauss-Newton steps before being judged.
constexpr double POLISH_LIMIT = 1e-5;
//! Gauss-Newton steps for polishing: quadratic convergence from 1e-5 needs 2-3.
constexpr int POLISH_STEPS = 4;
//! Relative damping of the polishing steps (as the numeric solver's smallest): negligible
//! next to any singular value that matters, it keeps the normal equations solvable at a
//! double root, where the Jacobian loses rank.
constexpr double POLISH_DAMPING = 1e-12;
//! Gauss-Newton steps at most for a candidate of a nearby arm (CheckOptions::repair).
//! From a candidate within POLISH_LIMIT of a regular solution two or three steps reach
//! round-off; at a double root (a fold) each step halves the distance, and twenty take
//! a candidate 1e-5 rad off to 1e-11.
constexpr int REPAIR_STEPS = 24;
//! The repair's damping follows the residual (Levenberg-Marquardt with λ = μ |e|²,
//! Yamashita and Fukushima 2001): a step minimises |J dq − e|² + μ |e|² |dq|², μ this
//! (1 / rad²). No step is then longer than 1 / (2 √μ) = 0.05 rad, however small σmin (a
//! step near a singular set does not leap to another solution), while near a solution
//! the damping vanishes: at a fold (two branches meeting), d rad from the double root
//! where σmin ≈ κ d and |e| ≈ κ d² / 2 for a curvature κ, it is μ d² / 4 of σmin², for
//! every κ, and each step still about halves d, down to round-off; at a regular solution
//! the convergence stays quadratic. A constant damping (POLISH_DAMPING's 1e-12 s, s the
//! normal matrix's mean diagonal) outweighs σmin² once σmin < 1e-6 √s and the steps
//! stall there: an elbow 3R whose axes 2 and 3 are 5e-10 off parallel had its candidates
//! at the stretched or folded elbow stop 1e-6 to 2e-4 rad from the solution, within the
//! tolerance's residual.
constexpr double REPAIR_DAMPING = 100.0;
//! ... and at least this, relative to s: the normal equations the steps are solved by
//! hold s to round-off only (1e-16 s), and a damping below it would leave the weak
//! direction's pivot to that round-off (on a near-degenerate planar 3R, whose third row,
//! across the plane, has σ about 1e-10, steps of 2 rad). Steps stall where σmin falls
//! below √(1e-15 s), 3e-8 √s: at a fold of curvature κ about √s, 3e-8 rad from the root,
//! where the residual is at round-off.
constexpr double REPAIR_DAMPING_FLOOR = 1e-15;
//! A repair stops when the residual, in units of the tolerances, is below this (its
//! round-off: 1e-14 m or rad for the default tolerances) ...
constexpr double REPAIR_QUIET = 1e-4;
//! ... or after this many steps in a row that did not lower it (the noise floor, or a
//! Newton step across a fold that overshoots before the next lands: steps are taken
//! whatever they do and the best point is kept). Near a singular set a candidate 1e-3
//! rad off takes steps that alternately overshoot and land (the residual up 1e3 times,
//! then down), and the best falls only every two or three steps.
constexpr int REPAIR_PATIENCE = 6;
//! Two solutions closer than this in every joint (rad or m, angles modulo 2π) are one.
constexpr double DEDUP_TOL = 1e-7;
//! Two solutions closer than this in every joint whose midpoint also meets the tolerances
//! are one solution to tolerance, given once, and the target is near a singular set:
//! branches that merge there (elbow up and down at a stretched elbow, a fold of a
//! closed form's equations), d apart, leave a midpoint off by about κ d² / 8 for a
//! curvature κ of the order of the arm's size; a change δ of the target moves them by
//! up to √(2 δ / κ) at the fold, 5e-7 rad for the round-off of a target of the order
//! of 1 m (δ 1e-13): branches this close are not told apart by the target (elbow up
//! and down 4.5e-7 apart, issue 34), while two 2e-6 apart, 1e-6 either side of a fold,
//! are two solutions (tests/ik/analytic/test_elbow_near.py).
constexpr double MERGE_SPAN = 1e-6;
//! Slack on joint limits for values computed by floating point (rad or m).
constexpr double LIMIT_TOL = 1e-12;

//! Scratch of checks of up to m candidates of an n-joint chain: made once per thread.
struct CheckWork {
    int m = 0, n = 0;
    std::vector<double> qs, angle, c, s, res, key, J, Jr, dq, c1, s1, qt, walked;
    std::vector<int> state;
    std::vector<WalkFrame> frames;  //!< the running frames of the candidate walked last

    CheckWork(int m_, int n_)
        : m(m_), n(n_), qs(static_cast<size_t>(m_ * n_)), angle(qs.size()), c(qs.size()),
          s(qs.size()), res(static_cast<size_t>(2 * m_)), key(static_cast<size_t>(m_)),
          J(static_cast<size_t>(6 * n_)), Jr(J.size()), dq(static_cast<size_t>(n_)),
          c1(dq.size()), s1(dq.size()), qt(dq.size()), walked(dq.size()),
          state(static_cast<size_t>(m_)), frames(dq.size()) {}
};

//! Where the check writes one target's outcome: rows within the limits first, sorted,
//! then those outside, sorted; NaN (slot -1) after.
struct CheckOut {
    double* q;    //!< (m, n)
    int* slot;    //!< (m,) the candidate slot of each row (its branch label)
    double* res;  //!< (m, 2) position (m) and rotation (rad) residuals
};

namespace detail {

//! Position (m) and rotation (rad) error of a tool pose P against T, weighted by w.
//!
//! Unweighted, the rotation error is the angle of Rtᵀ R (exact near 0); with weights,
//! the norms of the weighted error components.
KM_HD KM_INLINE void pose_residual(const Pose& P, const Pose& T, const double* w, double& p_err,
                                   double& r_err) {
    const bool plain = w[0] == 1.0 && w[1] == 1.0 && w[2] == 1.0 && w[3] == 1.0 &&
                       w[4] == 1.0 && w[5] == 1.0;
    if (plain) {
        const double dx = T.p.x - P.p.x, dy = T.p.y - P.p.y, dz = T.p.z - P.p.z;
        p_err = std::sqrt(dx * dx + dy * dy + dz * dz);
        r_err = angle_between(P, T);
        return;
    }
    const Twist e = pose_error(P, T);
    double p2 = 0.0, r2 = 0.0;
    for (int i = 0; i < 3; ++i) {
        p2 += (w[i] * e.e[i]) * (w[i] * e.e[i]);
        r2 += (w[i + 3] * e.e[i + 3]) * (w[i + 3] * e.e[i + 3]);
    }
    p_err = std::sqrt(p2);
    r_err = std::sqrt(r2);
}

//! pose_residual of q (its trigonometry c[i stride], s[i stride]) against T.
KM_HD KM_INLINE void residual(const ChainView& ch, const double* q, const double* c,
                              const double* s, int stride, const Pose& T, const double* w,
                              double& p_err, double& r_err) {
    pose_residual(walk(ch, q, c, s, NoRecord{}, stride), T, w, p_err, r_err);
}

//! The tool pose of candidate q (trigonometry c, s), the walk resumed after the leading
//! joints q shares, bit for bit, with the candidate walked before it (its joints in
//! `walked`, its running frames in `frames`; none yet: `count` 0).
//!
//! A closed form's candidates share their first joints in twos and fours (a spherical
//! wrist's pairs share q1-q3, the shoulder's q1): those joints are walked once.
KM_HD KM_INLINE Pose walk_shared(const ChainView& ch, const double* q, const double* c,
                                 const double* s, double* walked, WalkFrame* frames,
                                 int& count) {
    const int n = ch.n;
    int first = 0;
    if (count > 0) {  // the same bits of q give the same bits of every product
        while (first < n - 1 && std::memcmp(q + first, walked + first, sizeof(double)) == 0) {
            ++first;
        }
    }
    for (int k = first; k < n; ++k) walked[k] = q[k];
    ++count;
    const WalkFrame start = first == 0 ? WalkFrame{ch.start.x, ch.start.y, ch.start.z, ch.start.p}
                                       : frames[first - 1];
    return walk_from(ch, q, c, s, NoRecord{}, 1, first, start, frames);
}

//! One Gauss-Newton step on q towards T (weighted rows only), damped by POLISH_DAMPING,
//! or (repairing) by REPAIR_DAMPING times the squared residual.
KM_HD inline void gauss_newton_step(const ChainView& ch, double* q, const Pose& T,
                                    const double* w, CheckWork& work, bool repairing = false) {
    const int n = ch.n;
    double* c = work.c1.data();
    double* s = work.s1.data();
    double* J = work.J.data();
    double* Jr = work.Jr.data();
    double* dq = work.dq.data();
    double er[6];
    joint_trig(ch, q, c, s);
    const Pose P = jacobian(ch, q, c, s, false, J);
    const Twist e = pose_error(P, T);
    int r = 0;
    for (int k = 0; k < 6; ++k) {
        if (w[k] > 0.0) {
            er[r] = w[k] * e.e[k];
            for (int j = 0; j < n; ++j) Jr[r * n + j] = w[k] * J[k * n + j];
            ++r;
        }
    }
    NormalMatrix N;
    normal_matrix(Jr, r, n, N);
    double lam = POLISH_DAMPING;  // relative to s, as damped_step takes it
    if (repairing) {
        double e2 = 0.0;
        for (int k = 0; k < r; ++k) e2 += er[k] * er[k];
        lam = REPAIR_DAMPING * e2 / N.scale;  // μ |e|², relative to s
        if (lam < REPAIR_DAMPING_FLOOR) lam = REPAIR_DAMPING_FLOOR;
    }
    damped_step(N, Jr, r, n, er, lam, dq);
    for (int j = 0; j < n; ++j) {
        q[j] += dq[j];
        if (!ch.joint[j].prismatic) q[j] = wrap(q[j]);
    }
}

//! POLISH_STEPS Gauss-Newton steps on q towards T (weighted rows only).
KM_HD inline void polish(const ChainView& ch, double* q, const Pose& T, const double* w,
                         CheckWork& work) {
    for (int step = 0; step < POLISH_STEPS; ++step) gauss_newton_step(ch, q, T, w, work);
}

//! A candidate of a nearby arm carried to this arm's solution: Gauss-Newton steps from q
//! (residuals p_err, r_err on entry), damped by the residual (REPAIR_DAMPING: an undamped
//! step near a singular set may leap to another solution), until the residual is at round-off
//! (REPAIR_QUIET), has not fallen for REPAIR_PATIENCE steps, or after REPAIR_STEPS; q and
//! the residuals become the best point's.
KM_HD inline void repair(const ChainView& ch, double* q, const Pose& T,
                         const CheckOptions& opts, CheckWork& work, double& p_err,
                         double& r_err) {
    const int n = ch.n;
    const double* w = opts.weights;
    double* qt = work.qt.data();
    const auto score = [&](double p, double r) {
        return std::fmax(p / opts.tol.position, r / opts.tol.rotation);
    };
    double best = score(p_err, r_err);
    for (int j = 0; j < n; ++j) qt[j] = q[j];
    int idle = 0;
    for (int step = 0; step < REPAIR_STEPS && best > REPAIR_QUIET && idle < REPAIR_PATIENCE;
         ++step) {
        gauss_newton_step(ch, qt, T, w, work, true);
        joint_trig(ch, qt, work.c1.data(), work.s1.data());
        double p = INF, r = INF;
        residual(ch, qt, work.c1.data(), work.s1.data(), 1, T, w, p, r);
        const double now = score(p, r);
        if (now < best) {
            best = now;
            p_err = p;
            r_err = r;
            for (int j = 0; j < n; ++j) q[j] = qt[j];
            idle = 0;
        } else {
            ++idle;
        }
    }
}

//! True when rows a and b agree within tol in every joint (angles modulo 2π).
KM_HD KM_INLINE bool same(const ChainView& ch, const double* qa, const double* qb,
                          double tol = DEDUP_TOL) {
    for (int j = 0; j < ch.n; ++j) {
        double d = qa[j] - qb[j];
        if (!ch.joint[j].prismatic) {
            d = std::fabs(d);
            // (rows are finite here: a plain comparison, not std::fmin's library call)
            d = d <= TWO_PI ? (TWO_PI - d < d ? TWO_PI - d : d) : std::fabs(wrap(d));
        }
        if (!(std::fabs(d) < tol)) return false;
    }
    return true;
}

//! True when the midpoint of rows a and b (angles: along the shorter way) meets the
//! tolerances on T (MERGE_SPAN: the two are one solution to tolerance). Scratch: work.qt,
//! work.c1, work.s1.
KM_HD inline bool midpoint_solves(const ChainView& ch, const double* qa, const double* qb,
                                  const Pose& T, const CheckOptions& opts, CheckWork& work) {
    double* qt = work.qt.data();
    for (int k = 0; k < ch.n; ++k) {
        const double d = qa[k] - qb[k];
        qt[k] = qb[k] + 0.5 * (ch.joint[k].prismatic ? d : wrap(d));
    }
    joint_trig(ch, qt, work.c1.data(), work.s1.data());
    double p = INF, r = INF;
    residual(ch, qt, work.c1.data(), work.s1.data(), 1, T, opts.weights, p, r);
    return p <= opts.tol.position && r <= opts.tol.rotation;
}

}  // namespace detail

//! Check the m candidates Q (m x n, row-major; NaN rows: no solution on that branch) of
//! one target T against the chain; q0 (n) sorts the solutions when given (else nullptr).
KM_HD KM_INLINE CheckReport check(const ChainView& ch, const Pose& T, const double* Q, int m,
                                  const SolverInfo& info, const CheckOptions& opts,
                                  const double* q0, CheckWork& work, const CheckOut& out) {
    const int n = ch.n;
    const double tol_p = opts.tol.position, tol_r = opts.tol.rotation;
    double* qs = work.qs.data();
    double* res = work.res.data();
    double* key = work.key.data();
    int* state = work.state.data();
    bool close = false, lost = false, merged = false;
    double near_p = NaN, near_r = NaN, near_score = INF;
    for (int j = 0; j < m; ++j) {
        state[j] = 0;
        for (int k = 0; k < n; ++k) {
            const double v = Q[j * n + k];
            qs[j * n + k] = ch.joint[k].prismatic ? v : wrap(v);
        }
    }
    joint_trig_rows(ch, qs, m, work.angle.data(), work.c.data(), work.s.data());
    int walks = 0;  // candidates walked (walk_shared)
    for (int j = 0; j < m; ++j) {
        double* qj = qs + j * n;
        bool valid = true;
        for (int k = 0; k < n; ++k) valid = valid && std::isfinite(qj[k]);
        if (!valid) continue;
        const double* cj = work.c.data() + j * n;  // joint_trig_rows is row-major: row j
        const double* sj = work.s.data() + j * n;
        int stride = 1;
        double p_err = INF, r_err = INF;
        bool ok = false;
        const Pose P = detail::walk_shared(ch, qj, cj, sj, work.walked.data(),
                                           work.frames.data(), walks);
        if (opts.repair) {
            detail::pose_residual(P, T, opts.weights, p_err, r_err);
            if (std::fmax(p_err, r_err) < POLISH_LIMIT) {
                detail::repair(ch, qj, T, opts, work, p_err, r_err);
            }
            ok = p_err <= tol_p && r_err <= tol_r;
        } else {
            for (int attempt = 0; attempt < 2; ++attempt) {
                if (attempt == 0) {
                    detail::pose_residual(P, T, opts.weights, p_err, r_err);
                } else {
                    detail::residual(ch, qj, cj, sj, stride, T, opts.weights, p_err, r_err);
                }
                ok = p_err <= tol_p && r_err <= tol_r;
                if (ok || attempt == 1 || !(std::fmax(p_err, r_err) < POLISH_LIMIT)) break;
                detail::polish(ch, qj, T, opts.weights, work);
                joint_trig(ch, qj, work.c1.data(), work.s1.data());
                cj = work.c1.data();
                sj = work.s1.data();
                stride = 1;
            }
        }
        close = close || std::fmax(p_err, r_err) < POLISH_LIMIT;
        // a nearby arm's candidate that came close and could not be carried to a
        // solution: one lies near it, at a configuration where the arm is singular to
        // within the difference of the arms (the repair's steps stall there)
        lost = lost || (opts.repair && !ok && std::fmax(p_err, r_err) < POLISH_LIMIT);
        if (!ok) {
            const double score = std::fmax(p_err / tol_p, r_err / tol_r);
            if (score < near_score) {
                near_score = score;
                near_p = p_err;
                near_r = r_err;
            }
            continue;
        }
        // An angle outside its limits whose turn ±2π is inside is taken there; then
        // within its limits or not (one pass over the joints).
        bool inside = true;
        if (opts.respect_limits) {
            for (int k = 0; k < n; ++k) {
                const double lo = ch.joint[k].qlo - LIMIT_TOL;
                const double hi = ch.joint[k].qhi + LIMIT_TOL;
                double v = qj[k];
                if (!ch.joint[k].prismatic) {
                    if (v < lo && v + TWO_PI <= hi) {
                        v += TWO_PI;
                        qj[k] = v;
                    } else if (v > hi && v - TWO_PI >= lo) {
                        v -= TWO_PI;
                        qj[k] = v;
                    }
                }
                inside = inside && lo <= v && v <= hi;
            }
        }
        bool duplicate = false;  // (modulo 2π: the turn above changes nothing here)
        for (int i = 0; i < j; ++i) {
            if (state[i] == 0 || !detail::same(ch, qj, qs + i * n, MERGE_SPAN)) continue;
            if (detail::same(ch, qj, qs + i * n)) {
                duplicate = true;
                break;
            }
            if (detail::midpoint_solves(ch, qj, qs + i * n, T, opts, work)) {
                duplicate = true;  // one solution to tolerance: branches merging
                merged = true;
                break;
            }
        }
        if (duplicate) continue;
        state[j] = inside ? 1 : 2;
        res[2 * j] = p_err;
        res[2 * j + 1] = r_err;
        if (q0 != nullptr) {
            double d2 = 0.0;
            for (int k = 0; k < n; ++k) {
                double d = qj[k] - q0[k];
                if (!ch.joint[k].prismatic) d = wrap(d);
                d2 += d * d;
            }
            key[j] = std::sqrt(d2);
        } else {
            key[j] = j;
        }
    }
    // Within the limits first, then outside; each sorted by key (insertion sort: m is small).
    int row = 0, count = 0;
    for (int group = 1; group <= 2; ++group) {
        const int first = row;
        for (int j = 0; j < m; ++j) {
            if (state[j] != group) continue;
            int pos = row;
            while (pos > first && key[out.slot[pos - 1]] > key[j]) {
                out.slot[pos] = out.slot[pos - 1];
                --pos;
            }
            out.slot[pos] = j;
            ++row;
        }
        if (group == 1) count = row;
    }
    for (int r = 0; r < m; ++r) {
        if (r < row) {
            const int j = out.slot[r];
            for (int k = 0; k < n; ++k) out.q[r * n + k] = qs[j * n + k];
            out.res[2 * r] = res[2 * j];
            out.res[2 * r + 1] = res[2 * j + 1];
        } else {
            out.slot[r] = -1;
            for (int k = 0; k < n; ++k) out.q[r * n + k] = NaN;
            out.res[2 * r] = NaN;
            out.res[2 * r + 1] = NaN;
        }
    }
    CheckReport rep;
    rep.count = count;
    rep.out_count = row - count;
    const double gap = info.gap;
    if (count > 0) {
        rep.status = info.singular ? Status::singular : Status::ok;
    } else if (rep.out_count > 0) {
        // a search stays within the limits: a candidate the polish carried just past one
        // does not show that no solution lies within them
        rep.status = opts.complete ? Status::out_of_limits : Status::not_found;
    } else if (gap > tol_p + opts.gap_slack || (opts.complete && !close && !info.near)) {
        rep.status = Status::unreachable;
    } else {
        rep.status = Status::not_found;
    }
    rep.gap = rep.status == Status::unreachable ? gap : NaN;
    rep.nearest_position = near_p;
    rep.nearest_rotation = near_r;
    rep.near = info.near || lost || merged;
    rep.free = info.free;
    return rep;
}

//! A malformed target's outcome: no numbers.
KM_HD inline CheckReport invalid_target(int m, int n, const CheckOut& out) {
    for (int r = 0; r < m; ++r) {
        out.slot[r] = -1;
        for (int k = 0; k < n; ++k) out.q[r * n + k] = NaN;
        out.res[2 * r] = NaN;
        out.res[2 * r + 1] = NaN;
    }
    return CheckReport{};
}

}  // namespace km
