"""Closed-form IK solvers, chosen from the geometry of the joint axes.

:data:`SOLVERS` lists every solver's :class:`~kinematica.ik.registry.SolverSpec`
in the order they are tried.
"""

from __future__ import annotations

from kinematica.ik.analytic import (
    arm_position,
    cylindrical,
    elbow_arms,
    general_6r,
    parallel,
    planar_arms,
    spherical_shoulder,
    spherical_wrist,
    srs,
)
from kinematica.ik.registry import SolverSpec

__all__ = ["SOLVERS"]

# Three-parallel first: an arm with axes 2-3-4 parallel and a spherical wrist
# (axes 4, 5, 6 meeting: d5 = a5 = 0) is a UR-type arm, whose solver handles it whole.
SOLVERS: tuple[SolverSpec, ...] = (
    parallel.SPEC,
    *planar_arms.SPECS,
    *cylindrical.SPECS,
    *elbow_arms.SPECS,
    *spherical_wrist.SPECS,
    *spherical_shoulder.SPECS,  # an arm with a spherical wrist too is the wrist's
    srs.SPEC,  # at an arm angle only (robot.ik(T, arm_angle=...))
    general_6r.SPEC,  # any other 6R arm: after every special family, which keep theirs
    arm_position.SPEC,  # position targets of any longer arm: tried last
)
