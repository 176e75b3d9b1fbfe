"""Closed-form IK solvers, chosen from the geometry of the joint axes.

:data:`SOLVERS` lists every solver's :class:`~kinematica.ik.registry.SolverSpec`
in the order they are tried.
"""

from __future__ import annotations

from kinematica.ik.analytic import arm_position, elbow_arms, planar_arms, spherical_wrist
from kinematica.ik.registry import SolverSpec

__all__ = ["SOLVERS"]

SOLVERS: tuple[SolverSpec, ...] = (
    *planar_arms.SPECS,
    *elbow_arms.SPECS,
    *spherical_wrist.SPECS,
    arm_position.SPEC,  # position targets of any longer arm: tried last
)
