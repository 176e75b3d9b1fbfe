"""Closed-form solvers: which structure each handles, and how it is built.

A closed-form solver is a kernel over one target (and the same kernel in a
parallel loop for a batch) with its parameters, computed once per arm from
the geometry of its joint axes (:class:`Features`). Each solver module
declares a :class:`SolverSpec`: the structure it handles (a ``kind`` and a
one-line ``summary`` for people), a predicate on the features, and a builder
that returns a :class:`ClosedForm` (or ``None`` when a finer test fails).

Adding a solver: write its kernel (``solve(params, T, Q, info)``, see
:mod:`kinematica.kernels.ik_check` for ``Q`` and ``info``) and a batch loop
over it, a builder packing its parameters, a ``SolverSpec``, and add the spec
to :data:`SOLVERS`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
from numpy.typing import NDArray

from kinematica.dh import DHChain
from kinematica.ik.structure import Features

__all__ = ["ClosedForm", "SolverSpec", "TargetKind", "describe"]

FloatArray = NDArray[np.float64]
TargetKind = Literal["pose", "position"]


@dataclass(frozen=True, eq=False)
class ClosedForm:
    """A closed-form solver built for one arm.

    Attributes:
        name: Short name; results say ``method="analytic:<name>"``.
        labels: ``(m,)`` branch names of the candidate slots.
        params: The kernel's parameters (a flat float array).
        solve_one: Kernel ``(params, T (4, 4), Q (m, n), info) -> None``.
        solve_batch: Kernel ``(params, T (N, 4, 4), Q (N, m, n), info (N, k)) -> None``.
        position_only: True when it places the tool origin only (for a pose
            target of a reduced arm its candidates are checked on the whole pose).
        partial: True when its candidates are representatives with some joints
            held at 0 (position targets of longer arms): never a pose solver.
    """

    name: str
    labels: tuple[str, ...]
    params: FloatArray
    solve_one: Any
    solve_batch: Any
    position_only: bool = False
    partial: bool = False

    @property
    def slots(self) -> int:
        """Number of candidate slots m."""
        return len(self.labels)

    @property
    def method(self) -> str:
        """The method name results carry: ``"analytic:<name>"``."""
        return f"analytic:{self.name}"


@dataclass(frozen=True)
class SolverSpec:
    """The structure a closed-form solver handles, and its builder.

    Attributes:
        kind: Machine-readable structure, e.g. ``"spherical-wrist-6R"``.
        summary: One line for people, e.g. ``"6R, spherical wrist"``.
        handles: True for the features of arms of this structure.
        build: ``(chain, features, target kind) -> ClosedForm | None``.
        describes: False for a solver of some targets of arms of many
            structures (it names no structure: :func:`describe` passes it by).
    """

    kind: str
    summary: str
    handles: Callable[[Features], bool]
    build: Callable[[DHChain, Features, TargetKind], ClosedForm | None]
    describes: bool = True


def describe(features: Features, specs: tuple[SolverSpec, ...]) -> tuple[str, str]:
    """``(kind, summary)`` of an arm: the first spec that handles it, else a general one."""
    for spec in specs:
        if spec.describes and spec.handles(features):
            return spec.kind, spec.summary
    n, types = features.dof, features.joint_types
    summary = f"{n} joints ({types})"
    if n == 6 and types == "RRRRRR" and {(0, 1), (1, 2)} <= set(features.parallel):
        summary = "6R, three parallel axes (1-2-3)"
    elif n > 6:
        summary += ", redundant"
        if features.wrist_center is not None:
            summary += ", spherical wrist"
    elif features.wrist_center is not None:
        summary += ", last three axes meet (wrist)"
    return "general", summary
