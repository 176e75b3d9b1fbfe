"""A redundant arm's ``method="auto"``: every solution at a parameter value, said so.

A 7-joint arm reaches a pose along a one-parameter family of configurations. With
no parameter given, ``auto`` holds one joint at a value (q0's when given, else
the joint's :meth:`~kinematica.ik.parameter.JointParameter.default`) and returns
every solution there, from the closed form the registry has for the arm that
lock leaves; the result names the parameter (``result.parameter``) and a note
says why that value. The joint is the first in :func:`preference` whose locked
arm the registry solves in closed form; an arm with none is searched
numerically over all its joints, as any arm without a closed form. Where the
lock finds no solution, the pose is not declared unreachable: the numeric search
over every joint answers, and says so.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

import kinematica._core as _core
from kinematica.core import Chain, resolve_workers
from kinematica.errors import KinematicaError
from kinematica.ik.arm_angle import ArmAngleParameter, arm_angle_parameter
from kinematica.ik.held_aside import solved_except
from kinematica.ik.local_search import LOCAL_SEARCH
from kinematica.ik.moved import end_arm, move_parts, moved_targets, on_axis
from kinematica.ik.parameter import (
    JointParameter,
    Parameter,
    joint_names,
    locked_chain,
    solve_fixed,
)
from kinematica.ik.reach_bounds import may_reach, reach_bounds
from kinematica.ik.request import IKRequest
from kinematica.ik.result import IKBatchResult, IKResult, amended
from kinematica.ik.solve import REDUNDANT_DOF, solve_ik
from kinematica.ik.solvers import closed_form, plan_of
from kinematica.ik.stack import replace_rows
from kinematica.ik.targets import Targets, parse_q0, parse_targets
from kinematica.ik.tolerance import parse_tolerance

if TYPE_CHECKING:
    from kinematica.ik.options import IKOptions

FloatArray = NDArray[np.float64]

__all__ = [
    "PARAMETER_SWEEP",
    "REDUNDANT_DOF",
    "choose",
    "default_value",
    "held_note",
    "preference",
    "solve_arm",
]

#: Values of the parameter tried, evenly across its span, when a target has no solution
#: at q0's value or the default: the nearest one with a solution answers (every
#: solution there), before the numeric search over every joint is asked. 73 values
#: over a joint's ±166° are 4.6° apart.
PARAMETER_SWEEP = 73

#: Why a q0 has no value of the parameter (an SRS arm's arm angle), in its note.
UNDEFINED_AT_Q0 = (
    "its elbow is on the line from the shoulder to the wrist centre, or that line is "
    "along axis 1: no value is nearer q0 than another"
)

_INVALID = _core.STATUS["invalid"]
#: One target's value is defined (read only).
_DEFINED = np.zeros(1, dtype=bool)
_DEFINED.flags.writeable = False


def preference(n: int) -> tuple[int, ...]:
    """The joints (0-based) tried as an n-joint arm's parameter, in order of preference.

    The last joint first, then the first (either only moves the tool or the base,
    so one locked arm serves every value), then the others from the base out.
    """
    return (n - 1, 0, *range(1, n - 1))


def choose(chain: Chain, names: Sequence[str] | None = None) -> Parameter | None:
    """The parameter ``auto`` uses for this arm, or None (not redundant, or no closed form).

    An SRS arm's arm angle (:mod:`kinematica.ik.arm_angle`): all 8 solutions at
    any value, every joint free to take its whole range. Else the first joint of
    :func:`preference` whose locked arm (at its default value) has a closed-form
    pose solver of a special family, else of the general 6R; chosen once per chain.
    """
    if chain.dof != REDUNDANT_DOF:
        return None
    angle = arm_angle_parameter(chain)
    if angle is not None:
        return angle
    memo = chain.memo
    if "held joint" not in memo:
        # a closed form that answers every target itself (a special family) before one
        # that may hand a target to the search (the general 6R's elimination)
        found, fallback = None, None
        for k in preference(chain.dof):
            joint = JointParameter(k, f"q{k + 1}", bool(chain.prismatic[k]))
            closed = closed_form(locked_chain(chain, k, joint.default(chain)), "pose")
            if closed is None or closed.partial:
                continue
            if not closed.search_note:
                found = k
                break
            if fallback is None:
                fallback = k
        memo["held joint"] = found if found is not None else fallback
    chosen: int | None = memo["held joint"]  # type: ignore[assignment]
    if chosen is None:
        return None
    key = ("held parameter", None if names is None else tuple(names))
    held = memo.get(key)
    if held is None:
        name = joint_names(chain, names)[chosen]
        held = memo[key] = JointParameter(chosen, name, bool(chain.prismatic[chosen]))
    return held  # type: ignore[return-value]


def solve_arm(
    chain: Chain, target: ArrayLike, options: IKOptions, names: Sequence[str] | None = None
) -> IKResult | IKBatchResult:
    """``robot.ik``: a joint held at a value when asked or chosen, else the chain as it is.

    Args:
        chain: The arm.
        target: As :func:`~kinematica.ik.solve_ik` takes it.
        options: The IK settings (``fixed``: a joint held at a value).
        names: The joints' display names (``q1..qn`` when None).
    """
    if options.arm_angle is not None:  # an SRS arm's own parameter: no joint held
        if options.fixed is not None:
            raise KinematicaError(
                "give one redundancy parameter: arm_angle or fixed, not both", arg="arm_angle"
            )
        return ArmAngleParameter().solve(chain, target, options.arm_angle, options)
    if options.fixed is not None:
        return solve_fixed(chain, target, options, names)
    if options.method == "auto" and options.mask is None and chain.dof == REDUNDANT_DOF:
        joint = choose(chain, names)
        if joint is not None:
            targets = parse_targets(target)
            if not targets.position:
                return _at_parameter(chain, joint, target, targets, options)
    return solve_ik(chain, target, options)


def _at_parameter(
    chain: Chain, joint: Parameter, target: ArrayLike, targets: Targets, options: IKOptions
) -> IKResult | IKBatchResult:
    """Every solution with ``joint`` at q0's value (or its default).

    A target with no solution there is answered at the nearest value that has one
    (:data:`PARAMETER_SWEEP`), and only where none has, by the numeric search over
    every joint.
    """
    n = chain.dof
    q0s = _q0_rows(options.q0, targets.shape, n)
    default, default_why = default_value(chain, joint)
    N = targets.poses.shape[0]
    undefined = _DEFINED if N == 1 else np.zeros(N, dtype=bool)
    if q0s is None:
        why = default_why
        values = np.full(N, default)
    else:
        at_q0 = joint.value_of(chain, q0s)
        # an arm angle is undefined at a q0 whose elbow is on the shoulder-wrist line (or
        # that line along axis 1): that target is held at the default, and its note says so
        undefined = ~np.isfinite(at_q0)
        values = np.clip(np.where(undefined, default, at_q0), *joint.span(chain))
        why = "q0's value, within its limits"
    one = targets.single  # one target: its value as a number
    # one target proved to have no solution at its value: not solved there (its answer
    # is the nearest value's, or the search's, either way); the value moves the target
    # exactly (the first joint, or the last about an axis through the tool point), so
    # the moved target is held to the same tolerance
    exact = isinstance(joint, JointParameter) and (joint.index == 0 or on_axis(chain))
    # a batch likewise: its targets proved out of reach at the value are left unsolved
    # there (every target at one value, each valid and read as given)
    plain = N and not (targets.invalid or targets.notes) and bool(np.all(values == values[0]))
    aside = np.zeros(N, dtype=bool)
    if exact and (one or plain):
        aside = ~_possible(chain, joint, targets.poses, values[:1], options)[:, 0]
    res: IKResult | IKBatchResult | None
    if one:
        res = None if aside[0] else joint.solve(chain, target, float(values[0]), options)
    elif aside.any():
        res = solved_except(chain, joint, targets.poses, targets.shape, values, options, q0s, aside)
    else:
        res = joint.solve(chain, target, values, options)

    def whence(undef: bool) -> str:
        if not undef:
            return why
        return f"{default_why}; q0's {joint.name} is undefined: {UNDEFINED_AT_Q0}"

    def note(value: float, undef: bool = False) -> str:
        if q0s is not None:
            return held_note(chain, joint, value, whence(undef))
        key = ("held note", joint.name, value)  # the default value's: said once
        text = chain.memo.get(key)
        if text is None:
            text = chain.memo[key] = held_note(chain, joint, value, why)
        return text  # type: ignore[return-value]

    def fallback(value: float) -> str:
        return (
            f"no solution with {joint.describe(value)}: the numeric search over all "
            f"{chain.dof} joints answered, {LOCAL_SEARCH}"
        )

    def nearer(value: float, start: float, undef: bool = False) -> str:
        keyword = "fixed=" if isinstance(joint, JointParameter) else "arm_angle="
        return (
            f"{chain.dof}-joint arm: no solution with {joint.describe(start)} "
            f"({whence(undef)}); every "
            f"solution with {joint.describe(value)}, the nearest of {PARAMETER_SWEEP} values "
            f"across its span with one, its redundancy parameter; give q0 or {keyword} for "
            f"another value, robot.self_motion for all of them"
        )

    if res is None or isinstance(res, IKResult):
        value, undef = float(values[0]), bool(undefined[0])
        if res is not None and res.success:
            return amended(res, notes=(*res.notes, note(value, undef)))
        first = np.array([0])
        found, moved = _nearest_with_solutions(chain, joint, targets, first, values, options)
        again = joint.solve(chain, target, float(moved[0]), options) if found.size else None
        if isinstance(again, IKResult) and again.success:
            moved_note = nearer(float(moved[0]), value, undef)
            return dataclasses.replace(again, notes=(*again.notes, moved_note))
        full = solve_ik(chain, target, IKRequest.of(options).but(method="numeric"))
        assert isinstance(full, IKResult)
        return dataclasses.replace(full, notes=(*full.notes, fallback(value)))
    raw = res.raw
    missed = np.flatnonzero((raw.count == 0) & (raw.status != _INVALID))
    notes = dict(res.notes)
    said: dict[tuple[float, bool], str] = {}  # one note per value, shared by its targets
    held = np.flatnonzero(raw.count > 0)
    # plain ints and floats, made once: this loop runs once per target of a batch
    cells = np.stack(np.unravel_index(held, res.shape), axis=-1).tolist()
    keys = zip(values[held].tolist(), undefined[held].tolist(), strict=True)
    for key, idx in zip(keys, cells, strict=True):
        text = said.get(key) or said.setdefault(key, note(*key))
        where = tuple(idx)
        old = notes.get(where)
        notes[where] = (text,) if old is None else (*old, text)
    res = dataclasses.replace(res, notes=notes)
    if missed.size:  # the nearest value with a solution, where there is one
        found, moved = _nearest_with_solutions(chain, joint, targets, missed, values, options)
        # one value at a time: the targets held at a value are solved as a single call
        # at that value would solve them (batch == single, to the bit)
        answered: list[tuple[NDArray[np.intp], float]] = []
        for v in np.unique(moved).tolist():
            rows = found[moved == v]
            again = _solved_at(chain, joint, targets, rows, v, q0s, options)
            kept = rows[np.asarray(again.raw.count) > 0]  # the screen's value, confirmed
            if kept.size and kept.size < rows.size:
                again = _solved_at(chain, joint, targets, kept, v, q0s, options)
            if kept.size:
                res = replace_rows(res, kept, again, None)
                answered.append((kept, v))
        if answered:
            assert res.parameter is not None
            held_at = np.array(res.parameter[1], dtype=float).reshape(-1)
            notes = dict(res.notes)
            for rows, v in answered:
                held_at[rows] = v
                for i in rows.tolist():
                    where = tuple(int(c) for c in np.unravel_index(i, res.shape))
                    moved_note = nearer(v, float(values[i]), bool(undefined[i]))
                    notes[where] = (*notes.get(where, ()), moved_note)
                missed = np.setdiff1d(missed, rows)
            res = dataclasses.replace(
                res, notes=notes, parameter=(res.parameter[0], held_at.reshape(res.shape))
            )
    if missed.size:
        sub = targets.replace(
            poses=np.ascontiguousarray(targets.poses[missed]),
            shape=(int(missed.size),),
            invalid={},
            notes={},
        )
        q0 = None if q0s is None else q0s[missed]
        full = solve_ik(chain, sub, IKRequest.of(options).but(method="numeric", q0=q0))
        assert isinstance(full, IKBatchResult)
        res = replace_rows(res, missed, full, [fallback(float(values[i])) for i in missed])
    return res


def _solved_at(
    chain: Chain,
    joint: Parameter,
    targets: Targets,
    rows: NDArray[np.intp],
    value: float,
    q0s: FloatArray | None,
    options: IKOptions,
) -> IKBatchResult:
    """The targets ``rows`` (flat) solved with the parameter at ``value``."""
    opts = options if q0s is None else dataclasses.replace(options, q0=q0s[rows])
    out = joint.solve(chain, np.ascontiguousarray(targets.poses[rows]), value, opts)
    assert isinstance(out, IKBatchResult)
    return out


def _nearest_with_solutions(
    chain: Chain,
    joint: Parameter,
    targets: Targets,
    rows: NDArray[np.intp],
    start: FloatArray,
    options: IKOptions,
) -> tuple[NDArray[np.intp], FloatArray]:
    """For the targets ``rows`` (flat), the parameter value nearest ``start`` with a solution.

    The parameter's candidates are :data:`PARAMETER_SWEEP` values evenly across its
    span; a target takes the nearest to its start value whose answer has a
    solution (within the limits, when they are respected; of two as near, the lower).
    Values proved to have none (:mod:`kinematica.ik.reach_bounds`) are left out; the
    others are tried nearest first, one, then twice as many each round (most of
    them have one), and a target leaves the rounds at its first value with one. The
    caller solves the target again at that value, and keeps it only if that answer
    has one.

    Returns:
        The rows that have such a value, and the value of each.
    """
    lo, hi = joint.span(chain)
    if not (np.isfinite(lo) and np.isfinite(hi)) or not rows.size:
        return rows[:0], np.empty(0)
    grid = np.linspace(lo, hi, PARAMETER_SWEEP)
    poses = targets.poses[rows]
    request = IKRequest.of(options).but(q0=None, fixed=None)  # every value's, made once
    near = np.abs(grid[None, :] - start[rows][:, None])
    # values proved to have no solution (kinematica.ik.reach_bounds) are not tried: the
    # first value with one in each target's order is the same without them
    near = np.where(_possible(chain, joint, poses, grid, request), near, np.inf)
    # the grid in each target's order: nearest first, the lower of two as near first
    order = np.argsort(near, axis=1, kind="stable")
    count = np.isfinite(near).sum(axis=1)  # each target's values to try
    best = np.full(rows.size, -1)
    first, size = 0, 1
    while first < grid.size:
        todo = np.flatnonzero((best < 0) & (count > first))
        if not todo.size:
            break
        ranks = order[todo, first : first + size]  # (t, r) grid indices to try
        width = ranks.shape[1]
        i, r = np.nonzero(first + np.arange(width)[None, :] < count[todo][:, None])
        has = np.zeros(ranks.shape, dtype=bool)
        has[i, r] = _has_solutions(chain, joint, poses[todo[i]], grid[ranks[i, r]], request)
        hit = has.any(axis=1)
        best[todo[hit]] = ranks[hit, np.argmax(has[hit], axis=1)]
        first, size = first + width, 2 * size
    ok = best >= 0
    return rows[ok], grid[best[ok]]


def _possible(
    chain: Chain,
    joint: Parameter,
    poses: FloatArray,
    grid: FloatArray,
    request: IKRequest | IKOptions,
) -> NDArray[np.bool_]:
    """``(t, G)`` False where pose i proves to have no solution at ``grid[j]``.

    The first or last joint of an arm whose 6 other joints turn: the targets moved
    for the arm locked once (:mod:`kinematica.ik.moved`), checked against that arm's
    :func:`~kinematica.ik.reach_bounds.reach_bounds` with the screen's tolerance.
    """
    k = joint.index if isinstance(joint, JointParameter) else -1
    if k not in (0, chain.dof - 1) or chain.prismatic[k]:
        return np.ones((poses.shape[0], grid.size), dtype=bool)
    limits = bool(request.respect_limits)
    bounds = reach_bounds(end_arm(chain, k), limits)
    if bounds is None:
        return np.ones((poses.shape[0], grid.size), dtype=bool)
    move = move_parts(chain, k)
    return may_reach(bounds, poses, parse_tolerance(request.tol), grid, move, limits)


def _has_solutions(
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
        return _screen(end_arm(chain, joint.index), moved, request)
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


def _screen(arm: Chain, poses: FloatArray, request: IKRequest) -> NDArray[np.bool_]:
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


def default_value(chain: Chain, joint: Parameter) -> tuple[float, str]:
    """The value ``auto`` holds ``joint`` at when no q0 is given, and why (for its note)."""
    key = ("default", joint.name)
    found = chain.memo.get(key)
    if found is None:
        found = chain.memo[key] = _default_value(chain, joint)
    return found  # type: ignore[return-value]


def _default_value(chain: Chain, joint: Parameter) -> tuple[float, str]:
    """:func:`default_value`, found."""
    why = "its default value"
    if isinstance(joint, ArmAngleParameter):
        why = "0: the elbow in the plane of axis 1 and the shoulder-wrist line"
    if isinstance(joint, JointParameter):
        middle = np.isfinite(chain.own_limits[joint.index]).all()
        why = "the middle of its limits" if middle else "0: it has no limits"
    return joint.default(chain), why


def held_note(chain: Chain, joint: Parameter, value: float, why: str) -> str:
    """The note of an ``auto`` answer with ``joint`` held at ``value`` (``why``: whence)."""
    keyword = "fixed=" if isinstance(joint, JointParameter) else "arm_angle="
    return (
        f"{chain.dof}-joint arm: every solution with {joint.describe(value)} ({why}), "
        f"its redundancy parameter; give q0 or {keyword} for another value, "
        f"robot.self_motion for all of them"
    )


def _q0_rows(q0: ArrayLike | None, shape: tuple[int, ...], n: int) -> FloatArray | None:
    """``(N, n)`` q0 per target (flat, C order), or None; checked (finite) as solve_ik does."""
    if q0 is None:
        return None
    return parse_q0(q0, n, shape)
