"""Closed-form solvers: which structure each handles, how it is built, arms to test it on.

A closed-form solver is one C++ header (its ``Params`` struct with named fields and
``solve``, under ``cpp/include/kinematica/solvers/``) plus one Python module under
:mod:`kinematica.ik.analytic` declaring a :class:`SolverSpec`: the structure it
handles (a ``kind`` and one-line summaries in English and Spanish), a predicate on
the arm's :class:`Features`, a builder that fills the ``Params`` from the geometry
of the joint axes (a :class:`ClosedForm`, or ``None`` when a finer test fails), and
``sample_arm``, a generator of arms of the family (degenerate ones on request) that
the conformance tests solve. :data:`kinematica.ik.analytic.SOLVERS` lists the specs
in the order they are tried; nothing else names solver kinds.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.core import Chain
from kinematica.dh.joints import Convention, Joint
from kinematica.ik.structure import Features

__all__ = ["ArmSample", "ClosedForm", "SolverSpec", "TargetKind", "describe", "describing"]

FloatArray = NDArray[np.float64]
TargetKind = Literal["pose", "position"]


@dataclass(frozen=True, slots=True, eq=False)
class ClosedForm:
    """A closed-form solver built for one arm.

    Attributes:
        name: Short name; results say ``method="analytic:<name>"``.
        labels: ``(m,)`` branch names of the candidate slots.
        params: The family's C++ ``Params`` (from :mod:`kinematica._core`), filled
            for this arm: its ``ik``, ``ik_batch`` and ``candidates`` solve targets.
        position_only: True when it places the tool origin only (for a pose
            target of a reduced arm its candidates are checked on the whole pose).
        partial: True when its candidates are representatives with some joints
            held at 0 (position targets of longer arms): never a pose solver.
        exact: True when its answers are complete even on an arm whose axis
            relations hold only within tolerance (it reads no relation as exact:
            the general 6R's elimination).
        search_note: When not empty, a target it finds nothing for is searched
            numerically too, and this note says why (an elimination that may
            lose a root to round-off); such a solver is the last resort of a family.
        mark_searched: With ``search_note``: what it says of the search's answers,
            ``(poses (k, 4, 4), q (k, n), status (k,), free (k, n))``, the last two
            changed in place (the general 6R: singular, with the free joints, where a
            solution lies on a continuum); None: nothing.
    """

    name: str
    labels: tuple[str, ...]
    params: Any
    position_only: bool = False
    partial: bool = False
    exact: bool = False
    search_note: str = ""
    mark_searched: Callable[[FloatArray, FloatArray, Any, Any], None] | None = None

    @property
    def slots(self) -> int:
        """Number of candidate slots m."""
        return len(self.labels)

    @property
    def method(self) -> str:
        """The method name results carry: ``"analytic:<name>"``."""
        return f"analytic:{self.name}"


@dataclass(frozen=True, slots=True, eq=False)
class ArmSample:
    """An arm of a solver's family, as a DH table (what ``sample_arm`` gives).

    Attributes:
        links: The DH rows, base to tip.
        convention: ``"standard"`` or ``"modified"``.
        base: ``(4, 4)`` pose of frame 0, or ``None`` (identity).
        tool: ``(4, 4)`` tool in frame n, or ``None`` (identity).
        note: What is special about it (``""`` for a generic arm).
    """

    links: tuple[Joint, ...]
    convention: Convention = "standard"
    base: FloatArray | None = None
    tool: FloatArray | None = None
    note: str = ""


@dataclass(frozen=True, slots=True)
class SolverSpec:
    """The structure a closed-form solver handles, its builder, and arms of its family.

    Attributes:
        kind: Machine-readable structure, e.g. ``"spherical-wrist-6R"``.
        summary: One line for people, e.g. ``"6R, spherical wrist"``.
        summary_es: The same line in Spanish (derivation reports).
        handles: True for the features of arms of this structure.
        build: ``(chain, features, target kind) -> ClosedForm | None``.
        sample_arm: ``(rng, degenerate) -> ArmSample``: a random arm this spec
            handles; with ``degenerate``, one of the family's edge geometries
            (equal links, offsets of 1e-10, axes parallel within 1e-9, ...).
        targets: The target kinds it solves (``"pose"``, ``"position"``).
        describes: False for a solver of some targets of arms of many
            structures (it names no structure: :func:`describe` passes it by).
        derivation: The textbook derivation :mod:`kinematica.symbolic` writes for
            arms of this structure (its recipe's name), or ``None``; the recipe
            ``"reversed-spherical-wrist"`` has no symbolic steps: the report says
            the method in words.
        geometric: The geometric method's recipe for the position (``"planar"``,
            ``"arm-plane"``), or ``None``.
        singular: The named singularities of the structure (``"shoulder"``,
            ``"elbow"``, ``"wrist"``) that ``robot.singularities`` looks for.
        parameter: For a redundant arm's solver, the ``robot.ik`` keyword of the
            parameter it solves at (``"arm_angle"``); it is used only when that is
            given. ``None`` for the others.
        parameter_of: ``(chain, q (..., n)) -> (...)`` the parameter's value at
            configurations (what makes ``q`` one of the solutions at it).
    """

    kind: str
    summary: str
    summary_es: str
    handles: Callable[[Features], bool]
    build: Callable[[Chain, Features, TargetKind], ClosedForm | None]
    sample_arm: Callable[[np.random.Generator, bool], ArmSample]
    targets: tuple[TargetKind, ...] = ("pose",)
    describes: bool = True
    derivation: str | None = None
    geometric: str | None = None
    singular: frozenset[str] = frozenset()
    parameter: str | None = None
    parameter_of: Callable[[Chain, ArrayLike], FloatArray] | None = None


def describing(features: Features, specs: Iterable[SolverSpec]) -> SolverSpec | None:
    """The first spec that describes an arm of these features, or ``None``."""
    for spec in specs:
        if spec.describes and spec.handles(features):
            return spec
    return None


def describe(features: Features, specs: Iterable[SolverSpec]) -> tuple[str, str, str]:
    """``(kind, summary, summary in Spanish)`` of an arm: the first spec that handles it.

    An arm no spec describes is ``"general"``, summarised from its joint types
    and what its axes have in common.
    """
    spec = describing(features, specs)
    if spec is not None:
        return spec.kind, spec.summary, spec.summary_es
    n, types = features.dof, features.joint_types
    summary, summary_es = f"{n} joints ({types})", f"{n} articulaciones ({types})"
    if n == 6 and types == "RRRRRR" and {(0, 1), (1, 2)} <= set(features.parallel):
        summary = "6R, three parallel axes (1-2-3)"
        summary_es = "6R con tres ejes paralelos (1-2-3)"
    elif n > 6:
        summary += ", redundant"
        summary_es += ", redundante"
        if features.shoulder_center is not None:
            summary += ", spherical shoulder"
            summary_es += ", con hombro esférico"
        if features.wrist_center is not None:
            summary += ", spherical wrist"
            summary_es += ", con muñeca esférica"
    elif features.wrist_center is not None:
        summary += ", last three axes meet (wrist)"
        summary_es += ", los tres últimos ejes se cortan (muñeca)"
    elif features.shoulder_center is not None:
        summary += ", first three axes meet (shoulder)"
        summary_es += ", los tres primeros ejes se cortan (hombro)"
    return "general", summary, summary_es
