"""The Levenberg-Marquardt search of numeric IK, vectorised across targets.

The search works on *rows*: one attempt at one target each. All rows iterate
together as arrays; each iteration is one forward-kinematics-and-Jacobian
evaluation and one batch of small damped normal equations. A row leaves when
its attempt converges or fails; a target whose attempt failed gets a new row
from a random configuration (a restart) while it has restarts left. When few
targets remain, each gets several rows at once (:data:`MIN_ROWS`): a batch of
a few rows costs about as much per iteration as a batch of one, so running a
straggler's restarts side by side shortens the tail. A target is done as soon
as any of its rows converges. See :mod:`kinematica.ik.numeric` for the
algorithm and the public entry point.

Arrays are held "structure of arrays" where that saves numpy calls: frames as
``(3, R)`` columns, the Jacobian assembled as ``(m, n, R)`` then laid out as
``(R, m, n)`` for the batched solve.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from kinematica.dh import DHChain

__all__ = [
    "LAMBDA_DOWN",
    "LAMBDA_INIT",
    "LAMBDA_MAX",
    "LAMBDA_MIN",
    "LAMBDA_UP",
    "MIN_ROWS",
    "STALL_FACTOR",
    "STALL_WINDOW",
    "LMProblem",
    "Sampler",
    "SearchResult",
    "pose_error",
    "search_batch",
]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
BoolArray = NDArray[np.bool_]
#: ``sample(count)``: ``(count, n)`` random configurations for restarts.
Sampler = Callable[[int], FloatArray]

TWO_PI = 2.0 * math.pi

#: Initial damping, relative to the mean diagonal of the normal matrix: about
#: as strong as the Jacobian itself, a safe first step from a distant guess.
LAMBDA_INIT = 1.0
#: Damping factor after an accepted step (towards Gauss-Newton) ...
LAMBDA_DOWN = 0.1
#: ... and after a rejected one (towards short gradient steps).
LAMBDA_UP = 5.0
#: Smallest relative damping: negligible next to any singular value that
#: matters (so the last steps converge quadratically), yet it keeps the normal
#: matrix positive definite in floating point, rank-deficient Jacobian or not.
LAMBDA_MIN = 1e-12
#: Damping at which an attempt has stalled: even tiny gradient steps no longer
#: reduce the error (a local minimum, or the error is at round-off level).
LAMBDA_MAX = 1e8
#: Progress check: every STALL_WINDOW steps the squared error must have
#: dropped below STALL_FACTOR times its value at the previous check (the error
#: norm must halve), else the attempt has stalled and a restart is better.
STALL_WINDOW = 8
STALL_FACTOR = 0.25
#: Mean diagonal below which the normal matrix is treated as zero (every
#: column blocked, or a fresh row): its damping is then taken as absolute.
SCALE_FLOOR = 1e-300
#: Fewest rows the search keeps while targets have restarts left (see module doc).
MIN_ROWS = 128


@dataclass(frozen=True, eq=False)
class LMProblem:
    """Everything the kernels need about one call, prepared once.

    Attributes:
        chain: The robot's compiled DH chain (its regrouped link parameters).
        rows: ``(m,)`` indices in ``(x, y, z, rx, ry, rz)`` of the error
            components that count (mask weight > 0).
        weight: ``(m,)`` square roots of their weights: LM minimises
            ``½ Σ w_i e_i²``.
        check: ``(m,)`` scale of each component in the convergence test,
            ``max(w_i, 1)``: converged means the scaled norms are within the
            tolerances, hence so are both the plain and the weighted norms.
        is_position: ``(m,)`` True for rows 0-2 (metres), False for 3-5 (rad).
        wrap_base: ``(n,)`` start of each revolute joint's 2π window
            ``[wrap_base, wrap_base + 2π)``; unused for prismatic joints.
        lower: ``(n,)`` clamp bounds (−inf where none).
        upper: ``(n,)`` clamp bounds (+inf where none).
        tol_position: Convergence tolerance on the position error (m).
        tol_angle: Convergence tolerance on the rotation error (rad).
        max_iterations: Steps per attempt.
    """

    chain: DHChain
    rows: IntArray
    weight: FloatArray
    check: FloatArray
    is_position: BoolArray
    wrap_base: FloatArray
    lower: FloatArray
    upper: FloatArray
    tol_position: float
    tol_angle: float
    max_iterations: int

    @property
    def prismatic(self) -> BoolArray:
        """``(n,)`` True for prismatic joints."""
        return self.chain.prismatic

    @property
    def dof(self) -> int:
        """Number of joints n."""
        return self.chain.dof

    @property
    def orientation(self) -> bool:
        """True if any rotation component counts."""
        return not bool(np.all(self.is_position))

    def project(self, q: FloatArray) -> FloatArray:
        """Wrap revolute angles into their window, then clamp into the limits.

        A revolute angle beyond its upper limit (after wrapping into
        ``[lower, lower + 2π)``) goes to the nearer limit around the circle.

        Args:
            q: ``(R, n)`` joint values.

        Returns:
            ``(R, n)`` projected joint values.
        """
        revolute = ~self.prismatic
        base = self.wrap_base
        q = np.where(revolute, base + np.mod(q - base, TWO_PI), q)
        lo, hi = self.lower, self.upper
        over = q > hi
        if over.any():
            to_lower = revolute & (q - hi > lo + TWO_PI - q)
            q = np.where(over, np.where(to_lower, lo, hi), q)
        return np.maximum(q, lo)


@dataclass(frozen=True)
class SearchResult:
    """Per-target outcome of a search.

    Attributes:
        q: ``(N, n)`` the converged configuration, or the best failed one.
        converged: ``(N,)`` True where an attempt met the tolerances.
        iterations: ``(N,)`` evaluations spent on the target, all rows summed.
        attempts: ``(N,)`` attempts started (1 + restarts used).
    """

    q: FloatArray
    converged: BoolArray
    iterations: IntArray
    attempts: IntArray


# ------------------------------------------------------------ kinematics
def _rotate(X: FloatArray, Y: FloatArray, c: float, s: float) -> tuple[FloatArray, FloatArray]:
    """``(c X + s Y, c Y − s X)`` for constants, skipping exact zeros."""
    if s == 0.0:
        return (X, Y) if c == 1.0 else (-X, -Y)
    if c == 0.0:
        return (Y, -X) if s == 1.0 else (-Y, X)
    return c * X + s * Y, c * Y - s * X


def _frames(
    chain: DHChain, q: FloatArray
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray, FloatArray, FloatArray]:
    """Tool frame and joint axes, by the same regrouped product as ``DHChain``.

    Args:
        chain: The compiled chain.
        q: ``(R, n)`` joint values.

    Returns:
        ``(X, Y, Z, P, axes, points)``: the tool's rotation columns and origin,
        each ``(3, R)``; each joint's axis direction and a point on it, each
        ``(n, 3, R)``. All in the base frame.
    """
    n = chain.dof
    R = q.shape[0]
    qt = q.T
    prismatic = chain.prismatic
    theta = np.where(prismatic[:, None], chain.theta[:, None], qt + chain.theta[:, None])
    ct, st = np.cos(theta), np.sin(theta)
    S = chain.start
    ones = np.ones((1, R))
    X, Y, Z, P = S[:3, 0:1] * ones, S[:3, 1:2] * ones, S[:3, 2:3] * ones, S[:3, 3:4] * ones
    axes = np.empty((n, 3, R))
    points = np.empty((n, 3, R))
    for i in range(n):
        axes[i] = Z
        points[i] = P
        if prismatic[i]:
            X1, W = _rotate(X, Y, float(ct[i, 0]), float(st[i, 0]))
            P = P + (qt[i] + chain.d[i]) * Z
        else:
            c, s = ct[i], st[i]
            X1 = c * X + s * Y
            W = c * Y - s * X
            if chain.d[i] != 0.0:
                P = P + chain.d[i] * Z
        if chain.a[i] != 0.0:
            P = P + chain.a[i] * X1
        X = X1
        Y, Z = _rotate(W, Z, float(chain.ca[i]), float(chain.sa[i]))
    E = chain.end
    if not np.array_equal(E, np.eye(4)):
        X, Y, Z, P = (
            E[0, 0] * X + E[1, 0] * Y + E[2, 0] * Z,
            E[0, 1] * X + E[1, 1] * Y + E[2, 1] * Z,
            E[0, 2] * X + E[1, 2] * Y + E[2, 2] * Z,
            P + E[0, 3] * X + E[1, 3] * Y + E[2, 3] * Z,
        )
    return X, Y, Z, P, axes, points


def _rotvec(M: FloatArray) -> FloatArray:
    """Rotation vectors ``(3, R)`` of rotations ``M (3, 3, R)``, exact at 0 and near π.

    ``θ = atan2(|v|, (tr M − 1)/2)`` with ``v`` the skew part's vector; the axis
    comes from ``v`` up to π/2 and from the symmetric part beyond, where ``v``
    loses accuracy: the branches of :func:`kinematica.spatial.rotvec_from_matrix`,
    in this module's layout and without its validation.
    """
    v = 0.5 * np.stack([M[2, 1] - M[1, 2], M[0, 2] - M[2, 0], M[1, 0] - M[0, 1]])
    sin = np.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
    cos = 0.5 * (M[0, 0] + M[1, 1] + M[2, 2] - 1.0)
    angle = np.arctan2(sin, cos)
    rotvec = v * np.divide(angle, sin, out=np.ones_like(angle), where=sin > 0.0)
    near_pi = np.flatnonzero(cos < 0.0)
    if near_pi.size:
        # (M + Mᵀ)/2 − cos θ I = (1 − cos θ) n nᵀ: the column with the largest
        # diagonal is the best-conditioned multiple of n; its sign follows v.
        Mn = M[:, :, near_pi]
        S = 0.5 * (Mn + Mn.transpose(1, 0, 2)) - cos[near_pi] * np.eye(3)[:, :, None]
        col = np.argmax(np.stack([S[0, 0], S[1, 1], S[2, 2]]), axis=0)
        axis = S[:, col, np.arange(near_pi.size)]
        axis /= np.sqrt(np.sum(axis * axis, axis=0))
        axis *= np.where(np.sum(axis * v[:, near_pi], axis=0) < 0.0, -1.0, 1.0)
        rotvec[:, near_pi] = axis * angle[near_pi]
    return rotvec


def pose_error(
    problem: LMProblem,
    X: FloatArray,
    Y: FloatArray,
    Z: FloatArray,
    P: FloatArray,
    p_target: FloatArray,
    R_target: FloatArray | None,
) -> FloatArray:
    """The counted error components, unweighted.

    Args:
        problem: The problem.
        X: ``(3, R)`` the tool's x axis (base frame); Y and Z likewise.
        Y: ``(3, R)``.
        Z: ``(3, R)``.
        P: ``(3, R)`` the tool origin (m).
        p_target: ``(3, R)`` target positions.
        R_target: ``(3, 3, R)`` target rotations, or None for position targets.

    Returns:
        ``(m, R)``: the components ``problem.rows`` of ``(Δp, Δω)``, with
        ``Δp = p_target − p`` (m) and ``Δω`` the rotation vector of
        ``R_target · Rᵀ`` (rad), both in the base frame.
    """
    dp = p_target - P
    if R_target is None or not problem.orientation:
        return dp[problem.rows]
    # (R_target Rᵀ)[i, j] = Σ_k R_target[i, k] R[j, k], R's columns being X, Y, Z.
    M = np.stack([R_target[i, 0] * X + R_target[i, 1] * Y + R_target[i, 2] * Z for i in range(3)])
    return np.concatenate([dp, _rotvec(M)])[problem.rows]


def _evaluate(
    problem: LMProblem, q: FloatArray, p_target: FloatArray, R_target: FloatArray | None
) -> tuple[FloatArray, FloatArray]:
    """Counted errors ``(R, m)`` (unweighted) and weighted Jacobian rows ``(R, m, n)``.

    Column i of the geometric Jacobian is ``[z × (p − o); z]`` for a revolute
    joint with axis ``z`` through ``o``, ``[z; 0]`` for a prismatic one.
    """
    X, Y, Z, P, axes, points = _frames(problem.chain, q)
    err = pose_error(problem, X, Y, Z, P, p_target, R_target)
    d = P - points  # (n, 3, R)
    z0, z1, z2 = axes[:, 0], axes[:, 1], axes[:, 2]
    prismatic = problem.prismatic[:, None]
    has_prismatic = bool(problem.prismatic.any())
    columns = []
    for r in problem.rows.tolist():
        if r == 0:
            c = z1 * d[:, 2] - z2 * d[:, 1]
        elif r == 1:
            c = z2 * d[:, 0] - z0 * d[:, 2]
        elif r == 2:
            c = z0 * d[:, 1] - z1 * d[:, 0]
        else:
            c = axes[:, r - 3]
        if has_prismatic:
            c = np.where(prismatic, axes[:, r] if r < 3 else 0.0, c)
        columns.append(c)
    J = np.stack(columns) * problem.weight[:, None, None]  # (m, n, R)
    return err.T, np.ascontiguousarray(J.transpose(2, 0, 1))


# ------------------------------------------------------------------ steps
def _damped_solve(J: FloatArray, e: FloatArray, lam: FloatArray) -> FloatArray:
    """Damped least-squares steps ``argmin ‖J dq − e‖² + λ s ‖dq‖²``, batched.

    ``s`` is the mean diagonal of the normal matrix, which makes ``λ``
    dimensionless. The smaller system is solved: ``dq = Jᵀ (J Jᵀ + λs I)⁻¹ e``
    when ``m ≤ n`` (redundant or square), ``(JᵀJ + λs I)⁻¹ Jᵀ e`` otherwise;
    the two are the same step.

    Args:
        J: ``(R, m, n)`` weighted Jacobian rows.
        e: ``(R, m)`` weighted errors.
        lam: ``(R,)`` relative damping.

    Returns:
        ``(R, n)`` joint steps.
    """
    R, m, n = J.shape
    Jt = np.swapaxes(J, 1, 2)
    wide = m <= n
    A = J @ Jt if wide else Jt @ J
    k = A.shape[1]
    diag = A.reshape(R, k * k)[:, :: k + 1]  # a view of the diagonals (A is fresh)
    scale = diag.sum(axis=1) / k
    diag += (lam * np.where(scale > SCALE_FLOOR, scale, 1.0))[:, None]
    rhs = e[:, :, None] if wide else Jt @ e[:, :, None]
    try:
        x = np.asarray(np.linalg.solve(A, rhs), dtype=np.float64)
    except np.linalg.LinAlgError:  # pragma: no cover - the damping keeps A definite
        x = np.linalg.pinv(A) @ rhs
    return (Jt @ x)[:, :, 0] if wide else x[:, :, 0]


def _step(
    problem: LMProblem, J: FloatArray, e: FloatArray, lam: FloatArray, q: FloatArray
) -> FloatArray:
    """One LM step with the joints held at a limit they push against removed.

    A joint sitting on a clamp bound whose step points outwards would only be
    clamped back, and the rest of the step would no longer fit its model; it
    is blocked (its column zeroed, so its step is exactly 0) and the others'
    step recomputed.
    """
    dq = _damped_solve(J, e, lam)
    blocked = ((q <= problem.lower) & (dq < 0.0)) | ((q >= problem.upper) & (dq > 0.0))
    hit = np.flatnonzero(blocked.any(axis=1))
    if hit.size:
        Jb = J[hit] * ~blocked[hit][:, None, :]
        dq[hit] = _damped_solve(Jb, e[hit], lam[hit])
    return dq


def _scaled_norms(problem: LMProblem, err: FloatArray) -> tuple[FloatArray, FloatArray]:
    """``(R,)`` position and rotation norms of ``err (R, m)`` scaled by ``check``."""
    sq = (err * problem.check) ** 2
    return (
        np.sqrt(sq[:, problem.is_position].sum(axis=1)),
        np.sqrt(sq[:, ~problem.is_position].sum(axis=1)),
    )


def score(problem: LMProblem, err: FloatArray) -> FloatArray:
    """``(R,)`` worst scaled error relative to its tolerance (≤ 1: converged)."""
    pos, rot = _scaled_norms(problem, err)
    return np.maximum(pos / problem.tol_position, rot / problem.tol_angle)


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
    w = problem.weight
    W, F, K = STALL_WINDOW, STALL_FACTOR, problem.max_iterations
    best_q = np.array(start, dtype=float)
    best_score = np.full(N, np.inf)
    converged = np.zeros(N, dtype=bool)
    iterations = np.zeros(N, dtype=np.int64)
    attempts = np.ones(N, dtype=np.int64)
    left = np.full(N, restarts, dtype=np.int64)
    pt_all = np.ascontiguousarray(p_target.T)
    Rt_all = None if R_target is None else np.ascontiguousarray(R_target.transpose(1, 2, 0))

    # Rows. A fresh row has err = 0 and J = 0 (so its first step is 0 and its
    # first evaluation is of its start) and E = inf (so that one is accepted).
    tgt = np.arange(N)
    q = problem.project(best_q)
    J = np.zeros((N, m, n))
    err = np.zeros((N, m))
    E = np.full(N, np.inf)
    E_ref = E.copy()
    lam = np.full(N, LAMBDA_INIT)
    k = np.full(N, -1, dtype=np.int64)
    pt, Rt = pt_all, Rt_all
    while tgt.size:
        dq = _step(problem, J, err * w, lam, q)
        q_new = problem.project(q + dq)
        err_new, J_new = _evaluate(problem, q_new, pt, Rt)
        E_new = 0.5 * np.sum((err_new * w) ** 2, axis=1)
        better = E_new < E
        q = np.where(better[:, None], q_new, q)
        J = np.where(better[:, None, None], J_new, J)
        err = np.where(better[:, None], err_new, err)
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
            best_q[tgt[ok]] = q[ok]
        failed = np.flatnonzero(ended & ~ok)
        if failed.size:
            s = np.maximum(pos[failed] / problem.tol_position, rot[failed] / problem.tol_angle)
            order = np.argsort(-s, kind="stable")  # the best written last wins
            f, s = failed[order], s[order]
            improves = (s < best_score[tgt[f]]) & ~converged[tgt[f]]
            best_score[tgt[f[improves]]] = s[improves]
            best_q[tgt[f[improves]]] = q[f[improves]]

        keep = ~ended & ~converged[tgt]
        if not keep.all():
            tgt, q, J, err, E, E_ref, lam, k = (a[keep] for a in (tgt, q, J, err, E, E_ref, lam, k))
            pt = pt[:, keep]
            Rt = None if Rt is None else Rt[:, :, keep]

        # Restarts: a row for every target left without one, and spare rows
        # for the last few targets (MIN_ROWS in all), while restarts remain.
        count = np.bincount(tgt, minlength=N)
        live = ~converged & ((count > 0) | (left > 0))
        n_live = int(live.sum())
        if n_live == 0:
            break
        want = max(1, -(-MIN_ROWS // n_live))
        spawn = np.where(live, np.clip(want - count, 0, left), 0)
        total = int(spawn.sum())
        if total:
            new_t = np.repeat(np.arange(N), spawn)
            left -= spawn
            attempts += spawn
            tgt = np.concatenate([tgt, new_t])
            q = np.concatenate([q, problem.project(sample(total))])
            J = np.concatenate([J, np.zeros((total, m, n))])
            err = np.concatenate([err, np.zeros((total, m))])
            E = np.concatenate([E, np.full(total, np.inf)])
            E_ref = np.concatenate([E_ref, np.full(total, np.inf)])
            lam = np.concatenate([lam, np.full(total, LAMBDA_INIT)])
            k = np.concatenate([k, np.full(total, -1, dtype=np.int64)])
            pt = np.concatenate([pt, pt_all[:, new_t]], axis=1)
            if Rt is not None and Rt_all is not None:
                Rt = np.concatenate([Rt, Rt_all[:, :, new_t]], axis=2)
    return SearchResult(best_q, converged, iterations, attempts)
