"""A redundant arm's ``method="auto"``: every solution at a parameter value, said so.

A 7-joint arm reaches a pose along a one-parameter family of configurations. With
no parameter given, ``auto`` holds one joint at a value (q0's when given, else
the joint's :meth:`~kinematica.ik.parameter.JointParameter.default`) and returns
every solution there, from the closed form the registry has for the arm that
lock leaves; the result names the parameter (``result.parameter``) and a note
says why that value. The joint is the first in :func:`preference` whose locked
arm the registry solves in closed form (a special family before the general 6R; of
two end joints that both leave the general 6R, the one whose default answers more
poses: :func:`choose`); an arm with none is searched
numerically over all its joints, as any arm without a closed form. Where the
lock finds no solution, the pose is not declared unreachable: the numeric search
over every joint answers, and says so.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, cast

import numpy as np
from numpy.typing import ArrayLike, NDArray

import kinematica._core as _core
from kinematica.core import Chain, resolve_workers
from kinematica.errors import KinematicaError
from kinematica.ik.arm_angle import ArmAngleParameter, arm_angle_parameter
from kinematica.ik.fixed import solve_fixed
from kinematica.ik.held_aside import solved_except
from kinematica.ik.local_search import LOCAL_SEARCH
from kinematica.ik.moved import end_arm, held_completed, on_axis
from kinematica.ik.nearest_value import (
    PARAMETER_SWEEP,
    has_solutions,
    lean_call,
    nearest_answer,
    nearest_with_solutions,
    possible,
    swept,
)
from kinematica.ik.parameter import JointParameter, Parameter, joint_names, locked_chain
from kinematica.ik.request import IKRequest
from kinematica.ik.result import IKBatchResult, IKResult, amended
from kinematica.ik.solve import REDUNDANT_DOF, solve_ik
from kinematica.ik.solvers import closed_form
from kinematica.ik.stack import replace_rows, stack_results
from kinematica.ik.targets import Targets, parse_q0, parse_targets

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
    pose solver of a special family, else of the general 6R; where both end joints'
    locks are the general 6R, the one at whose default more of :data:`PROBES` poses
    of the arm have a solution (:func:`_reached_more`). Chosen once per chain.
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
        found, general = None, []
        for k in preference(chain.dof):
            joint = JointParameter(k, f"q{k + 1}", bool(chain.prismatic[k]))
            closed = closed_form(locked_chain(chain, k, joint.default(chain)), "pose")
            if closed is None or closed.partial:
                continue
            if not closed.search_note:
                found = k
                break
            general.append(k)
        ends = [k for k in general if k in (0, chain.dof - 1)]
        if found is None and len(ends) == 2:
            found = _reached_more(chain, ends)
        memo["held joint"] = found if found is not None else (general[0] if general else None)
    chosen: int | None = memo["held joint"]  # type: ignore[assignment]
    if chosen is None:
        return None
    key = ("held parameter", None if names is None else tuple(names))
    held = memo.get(key)
    if held is None:
        name = joint_names(chain, names)[chosen]
        held = memo[key] = JointParameter(chosen, name, bool(chain.prismatic[chosen]))
    return held  # type: ignore[return-value]


#: Configurations, uniform within the joint limits (from :data:`PROBE_SEED`), whose poses
#: choose between two end joints whose locks are both the general 6R: measured on the
#: makers' 7R arms, the GEN72's first joint held at its default answers 61 % of random
#: poses there and its last joint 32 %; the Gen3's and the RM75's last joint answer more.
PROBES = 48
PROBE_SEED = 7


def _reached_more(chain: Chain, ends: list[int]) -> int | None:
    """Of two end joints, the one whose lock answers more poses at its default.

    ``ends`` in :func:`preference`'s order; the first on a tie. The poses are
    :data:`PROBES` of the arm: fewer of its poses are then moved to another value by
    ``auto``'s sweep. None where a joint has no limits to draw the poses within (a
    prismatic joint's ±inf).
    """
    lo, hi = chain.qlim.T
    if not (np.isfinite(lo).all() and np.isfinite(hi).all()):
        return None
    q = np.random.default_rng(PROBE_SEED).uniform(lo, hi, size=(PROBES, chain.dof))
    poses = np.ascontiguousarray(chain.fk(q)[0])
    request = IKRequest(workers=1)
    counts = []
    for k in ends:
        joint = JointParameter(k, f"q{k + 1}", bool(chain.prismatic[k]))
        at = np.full(PROBES, joint.default(chain))
        counts.append(int(has_solutions(chain, joint, poses, at, request).sum()))
    return ends[int(np.argmax(counts))]


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
            start = _start_value(chain, joint, target, options)
            pose = cast(FloatArray, target)  # one (4, 4) array where there is a start
            done = None if start is None else _at_start(chain, joint, pose, options, start[0])
            if start is not None and done is not None and done.success:
                value, why = start
                note = (_default_note(chain, joint, value, why) if options.q0 is None
                        else held_note(chain, joint, value, why))  # fmt: skip
                return amended(done, notes=(*done.notes, note))
            targets = parse_targets(target)
            if not targets.position:
                return _at_parameter(chain, joint, target, targets, options, done)
    return solve_ik(chain, target, options)


def _start_value(
    chain: Chain, joint: Parameter, target: ArrayLike, options: IKOptions
) -> tuple[float, str] | None:
    """The value ``auto`` holds one pose at first, and why; None for any other call.

    q0's (a float64 ``(n,)`` q0's value of it, within its span), else the default.
    """
    if target.__class__ is not np.ndarray or target.shape != (4, 4):
        return None
    q0 = options.q0
    if q0 is None:
        return default_value(chain, joint)
    if q0.__class__ is not np.ndarray or q0.dtype != np.float64 or q0.shape != (chain.dof,):
        return None
    if isinstance(joint, JointParameter):
        value = float(q0[joint.index])
    else:  # an arm angle: q0's own
        value = float(joint.value_of(chain, q0[None])[0])
    # the general path says what is wrong with q0, or that its arm angle is undefined
    if not math.isfinite(value):
        return None
    lo, hi = joint.span(chain)  # as _at_parameter's np.clip of q0's values
    return min(max(value, lo), hi), "q0's value, within its limits"


def _at_start(
    chain: Chain, joint: Parameter, target: FloatArray, options: IKOptions, value: float
) -> IKResult | None:
    """``auto``'s answer of one pose at its start value, as ``joint.solve`` gives it.

    An SRS arm's arm angle by its closed form at the value; an end joint whose lock has
    a prepared call (:meth:`~kinematica.ik.parameter.JointParameter.lean`) by that one
    core call (``q0`` beside it), without the targets read or a new request, and where
    its lock's closed form may hand a target to the search, only if the value's bounds
    do not prove it out of reach. Else None.
    """
    if isinstance(joint, ArmAngleParameter):
        res = joint.solve(chain, target, value, options)
        return res if isinstance(res, IKResult) else None
    if not isinstance(joint, JointParameter):
        return None
    q0 = cast("FloatArray | None", options.q0)  # None, or (n,) float64 (_start_value)
    request = IKRequest.of(options) if q0 is None else IKRequest.of(options).but(q0=None)
    ready = joint.lean(chain, request)
    if ready is None:
        return None
    # a lock whose closed form may hand a target to the search (the general 6R's
    # elimination, tens of µs): not solved where the bounds prove the value out of reach
    # (None: _at_parameter says so); a special family's answer costs less than the check
    closed = closed_form(end_arm(chain, joint.index), "pose")
    searched = closed is not None and bool(closed.search_note)
    if searched and not possible(chain, joint, target[None], np.array([value]), request)[0, 0]:
        return None
    got = ready.at(target, value, q0)
    if got is None or got.__class__ is IKResult:
        return got
    return held_completed(chain, joint.index, joint.name, request, target, value, got, q0)


def _at_parameter(
    chain: Chain,
    joint: Parameter,
    target: ArrayLike,
    targets: Targets,
    options: IKOptions,
    done: IKResult | None = None,
) -> IKResult | IKBatchResult:
    """Every solution with ``joint`` at q0's value (or its default).

    A target with no solution there is answered at the nearest value that has one
    (:data:`PARAMETER_SWEEP`), and only where none has, by the numeric search over
    every joint. ``done``: one target's answer at its start value, made (:func:`_at_start`).
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
    if exact and (one or plain) and done is None:
        aside = ~possible(chain, joint, targets.poses, values[:1], options)[:, 0]
    res: IKResult | IKBatchResult | None
    if done is not None:
        res = done
    elif one:
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
        return _default_note(chain, joint, value, why)

    def fallback(value: float) -> str:
        return (
            f"no solution with {joint.describe(value)}: the numeric search over all "
            f"{chain.dof} joints answered, {LOCAL_SEARCH}"
        )

    def nearer(value: float, start: float, undef: bool = False) -> str:
        return (
            f"{chain.dof}-joint arm: no solution with {joint.describe(start)} "
            f"({whence(undef)}); every "
            f"solution with {joint.describe(value)}, the nearest of {PARAMETER_SWEEP} values "
            f"across its span with one, its redundancy parameter; give q0 or {joint.keyword} for "
            f"another value, robot.self_motion for all of them"
        )

    if res is None or isinstance(res, IKResult):
        value, undef = float(values[0]), bool(undefined[0])
        if res is not None and res.success:
            return amended(res, notes=(*res.notes, note(value, undef)))
        again: IKResult | IKBatchResult | None
        # the value's closed form found nothing (or it is proved out): not tried again
        tried = res is None or res.count == 0
        hit = nearest_answer(chain, joint, target, targets, values, options,
                             value if tried else math.nan)  # fmt: skip
        if hit is not None:  # the prepared call's answer at the first value with one
            again, at = hit
        else:  # the screen, then the value found solved again
            first = np.array([0])
            found, moved = nearest_with_solutions(chain, joint, targets, first, values, options,
                                                  tried)  # fmt: skip
            again = joint.solve(chain, target, float(moved[0]), options) if found.size else None
            at = float(moved[0]) if found.size else value
        if isinstance(again, IKResult) and again.success:
            moved_note = nearer(at, value, undef)
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
    answered: list[tuple[NDArray[np.intp], float]] = []
    lean = None if targets.invalid or targets.notes else lean_call(chain, joint, options)
    if missed.size and lean is not None:  # each target's single call's answer, as it is
        assert isinstance(joint, JointParameter)  # lean_call's
        # every row in one core call; its value at the start found nothing (or is proved out)
        start = values[missed]
        poses = np.ascontiguousarray(targets.poses[missed])
        hits = swept(chain, joint, lean, poses, start, start, resolve_workers(options.workers))
        got: dict[int, IKResult] = {}
        values_at: list[float] = []
        for j, i in enumerate(missed.tolist() if hits is not None else ()):
            assert hits is not None
            index, grid, answers = hits
            answer = answers[j]
            if answer is not None and answer.success:
                got[len(got)] = answer
                values_at.append(float(grid[index[j]]))
                answered.append((np.array([i]), values_at[-1]))
        if got:
            kept = np.array([rows[0] for rows, _ in answered])
            sub = targets.replace(poses=targets.poses[kept], shape=(kept.size,), invalid={})
            again = stack_results(got, sub, n, joint.name, np.array(values_at))
            res = replace_rows(res, kept, again, None)
    elif missed.size:  # the nearest value with a solution, where there is one
        found, moved = nearest_with_solutions(chain, joint, targets, missed, values, options,
                                              True)  # fmt: skip
        # one value at a time: the targets held at a value are solved as a single call
        # at that value would solve them (batch == single, to the bit)
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
        held_values = np.array(res.parameter[1], dtype=float).reshape(-1)
        notes = dict(res.notes)
        for rows, v in answered:
            held_values[rows] = v
            for i in rows.tolist():
                where = tuple(int(c) for c in np.unravel_index(i, res.shape))
                moved_note = nearer(v, float(values[i]), bool(undefined[i]))
                read = targets.notes.get(i, ())  # how it was read: its answer's first notes
                notes[where] = (*read, *notes.get(where, ()), moved_note)
            missed = np.setdiff1d(missed, rows)
        res = dataclasses.replace(
            res, notes=notes, parameter=(res.parameter[0], held_values.reshape(res.shape))
        )
    if missed.size:
        how = [(j, targets.notes.get(i, ())) for j, i in enumerate(missed.tolist())]
        sub = targets.replace(
            poses=np.ascontiguousarray(targets.poses[missed]),
            shape=(int(missed.size),),
            invalid={},
            notes={j: n for j, n in how if n},  # how each was read, first in its notes
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


def default_value(chain: Chain, joint: Parameter) -> tuple[float, str]:
    """The value ``auto`` holds ``joint`` at when no q0 is given, and why (for its note)."""
    key = ("default", joint.name)
    found = chain.memo.get(key)
    if found is None:
        found = chain.memo[key] = (joint.default(chain), joint.default_reason(chain))
    return found  # type: ignore[return-value]


def _default_note(chain: Chain, joint: Parameter, value: float, why: str) -> str:
    """:func:`held_note` of the default value, made once per chain."""
    key = ("held note", joint.name, value)
    text = chain.memo.get(key)
    if text is None:
        text = chain.memo[key] = held_note(chain, joint, value, why)
    return text  # type: ignore[return-value]


def held_note(chain: Chain, joint: Parameter, value: float, why: str) -> str:
    """The note of an ``auto`` answer with ``joint`` held at ``value`` (``why``: whence)."""
    return (
        f"{chain.dof}-joint arm: every solution with {joint.describe(value)} ({why}), "
        f"its redundancy parameter; give q0 or {joint.keyword} for another value, "
        f"robot.self_motion for all of them"
    )


def _q0_rows(q0: ArrayLike | None, shape: tuple[int, ...], n: int) -> FloatArray | None:
    """``(N, n)`` q0 per target (flat, C order), or None; checked (finite) as solve_ik does."""
    if q0 is None:
        return None
    return parse_q0(q0, n, shape)
