"""Which solver answers an arm's targets: its :class:`Plan` for one request's settings.

The closed form the structure of the joint axes allows (the first of the registry's
specs that handles the arm and builds), else the numeric search: chosen and built
once per chain (:func:`closed_form`). :func:`plan_of` readies that choice for the
targets of one kind and one request's settings (the solver, the check's options,
the notes its answers carry, what completes a closed form that may miss a
solution), made once per chain and settings and kept by the chain
(:attr:`kinematica.core.Chain.memo`): every call of :func:`kinematica.ik.solve.solve`
with those settings finds it by one look-up.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

import kinematica._core as _core
from kinematica.core import Chain
from kinematica.errors import KinematicaError
from kinematica.ik.analytic import SOLVERS, general_6r, solvers_at
from kinematica.ik.fallback import FALLBACK_NOTE, PARTIAL_NOTE, searched_note
from kinematica.ik.numeric import numeric_solver
from kinematica.ik.reach import ANSWERED as _ANSWERED
from kinematica.ik.registry import ClosedForm, TargetKind, describe
from kinematica.ik.result import prepared
from kinematica.ik.structure import features
from kinematica.ik.tolerance import Tolerance

if TYPE_CHECKING:
    from kinematica.ik.request import IKRequest

__all__ = [
    "PLANS",
    "POSE_DOF",
    "POSE_WEIGHTS",
    "POSITION_WEIGHTS",
    "REDUNDANT_DOF",
    "Plan",
    "check_options",
    "closed_form",
    "generating_found",
    "plan_of",
    "rank_five_of",
    "structure_of",
    "why_numeric",
]

FloatArray = NDArray[np.float64]

#: Joints a pose fixes: an arm of fewer reads a pose target as over-determined...
POSE_DOF = 6
#: ... and the arms ``auto`` solves at a parameter: 7 joints, one more than a pose needs.
#: Neither's plan is lean (:attr:`Plan.lean`): their answers are read again.
REDUNDANT_DOF = 7

#: The weights of the error components x, y, z, rx, ry, rz of a pose target...
POSE_WEIGHTS: tuple[float, ...] = (1.0, 1.0, 1.0, 1.0, 1.0, 1.0)
#: ... and of a position target (the orientation is free).
POSITION_WEIGHTS: tuple[float, ...] = (1.0, 1.0, 1.0, 0.0, 0.0, 0.0)


def structure_of(chain: Chain) -> tuple[str, str, str]:
    """``(kind, summary, summary in Spanish)`` of a chain's structure (see :func:`describe`)."""
    f = features(chain)
    return describe(f, SOLVERS)


def closed_form(
    chain: Chain, target: TargetKind, parameter: str | None = None
) -> ClosedForm | None:
    """The closed-form solver of a chain for pose or position targets, if there is one.

    A reduced arm (fewer than 6 joints) without a pose solver takes its
    position solver for poses: the whole pose is then checked. With
    ``parameter`` (``"arm_angle"``), the solver of a redundant arm at that
    parameter (:attr:`SolverSpec.parameter`); without, only solvers that need none.
    """
    # built once per chain (a chain is immutable: the solver is a pure function of it)
    per_chain: dict[tuple[str, str | None], ClosedForm | None]
    per_chain = chain.memo.setdefault("closed forms", {})  # type: ignore[assignment]
    key = (target, parameter)
    if key not in per_chain:
        found = None
        f = features(chain)
        for spec in solvers_at(parameter):
            if spec.handles(f):
                found = spec.build(chain, f, target)
                if found is not None:
                    break
        if found is not None and target == "pose" and parameter is None:
            found = _near_family_or_general(chain, found)
        if found is None and target == "pose" and chain.dof < 6 and parameter is None:
            position = closed_form(chain, "position")
            found = position if position is not None and not position.partial else None
        per_chain[key] = found
    return per_chain[key]


#: Configurations a family's closed form on a 6R arm near its structure is probed at.
NEAR_PROBES = 4
#: Their seed (the same verdict for the same arm, every call).
NEAR_PROBE_SEED = 32
#: A probe's own configuration counts as found where a solution is within this of it
#: (rad, every joint, mod 2π): solutions are exact to the pose tolerance, so a random
#: (regular) configuration's joints to about that over the Jacobian's σmin.
NEAR_PROBE_MATCH = 1e-6


def _near_family_or_general(chain: Chain, found: ClosedForm) -> ClosedForm:
    """A 6R family's closed form on an arm near its structure, or the general 6R's.

    Axes that have the family's structure only within the line geometry's tolerance
    (``slack``) are solved by the family's candidates, repaired; farther from it, within
    the tolerance still, the candidates reach no target (a PUMA 560 with every DH value
    moved by 2.7e-9: slack 5e-9, every pose searched, one solution). The family is
    probed on the poses of :data:`NEAR_PROBES` random configurations: where it misses
    the configuration that made one of them (:func:`generating_found`), the pose not
    solved or solved by other branches only, and the general 6R builds, that answers.
    """
    f = features(chain)
    if found.exact or f.slack <= 0.0 or f.joint_types != "RRRRRR" or found.name == "general-6R":
        return found
    rng = np.random.default_rng(NEAR_PROBE_SEED)
    Q = rng.uniform(-np.pi, np.pi, (NEAR_PROBES, 6))
    poses = np.ascontiguousarray(chain.fk(Q)[0])
    opts = check_options(Tolerance(), False, False, POSE_WEIGHTS, f.slack)
    raw = found.params.ik_batch(chain.core, poses, opts, None, None, 1)
    if generating_found(np.asarray(raw.q), np.asarray(raw.count), Q):
        return found
    general = general_6r.build(chain, f, "pose")
    return found if general is None else general


def generating_found(
    solutions: NDArray[np.float64],
    count: NDArray[np.int64],
    Q: NDArray[np.float64],
    match: float = NEAR_PROBE_MATCH,
) -> bool:
    """Whether every pose's solutions hold the configuration that made it.

    Args:
        solutions: ``(N, S, n)`` each pose's solutions (rad), its first ``count`` rows.
        count: ``(N,)`` how many solutions each pose has.
        Q: ``(N, n)`` the configurations that made the poses (rad).
        match: The largest joint difference (rad, mod 2π) of a solution found.
    """
    for q, k, made in zip(solutions, count.tolist(), Q, strict=True):
        gap = np.abs((q[:k] - made + np.pi) % (2.0 * np.pi) - np.pi)
        if not bool((gap.max(axis=-1, initial=0.0) <= match).any()):
            return False
    return True


def why_numeric(
    chain: Chain, closed: ClosedForm | None, kind: TargetKind, mask: Any
) -> tuple[str, ...]:
    """``auto``'s note on the search's answer where no closed form applies (``()``: one does).

    It says the answer is one solution of a local search, more may exist, and why no
    closed form applies (:mod:`kinematica.ik.local_search`).
    """
    if closed is not None:
        return ()
    from kinematica.ik.local_search import numeric_reason, search_note  # the search's note

    return (search_note(numeric_reason(chain, kind, mask is not None)),)


def check_options(
    tolerance: Tolerance,
    respect_limits: bool,
    complete: bool,
    weights: tuple[float, ...],
    gap_slack: float = 0.0,
) -> _core.CheckOptions:
    """The check's options for these settings (a plan keeps its own: :class:`Plan`)."""
    opts = _core.CheckOptions()
    opts.tol = _core.Tolerance(tolerance.position, tolerance.rotation)
    opts.respect_limits = bool(respect_limits)
    opts.complete = complete
    opts.weights = weights
    opts.gap_slack = gap_slack
    opts.repair = gap_slack > 0.0  # a near-degenerate arm: its family's closed form
    return opts


@dataclass(frozen=True, slots=True, eq=False)
class Plan:
    """How one chain solves the targets of one kind with one request's settings.

    Attributes:
        closed: The closed form, or None (the numeric search).
        solver: Its ``Params`` (``ik``, ``ik_batch``, ``prepare``), or the search's set-up.
        labels: The branch names of its slots.
        method: The method name results carry.
        complete: It gives every solution (an exact closed form).
        options: The check's options.
        weights: The weights of the error components x, y, z, rx, ry, rz.
        slack: The closed form's slack on a near-degenerate arm (m; 0: exact).
        search: The note of a target the closed form found nothing for, which the
            numeric search answers; None: no such search.
        notes: The notes of every answer (``auto``'s search: why no closed form applies).
        coaxial: A 6R arm's coaxial pair, whose answers :mod:`kinematica.ik.coaxial`
            gives; None.
        rank_five: A 6R arm's rank-5 structure (:mod:`kinematica.ik.rank_five`), whose
            answers :mod:`kinematica.ik.continuum_6r` (or, near one,
            :mod:`kinematica.ik.near_rank_five`) gives; None.
        direct: One target is one core call (:attr:`prepared`): neither ``coaxial`` nor
            ``rank_five``.
        prepared: The solver made ready for one target of a direct plan at no parameter
            (:func:`~kinematica.ik.result.prepared`: one core call gives the result of a
            final answer, or the answer to complete); None.
        lean: One pose target goes straight to :attr:`prepared`
            (:func:`kinematica.ik.door.solve`): an arm of 6 joints or more, but not 7.
        final: The status codes of the core's answers to one target that are final as
            they are (no search, no limited reach, no note to add): read once per plan,
            not on every call.
    """

    closed: ClosedForm | None
    solver: Any
    labels: tuple[str, ...]
    method: str
    complete: bool
    options: _core.CheckOptions
    weights: tuple[float, ...]
    slack: float
    search: str | None
    notes: tuple[str, ...]
    coaxial: Any
    rank_five: Any = None
    prepared: Any = None
    lean: bool = False
    direct: bool = field(init=False)
    final: frozenset[int] = field(init=False)

    def __post_init__(self) -> None:
        put = object.__setattr__
        put(self, "direct", self.coaxial is None and self.rank_five is None)
        final: frozenset[int] = frozenset()
        if not self.slack:  # the core's answer is the answer...
            # ...unless the limited reach may prove "unreachable" (limits respected), or
            # the closed form found nothing and the search completes it
            final = _ANSWERED if self.options.respect_limits else frozenset(_core.STATUS.values())
            if self.search is not None:
                final = final - {_core.STATUS["not_found"]}
        put(self, "final", final)


#: Plans a chain keeps (past it the oldest goes: a sweep over many tolerances).
PLANS = 32


def plan_of(
    chain: Chain, kind: TargetKind, request: IKRequest, parameter: str | None = None
) -> Plan:
    """The plan of ``chain`` for targets of ``kind`` with ``request``'s settings.

    With ``parameter`` (``"arm_angle"``), the closed form at that parameter (its value
    is the call's: see :mod:`kinematica.ik.at_values`).

    Raises:
        KinematicaError: ``method="analytic"`` on an arm without a closed form, or
            ``arm_angle`` where it is no closed form's parameter.
    """
    memo = chain.memo
    settings = request.key
    if settings is None:  # a Generator's seed: drawn from on every call
        return _plan(chain, kind, request, parameter)
    # one whole number per (settings, kind, parameter): the look-up of every call (one
    # target is looked up so in kinematica.ik.solve too)
    key = 4 * settings + (kind == "position") + 2 * (parameter is not None)
    found = memo.get(key)
    if found is None:
        found = _plan(chain, kind, request, parameter)
        plans = [k for k in memo if type(k) is int]
        if len(plans) >= PLANS:
            del memo[plans[0]]
        memo[key] = found
    return found  # type: ignore[return-value]


def _plan(chain: Chain, kind: TargetKind, request: IKRequest, parameter: str | None) -> Plan:
    """:func:`plan_of`, made."""
    assert parameter in (None, "arm_angle")  # plan_of's keys know of one parameter
    method, masked, tolerance = request.method, request.mask is not None, request.tolerance
    w = POSITION_WEIGHTS if kind == "position" else POSE_WEIGHTS
    if request.mask is not None:
        mask = np.asarray(request.mask, dtype=float)
        w = tuple(float(a * b) for a, b in zip(mask.tolist(), w, strict=True))
    closed = None if method == "numeric" or masked else closed_form(chain, kind, parameter)
    if parameter is not None:
        if method == "numeric" or masked:
            why = "method='numeric'" if method == "numeric" else "a mask"
            raise KinematicaError(
                f"arm_angle is the parameter of a closed form: it takes no {why}", arg="arm_angle"
            )
        if closed is None:
            raise KinematicaError(
                "arm_angle is a parameter of pose targets of SRS 7R arms (axes 1-3 and 5-7 "
                f"meeting) only; this arm: {structure_of(chain)[1]}",
                arg="arm_angle",
            )
    coaxial = None
    if closed is None and method != "numeric" and not masked and kind == "pose":
        from kinematica.ik.coaxial_pair import coaxial_pair  # arms without a closed form only

        coaxial = coaxial_pair(chain)
    five = None
    if method != "numeric" and not masked and kind == "pose" and parameter is None:
        five = rank_five_of(chain, closed)
    if method == "analytic" and closed is None and coaxial is None and five is None:
        why = "a mask was given" if masked else f"structure: {structure_of(chain)[1]}"
        at_angle = not masked and closed_form(chain, kind, "arm_angle") is not None
        raise KinematicaError(
            f"no closed-form solver for this arm ({why}) without an arm angle"
            if at_angle
            else f"no closed-form solver for this arm ({why})",
            arg="method",
            suggest=("arm_angle", 0.0) if at_angle else ("method", "numeric"),
        )
    respect = request.respect_limits
    if closed is not None:
        solver, labels, name = closed.params, closed.labels, closed.method
    else:
        solver, labels, name = numeric_solver(chain, tolerance, respect, request.seed, w)
    slack = features(chain).slack if closed is not None and not closed.exact else 0.0
    complete = closed is not None and slack == 0.0
    search = None  # a closed form that may miss a solution: a target it missed is searched
    if closed is not None and parameter is None:
        if closed.search_note:
            search = searched_note(closed.search_note)
        elif slack:
            search = FALLBACK_NOTE
        elif closed.partial:
            search = PARTIAL_NOTE
    notes = why_numeric(chain, closed, kind, request.mask) if method == "auto" else ()
    options = check_options(tolerance, respect, complete, w, slack)
    plan = Plan(
        closed, solver, labels, name, complete, options, w, slack, search, notes, coaxial, five
    )
    if not plan.direct or parameter is not None:
        return plan
    ready = prepared(solver, chain.core, options, labels, name, complete, notes, plan.final)
    lean = POSE_DOF <= chain.dof != REDUNDANT_DOF
    return replace(plan, prepared=ready, lean=lean)


def rank_five_of(chain: Chain, closed: ClosedForm | None) -> Any:
    """A 6R arm's rank-5 structure (exact or near) where no family's closed form answers it.

    None for the others: an arm with a closed form that is not the general 6R's last
    resort (its ``search_note``), unless that closed form is a family's on a
    near-degenerate arm (its slack): near a rank-5 arm, that family's candidates only
    seed :mod:`kinematica.ik.near_rank_five`.
    """
    if chain.dof != 6:
        return None
    near_family = closed is not None and not closed.exact and features(chain).slack > 0.0
    if closed is not None and not closed.search_note and not near_family:
        return None
    from kinematica.ik.rank_five import rank_five  # 6R arms without a family

    five = rank_five(chain)
    if five is not None and five.exact and near_family:
        return replace(five, exact=False)  # its relations within tolerance only
    return five
