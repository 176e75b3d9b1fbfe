"""Planning and simulating measurements: ``next_poses`` and ``simulate``.

``next_poses`` adds the configurations that most improve the identification, by the
D-optimal criterion: the largest ``log det(JᵀJ)`` of the identifiable parameters'
Jacobian (the volume of their confidence ellipsoid shrinks most), chosen greedily among
random configurations within the joint limits. Adding a configuration with Jacobian rows
``B`` multiplies the determinant by ``det(I + B (JᵀJ)⁻¹ Bᵀ)`` (the matrix determinant
lemma), so every candidate is scored by one small determinant.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.arguments import check_count
from kinematica.calibration.checks import check_kind, check_noise, check_readings
from kinematica.calibration.fit import DEFAULT_NOISE, identifiable
from kinematica.calibration.model import ErrorModel
from kinematica.calibration.residuals import Measurements, jacobian
from kinematica.spatial import matrix_from_rotvec

if TYPE_CHECKING:
    from kinematica.robot import Robot

__all__ = ["RIDGE", "next_poses", "simulate"]

FloatArray = NDArray[np.float64]

#: Added to the diagonal of ``JᵀJ`` (times its mean diagonal) while fewer measurements
#: than parameters are planned, so that the first choices are scored too.
RIDGE = 1e-9


def _rows(
    robot: Robot, model: ErrorModel, q: FloatArray, kind: str, columns: NDArray[np.intp]
) -> FloatArray:
    """``(m, k, p)`` the Jacobian rows of each configuration (unit noise)."""
    T = model.fk(np.zeros(model.size), q)
    data = Measurements(q, T if kind == "pose" else T[:, :3, 3], kind, (1.0, 1.0))  # type: ignore[arg-type]
    _, J = jacobian(model, np.zeros(model.size), data, columns)
    return J.reshape(len(q), data.per_pose, -1)


def next_poses(
    robot: Robot,
    q_done: ArrayLike | None,
    k: int,
    *,
    kind: str = "pose",
    candidates: int = 500,
    seed: int | None = 0,
) -> FloatArray:
    """The ``k`` configurations that most improve the identification (D-optimal).

    Args:
        robot: The nominal robot.
        q_done: ``(m, n)`` configurations measured already (or ``None``).
        k: How many to add.
        kind: ``"pose"`` or ``"position"`` measurements.
        candidates: Random configurations within the joint limits to choose from.
        seed: Of the candidates.

    Returns:
        ``(k, n)`` configurations within the joint limits, best first.
    """
    kind = check_kind(kind)
    k = check_count(k, "k", lo=1)
    candidates = check_count(candidates, "candidates", lo=1)
    model = ErrorModel.of(robot.chain)
    columns = identifiable(robot, kind).chosen
    p = len(columns)
    A = np.zeros((p, p))
    if q_done is not None:
        done = check_readings(robot, q_done)
        if len(done):
            B = _rows(robot, model, done, kind, columns).reshape(-1, p)
            A = B.T @ B
    pool = robot.random_q(candidates, seed=seed)
    rows = _rows(robot, model, pool, kind, columns)  # (N, k, p)
    chosen: list[int] = []
    for _ in range(k):
        scale = max(float(np.trace(A)) / p, 1.0)
        Ainv = np.linalg.inv(A + RIDGE * scale * np.eye(p))
        M = np.eye(rows.shape[1]) + rows @ Ainv @ np.swapaxes(rows, 1, 2)
        score = np.linalg.slogdet(M)[1]
        score[chosen] = -np.inf
        best = int(np.argmax(score))
        chosen.append(best)
        A = A + rows[best].T @ rows[best]
    return pool[chosen]


def simulate(
    robot_true: Robot,
    q: ArrayLike,
    noise: tuple[float, float] = DEFAULT_NOISE,
    *,
    kind: str = "pose",
    seed: int | None = None,
) -> FloatArray:
    """What a tracker would measure on ``robot_true``: its FK plus Gaussian noise.

    Args:
        robot_true: The arm as it is.
        q: ``(m, n)`` joint readings.
        noise: ``(σ_position (m), σ_orientation (rad))``: each coordinate of the
            point gets ``N(0, σ_position²)``; the rotation is turned (world frame)
            by a rotation vector with each component ``N(0, σ_orientation²)``.
        kind: ``"pose"`` (``(m, 4, 4)``) or ``"position"`` (``(m, 3)``).
        seed: Of the noise.

    Returns:
        ``(m, 4, 4)`` poses or ``(m, 3)`` points.
    """
    kind = check_kind(kind)
    sp, sr = check_noise(noise)
    qa = check_readings(robot_true, q)
    rng = np.random.default_rng(seed)
    T = np.array(robot_true.fk(qa), dtype=float).reshape(-1, 4, 4)
    T[:, :3, 3] += rng.normal(0.0, sp, (len(T), 3))
    if kind == "position":
        return T[:, :3, 3].copy()
    turn = matrix_from_rotvec(rng.normal(0.0, sr, (len(T), 3)))
    T[:, :3, :3] = turn @ T[:, :3, :3]
    return T
