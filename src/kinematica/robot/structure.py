"""The structure of an arm, read from the geometry of its joint axes."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from kinematica.ik.analytic import SOLVERS
from kinematica.ik.registry import describe, describing
from kinematica.ik.structure import Features, features

if TYPE_CHECKING:
    from kinematica.ik.registry import SolverSpec
    from kinematica.robot.description import RobotDescription

__all__ = ["Structure", "classify"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class Structure:
    """What the joint axes of an arm have in common, and the class it belongs to.

    Attributes:
        kind: Machine-readable class: the structure a closed-form solver
            handles (``"planar-2R"``, ``"planar-3R"``, ``"planar-PR"``,
            ``"planar-PRR"``, ``"scara"``, ``"anthropomorphic-3R"``,
            ``"elbow-3R"``, ``"spherical-wrist-6R"``, ``"three-parallel-6R"``,
            ``"rrp-spherical-wrist"``, ``"srs-7R"``), or ``"general"``.
        summary: One line for people, e.g. ``"6R, spherical wrist"``.
        features: The geometry of the joint axes at q = 0.
        summary_es: The line in Spanish, e.g. ``"6R con muñeca esférica"``.
        spec: The closed-form solver's spec of the class (its derivation, its named
            singularities), or ``None`` for ``"general"``.
    """

    kind: str
    summary: str
    features: Features
    summary_es: str = ""
    spec: SolverSpec | None = None

    @property
    def joint_types(self) -> str:
        """One letter per joint, e.g. ``"RRRRRR"``."""
        return self.features.joint_types

    @property
    def parallel(self) -> tuple[tuple[int, int], ...]:
        """Index pairs ``(i, i+1)`` (0-based) of consecutive parallel axes."""
        return self.features.parallel

    @property
    def intersecting(self) -> tuple[tuple[int, int], ...]:
        """Index pairs ``(i, i+1)`` of consecutive axes that meet."""
        return self.features.intersecting

    @property
    def wrist_center(self) -> FloatArray | None:
        """``(3,)`` where the last three axes meet at q = 0 (base frame), or None."""
        return self.features.wrist_center


def classify(robot: RobotDescription) -> Structure:
    """Classify an arm from its joint axes at q = 0 (never from its name)."""
    f = features(robot.chain)
    kind, summary, summary_es = describe(f, SOLVERS)
    return Structure(kind, summary, f, summary_es, describing(f, SOLVERS))
