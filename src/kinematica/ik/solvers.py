"""Which solver answers an arm's targets, and the one-pose path of ``robot.ik``.

The closed form the structure of the joint axes allows (the first of the registry's
specs that handles the arm and builds), else the numeric search: chosen and built
once per chain (:func:`closed_form`), with the check's options once per settings
(:func:`check_options`). :func:`pose_solver` readies the choice for one rigid
target with every default, the path ``robot.ik(T)`` takes without the general
parsing of :func:`kinematica.ik.solve.solve_ik`, whose module (and the modules
of its options, of the arm angle's values, ...) it does not import.
"""

from __future__ import annotations

import weakref
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from numpy.typing import NDArray

import kinematica._core as _core
from kinematica.core import Chain
from kinematica.ik.analytic import SOLVERS, solvers_at
from kinematica.ik.reach import ANSWERED, needs_proof
from kinematica.ik.registry import ClosedForm, TargetKind, describe
from kinematica.ik.result import CoreAnswer, IKResult, result_of
from kinematica.ik.structure import features
from kinematica.ik.tolerance import parse_tolerance
from kinematica.spatial import ROUNDOFF_TOL

if TYPE_CHECKING:
    from kinematica.ik.tolerance import Tolerance

__all__ = [
    "POSE_WEIGHTS",
    "POSITION_WEIGHTS",
    "PoseSolver",
    "check_options",
    "closed_form",
    "pose_solver",
    "solver_of",
    "structure_of",
    "why_numeric",
]

FloatArray = NDArray[np.float64]

#: The weights of the error components x, y, z, rx, ry, rz of a pose target...
POSE_WEIGHTS: tuple[float, ...] = (1.0, 1.0, 1.0, 1.0, 1.0, 1.0)
#: ... and of a position target (the orientation is free).
POSITION_WEIGHTS: tuple[float, ...] = (1.0, 1.0, 1.0, 0.0, 0.0, 0.0)

# Closed-form solvers are built once per chain (a chain is immutable, so the
# solver is a pure function of it); the cache forgets a chain when it dies.
_SOLVERS: weakref.WeakKeyDictionary[Chain, dict[tuple[str, str | None], ClosedForm | None]] = (
    weakref.WeakKeyDictionary()
)


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
    per_chain = _SOLVERS.setdefault(chain, {})
    key = (target, parameter)
    if key not in per_chain:
        found = None
        f = features(chain)
        for spec in solvers_at(parameter):
            if spec.handles(f):
                found = spec.build(chain, f, target)
                if found is not None:
                    break
        if found is None and target == "pose" and chain.dof < 6 and parameter is None:
            position = closed_form(chain, "position")
            found = position if position is not None and not position.partial else None
        per_chain[key] = found
    return per_chain[key]


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


# The core's check options, one per combination of settings seen.
_CHECK_OPTIONS: dict[tuple[object, ...], _core.CheckOptions] = {}


def check_options(
    tolerance: Tolerance,
    respect_limits: bool,
    complete: bool,
    weights: tuple[float, ...],
    gap_slack: float = 0.0,
) -> _core.CheckOptions:
    """The check's options for these settings (built once, then reused)."""
    key = (
        tolerance.position, tolerance.rotation, bool(respect_limits), complete, weights, gap_slack
    )  # fmt: skip
    opts = _CHECK_OPTIONS.get(key)
    if opts is None:
        opts = _core.CheckOptions()
        opts.tol_position = tolerance.position
        opts.tol_rotation = tolerance.rotation
        opts.respect_limits = bool(respect_limits)
        opts.complete = complete
        opts.weights = weights
        opts.gap_slack = gap_slack
        opts.repair = gap_slack > 0.0  # a near-degenerate arm: its family's closed form
        if len(_CHECK_OPTIONS) < 64:
            _CHECK_OPTIONS[key] = opts
    return opts


class PoseSolver:
    """What ``robot.ik(T)`` with every default runs for one pose (see :func:`pose_solver`).

    A plain class (a named tuple's class took 0.15 ms to make, at the first ``robot.ik``).

    Attributes:
        ik_rigid: The solver's ``ik_rigid(chain, T, options, roundoff, labels)``.
        options: The check's options.
        labels: The branch names of its slots.
        method: The method name results carry.
        complete: It gives every solution (a closed form).
        direct: Its answer is the whole answer where it proves something (False for
            a closed form on a near-degenerate arm: see :mod:`kinematica.ik.fallback`).
        notes: The notes of its answers (``auto``'s search: why no closed form applies).
    """

    __slots__ = ("complete", "direct", "ik_rigid", "labels", "method", "notes", "options")

    def __init__(
        self,
        ik_rigid: Any,
        options: _core.CheckOptions,
        labels: tuple[str, ...],
        method: str,
        complete: bool,
        direct: bool = True,
        notes: tuple[str, ...] = (),
    ) -> None:
        self.ik_rigid = ik_rigid
        self.options = options
        self.labels = labels
        self.method = method
        self.complete = complete
        self.direct = direct
        self.notes = notes

    def rigid(self, chain: _core.Chain, pose: FloatArray) -> IKResult | None:
        """The answer for one rigid ``(4, 4)`` pose, or None when the general path must give it.

        None when the core found nothing it can vouch for without the reach within
        the limits, which only the general path tries.
        """
        out: CoreAnswer | None = self.ik_rigid(chain, pose, self.options, ROUNDOFF_TOL, self.labels)
        if out is None or (out[5][0] not in ANSWERED and needs_proof(out[5][0], out[5][1])):
            return None
        return result_of(*out, self.method, self.complete, self.notes)


def pose_solver(
    chain: Chain,
    kind: TargetKind = "pose",
    parameter: str | None = None,
    method: Literal["auto", "numeric"] = "auto",
) -> PoseSolver:
    """The solver ``solve_ik`` picks for one target of this kind with the default options.

    The same choice and settings as :func:`solve_ik` makes (closed form when the
    structure allows, else the numeric search with the default seed; with ``method``
    ``"numeric"``, the search), ready for ``robot.ik``'s one-target path, which skips
    the general parsing when the target is a rigid transform to round-off (a position:
    placed in the identity pose, as :func:`~kinematica.ik.targets.parse_targets` places
    it). With ``parameter`` (``"arm_angle"``), the closed form at it, which the chain
    must have (:func:`closed_form`); its ``ik_rigid`` solves at the value its ``Params``
    hold.
    """
    tolerance = parse_tolerance(None)
    w = POSITION_WEIGHTS if kind == "position" else POSE_WEIGHTS
    closed = None if method == "numeric" else closed_form(chain, kind, parameter)
    if parameter is not None and closed is None:
        raise ValueError(f"this chain has no closed form at the parameter {parameter!r}")
    solver, labels, name = solver_of(chain, closed, tolerance, True, None, w)
    complete = closed is not None
    opts = check_options(tolerance, True, complete, w)
    # (a closed form with a search_note, or a partial one, says not_found where it proves
    # nothing, and the one-pose path hands not_found to the general one, which searches)
    direct = closed is None or closed.exact or features(chain).slack == 0.0
    if closed is None and method == "auto" and kind == "pose" and _coaxial(chain):
        direct = False  # the general path answers: a continuum (kinematica.ik.coaxial)
    # the search's answers for "auto" say why no closed form applies; "numeric" was asked for
    notes = why_numeric(chain, closed, kind, None) if method == "auto" else ()
    return PoseSolver(solver.ik_rigid, opts, labels, name, complete, direct, notes)


def _coaxial(chain: Chain) -> bool:
    """True for a 6R arm with two consecutive joints on one line (:mod:`kinematica.ik.coaxial`)."""
    from kinematica.ik.coaxial_pair import coaxial_pair  # arms without a closed form only

    return coaxial_pair(chain) is not None


def solver_of(
    chain: Chain,
    closed: ClosedForm | None,
    tolerance: Tolerance,
    respect_limits: bool,
    seed: int | np.random.Generator | None,
    weights: tuple[float, ...],
) -> tuple[Any, tuple[str, ...], str]:
    """``(solver, branch labels, method name)``: the closed form, else the numeric search.

    (:func:`kinematica.ik.solve.solve_ik`, which loads the numeric module anyway, asks
    :func:`~kinematica.ik.numeric.numeric_solver` itself: no import on each call.)
    """
    if closed is not None:
        return closed.params, closed.labels, closed.method
    from kinematica.ik.numeric import numeric_solver  # an arm without a closed form

    return numeric_solver(chain, tolerance, respect_limits, seed, weights)
