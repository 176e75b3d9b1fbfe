"""``robot.ik``: choose a solver, run it on a batch of targets, check the answers."""

from __future__ import annotations

import dataclasses
import math
import weakref
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.errors import DimensionError, KinematicaError
from kinematica.ik.analytic import find_solver
from kinematica.ik.candidates import AnalyticSolver
from kinematica.ik.finalize import Tolerance, finalize
from kinematica.ik.finalize_one import finalize_one
from kinematica.ik.numeric import solve_numeric
from kinematica.ik.result import IKBatchResult, IKResult
from kinematica.robot import Robot, classify
from kinematica.spatial import ORTHONORMAL_TOL, check_transform

__all__ = ["Method", "solve_ik"]

FloatArray = NDArray[np.float64]
Method = Literal["auto", "analytic", "numeric"]

# Closed-form solvers are built once per robot (a Robot is immutable, so the
# solver is a pure function of it); the cache forgets a robot when it dies.
_SOLVERS: weakref.WeakKeyDictionary[Robot, dict[bool, AnalyticSolver | None]] = (
    weakref.WeakKeyDictionary()
)


def _solver(robot: Robot, position_only: bool) -> AnalyticSolver | None:
    per_robot = _SOLVERS.setdefault(robot, {})
    if position_only not in per_robot:
        per_robot[position_only] = find_solver(robot, position_only=position_only)
    return per_robot[position_only]


def _parse_targets(target: ArrayLike) -> tuple[FloatArray, bool, bool, dict[int, str]]:
    """Return ``(targets (N, 4, 4) or (N, 3), single, position_only, bad rows)``.

    A single malformed target raises. In a batch, malformed rows are reported
    (row -> what is wrong) and replaced by a harmless placeholder, so that the
    other rows are still solved.
    """
    try:
        arr = np.asarray(target, dtype=float)
    except (TypeError, ValueError) as exc:
        raise DimensionError(f"target must be numbers, got {target!r}") from exc
    if arr.shape == (3,) or (arr.ndim == 2 and arr.shape[-1] == 3):
        if arr.ndim == 1:
            if not np.all(np.isfinite(arr)):
                raise DimensionError("target position holds NaN or inf")
            return arr.reshape(1, 3), True, True, {}
        bad_rows = np.flatnonzero(~np.all(np.isfinite(arr), axis=-1))
        problems = {int(i): f"target row {i}: position holds NaN or inf" for i in bad_rows}
        arr = arr.copy()
        arr[bad_rows] = 0.0
        return arr, False, True, problems
    if arr.shape == (4, 4):
        if not _rigid(arr.tolist()):
            check_transform(arr, name="target")  # raises, saying what is wrong
        return arr[None], True, False, {}
    if arr.ndim == 3 and arr.shape[-2:] == (4, 4):
        try:
            return check_transform(arr, name="target"), False, False, {}
        except DimensionError:
            pass  # some rows are malformed: find them all, say what is wrong with each
        problems = {}
        for i in _malformed_rows(arr):
            try:
                check_transform(arr[i], name=f"target row {i}")
            except DimensionError as exc:
                problems[int(i)] = str(exc)
        if problems:
            arr = arr.copy()
            arr[list(problems)] = np.eye(4)
        return arr, False, False, problems
    raise DimensionError(
        "target must be a pose (4, 4), a position (3,), or batches (N, 4, 4) / (N, 3); "
        f"got shape {arr.shape}"
    )


def _rigid(T: list[list[float]]) -> bool:
    """One 4x4 pose (as lists) is a rigid transform, checked on floats (fast path)."""
    if not all(math.isfinite(v) for row in T for v in row):
        return False
    if max(abs(a - b) for a, b in zip(T[3], (0.0, 0.0, 0.0, 1.0), strict=True)) > ORTHONORMAL_TOL:
        return False
    cols = [[T[0][j], T[1][j], T[2][j]] for j in range(3)]
    for i in range(3):
        for j in range(i, 3):
            dot = sum(a * b for a, b in zip(cols[i], cols[j], strict=True))
            if abs(dot - (1.0 if i == j else 0.0)) > ORTHONORMAL_TOL:
                return False
    x, y, z = cols
    det = (
        x[0] * (y[1] * z[2] - y[2] * z[1])
        - y[0] * (x[1] * z[2] - x[2] * z[1])
        + z[0] * (x[1] * y[2] - x[2] * y[1])
    )
    return det > 0.0


def _malformed_rows(T: FloatArray) -> NDArray[np.intp]:
    """Indices of the ``(N, 4, 4)`` rows that are not rigid transforms."""
    finite = np.all(np.isfinite(T), axis=(-1, -2))
    Tf = np.where(finite[:, None, None], T, np.eye(4))
    R = Tf[:, :3, :3]
    gram = np.abs(np.swapaxes(R, -1, -2) @ R - np.eye(3)).max(axis=(-1, -2))
    last = np.abs(Tf[:, 3] - [0.0, 0.0, 0.0, 1.0]).max(axis=-1)
    ok = finite & (gram <= ORTHONORMAL_TOL) & (last <= ORTHONORMAL_TOL)
    ok &= np.linalg.det(R) > 0
    return np.flatnonzero(~ok)


def _mark_invalid(result: IKBatchResult, problems: dict[int, str]) -> IKBatchResult:
    """Blank the rows whose targets were malformed and say why."""
    if not problems:
        return result
    rows = list(problems)
    count, ocount = result.count.copy(), result.out_of_limits_count.copy()
    status = result.status.astype(object)
    sol, osol = result.solutions.copy(), result.out_of_limits.copy()
    count[rows] = ocount[rows] = 0
    status[rows] = "invalid"
    sol[rows] = np.nan
    osol[rows] = np.nan
    return dataclasses.replace(
        result,
        solutions=sol,
        count=count,
        status=status.astype(str),
        out_of_limits=osol,
        out_of_limits_count=ocount,
        errors=problems,
    )


def _parse_mask(mask: ArrayLike | None) -> FloatArray | None:
    if mask is None:
        return None
    m = np.asarray(mask, dtype=float)
    if m.shape != (6,) or not np.all(np.isfinite(m)) or np.any(m < 0):
        raise DimensionError(
            "mask must be 6 non-negative weights for x, y, z, rx, ry, rz; "
            f"got {np.asarray(mask).tolist()}"
        )
    return None if np.all(m == 1.0) else m


def solve_ik(
    robot: Robot,
    target: ArrayLike,
    *,
    method: Method = "auto",
    respect_limits: bool = True,
    q0: ArrayLike | None = None,
    mask: ArrayLike | None = None,
    seed: int | np.random.Generator | None = None,
    tol: Tolerance | None = None,
) -> IKResult | IKBatchResult:
    """Every inverse-kinematics solution of a target, or an honest status.

    In a batch, a malformed target (NaN, not a rigid transform) does not stop
    the others: its row gets the status ``"invalid"`` and a message saying what
    is wrong with it.

    Args:
        robot: The robot.
        target: A pose ``(4, 4)`` (tool in the base frame), a position ``(3,)``
            (tool origin; orientation free), or batches ``(N, 4, 4)`` / ``(N, 3)``.
        method: ``"auto"`` (closed form when the structure allows, else
            numeric), ``"analytic"`` or ``"numeric"``.
        respect_limits: Keep solutions outside the joint limits apart
            (``out_of_limits``) rather than among ``solutions``.
        q0: ``(n,)`` or ``(N, n)``: the numeric initial guess, and the
            configuration solutions are sorted by distance to.
        mask: ``(6,)`` weights of the error components x, y, z, rx, ry, rz
            (numeric only); e.g. ``[1, 1, 1, 0, 0, 1]``.
        seed: Seed of the numeric restarts.
        tol: Acceptance tolerances (default 1e-10 m and 1e-10 rad).

    Returns:
        An :class:`IKResult` for one target, an :class:`IKBatchResult` for a batch.

    Raises:
        DimensionError: On malformed targets, ``q0`` or ``mask``.
        KinematicaError: ``method="analytic"`` for a structure with no closed form.
    """
    if method not in ("auto", "analytic", "numeric"):
        raise KinematicaError(f"method must be 'auto', 'analytic' or 'numeric', got {method!r}")
    targets, single, position_only, problems = _parse_targets(target)
    m = _parse_mask(mask)
    q0a = None if q0 is None else robot.check_q(q0, name="q0")
    if q0a is not None and q0a.ndim == 2 and q0a.shape[0] != targets.shape[0]:
        raise DimensionError(f"q0 has {q0a.shape[0]} rows for {targets.shape[0]} targets")
    if q0a is not None and q0a.ndim > 2:
        raise DimensionError(f"q0 must be (n,) or (N, n), got shape {q0a.shape}")

    solver = None
    if method != "numeric" and m is None:
        solver = _solver(robot, position_only)
        if solver is None and not position_only and robot.dof < 6:
            # A reduced arm: solve the position in closed form, check the whole pose.
            solver = _solver(robot, True)
    if method == "analytic" and solver is None:
        why = "a mask was given" if m is not None else f"structure: {classify(robot).summary}"
        raise KinematicaError(
            f"no closed-form solver for {robot.name} ({why}); use method='numeric'"
        )

    tol = tol or Tolerance()
    if solver is not None:
        solver_targets = (
            targets[:, :3, 3] if solver.position_only and not position_only else targets
        )
        cand = solver.solve(solver_targets)
        if single:
            one = finalize_one(
                robot,
                targets[0],
                cand,
                method=f"analytic:{solver.name}",
                complete=True,
                respect_limits=respect_limits,
                q0=None if q0a is None else q0a.reshape(-1, robot.dof)[0],
                tol=tol,
            )
            if one is not None:
                return one
        result = finalize(
            robot,
            targets,
            cand,
            method=f"analytic:{solver.name}",
            complete=True,
            respect_limits=respect_limits,
            q0=q0a,
            tol=tol,
        )
    else:
        cand = solve_numeric(
            robot,
            targets,
            q0=q0a,
            mask=m,
            seed=seed,
            tol_position=tol.position,
            tol_angle=tol.rotation,
            respect_limits=respect_limits,
            position_only=position_only,
        )
        result = finalize(
            robot,
            targets,
            cand,
            method="numeric:lm",
            complete=False,
            respect_limits=respect_limits,
            q0=q0a,
            mask=m,
            tol=tol,
        )
    return result[0] if single else _mark_invalid(result, problems)
