"""Closed-form IK solvers, chosen from the geometry of the joint axes."""

from __future__ import annotations

from collections.abc import Callable

from kinematica.ik.analytic.arm3r import make_arm3r_solver
from kinematica.ik.analytic.parallel import make_three_parallel_solver
from kinematica.ik.analytic.planar import make_planar_solver
from kinematica.ik.analytic.wrist import make_rrp_wrist_solver, make_spherical_wrist_solver
from kinematica.ik.candidates import AnalyticSolver
from kinematica.robot import Robot

__all__ = ["find_solver"]

_FACTORIES: tuple[Callable[[Robot], AnalyticSolver | None], ...] = (
    make_spherical_wrist_solver,
    make_rrp_wrist_solver,
    make_three_parallel_solver,
    make_planar_solver,
    make_arm3r_solver,
)


def find_solver(robot: Robot, *, position_only: bool) -> AnalyticSolver | None:
    """The closed-form solver for this robot and kind of target, if there is one.

    Args:
        robot: The robot.
        position_only: True for position targets ``(N, 3)``, False for poses.

    Returns:
        A solver whose ``position_only`` matches, or ``None``.
    """
    for factory in _FACTORIES:
        solver = factory(robot)
        if solver is not None and solver.position_only == position_only:
            return solver
    return None
