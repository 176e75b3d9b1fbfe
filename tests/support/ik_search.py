"""Independent references for IK tests: joint distances, and a multi-start search.

The search knows nothing of the closed forms: damped least squares from many
random starts on the robot's own FK and Jacobian (numpy, scipy's rotation
vector), then Gauss-Newton steps; every converged start is a solution. It is
the completeness reference of the closed-form tests.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray
from scipy.spatial.transform import Rotation

from kinematica.robot import Robot

FloatArray = NDArray[np.float64]


#: Round-off of a target, with a margin of 1,000 (m or rad, for arms of about a metre):
#: the configuration that made a target is found to within what it moves a solution by.
FOUND_SCALE = 1e-13
#: ... but never asked closer than this (rad).
FOUND_FLOOR = 1e-9


def found_tolerance(robot: Robot, q: FloatArray, position: bool = False) -> float:
    """How close to ``q`` a solution of the target ``fk(q)`` must be (rad).

    A change δ of the target (FOUND_SCALE) moves a solution by δ / σmin where the
    Jacobian is well conditioned, and by at most √(2 δ / κ) at a fold (two branches
    meeting), κ the curvature of the forward kinematics along the Jacobian's null
    direction (m / rad²): the smaller of the two, at least FOUND_FLOOR.

    Args:
        robot: The robot.
        q: ``(n,)`` the configuration that made the target.
        position: The target is the tool origin only (the Jacobian's linear rows).
    """
    rows = 3 if position else 6

    def task(x: FloatArray) -> FloatArray:
        T = robot.fk(x)
        if position:
            return np.asarray(T[:3, 3])
        rot = Rotation.from_matrix(T[:3, :3] @ robot.fk(q)[:3, :3].T).as_rotvec()
        return np.concatenate([T[:3, 3], rot])

    U, S, Vt = np.linalg.svd(robot.jacobian(q)[:rows])  # (a square Jacobian: n = rows)
    v = Vt[rows - 1]
    h = 1e-4  # central second difference along the null direction
    d2 = (task(q + h * v) - 2.0 * task(q) + task(q - h * v)) / (h * h)
    kappa = abs(float(U[:, rows - 1] @ d2))
    sigma = float(S[rows - 1])
    by_sigma = FOUND_SCALE / max(sigma, 1e-300)
    by_fold = math.sqrt(2.0 * FOUND_SCALE / max(kappa, 1e-300))
    return max(FOUND_FLOOR, min(by_sigma, by_fold))


def joint_distance(robot: Robot, q1: FloatArray, q2: FloatArray) -> FloatArray:
    """Largest joint difference (angles modulo 2π), broadcast over leading axes."""
    d = np.asarray(q1, dtype=float) - np.asarray(q2, dtype=float)
    d = np.where(robot.is_prismatic, d, np.remainder(d + math.pi, 2 * math.pi) - math.pi)
    return np.abs(d).max(axis=-1)


def random_q(robot: Robot, rng: np.random.Generator, n: int) -> FloatArray:
    """``(n, dof)``: angles in (-π, π), slides in (-0.5, 0.8) m (limits ignored)."""
    q = rng.uniform(-math.pi, math.pi, (n, robot.dof))
    return np.where(robot.is_prismatic, rng.uniform(-0.5, 0.8, (n, robot.dof)), q)


def dls_solutions(
    robot: Robot, target: FloatArray, rng: np.random.Generator, starts: int = 200
) -> FloatArray:
    """Every distinct solution a multi-start damped-least-squares search finds.

    Args:
        robot: The robot.
        target: ``(3,)`` position or ``(4, 4)`` pose of the tool.
        rng: Random starts.
        starts: Number of random starts.

    Returns:
        ``(k, n)`` distinct solutions (revolute joints wrapped to (-π, π]).
    """
    position_only = target.shape == (3,)
    q = random_q(robot, rng, starts)
    turns = ~np.asarray(robot.chain.prismatic, dtype=bool)

    def error(q: FloatArray) -> FloatArray:
        T = robot.fk(q, workers=1)  # small batches: threads cost more than they give
        e = target[:3] - T[:, :3, 3] if position_only else target[:3, 3] - T[:, :3, 3]
        if position_only:
            return e
        rot = Rotation.from_matrix(target[:3, :3] @ np.swapaxes(T[:, :3, :3], 1, 2))
        return np.concatenate([e, rot.as_rotvec()], axis=1)

    for it in range(300):
        e = error(q)
        J = robot.jacobian(q, workers=1)[:, : e.shape[1]]
        if it < 200:  # damped least squares, then Gauss-Newton steps to polish
            Jt = np.swapaxes(J, 1, 2)
            step = Jt @ np.linalg.solve(J @ Jt + 1e-4 * np.eye(e.shape[1]), e[..., None])
        else:
            step = np.linalg.pinv(J) @ e[..., None]
        q = q + step[..., 0]
        # kept within a turn: the same poses, and no warning of angles given in degrees
        q[:, turns] = np.remainder(q[:, turns] + math.pi, 2.0 * math.pi) - math.pi
    done = np.abs(error(q)).max(axis=1) < 1e-10
    return distinct(robot, q[done], 1e-6)


def distinct(robot: Robot, q: FloatArray, tol: float) -> FloatArray:
    """``(k, n)`` the rows of ``q`` ``(m, n)`` that are more than ``tol`` from every row
    kept before them (revolute joints wrapped to (-π, π]).

    Rows equal once rounded to ``tol`` are one before the pairwise test: a search's
    hundreds of answers are mostly a few solutions found again and again.
    """
    q = np.where(robot.is_prismatic, q, np.angle(np.exp(1j * np.asarray(q, dtype=float))))
    q = q.reshape(-1, robot.dof)
    first = np.unique(np.round(q / tol), axis=0, return_index=True)[1]
    q = q[np.sort(first)]
    close = joint_distance(robot, q[:, None], q[None]) <= tol
    kept: list[int] = []
    taken = np.zeros(len(q), dtype=bool)
    for i in range(len(q)):
        if not taken[i]:
            kept.append(i)
            taken |= close[i]
    return q[kept].reshape(-1, robot.dof)
