// Numeric IK of one target: Levenberg-Marquardt with restarts.
//
// Damped least squares on the counted pose errors: each step solves
// (JᵀWJ + λ s I) Δq = JᵀW e (in its m x m form when the arm is redundant); W holds the
// mask weights, s the mean diagonal of the normal matrix, so λ is dimensionless.
//
// * A step that lowers ½ eᵀWe is accepted and λ shrinks fivefold (the last steps are
//   Gauss-Newton steps, quadratically convergent to the 1e-10 tolerances); one that does
//   not is rejected and λ grows fivefold. The Jacobian, the bound scaling and the normal
//   matrix are made at accepted points only: a rejected step changes λ alone.
// * Joint limits: the step is taken in variables scaled by the distance to the bound each
//   joint heads for (Coleman and Li's affine scaling, as scipy's least_squares "trf"), so
//   a joint slows down as it nears that bound and one on it is blocked; the new
//   configuration is then wrapped and clamped into the bounds.
// * An attempt stops when it converges, when λ exceeds LAMBDA_MAX, when ½ eᵀWe has not
//   fallen by a fifth over the last STALL_WINDOW steps (a local minimum, or a crawl towards
//   one: a restart is cheaper), or after the step budget.
// * An attempt that stops within POLISH_LIMIT of the target (a near miss) gets
//   Gauss-Newton steps taken whatever they do to the error and keeps the best point (the
//   end game): near a fold the damped steps stall a hair from the target, the error left
//   along a direction of tiny singular value that any damping above it freezes, and the
//   undamped step across the fold may first raise the error before the next one lands.
// * A failed attempt restarts from the next of the given samples (drawn once by the
//   caller from a seed: a batch uses the same ones for every target, so a target gets the
//   same answer alone or in a batch).
// * A target farther from the base than the reach bound is proven out of reach and not
//   searched; its distance is computed without overflow.
#pragma once

#include <cmath>
#include <vector>

#include "chain.hpp"
#include "check.hpp"
#include "jacobian.hpp"
#include "linalg.hpp"
#include "so3.hpp"

namespace km {

//! Initial damping, relative to the mean diagonal of the normal matrix: about as strong as
//! the Jacobian itself, a safe first step from a distant guess.
constexpr double LAMBDA_INIT = 1.0;
//! Damping factor after an accepted step (towards Gauss-Newton) ... (0.2 against 0.1:
//! 7-19 % fewer evaluations on the Panda, PUMA 560 and a general 6R arm, as many on the
//! iiwa14, with the stall test below; benchmarks/ik_numeric.py's arms, 4,000 poses each)
constexpr double LAMBDA_DOWN = 0.2;
//! ... and after a rejected one (towards short gradient steps).
constexpr double LAMBDA_UP = 5.0;
//! Smallest relative damping, far below the round-off of the normal matrix: the last steps
//! are Gauss-Newton steps, which converge along directions whose singular value is down to
//! 1e-9 of the largest (two prismatic axes 1e-9 rad from parallel; at 1e-18 such an arm is
//! no longer solved). Where round-off leaves a Cholesky pivot at or below zero, the pivot
//! is floored (linalg.hpp): the step is huge, the error grows, and the step is rejected.
constexpr double LAMBDA_MIN = 1e-21;
//! Damping at which an attempt has stalled: even tiny gradient steps no longer reduce the
//! error (a local minimum, or the error is at round-off level).
constexpr double LAMBDA_MAX = 1e8;
//! Progress check, at every step from the STALL_WINDOW-th on: ½ eᵀWe must be below
//! STALL_FACTOR times its value STALL_WINDOW steps (accepted or not) before. Failed
//! attempts crawl: most of a search's time went into them while the test looked every 8
//! steps for the error norm to halve, and a converging attempt gains more than this.
constexpr int STALL_WINDOW = 4;
constexpr double STALL_FACTOR = 0.8;
//! Distance to a bound (rad or m) below which a joint heading for it slows down: its
//! column and step are scaled by √min(distance / BOUND_SCALE, 1). Measured on the Panda
//! within its limits: 10-15 % fewer evaluations than blocking joints only on a bound.
constexpr double BOUND_SCALE = 1.0;

//! One joint's bounds in the search: the start of a revolute joint's 2π wrap window, and
//! the clamps (±inf where none; a full-turn revolute joint is wrapped, never clamped).
struct JointBound {
    double wrap = -PI, lo = -INF, hi = INF;
};

//! How the search runs.
struct LMSettings {
    Tolerance tol;                //!< the search stops within it of the target
    int max_steps = 60;           //!< steps per attempt
    double reach = INF;           //!< bound on the distance of the tool origin from `base` (m)
    Vec3 base{};                  //!< the start frame's origin
};

//! What a search reports.
struct LMStats {
    bool converged = false;
    int evaluations = 0;  //!< configurations evaluated
    int attempts = 0;     //!< the first guess and the restarts used
    double gap = NaN;     //!< when the target is proven out of reach (not searched), its gap (m)
};

//! Scratch of searches on an n-joint chain: made once per thread.
struct LMWork {
    int n;
    std::vector<double> q, q_new, q_best, dq, d, c, s, J6, J, Jb;
    Pose pose{};
    Twist e6{};
    NormalMatrix normal{};  //!< of the scaled rows Jb at the current point
    explicit LMWork(int n_)
        : n(n_), q(static_cast<size_t>(n_)), q_new(q.size()), q_best(q.size()), dq(q.size()),
          d(q.size()), c(q.size()), s(q.size()), J6(static_cast<size_t>(6 * n_)), J(J6.size()),
          Jb(J6.size()) {}
};

namespace lm {

//! The counted error components of weights w: indices, √w, max(w, 1).
struct Rows {
    int count = 0;
    int index[6] = {};
    double sw[6] = {};
    double scale[6] = {};
    bool exact = false;  //!< only some rotation components count: their rows need J_r⁻¹
    bool plain = false;  //!< every component counts with weight 1: the rows are J itself

    KM_HD explicit Rows(const double* w) {
        int rotations = 0;
        for (int k = 0; k < 6; ++k) {
            if (w[k] > 0.0) {
                index[count] = k;
                sw[count] = std::sqrt(w[k]);
                scale[count] = std::fmax(w[k], 1.0);
                ++count;
                if (k >= 3) ++rotations;
            }
        }
        exact = 0 < rotations && rotations < 3;
        plain = count == 6;
        for (int r = 0; r < count; ++r) plain = plain && sw[r] == 1.0;
    }
};

//! Distance (m) from origin to T's position, counted axes only, without overflow.
KM_HD KM_INLINE double distance(const Pose& T, const Vec3& origin, const double* w) {
    double big = 0.0;
    for (int k = 0; k < 3; ++k) {
        if (w[k] > 0.0) big = std::fmax(big, std::fabs(T.p[k] - origin[k]));
    }
    if (big == 0.0 || !std::isfinite(big)) return big;
    double s = 0.0;
    for (int k = 0; k < 3; ++k) {
        if (w[k] > 0.0) {
            const double r = (T.p[k] - origin[k]) / big;
            s += r * r;
        }
    }
    return big * std::sqrt(s);
}

//! Wrap revolute angles into their window, then clamp into the bounds (in place).
KM_HD KM_INLINE void project(const ChainView& ch, const JointBound* b, double* q) {
    for (int i = 0; i < ch.n; ++i) {
        const double lo = b[i].lo, hi = b[i].hi;
        double v = q[i];
        const bool revolute = !ch.joint[i].prismatic;
        // (inside its window already, as after most steps: no fmod call)
        if (revolute && !(b[i].wrap <= v && v < b[i].wrap + TWO_PI)) {
            v = b[i].wrap + floor_mod(v - b[i].wrap, TWO_PI);
        }
        if (v > hi) v = (revolute && v - hi > lo + TWO_PI - v) ? lo : hi;
        q[i] = v < lo ? lo : v;
    }
}

//! Pose at q, its axes (into work.J6), the full error e6 and the counted err.
KM_HD KM_INLINE void pose_errors(const ChainView& ch, const double* q, const Pose& T,
                                 const Rows& rows, LMWork& work, double* err) {
    joint_trig(ch, q, work.c.data(), work.s.data());
    work.pose = walk(ch, q, work.c.data(), work.s.data(),
                     detail::AxesIntoJacobian{work.J6.data(), ch.n});
    work.e6 = pose_error(work.pose, T);
    for (int r = 0; r < rows.count; ++r) err[r] = work.e6.e[rows.index[r]];
}

//! Weighted rows J (count x n) of the counted errors, from the last pose_errors.
KM_HD KM_INLINE void jacobian_rows(const ChainView& ch, const Rows& rows, LMWork& work) {
    const int n = ch.n;
    double* J6 = work.J6.data();
    jacobian_columns(ch, work.pose, false, J6);
    if (rows.exact) {  // only some rotation components count: rows J_r⁻¹(Δω) J_ω
        double A[9];
        inverse_right_jacobian(work.e6.e[3], work.e6.e[4], work.e6.e[5], A);
        for (int j = 0; j < n; ++j) {
            const double w0 = J6[3 * n + j], w1 = J6[4 * n + j], w2 = J6[5 * n + j];
            for (int k = 0; k < 3; ++k) J6[(3 + k) * n + j] = A[3 * k] * w0 + A[3 * k + 1] * w1 + A[3 * k + 2] * w2;
        }
    }
    if (rows.plain) {  // J is J6 itself: take it (the next pose_errors fills the other)
        work.J.swap(work.J6);
        return;
    }
    for (int r = 0; r < rows.count; ++r) {
        const int k = rows.index[r];
        for (int j = 0; j < n; ++j) work.J[r * n + j] = rows.sw[r] * J6[k * n + j];
    }
}

//! Position and rotation norms of err, each component scaled by rows.scale.
KM_HD KM_INLINE void norms(const Rows& rows, const double* err, double& pos, double& rot) {
    double p2 = 0.0, r2 = 0.0;
    for (int r = 0; r < rows.count; ++r) {
        const double v = (err[r] * rows.scale[r]) * (err[r] * rows.scale[r]);
        if (rows.index[r] < 3) {
            p2 += v;
        } else {
            r2 += v;
        }
    }
    pos = std::sqrt(p2);
    rot = std::sqrt(r2);
}

//! ½ Σ w_k e_k² of the counted errors.
KM_HD KM_INLINE double energy(const Rows& rows, const double* err) {
    double t = 0.0;
    for (int r = 0; r < rows.count; ++r) t += (err[r] * rows.sw[r]) * (err[r] * rows.sw[r]);
    return 0.5 * t;
}

//! Coleman-Li scaling: d (n) per joint, and the scaled rows J diag(d): J itself where
//! every d is 1 (no joint within BOUND_SCALE of the bound it heads for), else Jb.
KM_HD KM_INLINE const double* bound_scaling(const JointBound* b, const double* q,
                                            const double* J, int count, int n, const double* ew,
                                            double* Jb, double* d) {
    // g = Jᵀ ew into d first, row after row (each joint's sum in the order of the rows, as
    // a dot product's; the loops run along contiguous joints)
    for (int j = 0; j < n; ++j) d[j] = 0.0;
    for (int r = 0; r < count; ++r) {
        for (int j = 0; j < n; ++j) d[j] += J[r * n + j] * ew[r];
    }
    bool scaled = false;
    for (int j = 0; j < n; ++j) {
        const double g = d[j];
        double v = BOUND_SCALE;
        if (g > 0.0) {
            v = b[j].hi - q[j];
        } else if (g < 0.0) {
            v = q[j] - b[j].lo;
        }
        // (comparisons, not fmin / fmax calls: v is never NaN, as q is within its bounds)
        d[j] = v >= BOUND_SCALE ? 1.0 : std::sqrt((v > 0.0 ? v : 0.0) / BOUND_SCALE);
        scaled = scaled || d[j] != 1.0;
    }
    if (!scaled) return J;
    for (int r = 0; r < count; ++r) {
        for (int j = 0; j < n; ++j) Jb[r * n + j] = J[r * n + j] * d[j];
    }
    return Jb;
}

//! A Gauss-Newton step dq holding the joints on a bound that it would carry out (solved
//! again without each such joint until no held joint would leave: an active set).
KM_HD inline void active_step(const JointBound* b, const double* q, const double* J, int count,
                              int n, const double* ew, double damping, double* Jb, double* dq) {
    for (int i = 0; i < count * n; ++i) Jb[i] = J[i];
    for (int pass = 0; pass <= n; ++pass) {
        damped_least_squares(Jb, count, n, ew, damping, dq);
        bool held = false;
        for (int i = 0; i < n; ++i) {
            if ((q[i] <= b[i].lo && dq[i] < 0.0) || (q[i] >= b[i].hi && dq[i] > 0.0)) {
                for (int r = 0; r < count; ++r) Jb[r * n + i] = 0.0;
                held = true;
            }
        }
        if (!held) return;
    }
}

//! Gauss-Newton steps from a near miss q (its err and rows J in work), in place.
//!
//! POLISH_STEPS steps of damping LAMBDA_MIN, taken whatever they do to the error (across a
//! fold the first one may raise it), then, from the best point so far, as many of damping
//! POLISH_DAMPING (where the Jacobian has lost rank the undamped normal equations blow
//! up). Stops at the first point within the tolerances; otherwise leaves q, err and J at
//! the best point. Returns the number of evaluations.
KM_HD inline int end_game(const ChainView& ch, const JointBound* b, const Pose& T, const Rows& rows,
                          const LMSettings& set, double* q, double* err, LMWork& work) {
    const int n = ch.n;
    int evaluations = 0;
    double ew[6];
    for (int i = 0; i < n; ++i) work.q_best[i] = q[i];
    double E_low = energy(rows, err);
    const double dampings[2] = {LAMBDA_MIN, POLISH_DAMPING};
    for (const double damping : dampings) {
        for (int step = 0; step < POLISH_STEPS; ++step) {
            for (int r = 0; r < rows.count; ++r) ew[r] = err[r] * rows.sw[r];
            active_step(b, q, work.J.data(), rows.count, n, ew, damping, work.Jb.data(), work.dq.data());
            for (int i = 0; i < n; ++i) q[i] += work.dq[i];
            project(ch, b, q);
            pose_errors(ch, q, T, rows, work, err);
            jacobian_rows(ch, rows, work);
            ++evaluations;
            double pos, rot;
            norms(rows, err, pos, rot);
            if (pos <= set.tol.position && rot <= set.tol.rotation) return evaluations;
            const double E_new = energy(rows, err);
            if (E_new < E_low) {
                for (int i = 0; i < n; ++i) work.q_best[i] = q[i];
                E_low = E_new;
            }
        }
        for (int i = 0; i < n; ++i) q[i] = work.q_best[i];
        pose_errors(ch, q, T, rows, work, err);
        jacobian_rows(ch, rows, work);
        ++evaluations;
    }
    return evaluations;
}

}  // namespace lm

//! Search one target: attempts one after another, restarting failed ones.
//!
//! Args: the chain, bounds (n), weights w (6; 0: not counted), settings, target T, first
//! guess start (n), restart configurations samples (R x n, used in order), q_out (n; the
//! converged configuration, or the best failed one; NaN when the target was not searched).
KM_HD KM_INLINE LMStats lm_solve(const ChainView& ch, const JointBound* bounds, const double* w,
                                 const LMSettings& set, const Pose& T, const double* start,
                                 const double* samples, int R, double* q_out, LMWork& work) {
    using namespace lm;
    const int n = ch.n;
    LMStats stats;
    const double tol_p = set.tol.position, tol_r = set.tol.rotation;
    // A target beyond the reach bound is out of reach (leaving out components that do not
    // count only shortens a distance). A solution may miss by the tolerance in the
    // weighted norm, so the proof needs w_min · gap > tol_p.
    double w_min = INF;
    for (int k = 0; k < 3; ++k) {
        if (w[k] > 0.0) w_min = std::fmin(w_min, w[k]);
    }
    const double gap = distance(T, set.base, w) - set.reach;
    if (w_min < INF && gap * w_min > tol_p) {
        stats.gap = gap;
        for (int i = 0; i < n; ++i) q_out[i] = NaN;
        return stats;
    }
    const Rows rows(w);
    double err[6], err_new[6], ew[6];
    double* q = work.q.data();
    double* q_new = work.q_new.data();
    double best_score = INF;
    bool converged = false;
    for (int i = 0; i < n; ++i) q_out[i] = start[i];
    project(ch, bounds, q_out);
    double pos = INF, rot = INF;
    for (int attempt = 0; attempt <= R; ++attempt) {
        const double* from = attempt == 0 ? start : samples + (attempt - 1) * n;
        for (int i = 0; i < n; ++i) q[i] = from[i];
        project(ch, bounds, q);
        ++stats.attempts;
        pose_errors(ch, q, T, rows, work, err);
        jacobian_rows(ch, rows, work);
        ++stats.evaluations;
        double E = energy(rows, err);
        double recent[STALL_WINDOW];  // ½ eᵀWe at the last STALL_WINDOW steps (a ring)
        double lam = LAMBDA_INIT;
        int k = 0;
        bool moved = true;  // a new point: its scaling and normal matrix are to be made
        const double* Js = nullptr;  // the point's scaled rows (bound_scaling)
        while (true) {
            norms(rows, err, pos, rot);
            if (pos <= tol_p && rot <= tol_r) {
                converged = true;
                break;
            }
            const bool stalled = k >= STALL_WINDOW && STALL_FACTOR * recent[k % STALL_WINDOW] < E;
            if (stalled || lam > LAMBDA_MAX || k >= set.max_steps) break;
            recent[k % STALL_WINDOW] = E;
            // One damped step in bound-scaled variables, then back into the bounds. A
            // rejected step leaves the point, its scaling and its normal matrix as they were.
            if (moved) {
                for (int r = 0; r < rows.count; ++r) ew[r] = err[r] * rows.sw[r];
                Js = bound_scaling(bounds, q, work.J.data(), rows.count, n, ew, work.Jb.data(),
                                   work.d.data());
                normal_matrix(Js, rows.count, n, work.normal);
                moved = false;
            }
            damped_step(work.normal, Js, rows.count, n, ew, lam, work.dq.data());
            for (int i = 0; i < n; ++i) q_new[i] = q[i] + work.d[i] * work.dq[i];
            project(ch, bounds, q_new);
            pose_errors(ch, q_new, T, rows, work, err_new);
            ++stats.evaluations;
            const double E_new = energy(rows, err_new);
            if (E_new < E) {
                for (int i = 0; i < n; ++i) q[i] = q_new[i];
                for (int r = 0; r < rows.count; ++r) err[r] = err_new[r];
                jacobian_rows(ch, rows, work);
                E = E_new;
                moved = true;
                lam = std::fmax(lam * LAMBDA_DOWN, LAMBDA_MIN);
            } else {
                lam *= LAMBDA_UP;
            }
            ++k;
        }
        if (!converged && std::fmax(pos, rot) < POLISH_LIMIT) {
            stats.evaluations += end_game(ch, bounds, T, rows, set, q, err, work);
            norms(rows, err, pos, rot);
            converged = pos <= tol_p && rot <= tol_r;
        }
        norms(rows, err, pos, rot);
        const double score = std::fmax(pos / tol_p, rot / tol_r);
        if (converged || score < best_score) {
            best_score = score;
            for (int i = 0; i < n; ++i) q_out[i] = q[i];
        }
        if (converged) break;
    }
    stats.converged = converged;
    return stats;
}

}  // namespace km
