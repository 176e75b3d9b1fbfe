"""Numeric inverse kinematics on any serial chain, batched across targets.

Levenberg-Marquardt (damped least squares) on the pose error
``e = (Δp, Δω)`` in the base frame, ``Δp = p_target − p`` in metres and ``Δω``
the rotation vector of ``R_target · Rᵀ`` in radians, with the geometric
base-frame Jacobian ``J``. Each step solves
``(JᵀWJ + λ s I) Δq = JᵀW e``, in its ``m × m`` form ``Δq = Jᵀ(JJᵀ + λ s I)⁻¹e``
when the arm is redundant; ``W`` holds the mask weights and ``s`` the mean
diagonal of the normal matrix, so ``λ`` is dimensionless.

* A step that lowers ``½ eᵀWe`` is accepted and ``λ`` shrinks tenfold, so the
  last steps are Gauss-Newton steps, which converge quadratically to the
  1e-10 tolerances; a step that does not is rejected and ``λ`` grows fivefold.
* With only some rotation components counted, ``Δω`` need not vanish at a
  solution and its rows use the exact derivative ``−J_r⁻¹(Δω) J_ω``.
* Joint limits by projection: revolute angles are wrapped into a 2π window
  starting at the lower limit and clamped to the nearer limit around the
  circle; prismatic joints are clipped. A joint on a limit that the
  steepest-descent direction pushes outwards is blocked (its column zeroed)
  before the step, so the step matches its model.
* An attempt stops when it converges, when ``λ`` exceeds ``LAMBDA_MAX``, when
  the error norm has not halved over ``STALL_WINDOW`` steps (a local minimum),
  or after ``max_iterations`` steps (constants in
  :mod:`~kinematica.ik.numeric_problem`).
* A target whose attempt failed restarts from a random configuration, uniform
  within the limits (a prismatic joint without limits: ±:data:`PRISMATIC_SPAN`
  of zero, or ``2·PRISMATIC_SPAN`` from its one limit); the restarts come from
  ``seed``, so results are reproducible.

Targets iterate together as arrays (:mod:`~kinematica.ik.numeric_batch`); a
single target runs on Python floats (:mod:`~kinematica.ik.numeric_single`),
where numpy's per-call cost would dominate. Either way a slot is filled only
when the robot's own forward kinematics, at the end, puts the tool within
the tolerances (and the joints within their limits when ``respect_limits``).
A failed search is not a proof that the target is unreachable, except for a
target beyond the arm's reach (a bound from the DH lengths): that one is not
searched, and ``gap`` says by how much it is out of reach.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.errors import DimensionError, KinematicaError
from kinematica.ik.candidates import Candidates
from kinematica.ik.numeric_batch import search_batch
from kinematica.ik.numeric_model import pose_error
from kinematica.ik.numeric_problem import PRISMATIC_SPAN, Setup, compile_setup
from kinematica.ik.numeric_single import residuals_single, search_single
from kinematica.robot import Robot
from kinematica.spatial import check_transform, wrap_angle

__all__ = [
    "DEFAULT_MAX_ITERATIONS",
    "DEFAULT_RESTARTS",
    "DEFAULT_SEED",
    "PRISMATIC_SPAN",
    "NumericDetails",
    "solve_numeric",
    "solve_numeric_detailed",
]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

#: Steps per attempt. A converging attempt rarely needs more than 30; most
#: failing ones are stopped earlier by the stall test.
DEFAULT_MAX_ITERATIONS = 60
#: Restarts (from random configurations) for a target whose attempts failed.
#: Most targets need none; the hardest reachable ones seen (near the limits of
#: a 7-DOF arm, one pose in a few hundred) have 2-5 % of random starts
#: succeeding, and one in a few thousand used more than 100. An unreachable
#: target inside the reach bound costs them all.
DEFAULT_RESTARTS = 200
#: Seed of the restarts when none is given: results are reproducible.
DEFAULT_SEED = 0
#: The one label of the numeric solver's single candidate slot.
LABEL = "numeric"


@dataclass(frozen=True)
class NumericDetails:
    """Numeric IK candidates with the search's own figures.

    Attributes:
        candidates: The candidates (one slot, ``q`` of shape ``(N, 1, n)``).
        iterations: ``(N,)`` evaluations of the error and Jacobian spent on the
            target (one per attempt plus one per LM step), over all attempts.
        attempts: ``(N,)`` attempts made (1 + restarts used; 0 when the target
            is beyond the arm's reach and was not searched).
        position_error: ``(N,)`` position residual (m) of the returned or, on
            failure, the best configuration, by forward kinematics with the mask
            applied; NaN when not searched.
        angle_error: ``(N,)`` rotation residual (rad), likewise.
    """

    candidates: Candidates
    iterations: IntArray
    attempts: IntArray
    position_error: FloatArray
    angle_error: FloatArray


def solve_numeric(
    robot: Robot,
    targets: ArrayLike,
    *,
    q0: ArrayLike | None = None,
    mask: ArrayLike | None = None,
    seed: int | np.random.Generator | None = None,
    tol_position: float = 1e-10,
    tol_angle: float = 1e-10,
    max_iterations: int = DEFAULT_MAX_ITERATIONS,
    restarts: int = DEFAULT_RESTARTS,
    respect_limits: bool = True,
    position_only: bool = False,
) -> Candidates:
    """Numeric IK of N targets: one converged configuration each, or NaN.

    Args:
        robot: Any serial arm (redundant, prismatic, fewer than 6 joints).
        targets: ``(N, 4, 4)`` tool poses in the base frame (a single ``(4, 4)``
            is a batch of 1); with ``position_only``, ``(N, 3)`` tool positions
            (poses are accepted and their rotation ignored).
        q0: ``(n,)`` or ``(N, n)`` initial guess (projected into the limits
            when ``respect_limits``); default the middle of the joint limits
            (0 for joints without limits).
        mask: ``(6,)`` non-negative weights of the error components
            ``x, y, z, rx, ry, rz`` (base frame; a 0 frees that component).
            ``rx, ry, rz`` are components of the rotation vector of
            ``R_target · Rᵀ``. Default all 1.
        seed: Seed (or generator) of the random restarts; ``None`` means
            :data:`DEFAULT_SEED`, so results are reproducible.
        tol_position: Converged when the position error is within this (m)...
        tol_angle: ... and the rotation error within this (rad); both as
            norms of the counted components, each scaled by ``max(w, 1)``
            (so both the plain and the weighted errors are within them). The
            search reaches ~1e-15; much below 1e-13 it may not converge.
        max_iterations: LM steps per attempt.
        restarts: Random restarts allowed per target whose attempts failed.
        respect_limits: Keep the joints within ``robot.qlim``; otherwise only
            wrap revolute angles to (−π, π].
        position_only: Solve for the tool origin only: the mask is
            ``[1, 1, 1, 0, 0, 0]`` (or ``mask`` with its rotation part zeroed).

    Returns:
        Candidates with one slot labelled ``"numeric"``: ``q (N, 1, n)``, NaN
        where the search failed; ``singular`` and ``free`` all False; ``gap``
        NaN where solved, 0 (unknown) where the search failed, and a positive
        lower bound (m) where the target is beyond the arm's reach.

    Raises:
        DimensionError: Malformed ``targets``, ``q0`` or ``mask``.
        KinematicaError: Non-positive tolerances, iterations or restarts.
    """
    return solve_numeric_detailed(
        robot,
        targets,
        q0=q0,
        mask=mask,
        seed=seed,
        tol_position=tol_position,
        tol_angle=tol_angle,
        max_iterations=max_iterations,
        restarts=restarts,
        respect_limits=respect_limits,
        position_only=position_only,
    ).candidates


def solve_numeric_detailed(
    robot: Robot,
    targets: ArrayLike,
    *,
    q0: ArrayLike | None = None,
    mask: ArrayLike | None = None,
    seed: int | np.random.Generator | None = None,
    tol_position: float = 1e-10,
    tol_angle: float = 1e-10,
    max_iterations: int = DEFAULT_MAX_ITERATIONS,
    restarts: int = DEFAULT_RESTARTS,
    respect_limits: bool = True,
    position_only: bool = False,
) -> NumericDetails:
    """:func:`solve_numeric` with the iteration counts and residuals.

    Takes the same arguments as :func:`solve_numeric`.

    Returns:
        The candidates, ``(N,)`` iterations and attempts, and ``(N,)``
        position (m) and rotation (rad) residuals.
    """
    p_t, R_t = _parse_targets(targets, position_only)
    N, n = p_t.shape[0], robot.dof
    weights = _parse_mask(mask, position_only)
    _check_settings(tol_position, tol_angle, max_iterations, restarts)
    setup = compile_setup(
        robot, weights, respect_limits, float(tol_position), float(tol_angle), int(max_iterations)
    )
    problem = setup.problem
    start = _initial_guess(robot, q0, N, setup.middle)

    # Targets beyond the arm's reach are not searched: the bound proves them unreachable.
    offset = (p_t - setup.base_origin) * setup.counted_position
    gap = np.sqrt(np.einsum("ni,ni->n", offset, offset)) - setup.reach
    searched = np.flatnonzero(~(gap > problem.tol_position))
    q_best = np.full((N, n), np.nan)
    iterations = np.zeros(N, dtype=np.int64)
    attempts = np.zeros(N, dtype=np.int64)
    if searched.size:
        rngs: list[np.random.Generator] = []

        def sample(count: int) -> FloatArray:
            if not rngs:  # created on first use: most single solves need none
                rngs.append(np.random.default_rng(DEFAULT_SEED if seed is None else seed))
            return rngs[0].uniform(setup.sample_lo, setup.sample_hi, size=(count, n))

        R_s = None if R_t is None else R_t[searched]
        if searched.size == 1:
            i = int(searched[0])
            R_i = None if R_s is None else R_s[0]
            res = search_single(problem, p_t[i], R_i, start[i], restarts, sample)
        else:
            res = search_batch(problem, p_t[searched], R_s, start[searched], restarts, sample)
        q_best[searched] = res.q
        iterations[searched] = res.iterations
        attempts[searched] = res.attempts

    solved, pos, ang = _verify(robot, setup, q_best, p_t, R_t)
    q_out = np.where(solved[:, None], q_best, np.nan)
    if not respect_limits:
        revolute = ~problem.prismatic
        q_out[:, revolute] = wrap_angle(q_out[:, revolute])
    cand = Candidates(
        q=q_out[:, None, :],
        labels=(LABEL,),
        singular=np.zeros(N, dtype=bool),
        free=np.zeros((N, n), dtype=bool),
        gap=np.where(solved, np.nan, np.where(gap > problem.tol_position, gap, 0.0)),
    )
    return NumericDetails(cand, iterations, attempts, pos, ang)


# ----------------------------------------------------------------- set-up
def _parse_targets(targets: ArrayLike, position_only: bool) -> tuple[FloatArray, FloatArray | None]:
    """``(p (N, 3), R (N, 3, 3) or None)`` from the ``targets`` argument."""
    try:
        arr = np.asarray(targets, dtype=float)
    except (TypeError, ValueError) as exc:
        raise DimensionError(f"targets must be numbers, got {targets!r}") from exc
    if position_only and arr.ndim in (1, 2) and arr.shape[-1] == 3:
        if not np.all(np.isfinite(arr)):
            raise DimensionError("targets (positions) hold NaN or inf")
        return arr.reshape(-1, 3), None
    if arr.ndim in (2, 3) and arr.shape[-2:] == (4, 4):
        T = check_transform(arr, name="targets").reshape(-1, 4, 4)
        return T[:, :3, 3], (None if position_only else T[:, :3, :3])
    expected = "(N, 3) positions or (N, 4, 4) poses" if position_only else "(N, 4, 4) poses"
    raise DimensionError(f"targets must be {expected}, got shape {arr.shape}")


def _parse_mask(mask: ArrayLike | None, position_only: bool) -> FloatArray:
    """``(6,)`` weights; position-only zeroes the rotation part."""
    if mask is None:
        w = np.ones(6)
    else:
        w = np.asarray(mask, dtype=float)
        if w.shape != (6,) or not np.all(np.isfinite(w)) or np.any(w < 0):
            raise DimensionError(
                "mask must be 6 non-negative weights for x, y, z, rx, ry, rz; "
                f"got {np.asarray(mask).tolist()}"
            )
    if position_only:
        w = np.concatenate([w[:3], np.zeros(3)])
    if not np.any(w > 0):
        raise DimensionError("mask selects no error component: every weight is 0")
    return w


def _check_settings(tol_position: float, tol_angle: float, iters: int, restarts: int) -> None:
    for name, tol in (("tol_position", tol_position), ("tol_angle", tol_angle)):
        if not (math.isfinite(tol) and tol > 0):
            raise KinematicaError(f"{name} must be a positive number, got {tol!r}")
    if int(iters) != iters or iters < 1:
        raise KinematicaError(f"max_iterations must be an integer >= 1, got {iters!r}")
    if int(restarts) != restarts or restarts < 0:
        raise KinematicaError(f"restarts must be an integer >= 0, got {restarts!r}")


def _initial_guess(robot: Robot, q0: ArrayLike | None, N: int, middle: FloatArray) -> FloatArray:
    """``(N, n)`` first guesses: ``q0`` broadcast, or the middle of the sample box."""
    n = robot.dof
    if q0 is None:
        return np.broadcast_to(middle, (N, n))
    q = robot.check_q(q0, name="q0")
    if q.ndim == 1:
        return np.broadcast_to(q, (N, n))
    if q.shape != (N, n):
        raise DimensionError(f"q0 must be ({n},) or ({N}, {n}) for {N} targets, got {q.shape}")
    return q


# ------------------------------------------------------------------ check
def _verify(
    robot: Robot,
    setup: Setup,
    q: FloatArray,
    p_t: FloatArray,
    R_t: FloatArray | None,
) -> tuple[NDArray[np.bool_], FloatArray, FloatArray]:
    """Judge configurations by the robot's own forward kinematics.

    Returns:
        ``(solved, position_error, angle_error)``, each ``(N,)``: the counted
        residuals scaled as in the convergence test (NaN where ``q`` is NaN),
        and whether they are within the tolerances, with the joints within
        the limits when the set-up respects them.
    """
    problem = setup.problem
    N = q.shape[0]
    pos = np.full(N, np.nan)
    ang = np.full(N, np.nan)
    have = np.flatnonzero(np.all(np.isfinite(q), axis=1))
    if have.size == 1:
        i = int(have[0])
        T = robot.fk(q[i])
        pos[i], ang[i] = residuals_single(problem, T, p_t[i], None if R_t is None else R_t[i])
    elif have.size:
        T = robot.fk(q[have])
        X, Y, Z, P = (np.ascontiguousarray(T[:, :3, j].T) for j in range(4))
        R_h = None if R_t is None else np.ascontiguousarray(R_t[have].transpose(1, 2, 0))
        err = pose_error(problem, X, Y, Z, P, np.ascontiguousarray(p_t[have].T), R_h)
        sq = (err * problem.check[:, None]) ** 2
        pos[have] = np.sqrt(sq[problem.is_position].sum(axis=0))
        ang[have] = np.sqrt(sq[~problem.is_position].sum(axis=0))
    with np.errstate(invalid="ignore"):
        solved = (pos <= problem.tol_position) & (ang <= problem.tol_angle)
    if setup.respect_limits:
        lo, hi = setup.limits.T
        solved &= np.all((q >= lo) & (q <= hi), axis=1)
    return solved, pos, ang
