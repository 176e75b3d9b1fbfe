"""An arm solved as it is: the request, the arm's plan, one core call, the answer.

:func:`solve_ik` is where every target of ``robot.ik`` is solved (through
:func:`kinematica.ik.door.solve`; a redundant arm's parameter is held by
:func:`kinematica.ik.redundancy.solve_arm`, which comes back here with the arm the lock
leaves), one target or a batch of any shape. The chain's :class:`~kinematica.ik.
solvers.Plan` for the request's settings (made once, kept by the chain) names the
solver, a closed form's ``Params`` or the numeric search; the solver and the shared
check run in one core call per target or per batch (``cpp/include/kinematica/ik.hpp``),
which judges every candidate by forward kinematics; the outcome is wrapped in an
:class:`IKResult` (one target) or an :class:`IKBatchResult` (a batch).

One target given as the core reads it (a C-contiguous float ``(4, 4)`` pose, or a
``(3,)`` position placed in the identity pose) is not parsed: the core checks that it
is rigid to round-off in the same call (``Plan.prepared``), and only a target it refuses is
read by :func:`~kinematica.ik.targets.parse_targets` (projected onto SO(3) with a
note, or explained). What an answer then needs is decided by the answer: the numeric
search where a closed form that may miss a solution found none (:mod:`kinematica.ik.
fallback`), the limited reach where nothing was proven (:mod:`kinematica.ik.reach`),
the over-determined reading of an arm of fewer than 6 joints
(:mod:`kinematica.ik.printed`).
"""

from __future__ import annotations

import math
from typing import Any, cast

import numpy as np
from numpy.typing import ArrayLike, NDArray

import kinematica._core as _core
from kinematica.core import Chain, resolve_workers
from kinematica.ik.fallback import INCOMPLETE_NOTE, merge_batch, needs_search, seeds
from kinematica.ik.numeric import LABEL, METHOD, numeric_solver
from kinematica.ik.options import IKOptions
from kinematica.ik.reach import ANSWERED, beyond_limited_reach
from kinematica.ik.registry import ClosedForm, TargetKind
from kinematica.ik.request import IKRequest
from kinematica.ik.result import IKBatchResult, IKResult, amended, prepared, replaced, result_of
from kinematica.ik.solvers import (
    POSE_DOF,
    REDUNDANT_DOF,
    Plan,
    check_options,
    closed_form,
    plan_of,
    structure_of,
)
from kinematica.ik.status import STATUS_NAMES, IKStatus
from kinematica.ik.targets import Targets, parse_q0, parse_targets

__all__ = ["AT_VALUES", "REDUNDANT_DOF", "answered", "closed_form", "solve_ik", "structure_of"]

FloatArray = NDArray[np.float64]

_UNREACHABLE = _core.STATUS["unreachable"]
_OK = _core.STATUS["ok"]
_NOT_FOUND = _core.STATUS["not_found"]
_UNPROVEN = min(_UNREACHABLE, _NOT_FOUND)  # the least status code of an answer without a proof
_FLOAT64 = np.dtype(np.float64)
#: Where a position target is placed (the orientation is free).
_IDENTITY = np.eye(4)


def _searched_one(closed: ClosedForm | None, T: FloatArray, res: IKResult) -> IKResult:
    """The numeric search's answer for one target, as its closed form marks it.

    A closed form whose ``mark_searched`` is set (the general 6R: singular where the
    search's solution lies on a continuum) says of the search's answer what it says
    of its own; the batch path calls it on the searched rows.
    """
    if closed is None or closed.mark_searched is None or res.status != "ok" or not res.count:
        return res
    status = np.array([_OK])
    free = np.zeros((1, res.solutions.shape[1]), dtype=bool)
    closed.mark_searched(T[None], res.solutions[:1], status, free)
    if int(status[0]) == _OK:
        return res
    joints = tuple(int(j) for j in np.flatnonzero(free[0]))
    return amended(res, status=STATUS_NAMES[int(status[0])], free_joints=joints)


def _limited(chain: Chain, pose: FloatArray, res: IKResult, plan: Plan, tol: float) -> IKResult:
    """One target's answer, "unreachable" with its gap where the limited reach proves it."""
    code = _core.STATUS[res.status.value]
    if code in ANSWERED:
        return res
    gap = np.nan if res.gap is None else res.gap
    beyond, gaps = beyond_limited_reach(
        chain, pose[None], np.array([code]), np.array([gap]), tol, plan.weights
    )
    if not beyond[0]:
        return res
    return amended(res, status=IKStatus.UNREACHABLE, gap=float(gaps[0]))


def _search(chain: Chain, plan: Plan, request: IKRequest) -> tuple[Any, _core.CheckOptions]:
    """The numeric search that completes ``plan``'s closed form, and its check's options."""
    found = numeric_solver(chain, request.tolerance, request.respect_limits, request.seed,
                           plan.weights)[0]  # fmt: skip
    return found, check_options(request.tolerance, request.respect_limits, False, plan.weights)


def solve_ik(
    chain: Chain, target: ArrayLike | Targets, options: IKOptions, look: bool = True
) -> IKResult | IKBatchResult:
    """Every inverse-kinematics solution of a target of the chain as it is, or an honest status.

    See :meth:`kinematica.Robot.ik` for the arguments and what comes back. One pose
    target of an arm with fewer than 6 joints is over-determined (``look``: its answer
    is read so, :mod:`kinematica.ik.printed`). ``target`` may also be targets already
    parsed (:class:`~kinematica.ik.targets.Targets`). The chain is solved as it is:
    ``options.fixed`` and a redundant arm's parameter are :func:`kinematica.ik.door.solve`'s.
    """
    request = options if type(options) is IKRequest else IKRequest.of(options)
    if look and chain.dof < POSE_DOF and request.mask is None:
        first = solve_ik(chain, target, request, False)
        if isinstance(first, IKResult) and not isinstance(target, Targets):
            if np.shape(target) != (4, 4):
                return first
            from kinematica.ik.printed import answer_overdetermined  # a reduced arm's pose

            return answer_overdetermined(chain, target, request, first, _as_is, request.precision)
        return first
    kind: TargetKind | None = None
    angle = request.arm_angle  # one number (an SRS arm's arm angle) or None
    q0 = request.q0  # beside one arm angle: a float64 (n,) vector the core reads as it is
    if (
        type(target) is np.ndarray
        and target.dtype is _FLOAT64
        and (request.bare or (type(angle) is float and math.isfinite(angle) and _one_q0(chain, q0)))
    ):  # one target as the core reads it: not parsed
        if target.shape == (4, 4):
            pose, kind = target, "pose"
        elif target.shape == (3,):
            pose, kind = _IDENTITY.copy(), "position"
            pose[0, 3], pose[1, 3], pose[2, 3] = target.tolist()
    if kind is not None:  # the core checks that it is rigid, in the same call
        key = request.key  # the plan, found by a whole number (plan_of)
        plan: Plan | None = None
        if key is not None and angle is None:
            plan = chain.memo.get(4 * key + (kind == "position"))  # type: ignore[assignment]
        if plan is None:
            plan = plan_of(chain, kind, request, None if angle is None else "arm_angle")
        ready = plan.prepared if angle is None else _at(chain, plan, float(angle))  # type: ignore[arg-type]
        # one core call: the result (None where the core does not read the pose, or q0,
        # as it is: a q0 beyond the joints' limits or a turn is solved as a batch of one)
        got = None if ready is None else ready(pose, q0)
        if got.__class__ is IKResult:  # final as the core gives it (answered's first case)
            return got
        if got is not None:
            q0_one = cast("FloatArray | None", q0)  # None, or (n,) float64 (_one_q0)
            return answered(chain, plan, request, pose, kind, got, (), q0_one)
    targets = target if isinstance(target, Targets) else parse_targets(target)
    kind = "position" if targets.position else "pose"
    values = None
    if request.arm_angle is not None:
        from kinematica.ik.at_values import parameter_values  # an SRS arm's arm angle only

        values = parameter_values("arm_angle", request.arm_angle, targets.shape)
    plan = plan_of(chain, kind, request, None if values is None else "arm_angle")
    if plan.coaxial is not None:
        from kinematica.ik.coaxial import solve_coaxial  # a 6R with a coaxial pair

        return solve_coaxial(chain, plan.coaxial, targets, request, solve_ik)
    if plan.rank_five is not None and values is None:  # a 6R arm of rank 5, or near one
        from kinematica.ik.continuum_6r import solve_continuum
        from kinematica.ik.near_rank_five import solve_near

        if plan.rank_five.exact:
            return solve_continuum(chain, plan.rank_five, targets, request, solve_ik)
        return solve_near(chain, plan.rank_five, plan.closed, targets, request, solve_ik)
    solver = plan.solver
    if values is not None:
        from kinematica.ik.at_values import AtValues

        solver = AtValues(solver, values)
    q0s = parse_q0(request.q0, chain.dof, targets.shape)
    if targets.single:
        pose = targets.poses[0]
        q0 = None if q0s is None else q0s[0]
        out = solver.ik(chain.core, pose, plan.options, q0, plan.labels)
        notes = targets.notes.get(0, ()) if targets.notes else ()
        return answered(chain, plan, request, pose, kind, out, notes, q0)
    return _batch(chain, target, targets, request, plan, solver, q0s)


def _one_q0(chain: Chain, q0: object) -> bool:
    """True for no ``q0``, or one the core reads as it is: a float64 ``(n,)`` array."""
    return q0 is None or (
        type(q0) is np.ndarray and q0.dtype is _FLOAT64 and q0.shape == (chain.dof,)
    )


#: Closed forms at one value of their parameter a chain keeps (:func:`_at`).
AT_VALUES = 16


def _as_is(chain: Chain, target: ArrayLike, options: IKOptions) -> IKResult | IKBatchResult:
    """:func:`solve_ik` without the over-determined reading (:mod:`kinematica.ik.printed`'s)."""
    return solve_ik(chain, target, options, False)


def _at(chain: Chain, plan: Plan, value: float) -> Any:
    """``plan``'s closed form at ``value`` of its parameter, prepared (once per value, kept)."""
    memo: dict[tuple[Plan, float], Any]
    memo = chain.memo.setdefault("at values", {})  # type: ignore[assignment]
    found = memo.get((plan, value))
    if found is None:
        if len(memo) >= AT_VALUES:
            memo.clear()
        if not plan.direct:
            return None
        found = memo[plan, value] = prepared(
            plan.solver.at(value), chain.core, plan.options, plan.labels, plan.method,
            plan.complete, plan.notes, plan.final,
        )  # fmt: skip
    return found


def answered(
    chain: Chain,
    plan: Plan,
    request: IKRequest,
    pose: FloatArray,
    kind: TargetKind,
    out: _core.Answer,
    notes: tuple[str, ...],
    q0: FloatArray | None,
) -> IKResult:
    """The answer to one target from the core's ``out``, completed where it proves nothing."""
    code = out.status
    if plan.search is not None and code == _NOT_FOUND:  # the closed form found nothing
        numeric, nopts = _search(chain, plan, request)
        if q0 is None:
            assert plan.closed is not None
            q0 = seeds(plan.closed, chain, pose[None], kind == "position", numeric.middle)[0]
        res = result_of(numeric.ik(chain.core, pose, nopts, q0, (LABEL,)), METHOD, False,
                        (*notes, plan.search))  # fmt: skip
        res = _searched_one(plan.closed, pose, res)
        if request.respect_limits:
            res = _limited(chain, pose, res, plan, request.tolerance.position)
        return res
    if plan.slack:
        notes = (*notes, INCOMPLETE_NOTE)
    res = result_of(out, plan.method, plan.complete, (*notes, *plan.notes) if notes else plan.notes)
    if request.respect_limits and code not in ANSWERED:
        res = _limited(chain, pose, res, plan, request.tolerance.position)
    return res


def _batch(
    chain: Chain,
    target: ArrayLike | Targets,
    targets: Targets,
    request: IKRequest,
    plan: Plan,
    solver: Any,
    q0s: FloatArray | None,
) -> IKBatchResult:
    """The answers to a batch of targets (one core call, then the rows that need more)."""
    respect_limits, tolerance = request.respect_limits, request.tolerance
    labels, name, closed, w, slack = plan.labels, plan.method, plan.closed, plan.weights, plan.slack
    threads = resolve_workers(request.workers)
    invalid = None
    if targets.invalid:
        invalid = np.zeros(targets.poses.shape[0], dtype=bool)
        invalid[list(targets.invalid)] = True
    raw = solver.ik_batch(chain.core, targets.poses, plan.options, q0s, invalid, threads)
    shape = targets.shape
    at: list[tuple[int, ...]] = []  # the batch index of each flat row, made at once

    def where(i: int) -> tuple[int, ...]:
        if not at:  # (a row at a time cost 2 µs)
            rows = zip(*(a.ravel().tolist() for a in np.indices(shape)), strict=True)
            at.extend(rows if shape else [()])
        return at[i]

    batch_notes = {where(i): note for i, note in targets.notes.items()}
    if plan.notes:  # auto's search: why no closed form applies
        for i in range(targets.poses.shape[0]):
            if i not in targets.invalid:
                batch_notes[where(i)] = (*batch_notes.get(where(i), ()), *plan.notes)
    methods: dict[tuple[int, ...], str] = {}
    if plan.search is not None or slack:
        rows = np.flatnonzero(needs_search(raw.status) & (plan.search is not None))
        if rows.size:  # the closed form found nothing: the search answers
            numeric, nopts = _search(chain, plan, request)
            poses = np.ascontiguousarray(targets.poses[rows])
            if q0s is not None:
                guess = np.ascontiguousarray(q0s[rows])
            else:
                assert closed is not None
                guess = seeds(closed, chain, poses, targets.position, numeric.middle)
            searched = numeric.ik_batch(chain.core, poses, nopts, guess, None, threads)
            raw = merge_batch(raw, rows, searched, closed, poses)
            labels = (*labels, LABEL)
        searched_rows = set(rows.tolist())
        methods = {where(i): METHOD for i in searched_rows}
        # each searched row's note, and with slack every other row's (a valid target's)
        for i in range(targets.poses.shape[0]) if slack else sorted(searched_rows):
            if i in targets.invalid:
                continue
            idx = where(i)
            if i in searched_rows:
                batch_notes[idx] = (*batch_notes.get(idx, ()), str(plan.search))
            else:
                batch_notes[idx] = (*batch_notes.get(idx, ()), INCOMPLETE_NOTE)
    # only a row that proved nothing ("not found", or "unreachable" without a gap) can be
    # proved beyond the limited reach: none where every status is below both codes
    if respect_limits and raw.status.size and int(raw.status.max()) >= _UNPROVEN:
        beyond, gaps = beyond_limited_reach(
            chain, targets.poses, raw.status, raw.gap, tolerance.position, w
        )
        if beyond.any():
            status = np.where(beyond, _UNREACHABLE, raw.status)
            raw = replaced(raw, status=status, gap=np.where(beyond, gaps, raw.gap))
    over = chain.dof < POSE_DOF and request.mask is None and not targets.position
    if over and not isinstance(target, Targets):  # over-determined poses
        from kinematica.ik.printed import overdetermined_rows

        raw, more = overdetermined_rows(chain, target, request, raw, labels, q0s, solve_ik)
        for i, extra in more.items():
            batch_notes[where(i)] = extra
    return IKBatchResult(
        raw=raw,
        method=name,
        labels=labels,
        shape=shape,
        errors={where(i): msg for i, msg in targets.invalid.items()},
        notes=batch_notes,
        complete=plan.complete,
        methods=methods,
    )
