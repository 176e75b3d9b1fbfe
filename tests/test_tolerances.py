"""Every named tolerance of the core, pinned on both sides of its documented value.

Each test uses literal distances a factor of 5-50 inside and outside the value the
docstring states, so that a constant changed a thousandfold fails a test. Inputs
are built by hand (exact solutions of a planar 2R arm, perturbed on purpose) and
go straight to the core's check, so the solvers play no part.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from kinematica._core import internals

import kinematica as km
from kinematica import _core
from kinematica.spatial import euler_from_matrix, gimbal_locked, matrix_from_euler

L1 = L2 = 1.0
POSITION = np.array([1.0, 1.0, 1.0, 0.0, 0.0, 0.0])


def two_link(qlim: tuple[float, float] | None = None) -> km.Robot:
    return km.Robot.from_dh([km.Revolute(a=L1), km.Revolute(a=L2, qlim=qlim)])


def target_of(q: list[float]) -> np.ndarray:
    """The pose of the 2R arm at ``q``, by hand: x = c1 + c12, y = s1 + s12."""
    x = L1 * math.cos(q[0]) + L2 * math.cos(q[0] + q[1])
    y = L1 * math.sin(q[0]) + L2 * math.sin(q[0] + q[1])
    T = np.eye(4)
    T[:2, 3] = x, y
    return T


def check(robot: km.Robot, T: np.ndarray, Q: np.ndarray, respect_limits: bool = True):  # type: ignore[no-untyped-def]
    """The core's shared check of hand-made candidates Q (m, n) of a position target."""
    opts = _core.CheckOptions()
    opts.tol_position = opts.tol_rotation = 1e-10
    opts.respect_limits = respect_limits
    opts.complete = True
    opts.weights = POSITION.tolist()
    q, res, _, _, count, out, _ = internals.check(
        robot.chain.core,
        T,
        np.ascontiguousarray(Q, dtype=float),
        opts,
        math.nan,
        False,
        False,
        None,
    )
    return q, res, count, out


@pytest.mark.parametrize(("delta", "count"), [(2e-6, 2), (2e-9, 1)])
def test_dedup_tol_is_1e_7(delta: float, count: int) -> None:
    # Two exact solutions of one target, elbow ±delta apart (nearly stretched):
    # 4e-6 apart they are two solutions, 4e-9 apart one (DEDUP_TOL = 1e-7).
    robot = two_link()
    a, b = [0.3 - delta / 2, delta], [0.3 + delta / 2, -delta]
    T = target_of(a)
    assert np.hypot(*(target_of(b)[:2, 3] - T[:2, 3])) < 1e-15
    _, res, n, _ = check(robot, T, np.array([a, b]))
    assert n == count
    assert np.all(res[:n, 0] <= 1e-10)


@pytest.mark.parametrize(("offset", "solved"), [(1e-7, True), (1e-3, False)])
def test_polish_limit_is_1e_5(offset: float, solved: bool) -> None:
    # A candidate 1e-7 rad off is polished into the solution; 1e-3 off is not a candidate.
    robot = two_link()
    q = [0.4, 1.1]
    T = target_of(q)
    _, res, n, _ = check(robot, T, np.array([[q[0] + offset, q[1] - offset]]))
    assert n == int(solved)
    if solved:
        assert res[0, 0] < 1e-14


@pytest.mark.parametrize(("residual", "polished"), [(2e-11, False), (2e-9, True)])
def test_acceptance_tolerance_is_1e_10(residual: float, polished: bool) -> None:
    # A candidate within 1e-10 m is taken as it is (its residual reported); one
    # beyond it is polished first (its residual drops to round-off).
    robot = two_link()
    q = [0.4, 1.1]
    T = target_of(q)
    # moving q2 by e moves the tool by e * L2 (the second link's length is 1)
    _, res, n, _ = check(robot, T, np.array([[q[0], q[1] + residual]]))
    assert n == 1
    if polished:
        assert res[0, 0] < 1e-14
    else:
        assert res[0, 0] == pytest.approx(residual, rel=1e-3)


@pytest.mark.parametrize(("beyond", "inside"), [(2e-13, True), (2e-11, False)])
def test_limit_tol_is_1e_12(beyond: float, inside: bool) -> None:
    # An exact solution whose q2 is `beyond` past its upper limit: within the
    # 1e-12 slack it counts as inside the limits, beyond it as outside.
    q = [0.4, 1.1]
    robot = two_link(qlim=(-1.0, q[1] - beyond))
    _, _, n_in, n_out = check(robot, target_of(q), np.array([q]))
    assert (n_in, n_out) == ((1, 0) if inside else (0, 1))


@pytest.mark.parametrize(("error", "accepted"), [(1.5e-4, True), (3e-4, False)])
def test_projection_tol_is_2e_4(error: float, accepted: bool) -> None:
    # A target rotation orthonormal to 1.5e-4 (what a copy with 4 decimals can be)
    # is projected onto SO(3) (and said so); one orthonormal to 3e-4 only is an error.
    puma = km.load("puma560")
    T = puma.fk([0.2, -0.5, 0.3, 0.4, 0.8, -0.1])
    T[:3, :3] = T[:3, :3] @ np.diag([1.0 + error / 2.0, 1.0, 1.0])  # (RᵀR − I)₀₀ ≈ error
    if accepted:
        res = puma.ik(T, tol=1e-3)
        assert res.success and any("projected onto SO(3)" in n for n in res.notes)
    else:
        with pytest.raises(km.DimensionError, match="not orthonormal"):
            puma.ik(T)


@pytest.mark.parametrize(("delta", "locked"), [(1e-8, True), (2e-6, False)])
def test_gimbal_lock_tol_is_1e_7(delta: float, locked: bool) -> None:
    # ZYZ: the middle angle delta from 0 is in the lock band (1e-7) or not.
    R = matrix_from_euler([0.3, delta, -0.2], "ZYZ")
    assert bool(gimbal_locked(R, "ZYZ")) is locked
    angles = euler_from_matrix(R, "ZYZ")
    assert bool(angles[2] == 0.0) == locked  # the lock sets the third angle to 0


@pytest.mark.parametrize(("error", "accepted"), [(2e-7, True), (2e-5, False)])
def test_orthonormal_tol_of_a_tool_is_1e_6(error: float, accepted: bool) -> None:
    tool = np.eye(4)
    tool[0, 1] = error  # max |RᵀR - I| = error
    if accepted:
        robot = km.Robot.from_dh([km.Revolute(a=1.0)], tool=tool)
        R = robot.tool[:3, :3]
        assert np.abs(R.T @ R - np.eye(3)).max() < 1e-15
    else:
        with pytest.raises(km.DimensionError, match="not orthonormal"):
            km.Robot.from_dh([km.Revolute(a=1.0)], tool=tool)


@pytest.mark.parametrize(("eps", "exact"), [(1e-17, True), (1e-13, False)])
def test_snap_tol_is_1e_15(eps: float, exact: bool) -> None:
    # A twist within 1e-15 of 90 degrees has its cosine snapped to exactly 0:
    # then the frame of a joint at q = 0 has exact zeros; 1e-13 off it does not.
    robot = km.Robot.from_dh([km.Revolute(alpha=math.pi / 2 + eps)])
    T = robot.fk([0.0])
    assert bool(T[1, 1] == 0.0) == exact
