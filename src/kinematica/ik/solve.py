"""``robot.ik``: choose a solver, let the core solve and check the targets, wrap the answer.

One path for one target and for a batch of any shape (the solver chosen by
:mod:`kinematica.ik.solvers`): a closed-form solver's
``Params`` (or the numeric search) and the shared check run in one core call per
target or per batch (``cpp/include/kinematica/ik.hpp``), which judges every
candidate by forward kinematics; the outcome is wrapped in an :class:`IKResult`
(one target) or an :class:`IKBatchResult` (a batch).
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

import kinematica._core as _core
from kinematica.core import Chain, resolve_workers
from kinematica.errors import KinematicaError
from kinematica.ik.fallback import (
    FALLBACK_NOTE,
    INCOMPLETE_NOTE,
    PARTIAL_NOTE,
    merge_batch,
    needs_search,
    searched_note,
    seeds,
    slack_of,
)
from kinematica.ik.numeric import LABEL, METHOD, check_seed, numeric_solver
from kinematica.ik.options import IKOptions, Method
from kinematica.ik.reach import ANSWERED, beyond_limited_reach
from kinematica.ik.registry import ClosedForm, TargetKind
from kinematica.ik.result import CheckOutput, CoreAnswer, IKBatchResult, IKResult, result_of
from kinematica.ik.solvers import (
    POSE_WEIGHTS,
    POSITION_WEIGHTS,
    PoseSolver,
    check_options,
    closed_form,
    pose_solver,
    solver_of,
    structure_of,
    why_numeric,
)
from kinematica.ik.targets import (
    Targets,
    Tolerance,
    parse_mask,
    parse_q0,
    parse_targets,
    parse_tolerance,
)

__all__ = ["PoseSolver", "closed_form", "pose_solver", "solve_ik", "structure_of"]

FloatArray = NDArray[np.float64]


def _at_parameter(
    chain: Chain, closed: ClosedForm | None, options: IKOptions, masked: bool, values: FloatArray
) -> ClosedForm:
    """The closed form at the arm angle of each target (``robot.ik(T, arm_angle=...)``)."""
    if options.method == "numeric" or masked:
        why = "method='numeric'" if options.method == "numeric" else "a mask"
        raise KinematicaError(
            f"arm_angle is the parameter of a closed form: it takes no {why}", arg="arm_angle"
        )
    if closed is None:
        raise KinematicaError(
            "arm_angle is a parameter of pose targets of SRS 7R arms (axes 1-3 and 5-7 "
            f"meeting) only; this arm: {structure_of(chain)[1]}",
            arg="arm_angle",
        )
    from kinematica.ik.at_values import AtValues  # an SRS arm's arm angle only

    return replace(closed, params=AtValues(closed.params, values))


def _q0(chain: Chain, q0: ArrayLike | None, targets: Targets) -> FloatArray | None:
    """``(N, n)`` q0 per target, or None."""
    return parse_q0(q0, chain.dof, targets.shape)


_UNREACHABLE = _core.STATUS["unreachable"]
_OK = _core.STATUS["ok"]


def _searched_one(closed: ClosedForm | None, T: FloatArray, out: CoreAnswer) -> CoreAnswer:
    """The numeric search's answer for one target, as its closed form marks it.

    A closed form whose ``mark_searched`` is set (the general 6R: singular where the
    search's solution lies on a continuum) says of the search's answer what it says
    of its own; the batch path calls it on the searched rows.
    """
    if closed is None or closed.mark_searched is None:
        return out
    sols, *rest, report = out
    code, gap, near_p, near_r, near, _ = report
    if code != _OK or len(sols) == 0:
        return out
    status = np.array([code])
    free = np.zeros((1, sols.shape[1]), dtype=bool)
    closed.mark_searched(T[None], sols[:1], status, free)
    if int(status[0]) == code:
        return out
    joints = tuple(int(j) for j in np.flatnonzero(free[0]))
    return (sols, *rest, (int(status[0]), gap, near_p, near_r, near, joints))  # type: ignore[return-value]


def _limited(
    chain: Chain,
    poses: FloatArray,
    out: CoreAnswer,
    respect_limits: bool,
    tol: Tolerance,
    weights: tuple[float, ...],
) -> CoreAnswer:
    """One target's answer, "unreachable" with its gap where the limited reach proves it."""
    code, gap = out[-1][0], out[-1][1]
    if not respect_limits or code in ANSWERED:
        return out
    beyond, gaps = beyond_limited_reach(
        chain, poses[:1], np.array([code]), np.array([np.nan if gap is None else gap]),
        tol.position, weights,
    )  # fmt: skip
    if not beyond[0]:
        return out
    report = (_UNREACHABLE, float(gaps[0]), *out[-1][2:])
    return (*out[:-1], report)


def solve_ik(
    chain: Chain, target: ArrayLike | Targets, options: IKOptions
) -> IKResult | IKBatchResult:
    """Every inverse-kinematics solution of a target, or an honest status.

    See :meth:`kinematica.Robot.ik` for the arguments and what comes back. One pose
    target of an arm with fewer than 6 joints is over-determined: see
    :mod:`kinematica.ik.printed`. ``target`` may also be targets already parsed
    (:class:`~kinematica.ik.targets.Targets`). The chain is solved as it is:
    ``options.fixed`` and a redundant arm's parameter are
    :func:`kinematica.ik.redundancy.solve_arm`'s.
    """
    out = _solve(chain, target, options)
    overdetermined = (
        chain.dof < 6
        and options.mask is None
        and not isinstance(target, Targets)
        and np.shape(target) == (4, 4)
    )
    if overdetermined and isinstance(out, IKResult) and not isinstance(target, Targets):
        from kinematica.ik.printed import answer_overdetermined  # a reduced arm's pose only

        return answer_overdetermined(chain, target, options, out, _solve, options.precision)
    return out


def _solve(
    chain: Chain, target: ArrayLike | Targets, options: IKOptions
) -> IKResult | IKBatchResult:
    """:func:`solve_ik` without the over-determined targets' second look."""
    method: Method = options.method
    respect_limits, q0, workers = options.respect_limits, options.q0, options.workers
    if method not in ("auto", "analytic", "numeric"):
        raise KinematicaError(
            f"method must be 'auto', 'analytic' or 'numeric', got {method!r}", arg="method"
        )
    targets = target if isinstance(target, Targets) else parse_targets(target)
    m = parse_mask(options.mask)
    tolerance = parse_tolerance(options.tol)
    seed = check_seed(options.seed)
    threads = 1 if workers is None and targets.single else resolve_workers(workers)
    q0s = _q0(chain, q0, targets)
    kind: TargetKind = "position" if targets.position else "pose"
    w = POSITION_WEIGHTS if targets.position else POSE_WEIGHTS
    if m is not None:
        w = tuple(float(a * b) for a, b in zip(m, w, strict=True))
    values = None
    if options.arm_angle is not None:
        from kinematica.ik.at_values import parameter_values  # an SRS arm's arm angle only

        values = parameter_values("arm_angle", options.arm_angle, targets.shape)
    parameter = None if values is None else "arm_angle"
    closed = None if method == "numeric" or m is not None else closed_form(chain, kind, parameter)
    if values is not None:  # the search would not keep to the arm angle: never a fallback
        closed = _at_parameter(chain, closed, options, m is not None, values)
    if closed is None and method != "numeric" and m is None and kind == "pose":
        from kinematica.ik.coaxial import coaxial_pair, solve_coaxial  # a 6R with a coaxial pair

        pair = coaxial_pair(chain)
        if pair is not None:
            return solve_coaxial(chain, pair, targets, options, solve_ik)
    if method == "analytic" and closed is None:
        why = "a mask was given" if m is not None else f"structure: {structure_of(chain)[1]}"
        at_angle = m is None and closed_form(chain, kind, "arm_angle") is not None
        raise KinematicaError(
            f"no closed-form solver for this arm ({why}) without an arm angle"
            if at_angle
            else f"no closed-form solver for this arm ({why})",
            arg="method",
            suggest=("arm_angle", 0.0) if at_angle else ("method", "numeric"),
        )
    solver, labels, name = (
        solver_of(chain, closed, tolerance, respect_limits, seed, w)
        if closed is not None
        else numeric_solver(chain, tolerance, respect_limits, seed, w)
    )
    slack = slack_of(chain) if closed is not None and not closed.exact else 0.0
    complete = closed is not None and slack == 0.0
    opts = check_options(tolerance, respect_limits, complete, w, slack)

    # a closed form that may miss a solution: a target it found nothing for is searched
    partial = closed is not None and (closed.partial or bool(closed.search_note))
    search_text = FALLBACK_NOTE if slack else PARTIAL_NOTE
    if closed is not None and closed.search_note:
        search_text = searched_note(closed.search_note)

    def search(rows: Any) -> tuple[Any, _core.CheckOptions, FloatArray]:  # the second method
        """The search, its options, and the first guesses of the targets ``rows``."""
        found = numeric_solver(chain, tolerance, respect_limits, seed, w)[0]
        if q0s is not None:
            guess = np.ascontiguousarray(q0s[rows])
        else:
            assert closed is not None
            poses = targets.poses[rows]
            guess = seeds(closed, chain, poses, targets.position, found.middle)
        return found, check_options(tolerance, respect_limits, False, w), guess

    if targets.single:
        q0 = None if q0s is None else q0s[0]
        out: CoreAnswer = solver.ik(chain.core, targets.poses[0], opts, q0, labels)
        notes = targets.notes.get(0, ()) if targets.notes else ()
        if slack or partial:
            if needs_search(out[-1][0]) and values is None:
                numeric, nopts, guess = search(np.zeros(1, dtype=np.intp))
                out = numeric.ik(chain.core, targets.poses[0], nopts, guess[0], (LABEL,))
                out = _searched_one(closed, targets.poses[0], out)
                out = _limited(chain, targets.poses, out, respect_limits, tolerance, w)
                return result_of(*out, METHOD, False, (*notes, search_text))
            if slack:
                notes = (*notes, INCOMPLETE_NOTE)
        out = _limited(chain, targets.poses, out, respect_limits, tolerance, w)
        reason = why_numeric(chain, closed, kind, m) if method == "auto" else ()
        return result_of(*out, name, complete, (*notes, *reason))
    invalid = None
    if targets.invalid:
        invalid = np.zeros(targets.poses.shape[0], dtype=bool)
        invalid[list(targets.invalid)] = True
    raw = solver.ik_batch(chain.core, targets.poses, opts, q0s, invalid, threads)
    shape = targets.shape

    def where(i: int) -> tuple[int, ...]:
        return tuple(int(v) for v in np.unravel_index(i, shape))

    batch_notes = {where(i): note for i, note in targets.notes.items()}
    if method == "auto" and (reason := why_numeric(chain, closed, kind, m)):
        for i in range(targets.poses.shape[0]):
            if i not in targets.invalid:
                batch_notes[where(i)] = (*batch_notes.get(where(i), ()), *reason)
    methods: dict[tuple[int, ...], str] = {}
    if slack or partial:
        rows = np.flatnonzero(needs_search(raw["status"]) & (values is None))
        if rows.size:
            numeric, nopts, guess = search(rows)
            poses = np.ascontiguousarray(targets.poses[rows])
            searched = numeric.ik_batch(chain.core, poses, nopts, guess, None, threads)
            if closed is not None and closed.mark_searched is not None:
                q = searched["q"][:, 0]
                closed.mark_searched(poses, q, searched["status"], searched["free"])
            raw = merge_batch(raw, rows, searched)
            labels = (*labels, LABEL)
        searched_rows = set(rows.tolist())
        methods = {where(i): METHOD for i in searched_rows}
        for i in range(targets.poses.shape[0]):
            if i in targets.invalid:
                continue
            idx = where(i)
            if i in searched_rows:
                batch_notes[idx] = (*batch_notes.get(idx, ()), search_text)
            elif slack:
                batch_notes[idx] = (*batch_notes.get(idx, ()), INCOMPLETE_NOTE)
    if respect_limits:
        beyond, gaps = beyond_limited_reach(
            chain, targets.poses, raw["status"], raw["gap"], tolerance.position, w
        )
        if beyond.any():
            raw = dict(raw, status=np.where(beyond, _UNREACHABLE, raw["status"]))
            raw["gap"] = np.where(beyond, gaps, raw["gap"])
    over = chain.dof < 6 and m is None and not targets.position
    if over and not isinstance(target, Targets):  # over-determined poses
        from kinematica.ik.printed import overdetermined_rows

        raw, more = overdetermined_rows(chain, target, options, raw, labels, q0s, solve_ik)
        for i, extra in more.items():
            batch_notes[where(i)] = extra
    return IKBatchResult(
        raw=CheckOutput(**raw),
        method=name,
        labels=labels,
        shape=shape,
        errors={where(i): msg for i, msg in targets.invalid.items()},
        notes=batch_notes,
        complete=complete,
        methods=methods,
    )
