"""From raw candidates to checked, distinct, limit-aware IK results (batched).

Every candidate is judged by forward kinematics against the target at the
named tolerances, never by a solver's own flag. Candidates a little off (from
round-off near a double root) get a few Gauss-Newton steps first; they count
only if they then meet the tolerance.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from kinematica.ik.candidates import Candidates
from kinematica.ik.result import IKBatchResult
from kinematica.robot import Robot
from kinematica.spatial import rotation_angle, se3_error, wrap_angle

__all__ = ["POSITION_TOL", "ROTATION_TOL", "Tolerance", "finalize"]

FloatArray = NDArray[np.float64]

#: A solution must put the tool within this distance of the target (metres).
POSITION_TOL = 1e-10
#: ... and within this rotation angle of the target orientation (radians).
ROTATION_TOL = 1e-10
#: Candidates whose residual is below this (m or rad) but above the tolerance
#: are polished by Gauss-Newton steps before being judged.
POLISH_LIMIT = 1e-5
#: Gauss-Newton steps for polishing: quadratic convergence from 1e-5 needs 2-3.
POLISH_STEPS = 4
#: Two solutions closer than this in every joint (rad or m, angles modulo 2π)
#: are the same solution.
DEDUP_TOL = 1e-7
#: Slack on joint limits for values computed by floating point (rad or m).
LIMIT_TOL = 1e-12


@dataclass(frozen=True)
class Tolerance:
    """Acceptance tolerances of a solution: position (m) and rotation (rad)."""

    position: float = POSITION_TOL
    rotation: float = ROTATION_TOL


def _residuals(
    robot: Robot, q: FloatArray, targets: FloatArray, mask: FloatArray | None
) -> tuple[FloatArray, FloatArray]:
    """Position and rotation errors of configurations ``q (K, n)`` vs ``targets``.

    ``targets`` are ``(K, 4, 4)`` poses or ``(K, 3)`` positions. With a mask the
    errors are norms of the masked (position, rotation-vector) error parts.
    """
    T = robot.fk(q)
    if targets.ndim == 2:
        return np.linalg.norm(T[:, :3, 3] - targets, axis=-1), np.zeros(len(q))
    if mask is None:
        pos = np.linalg.norm(T[:, :3, 3] - targets[:, :3, 3], axis=-1)
        return pos, rotation_angle(T[:, :3, :3], targets[:, :3, :3])
    e = se3_error(T, targets) * mask
    return np.linalg.norm(e[:, :3], axis=-1), np.linalg.norm(e[:, 3:], axis=-1)


def _polish(
    robot: Robot, q: FloatArray, targets: FloatArray, mask: FloatArray | None
) -> FloatArray:
    """A few Gauss-Newton steps on ``q (K, n)`` towards ``targets``."""
    rows = np.ones(6) if mask is None else mask
    if targets.ndim == 2:
        rows = np.array([1.0, 1, 1, 0, 0, 0])
    rev = ~robot.is_prismatic
    for _ in range(POLISH_STEPS):
        T = robot.fk(q)
        if targets.ndim == 2:
            e = np.concatenate([targets - T[:, :3, 3], np.zeros((len(q), 3))], axis=-1)
        else:
            e = se3_error(T, targets)
        J = robot.jacobian(q) * rows[:, None]
        dq = np.einsum("kij,kj->ki", np.linalg.pinv(J, rcond=1e-12), e * rows)
        q = q + dq
        q[:, rev] = wrap_angle(q[:, rev])
    return q


def _shift_into_limits(
    q: FloatArray, lo: FloatArray, hi: FloatArray, rev: NDArray[np.bool_]
) -> FloatArray:
    """Move revolute angles by ±2π into their limit window where that helps."""
    two_pi = 2.0 * np.pi
    up = rev & (q < lo - LIMIT_TOL) & (q + two_pi <= hi + LIMIT_TOL)
    down = rev & (q > hi + LIMIT_TOL) & (q - two_pi >= lo - LIMIT_TOL)
    return np.where(up, q + two_pi, np.where(down, q - two_pi, q))


def _joint_diff(a: FloatArray, b: FloatArray, rev: NDArray[np.bool_]) -> FloatArray:
    d = a - b
    return np.where(rev, wrap_angle(d), d)


def _order(keep: NDArray[np.bool_], key: FloatArray) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
    """Slot order putting kept slots first, sorted by ``key``; and the counts."""
    order = np.argsort(np.where(keep, key, np.inf), axis=1, kind="stable")
    return order, keep.sum(axis=1).astype(np.int64)


def _gather(values: FloatArray, order: NDArray[np.int64], count: NDArray[np.int64]) -> FloatArray:
    """``values (N, m, d)`` reordered by ``order``, cut to the largest count, NaN-padded."""
    k = int(count.max(initial=0))
    out = np.take_along_axis(values, order[:, :k, None], axis=1)
    out[np.arange(k)[None, :] >= count[:, None]] = np.nan
    return out


def _labels(
    labels: tuple[str, ...], order: NDArray[np.int64], count: NDArray[np.int64]
) -> NDArray[np.str_]:
    """Branch labels of the reordered slots, ``""`` where padded."""
    k = int(count.max(initial=0))
    out = np.asarray(labels, dtype=str)[order[:, :k]]
    out[np.arange(k)[None, :] >= count[:, None]] = ""
    return out


def finalize(
    robot: Robot,
    targets: FloatArray,
    cand: Candidates,
    *,
    method: str,
    complete: bool,
    respect_limits: bool = True,
    q0: FloatArray | None = None,
    mask: FloatArray | None = None,
    tol: Tolerance | None = None,
) -> IKBatchResult:
    """Check, wrap, deduplicate, limit-filter and sort candidate solutions.

    Args:
        robot: The robot.
        targets: ``(N, 4, 4)`` poses or ``(N, 3)`` positions (base frame).
        cand: The solver's candidates, ``cand.q`` of shape ``(N, m, n)``.
        method: Method name for the result.
        complete: True when the candidates are every solution there is (a
            closed form): no checked solution then proves the target unreachable.
        respect_limits: Keep solutions outside the joint limits apart.
        q0: ``(n,)`` or ``(N, n)`` configuration to sort solutions by distance to.
        mask: ``(6,)`` weights of the error components, or None for all.
        tol: Acceptance tolerances.

    Returns:
        The batch result.
    """
    tol = tol or Tolerance()
    N, m, n = cand.q.shape
    rev = ~robot.is_prismatic
    q = cand.q.copy()
    q[..., rev] = wrap_angle(q[..., rev])
    valid = np.all(np.isfinite(q), axis=-1)

    # Residuals of every real candidate, with polishing of the near misses.
    pos = np.full((N, m), np.inf)
    rot = np.full((N, m), np.inf)
    rows, slots = np.nonzero(valid)
    if rows.size:
        tgt = targets[rows]
        flat = q[rows, slots]
        p_err, r_err = _residuals(robot, flat, tgt, mask)
        near = ((p_err > tol.position) | (r_err > tol.rotation)) & (
            np.maximum(p_err, r_err) < POLISH_LIMIT
        )
        if np.any(near):
            flat[near] = _polish(robot, flat[near], tgt[near], mask)
            p_err[near], r_err[near] = _residuals(robot, flat[near], tgt[near], mask)
        q[rows, slots] = flat
        pos[rows, slots], rot[rows, slots] = p_err, r_err
    solved = valid & (pos <= tol.position) & (rot <= tol.rotation)

    # Duplicates (modulo 2π): a slot repeating an earlier solved slot is dropped.
    # Angles are in (−π, π] here, so a difference d wraps to min(|d|, 2π − |d|).
    later, earlier = np.tril_indices(m, k=-1)  # every pair (i < j) once
    diff = np.abs(q[:, later] - q[:, earlier])  # (N, pairs, n)
    diff = np.where(rev, np.minimum(diff, 2.0 * np.pi - diff), diff)
    same = np.all(diff < DEDUP_TOL, axis=-1) & solved[:, earlier]
    dup = np.zeros((N, m, m), dtype=bool)
    dup[:, later, earlier] = same
    solved &= ~dup.any(axis=-1)

    qlim = robot.qlim
    lo, hi = qlim[:, 0], qlim[:, 1]
    if respect_limits:
        q = np.where(solved[..., None], _shift_into_limits(q, lo, hi, rev), q)
    inside = np.all((q >= lo - LIMIT_TOL) & (q <= hi + LIMIT_TOL), axis=-1)
    if not respect_limits:
        inside = np.ones_like(inside)
    keep_in, keep_out = solved & inside, solved & ~inside

    if q0 is None:
        key = np.broadcast_to(np.arange(m, dtype=float), (N, m))
    else:
        q0b = np.broadcast_to(np.asarray(q0, dtype=float), (N, n))
        key = np.linalg.norm(_joint_diff(q, q0b[:, None, :], rev), axis=-1)
        key = np.where(np.isfinite(key), key, np.inf)
    res = np.stack([pos, rot], axis=-1)
    order, count = _order(keep_in, key)
    oorder, ocount = _order(keep_out, key)
    sol, resid, br = (
        _gather(q, order, count),
        _gather(res, order, count),
        _labels(cand.labels, order, count),
    )
    osol, obr = _gather(q, oorder, ocount), _labels(cand.labels, oorder, ocount)

    # Status, honestly: "unreachable" only when the candidates were complete and
    # none came close, or the solver proved the target out of reach (gap > 0); a
    # near miss that would not converge, or a failed search, is "not_found".
    close = np.any(valid & (np.maximum(pos, rot) < POLISH_LIMIT), axis=1)
    none_left = (count == 0) & (ocount == 0)
    status = np.where(
        count > 0,
        np.where(cand.singular, "singular", "ok"),
        np.where(
            ocount > 0,
            "out_of_limits",
            np.where((complete & ~close) | (cand.gap > 0), "unreachable", "not_found"),
        ),
    )
    unsolved_err = np.where(valid & ~solved, np.maximum(pos, 0), np.inf)
    best = np.argmin(np.where(np.isfinite(unsolved_err), unsolved_err, np.inf), axis=1)
    nearest = res[np.arange(N), best]
    nearest[~np.any(valid & ~solved, axis=1)] = np.nan
    gap = np.where((status == "unreachable") & none_left, cand.gap, np.nan)
    free = cand.free & (status == "singular")[:, None]
    return IKBatchResult(
        solutions=sol,
        count=count,
        status=status.astype(str),
        method=method,
        residuals=resid,
        branches=br,
        out_of_limits=osol,
        out_of_limits_count=ocount,
        out_of_limits_branches=obr,
        free=free,
        gap=gap,
        nearest_error=nearest,
    )
