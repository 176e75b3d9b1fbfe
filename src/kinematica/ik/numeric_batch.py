"""The Levenberg-Marquardt search of numeric IK, vectorised across targets.

The search works on *rows*: one attempt at one target each. All rows iterate
together as arrays; each iteration is one forward-kinematics-and-Jacobian
evaluation and one batch of small damped normal equations. A row leaves when
its attempt converges or fails; a target whose attempt failed gets a new row
from a random configuration (a restart) while it has restarts left. Targets
likely to be hard get several rows at once (:data:`MIN_ROWS` among them): a
batch of a few rows costs about as much per iteration as a batch of one, so
running a straggler's restarts side by side shortens the tail. A target is
done as soon as any of its rows converges. See
:mod:`kinematica.ik.numeric` for the algorithm and the public entry point.

Rows lie along the last axis of every array, as in
:mod:`~kinematica.ik.numeric_model`.
"""

from __future__ import annotations

import itertools

import numpy as np
from numpy.typing import NDArray

from kinematica.ik.numeric_model import evaluate
from kinematica.ik.numeric_problem import (
    LAMBDA_DOWN,
    LAMBDA_INIT,
    LAMBDA_MAX,
    LAMBDA_MIN,
    LAMBDA_UP,
    SCALE_FLOOR,
    STALL_FACTOR,
    STALL_WINDOW,
    LMProblem,
    Sampler,
    SearchResult,
)

__all__ = ["CHOLESKY_ROWS", "MIN_ROWS", "SPARE_AFTER", "search_batch"]

FloatArray = NDArray[np.float64]

#: From this many rows on, the normal equations are solved by a Cholesky
#: factorisation written across rows rather than by LAPACK's batched solve.
CHOLESKY_ROWS = 200
#: Rows the search keeps for the targets likely to be hard (see module doc) ...
MIN_ROWS = 256
#: ... which are those that failed an attempt, or all unsolved after this many
#: steps (most attempts that succeed take fewer: median 11 on 7-DOF arms).
SPARE_AFTER = 2 * STALL_WINDOW


# ------------------------------------------------------------------ steps
def _cholesky_solve(A: FloatArray, b: FloatArray) -> FloatArray:
    """Solve SPD systems laid out across the last axis, by Cholesky.

    With ``R`` in the last axis each operation is one numpy call on ``R``
    contiguous numbers: for hundreds of small systems this beats LAPACK's
    batched solve, which pays per matrix.

    Args:
        A: ``(k, k, R)`` symmetric positive definite matrices.
        b: ``(k, R)`` right-hand sides.

    Returns:
        ``(k, R)`` solutions.
    """
    k = A.shape[0]
    L: list[list[FloatArray]] = [[] for _ in range(k)]  # L[i][j], j ≤ i; 1/L[j][j] stored
    for j in range(k):
        for i in range(j, k):
            t = A[i, j].copy()
            for p in range(j):
                t -= L[i][p] * L[j][p]
            if i == j:
                L[j].append(1.0 / np.sqrt(np.maximum(t, SCALE_FLOOR)))
            else:
                L[i].append(t * L[j][j])
    y: list[FloatArray] = []
    for i in range(k):
        t = b[i].copy()
        for p in range(i):
            t -= L[i][p] * y[p]
        y.append(t * L[i][i])
    x: list[FloatArray] = [y[0]] * k
    for i in reversed(range(k)):
        t = y[i].copy()
        for p in range(i + 1, k):
            t -= L[p][i] * x[p]
        x[i] = t * L[i][i]
    return np.stack(x)


def _damped_solve(J: FloatArray, e: FloatArray, lam: FloatArray) -> FloatArray:
    """Damped least-squares steps ``argmin ‖J dq − e‖² + λ s ‖dq‖²``, batched.

    ``s`` is the mean diagonal of the normal matrix, which makes ``λ``
    dimensionless. The smaller system is solved: ``dq = Jᵀ (J Jᵀ + λs I)⁻¹ e``
    when ``m ≤ n`` (redundant or square), ``(JᵀJ + λs I)⁻¹ Jᵀ e`` otherwise;
    the two are the same step.

    Args:
        J: ``(m, n, R)`` weighted Jacobian rows.
        e: ``(m, R)`` weighted errors.
        lam: ``(R,)`` relative damping.

    Returns:
        ``(n, R)`` joint steps.
    """
    m, n, R = J.shape
    wide = m <= n
    if wide:
        A = np.einsum("ikr,jkr->ijr", J, J)
        rhs = e
    else:
        A = np.einsum("ikr,ijr->kjr", J, J)
        rhs = np.einsum("ikr,ir->kr", J, e)
    k = A.shape[0]
    diag = np.arange(k)
    scale = A[diag, diag].sum(axis=0) / k
    A[diag, diag] += lam * np.where(scale > SCALE_FLOOR, scale, 1.0)
    if R >= CHOLESKY_ROWS:
        x = _cholesky_solve(A, rhs)
    else:
        try:
            x = np.linalg.solve(A.transpose(2, 0, 1), rhs.T[:, :, None])[:, :, 0].T
        except np.linalg.LinAlgError:  # pragma: no cover - the damping keeps A definite
            x = _cholesky_solve(A, rhs)
    return np.asarray(np.einsum("ikr,ir->kr", J, x) if wide else x, dtype=np.float64)


def _step(
    problem: LMProblem, J: FloatArray, e: FloatArray, lam: FloatArray, q: FloatArray
) -> FloatArray:
    """One LM step, with the joints held at a limit they would leave outwards blocked.

    A joint on a clamp bound whose steepest-descent direction ``Jᵀe`` points
    outwards would only be clamped back, and the rest of the step would no
    longer fit its model; its column is zeroed, so its step is exactly 0 (the
    binding set of projected Newton methods).
    """
    if problem.clamped:
        g = np.einsum("ikr,ir->kr", J, e)
        blocked = ((q <= problem.lower[:, None]) & (g < 0.0)) | (
            (q >= problem.upper[:, None]) & (g > 0.0)
        )
        if blocked.any():
            J = J * ~blocked
    return _damped_solve(J, e, lam)


def _scaled_norms(problem: LMProblem, err: FloatArray) -> tuple[FloatArray, FloatArray]:
    """``(R,)`` position and rotation norms of ``err (m, R)`` scaled by ``check``."""
    sq = (err * problem.check[:, None]) ** 2
    return (
        np.sqrt(sq[problem.is_position].sum(axis=0)),
        np.sqrt(sq[~problem.is_position].sum(axis=0)),
    )


# ----------------------------------------------------------------- search
def search_batch(
    problem: LMProblem,
    p_target: FloatArray,
    R_target: FloatArray | None,
    start: FloatArray,
    restarts: int,
    sample: Sampler,
) -> SearchResult:
    """Search N targets together, restarting failed attempts (see module doc).

    Args:
        problem: The problem.
        p_target: ``(N, 3)`` target positions (base frame, m).
        R_target: ``(N, 3, 3)`` target rotations, or None for position targets.
        start: ``(N, n)`` first guesses.
        restarts: Random restarts allowed per target.
        sample: Draws restart configurations.

    Returns:
        The per-target result.
    """
    N, n = start.shape
    m = problem.rows.shape[0]
    w = problem.weight[:, None]
    W, F, K = STALL_WINDOW, STALL_FACTOR, problem.max_iterations
    best_q = np.array(start, dtype=float)
    best_score = np.full(N, np.inf)
    converged = np.zeros(N, dtype=bool)
    has_failed = np.zeros(N, dtype=bool)
    iterations = np.zeros(N, dtype=np.int64)
    attempts = np.ones(N, dtype=np.int64)
    left = np.full(N, restarts, dtype=np.int64)
    pt_all = np.ascontiguousarray(p_target.T)
    Rt_all = None if R_target is None else np.ascontiguousarray(R_target.transpose(1, 2, 0))

    # Rows, one per column. A fresh row has err = 0 and J = 0 (so its first
    # step is 0 and its first evaluation is of its start) and E = inf (so that
    # evaluation is accepted); k = -1 until then.
    tgt = np.arange(N)
    q = problem.project(best_q.T)
    J = np.zeros((m, n, N))
    err = np.zeros((m, N))
    E = np.full(N, np.inf)
    E_ref = E.copy()
    lam = np.full(N, LAMBDA_INIT)
    k = np.full(N, -1, dtype=np.int64)
    pt, Rt = pt_all, Rt_all
    for step in itertools.count(1):
        if not tgt.size:
            break
        q_new = problem.project(q + _step(problem, J, err * w, lam, q))
        err_new, J_new = evaluate(problem, q_new, pt, Rt)
        E_new = 0.5 * np.sum((err_new * w) ** 2, axis=0)
        better = E_new < E
        q = np.where(better, q_new, q)
        J = np.where(better, J_new, J)
        err = np.where(better, err_new, err)
        E = np.where(better, E_new, E)
        lam = np.where(
            k < 0,
            LAMBDA_INIT,
            np.where(better, np.maximum(lam * LAMBDA_DOWN, LAMBDA_MIN), lam * LAMBDA_UP),
        )
        k += 1
        iterations += np.bincount(tgt, minlength=N)
        E_ref = np.where(k == 0, E, E_ref)

        # Judge every row: converged, stalled, or out of steps or damping.
        pos, rot = _scaled_norms(problem, err)
        ok = (pos <= problem.tol_position) & (rot <= problem.tol_angle)
        window = (k > 0) & (k % W == 0)
        ended = ok | (window & (F * E_ref < E)) | (lam > LAMBDA_MAX) | (k >= K)
        E_ref = np.where(window, E, E_ref)
        if ok.any():
            converged[tgt[ok]] = True
            best_q[tgt[ok]] = q[:, ok].T
        failed = np.flatnonzero(ended & ~ok)
        if failed.size:
            has_failed[tgt[failed]] = True
            s = np.maximum(pos[failed] / problem.tol_position, rot[failed] / problem.tol_angle)
            order = np.argsort(-s, kind="stable")  # the best is written last and wins
            f, s = failed[order], s[order]
            improves = (s < best_score[tgt[f]]) & ~converged[tgt[f]]
            best_score[tgt[f[improves]]] = s[improves]
            best_q[tgt[f[improves]]] = q[:, f[improves]].T

        keep = ~ended & ~converged[tgt]
        if not keep.all():
            tgt, E, E_ref, lam, k = (a[keep] for a in (tgt, E, E_ref, lam, k))
            q, J, err, pt = q[:, keep], J[:, :, keep], err[:, keep], pt[:, keep]
            Rt = None if Rt is None else Rt[:, :, keep]

        # Restarts, while a target has some left: a row for every target left
        # without one, and spare rows (MIN_ROWS among them) for the targets
        # likely to be hard: failed before, or unsolved after SPARE_AFTER steps.
        count = np.bincount(tgt, minlength=N)
        live = ~converged & ((count > 0) | (left > 0))
        if not live.any():
            break
        hard = live & (has_failed | (step >= SPARE_AFTER))
        n_hard = int(hard.sum())
        want = np.where(hard, max(1, -(-MIN_ROWS // max(n_hard, 1))), 1)
        spawn = np.where(live, np.clip(want - count, 0, left), 0)
        total = int(spawn.sum())
        if total:
            new = np.repeat(np.arange(N), spawn)
            left -= spawn
            attempts += spawn
            tgt = np.concatenate([tgt, new])
            q = np.concatenate([q, problem.project(sample(total).T)], axis=1)
            J = np.concatenate([J, np.zeros((m, n, total))], axis=2)
            err = np.concatenate([err, np.zeros((m, total))], axis=1)
            E = np.concatenate([E, np.full(total, np.inf)])
            E_ref = np.concatenate([E_ref, np.full(total, np.inf)])
            lam = np.concatenate([lam, np.full(total, LAMBDA_INIT)])
            k = np.concatenate([k, np.full(total, -1, dtype=np.int64)])
            pt = np.concatenate([pt, pt_all[:, new]], axis=1)
            if Rt is not None and Rt_all is not None:
                Rt = np.concatenate([Rt, Rt_all[:, :, new]], axis=2)
    return SearchResult(best_q, converged, iterations, attempts)
