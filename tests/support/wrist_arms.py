"""Spherical-wrist arms for the decoupled solvers' tests: random arms, candidates, solvers."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from kinematica import _core_testing
from kinematica.dh import Revolute
from kinematica.ik import ClosedForm, closed_form
from kinematica.ik.analytic.arm_point import ArmGeometry, geometry_of
from kinematica.ik.analytic.spherical_wrist import random_wrist_rows
from kinematica.ik.structure import features
from kinematica.robot import Robot
from support.helpers import transform_from

FloatArray = NDArray[np.float64]


def arm_geometry(
    h: FloatArray, p: FloatArray, prismatic: bool, c: FloatArray, size: float
) -> ArmGeometry | None:
    """The builders' reading of joints 1-3 (axes h, p (3, 3) at q = 0) placing the point
    c (3,) (``km::decoupled::arm_geometry``), or None where they cannot."""
    arm = _core_testing.decoupled.arm_geometry(
        np.asarray(h, float), np.asarray(p, float), bool(prismatic), c, float(size)
    )
    return None if arm is None else geometry_of(arm)


@dataclass(frozen=True)
class Info:
    """What a solver says of each of N targets besides its candidates.

    Attributes:
        singular: ``(N,)`` the solutions form a continuum.
        near: ``(N,)`` near a singular set or a fold.
        gap: ``(N,)`` a proven distance to the reachable set (m), NaN: unknown.
        free: ``(N, n)`` the joints free in the continuum.
    """

    singular: NDArray[np.bool_]
    near: NDArray[np.bool_]
    gap: FloatArray
    free: NDArray[np.bool_]


def candidates(solver: ClosedForm, robot: Robot, T: FloatArray) -> tuple[FloatArray, Info]:
    """The solver's raw candidates ``(N, m, n)`` and its info for targets ``T (N, 4, 4)``."""
    rows = [solver.params.candidates(robot.chain.core, np.ascontiguousarray(t)) for t in T]
    n = robot.dof
    Q = np.array([r[0] for r in rows]).reshape(len(T), solver.slots, n)
    free = np.array([[(r[4] >> j) & 1 for j in range(n)] for r in rows], dtype=bool)
    info = Info(
        singular=np.array([r[1] for r in rows], dtype=bool),
        near=np.array([r[2] for r in rows], dtype=bool),
        gap=np.array([r[3] for r in rows], dtype=float),
        free=free.reshape(len(T), n),
    )
    return Q, info


# ------------------------------------------------------------ random arms
def random_wrist_arm(rng: np.random.Generator, shoulder: str, joint3: str) -> Robot:
    """A random spherical-wrist arm (the solver spec's rows), random base, tool and convention.

    Args:
        rng: Random numbers.
        shoulder: ``"meet"`` (axes 1, 2 meet), ``"parallel"`` or ``"general"`` (skew).
        joint3: ``"R23"`` (revolute, axis 3 ∥ axis 2), ``"R"`` (revolute,
            general) or ``"P"`` (slide).
    """
    rows = random_wrist_rows(rng, shoulder, joint3)
    base = transform_from(rng.normal(size=4), rng.uniform(-0.5, 0.5, 3))
    tool = transform_from(rng.normal(size=4), rng.uniform(-0.2, 0.2, 3))
    robot = Robot.from_dh(
        rows, base=base, tool=tool, name=f"{shoulder}-{joint3}", convention="standard"
    )
    if rng.random() < 0.5:
        robot = robot.to_convention("modified")
    return robot


def solver(robot: Robot) -> ClosedForm:
    cf = closed_form(robot.chain, "pose")
    assert cf is not None
    return cf


PI = math.pi


# ---------------------------------------------------------------- the builder
def shoulder(alpha1: float, a1: float) -> str:
    """The builder's shoulder kind of a PUMA-like arm with twist α1 and offset a1."""
    rows = [
        Revolute(d=0.4, a=a1, alpha=alpha1),
        Revolute(a=0.4, alpha=0.7),
        Revolute(d=0.1, a=0.05, alpha=PI / 2),
    ]
    robot = Robot.from_dh([*rows, Revolute(d=0.4)], name="arm", convention="standard")
    h, p = robot.joint_axes()
    c = robot.fk(np.zeros(4))[:3, 3]
    arm = arm_geometry(h[:3], p[:3], False, c, features(robot.chain).size)
    assert arm is not None
    return arm.kind


def rank_ratio(robot: Robot) -> float:
    """Best σmin/σmax over the builder's probes of d(tool origin)/d(q1..q3), by differences."""
    best = 0.0
    for probe in _core_testing.decoupled.PLACE_PROBES:
        q = np.zeros(robot.dof)
        q[:3] = probe
        cols = []
        for j in range(3):
            dq = np.zeros(robot.dof)
            dq[j] = 1e-6
            cols.append((robot.fk(q + dq)[:3, 3] - robot.fk(q - dq)[:3, 3]) / 2e-6)
        s = np.linalg.svd(np.stack(cols, axis=1), compute_uv=False)
        best = max(best, s[-1] / s[0])
    return best


def arm_with_point_near_axis_3(eps: float) -> Robot:
    """Joint 3 moves the tool origin on a circle of radius eps (its axis almost through it)."""
    rows = [Revolute(d=0.4, alpha=PI / 2), Revolute(a=0.4), Revolute(a=eps)]
    return Robot.from_dh([*rows, Revolute(d=0.3)], name="point near axis 3", convention="standard")


def near_flags(robot: Robot, T: FloatArray) -> NDArray[np.bool_]:
    """``(N,)`` the pose solver's near flag for poses ``T (N, 4, 4)``."""
    return candidates(solver(robot), robot, T)[1].near


# ------------------------------------------------------ tolerances, both sides
def moved_target(T: FloatArray, shift: FloatArray) -> FloatArray:
    out = T.copy()
    out[:3, 3] += shift
    return out
