"""The held value nearest a start with a solution: a redundant arm's ``auto`` sweep.

Where a 7R arm's ``auto`` (:mod:`kinematica.ik.redundancy`) finds no solution with its
joint at the value asked, the nearest of :data:`PARAMETER_SWEEP` values across its span
with one answers. Values the reach bounds prove out of reach are left out
(:mod:`kinematica.ik.reach_bounds`); the others are tried nearest first. For one pose on
an end joint with a prepared call, the call that screens a value is the one whose answer
is kept (one elimination per value, :func:`swept`: one core call for a batch's poses);
else a screen by the closed
form alone picks the value, and the caller solves the target there
(:func:`nearest_with_solutions`).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.core import Chain, resolve_workers
from kinematica.ik.arm_angle import ArmAngleParameter
from kinematica.ik.moved import (
    end_arm,
    held_completed,
    lever,
    move_parts,
    moved_targets,
    on_axis,
)
from kinematica.ik.parameter import JointParameter, Parameter
from kinematica.ik.reach_bounds import ROUNDOFF_SLACK, may_reach, reach_bounds
from kinematica.ik.request import IKRequest
from kinematica.ik.result import IKBatchResult, IKResult
from kinematica.ik.solve import solve_ik
from kinematica.ik.solvers import plan_of
from kinematica.ik.targets import Targets
from kinematica.ik.tolerance import Tolerance, parse_tolerance

if TYPE_CHECKING:
    from kinematica.ik.options import IKOptions

FloatArray = NDArray[np.float64]

__all__ = [
    "PARAMETER_SWEEP",
    "has_solutions",
    "lean_call",
    "nearest_answer",
    "nearest_with_solutions",
    "possible",
    "screen",
    "sweep_order",
    "swept",
]

#: Values of the parameter tried, evenly across its span, when a target has no solution
#: at q0's value or the default: the nearest one with a solution answers (every
#: solution there), before the numeric search over every joint is asked. 73 values
#: over a joint's ±166° are 4.6° apart.
PARAMETER_SWEEP = 73


def nearest_with_solutions(
    chain: Chain,
    joint: Parameter,
    targets: Targets,
    rows: NDArray[np.intp],
    start: FloatArray,
    options: IKOptions,
    start_tried: bool = False,
) -> tuple[NDArray[np.intp], FloatArray]:
    """For the targets ``rows`` (flat), the parameter value nearest ``start`` with a solution.

    The parameter's candidates are :data:`PARAMETER_SWEEP` values evenly across its
    span; a target takes the nearest to its start value whose answer has a
    solution (within the limits, when they are respected; of two as near, the lower).
    Values proved to have none (:mod:`kinematica.ik.reach_bounds`) are left out, and with
    ``start_tried`` a value equal to the target's start (the caller found none there);
    the others are tried nearest first, in rounds of twice as many values as the last
    (most targets have one among the first), at least the parameter's
    :attr:`~kinematica.ik.parameter.Parameter.round_values` over a round's targets; a
    target leaves the rounds at its first value with one. The caller solves the target
    again at that value, and keeps it only if that answer has one.

    Returns:
        The rows that have such a value, and the value of each.
    """
    poses = targets.poses[rows]
    request = IKRequest.of(options).but(q0=None, fixed=None)  # every value's, made once
    sweep = sweep_order(chain, joint, poses, start[rows], request, start_tried)
    if sweep is None:
        return rows[:0], np.empty(0)
    grid, order, count = sweep
    best = np.full(rows.size, -1)
    first, size = 0, 1
    while first < grid.size:
        todo = np.flatnonzero((best < 0) & (count > first))
        if not todo.size:
            break
        size = max(size, -(-joint.round_values // todo.size))  # a round worth its cost
        ranks = order[todo, first : first + size]  # (t, r) grid indices to try
        width = ranks.shape[1]
        i, r = np.nonzero(first + np.arange(width)[None, :] < count[todo][:, None])
        has = np.zeros(ranks.shape, dtype=bool)
        has[i, r] = has_solutions(chain, joint, poses[todo[i]], grid[ranks[i, r]], request)
        hit = has.any(axis=1)
        best[todo[hit]] = ranks[hit, np.argmax(has[hit], axis=1)]
        first, size = first + width, 2 * size
    ok = best >= 0
    return rows[ok], grid[best[ok]]


def sweep_order(
    chain: Chain,
    joint: Parameter,
    poses: FloatArray,
    start: FloatArray,
    request: IKRequest,
    start_tried: bool = False,
) -> tuple[FloatArray, NDArray[np.intp], NDArray[np.intp]] | None:
    """The values to try for each pose, in order, or None (the parameter's span is unbounded).

    With ``start_tried``, a value equal to the pose's start is not tried (as the core's
    sweep leaves out its ``skip``).

    Returns:
        ``(G,)`` the grid (:data:`PARAMETER_SWEEP` values across the span), ``(t, G)``
        each pose's grid indices nearest ``start`` first (of two as near, the lower first),
        and ``(t,)`` how many of them to try (the values not proved out of reach).
    """
    grid = _grid(chain, joint)
    if grid is None or not poses.shape[0]:
        return None
    near = np.abs(grid[None, :] - start[:, None])
    # values proved to have no solution (kinematica.ik.reach_bounds) are not tried: the
    # first value with one in each target's order is the same without them
    near = np.where(possible(chain, joint, poses, grid, request), near, np.inf)
    if start_tried:
        near[grid[None, :] == start[:, None]] = np.inf
    order = np.argsort(near, axis=1, kind="stable")
    return grid, order, np.isfinite(near).sum(axis=1)


def nearest_answer(
    chain: Chain,
    joint: Parameter,
    target: ArrayLike,
    targets: Targets,
    values: FloatArray,
    options: IKOptions,
    skip: float = math.nan,
) -> tuple[IKResult | None, float] | None:
    """One pose's answer at the nearest value of the sweep with a solution, and that value.

    The value :func:`nearest_with_solutions` finds, and the answer there, in one core
    call (:func:`swept`): one elimination per value tried. ``(None, start)`` when no
    value has one; None where the end joint's prepared call does not apply (the caller
    screens). ``skip``: a value whose closed form is known to find nothing (the start's,
    solved already).
    """
    if type(target) is not np.ndarray or target.shape != (4, 4):
        return None
    if not isinstance(joint, JointParameter):
        return None
    lean = lean_call(chain, joint, options)
    # the core reads the pose in place only as C-ordered native doubles: else the screen
    f, kind = target.flags, target.dtype
    if lean is None or not (kind == np.float64 and kind.isnative and f.c_contiguous and f.aligned):
        return None
    start = float(values[0])
    hit = swept(chain, joint, lean, target[None], values[:1], np.array([skip]), 1)
    if hit is None or hit[0][0] == -1:
        return None, start
    index, grid, answers = hit
    return None if index[0] < 0 else (answers[0], float(grid[index[0]]))


def lean_call(chain: Chain, joint: Parameter, options: IKOptions) -> tuple[Any, IKRequest] | None:
    """The end joint's prepared call (:meth:`JointParameter.lean`) and its settings, or None."""
    if not isinstance(joint, JointParameter) or options.q0 is not None:
        return None
    request = IKRequest.of(options).but(q0=None, fixed=None, arm_angle=None)
    ready = joint.lean(chain, request)
    return None if ready is None else (ready, request)


def swept(
    chain: Chain,
    joint: JointParameter,
    lean: tuple[Any, IKRequest],
    poses: FloatArray,
    start: FloatArray,
    skip: FloatArray,
    workers: int,
) -> tuple[NDArray[np.int64], FloatArray, list[IKResult | None]] | None:
    """Each pose's answer at the first value of the sweep with a solution, in one core call.

    The prepared call (``Prepared.sweep``, :func:`~kinematica.ik.moved.held_prepared`)
    tries the :data:`PARAMETER_SWEEP` values across the span nearest ``start[i]`` first
    (of two as near, the lower), leaving out ``skip[i]`` and the values the reach bounds
    prove out of reach (:func:`possible`'s), on up to ``workers`` threads; its answer at
    the first with a solution is the answer (completed as ``held_at`` completes it).

    ``poses`` ``(N, 4, 4)`` of the whole arm, ``start`` and ``skip`` ``(N,)`` (NaN: none).
    Returns ``(index, grid, answers)``: ``(N,)`` the index in ``grid`` ``(G,)`` of the value
    answered (-1: none has a solution; -2: a pose the core does not read as rigid) and each
    pose's answer (None where index < 0); None where the span is unbounded (no sweep).
    """
    ready, request = lean
    grid = _grid(chain, joint)
    if grid is None:
        return None
    k = joint.index
    limits = bool(request.respect_limits)
    bounds = None if chain.prismatic[k] else reach_bounds(end_arm(chain, k), limits)
    tol = parse_tolerance(request.tol)
    index, got = ready.sweep(poses, start, grid, skip, bounds, tol.position, tol.rotation,
                             limits, ROUNDOFF_SLACK, workers)  # fmt: skip
    answers: list[IKResult | None] = []
    for i, answer in enumerate(got):
        if answer is not None and answer.__class__ is not IKResult:  # the core's, to complete
            v = float(grid[index[i]])
            answer = held_completed(chain, k, joint.name, request, poses[i], v, answer)
        answers.append(answer)
    return index, grid, answers


def _grid(chain: Chain, joint: Parameter) -> FloatArray | None:
    """The sweep's :data:`PARAMETER_SWEEP` values across the span, kept; None if unbounded."""
    key = ("sweep grid", joint.name, getattr(joint, "index", None))
    found = chain.memo.get(key, False)
    if found is False:
        lo, hi = joint.span(chain)
        found = None
        if np.isfinite(lo) and np.isfinite(hi):
            found = np.linspace(lo, hi, PARAMETER_SWEEP)
            found.flags.writeable = False
        chain.memo[key] = found
    return found  # type: ignore[return-value]


def possible(
    chain: Chain,
    joint: Parameter,
    poses: FloatArray,
    grid: FloatArray,
    request: IKRequest | IKOptions,
) -> NDArray[np.bool_]:
    """``(t, G)`` False where pose i proves to have no solution at ``grid[j]``.

    The first or last joint of an arm whose 6 other joints turn: the targets moved
    for the arm locked once (:mod:`kinematica.ik.moved`), checked against that arm's
    :func:`~kinematica.ik.reach_bounds.reach_bounds` with the request's tolerance; past
    a last joint whose axis misses the tool point, its position widened by the rotation
    times the move's :func:`~kinematica.ik.moved.lever` (a pose within the tolerance of
    the target is within that of the moved target).
    """
    k = joint.index if isinstance(joint, JointParameter) else -1
    limits = bool(request.respect_limits)
    tol = parse_tolerance(request.tol)
    key = ("possible", k, limits)  # the parts of the check, made once
    found: Any = chain.memo.get(key, False)
    if found is False:
        found = chain.memo[key] = _bounds_check(chain, k, limits)
    if found is None:
        return np.ones((poses.shape[0], grid.size), dtype=bool)
    bounds, move = found
    if k and not on_axis(chain):
        tol = Tolerance(tol.position + tol.rotation * lever(chain, k, grid), tol.rotation)
    return may_reach(bounds, poses, tol, grid, move, limits)


def _bounds_check(chain: Chain, k: int, limits: bool) -> tuple[Any, tuple[FloatArray, bool]] | None:
    """:func:`possible`'s bounds and move for joint ``k``; None: no bounds."""
    if k not in (0, chain.dof - 1) or chain.prismatic[k]:
        return None
    bounds = reach_bounds(end_arm(chain, k), limits)
    return None if bounds is None else (bounds, move_parts(chain, k))


def has_solutions(
    chain: Chain, joint: Parameter, poses: FloatArray, values: FloatArray, request: IKRequest
) -> NDArray[np.bool_]:
    """``(M,)`` True where pose i has a solution with the parameter at ``values[i]``.

    The first or last joint by the arm locked once with the targets moved
    (:mod:`kinematica.ik.moved`), its closed form alone (a target it finds nothing
    for is not searched: this is a screen, its value confirmed by the caller); the arm
    angle by its solver at a value per target; a middle joint one locked arm (one
    batch) per value (``request``: without q0 or a held joint).
    """
    if isinstance(joint, JointParameter) and joint.index in (0, chain.dof - 1):
        moved = moved_targets(chain, joint.index, poses, values)
        return screen(end_arm(chain, joint.index), moved, request)
    if isinstance(joint, ArmAngleParameter):
        out = joint.solve(chain, poses, values, request)
        assert isinstance(out, IKBatchResult)
        return np.asarray(out.raw.count) > 0
    has = np.zeros(values.size, dtype=bool)
    for v in np.unique(values).tolist():
        at = np.flatnonzero(values == v)
        one = joint.solve(chain, np.ascontiguousarray(poses[at]), v, request)
        assert isinstance(one, IKBatchResult)
        has[at] = np.asarray(one.raw.count) > 0
    return has


def screen(arm: Chain, poses: FloatArray, request: IKRequest) -> NDArray[np.bool_]:
    """``(M,)`` True where the arm's closed form has a solution of pose i (else its answer's).

    One core call of the closed form without the search that completes it: a screen
    of candidate values, which the caller confirms by solving the target again.
    """
    plan = plan_of(arm, "pose", request)
    if plan.closed is None or not plan.direct:
        out = solve_ik(arm, poses, request)
        assert isinstance(out, IKBatchResult)
        return np.asarray(out.raw.count) > 0
    workers = resolve_workers(request.workers)
    raw = plan.solver.ik_batch(arm.core, poses, plan.options, None, None, workers)
    return np.asarray(raw.count) > 0
