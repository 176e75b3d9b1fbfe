"""Closed-form IK solvers, chosen from the geometry of the joint axes.

:data:`SOLVERS` lists every solver's :class:`~kinematica.ik.registry.SolverSpec`
in the order they are tried.
"""

from __future__ import annotations

from kinematica.ik.analytic import elbow_arms, planar_arms
from kinematica.ik.registry import SolverSpec

__all__ = ["SOLVERS"]

SOLVERS: tuple[SolverSpec, ...] = (
    *planar_arms.SPECS,
    *elbow_arms.SPECS,
)
