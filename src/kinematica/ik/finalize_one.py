"""The single-target path of :func:`kinematica.ik.finalize.finalize`, on Python floats.

For one target and a handful of candidates numpy's per-call cost dominates, so
the same checks run here on floats: wrap, check by FK at the tolerances, shift
into the limit window, drop duplicates, split by limits, sort, decide the
status. Whatever this path cannot settle alone (a candidate that needs
polishing, a mask) it hands back to the batched path by returning ``None``.
"""

from __future__ import annotations

import math
import weakref

import numpy as np
from numpy.typing import NDArray

from kinematica.ik.candidates import Candidates
from kinematica.ik.finalize import DEDUP_TOL, LIMIT_TOL, POLISH_LIMIT, Tolerance
from kinematica.ik.result import IKResult, status_message
from kinematica.robot import Robot

__all__ = ["finalize_one"]

FloatArray = NDArray[np.float64]
TWO_PI = 2.0 * math.pi


def _wrap(v: float) -> float:
    w = math.remainder(v, TWO_PI)  # in [-π, π]
    return math.pi if w == -math.pi else w + 0.0


def _rotation_angle(T: list[list[float]], Tt: list[list[float]]) -> float:
    """Angle of ``Rtᵀ R`` (rotation parts of ``Tt`` and ``T``) via atan2 (exact near 0)."""
    tr = vx = vy = vz = 0.0
    for (r0, r1, r2, _), (t0, t1, t2, _) in zip(T[:3], Tt[:3], strict=True):
        tr += t0 * r0 + t1 * r1 + t2 * r2
        vx += t2 * r1 - t1 * r2
        vy += t0 * r2 - t2 * r0
        vz += t1 * r0 - t0 * r1
    return math.atan2(0.5 * math.sqrt(vx * vx + vy * vy + vz * vz), 0.5 * (tr - 1.0))


def _same(q: list[float], other: list[float], rev: list[bool]) -> bool:
    for a, b, r in zip(q, other, rev, strict=True):
        d = a - b
        if r:
            d = math.remainder(d, TWO_PI)
        if abs(d) >= DEDUP_TOL:
            return False
    return True


# Per-robot constants of this path, as Python lists (a Robot is immutable).
_LIMITS: weakref.WeakKeyDictionary[
    Robot, tuple[list[bool], list[float], list[float], list[int]]
] = weakref.WeakKeyDictionary()


def _limits(robot: Robot) -> tuple[list[bool], list[float], list[float], list[int]]:
    """``(revolute?, lower, upper, revolute joints whose window leaves (−π, π])``."""
    if robot not in _LIMITS:
        rev = (~robot.is_prismatic).tolist()
        lo, hi = robot.qlim.T.tolist()
        shiftable = [i for i, r in enumerate(rev) if r and (lo[i] < -math.pi or hi[i] > math.pi)]
        _LIMITS[robot] = (rev, lo, hi, shiftable)
    return _LIMITS[robot]


def finalize_one(
    robot: Robot,
    target: FloatArray,
    cand: Candidates,
    *,
    method: str,
    complete: bool,
    respect_limits: bool,
    q0: FloatArray | None,
    tol: Tolerance,
) -> IKResult | None:
    """Check the candidates of one target; ``None`` if the batched path must.

    Args:
        robot: The robot.
        target: ``(4, 4)`` pose or ``(3,)`` position.
        cand: Candidates with ``q`` of shape ``(1, m, n)``.
        method: Method name.
        complete: The candidates are every solution there is.
        respect_limits: Keep solutions outside the limits apart.
        q0: ``(n,)`` configuration to sort by, or None.
        tol: Acceptance tolerances.
    """
    rev, lo, hi, shiftable = _limits(robot)
    pose = target.shape == (4, 4)
    Tt = target.tolist()
    p_t = [Tt[0][3], Tt[1][3], Tt[2][3]] if pose else Tt
    kept: list[tuple[list[float], str, float, float]] = []
    nearest = (math.nan, math.nan)
    nearest_norm = math.inf
    for q_raw, label in zip(cand.q[0].tolist(), cand.labels, strict=True):
        if math.isnan(sum(q_raw)):
            continue
        q = [_wrap(v) if r else v for v, r in zip(q_raw, rev, strict=True)]
        T = robot._chain.pose_rows(q)
        pos = math.dist((T[0][3], T[1][3], T[2][3]), p_t)
        rot = _rotation_angle(T, Tt) if pose else 0.0
        if pos > tol.position or rot > tol.rotation:
            if max(pos, rot) < POLISH_LIMIT:
                return None  # a near miss: the batched path polishes it
            if max(pos, rot) < nearest_norm:
                nearest, nearest_norm = (pos, rot), max(pos, rot)
            continue
        if respect_limits:
            for i in shiftable:  # revolute joints whose limit window leaves (−π, π]
                if q[i] < lo[i] - LIMIT_TOL and q[i] + TWO_PI <= hi[i] + LIMIT_TOL:
                    q[i] += TWO_PI
                elif q[i] > hi[i] + LIMIT_TOL and q[i] - TWO_PI >= lo[i] - LIMIT_TOL:
                    q[i] -= TWO_PI
        if not any(_same(q, other[0], rev) for other in kept):
            kept.append((q, label, pos, rot))

    def inside(q: list[float]) -> bool:
        return all(lo[i] - LIMIT_TOL <= v <= hi[i] + LIMIT_TOL for i, v in enumerate(q))

    if q0 is not None:
        ref = q0.tolist()

        def dist(item: tuple[list[float], str, float, float]) -> float:
            q = item[0]
            return math.sqrt(
                sum(
                    (_wrap(a - b) if r else a - b) ** 2 for a, b, r in zip(q, ref, rev, strict=True)
                )
            )

        kept.sort(key=dist)
    within = [not respect_limits or inside(k[0]) for k in kept]
    good = [k for k, w in zip(kept, within, strict=True) if w]
    bad = [k for k, w in zip(kept, within, strict=True) if not w]
    singular = bool(cand.singular[0])
    gap = float(cand.gap[0])
    if good:
        status = "singular" if singular else "ok"
    elif bad:
        status = "out_of_limits"
    elif complete or gap > 0:  # near misses went to the batched path: none is left
        status = "unreachable"
    else:
        status = "not_found"
    free = tuple(int(i) for i in np.flatnonzero(cand.free[0])) if status == "singular" else ()
    gap_out = gap if status == "unreachable" and math.isfinite(gap) else math.nan
    n = robot.dof
    return IKResult(
        solutions=np.array([k[0] for k in good], dtype=float).reshape(-1, n),
        status=status,  # type: ignore[arg-type]
        method=method,
        residuals=np.array([k[2:] for k in good], dtype=float).reshape(-1, 2),
        branches=tuple(k[1] for k in good),
        out_of_limits=np.array([k[0] for k in bad], dtype=float).reshape(-1, n),
        out_of_limits_branches=tuple(k[1] for k in bad),
        free_joints=free,
        gap=None if math.isnan(gap_out) else gap_out,
        message=status_message(
            status,
            method=method,
            count=len(good),
            out_of_limits=len(bad),
            free=free,
            gap=gap_out,
            nearest=nearest,
        ),
    )
