"""The geometric Jacobian and the joint axes, against finite differences and by hand."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from support.helpers import (
    PROPERTY,
    JointSpec,
    RobotSpec,
    random_q,
    robot_specs,
    seeds,
    transform_from,
)

from kinematica.dh import Prismatic, Revolute
from kinematica.errors import DimensionError, KinematicaError, KinematicaWarning
from kinematica.robot import Robot

BATCHES = [(), (1,), (3, 2)]

#: Central-difference step (rad or m) and the agreement expected from it:
#: truncation ~h²·|f'''| ~ 1e-12 plus rounding ~1e-16 / h ~ 1e-10.
STEP = 1e-6
FD_TOL = 1e-8

MIXED = RobotSpec(
    (
        JointSpec("R", 0.3, 0.1, 0.7, 0.2),
        JointSpec("P", 0.4, -0.2, -math.pi / 2, 0.1),
        JointSpec("R", 0.0, 0.5, math.pi, -0.3),
        JointSpec("R", -0.25, 0.3, math.pi / 2, math.pi / 2),
    ),
    "modified",
    base=transform_from([0.9, 0.1, -0.3, 0.2], [0.1, -0.2, 0.3]),
    tool=transform_from([0.2, 0.7, 0.1, -0.4], [0.0, 0.05, 0.12]),
)


def finite_difference_jacobian(spec: RobotSpec, q: np.ndarray) -> np.ndarray:
    """``(6, n)`` from the reference FK: dp/dq, and ω from the skew matrix dR·Rᵀ."""
    n = spec.dof
    J = np.empty((6, n))
    R = spec.ref_fk(q)[:3, :3]
    for i in range(n):
        dq = np.zeros(n)
        dq[i] = STEP
        Tp, Tm = spec.ref_fk(q + dq), spec.ref_fk(q - dq)
        J[:3, i] = (Tp[:3, 3] - Tm[:3, 3]) / (2 * STEP)
        W = (Tp[:3, :3] - Tm[:3, :3]) / (2 * STEP) @ R.T  # skew(ω) up to O(h²)
        W = (W - W.T) / 2
        J[3:, i] = [W[2, 1], W[0, 2], W[1, 0]]
    return J


@PROPERTY
@given(spec=robot_specs(), seed=seeds)
def test_jacobian_equals_finite_differences(spec: RobotSpec, seed: int) -> None:
    robot = spec.build()
    for q in random_q(spec, np.random.default_rng(seed), (2,)):
        np.testing.assert_allclose(
            robot.jacobian(q), finite_difference_jacobian(spec, q), atol=FD_TOL, rtol=0
        )


@PROPERTY
@given(spec=robot_specs(), seed=seeds)
def test_tool_frame_jacobian_is_rotated_base_jacobian(spec: RobotSpec, seed: int) -> None:
    robot = spec.build()
    q = random_q(spec, np.random.default_rng(seed), (3,))
    J = robot.jacobian(q)
    Rt = np.swapaxes(robot.fk(q)[:, :3, :3], -1, -2)
    blockdiag = np.zeros((3, 6, 6))
    blockdiag[:, :3, :3] = Rt
    blockdiag[:, 3:, 3:] = Rt
    np.testing.assert_allclose(robot.jacobian(q, frame="tool"), blockdiag @ J, atol=1e-13)
    np.testing.assert_allclose(robot.jacobian(q, frame="base"), J, atol=0)


@PROPERTY
@given(spec=robot_specs(), seed=seeds)
def test_jacobian_columns_of_prismatic_joints(spec: RobotSpec, seed: int) -> None:
    # A prismatic column is [z; 0] with z its unit axis; a revolute one has |ω| = 1.
    robot = spec.build()
    q = random_q(spec, np.random.default_rng(seed))
    J = robot.jacobian(q)
    directions, _ = robot.joint_axes(q)
    for i, joint in enumerate(spec.joints):
        if joint.kind == "P":
            np.testing.assert_allclose(J[:3, i], directions[i], atol=1e-15)
            np.testing.assert_array_equal(J[3:, i], 0.0)
        else:
            np.testing.assert_allclose(J[3:, i], directions[i], atol=1e-15)
            assert abs(np.linalg.norm(J[3:, i]) - 1.0) < 1e-14


def test_planar_2r_jacobian_by_hand() -> None:
    # Two links l1, l2 in the plane: p = (l1 c1 + l2 c12, l1 s1 + l2 s12, 0), so
    # J = [[-l1 s1 - l2 s12, -l2 s12], [l1 c1 + l2 c12, l2 c12], [0, 0], [0, 0], [0, 0], [1, 1]].
    l1, l2 = 0.7, 0.4
    robot = Robot.from_dh([Revolute(a=l1), Revolute(a=l2)], convention="standard")
    q = np.random.default_rng(20).uniform(-math.pi, math.pi, (25, 2))
    s1, c1 = np.sin(q[:, 0]), np.cos(q[:, 0])
    s12, c12 = np.sin(q.sum(-1)), np.cos(q.sum(-1))
    expected = np.zeros((25, 6, 2))
    expected[:, 0] = np.stack([-l1 * s1 - l2 * s12, -l2 * s12], -1)
    expected[:, 1] = np.stack([l1 * c1 + l2 * c12, l2 * c12], -1)
    expected[:, 5] = 1.0
    np.testing.assert_allclose(robot.jacobian(q), expected, atol=1e-15)


def test_cartesian_prr_jacobian_by_hand() -> None:
    # A vertical slide then a planar 2R arm about z: the slide's column is
    # [0, 0, 1, 0, 0, 0] and the rest is the planar Jacobian.
    l1, l2 = 0.5, 0.3
    robot = Robot.from_dh([Prismatic(), Revolute(a=l1), Revolute(a=l2)], convention="standard")
    q = np.array([0.2, 0.4, -1.1])
    s1, c1, s12, c12 = math.sin(0.4), math.cos(0.4), math.sin(-0.7), math.cos(-0.7)
    expected = np.array(
        [
            [0, -l1 * s1 - l2 * s12, -l2 * s12],
            [0, l1 * c1 + l2 * c12, l2 * c12],
            [1, 0, 0],
            [0, 0, 0],
            [0, 0, 0],
            [0, 1, 1],
        ]
    )
    np.testing.assert_allclose(robot.jacobian(q), expected, atol=1e-15)


@pytest.mark.parametrize("frame", ["base", "tool"])
@pytest.mark.parametrize("batch", BATCHES)
def test_jacobian_batch_shapes(batch: tuple[int, ...], frame: str) -> None:
    robot = MIXED.build()
    q = random_q(MIXED, np.random.default_rng(21), batch)
    J = robot.jacobian(q, frame=frame)  # type: ignore[arg-type]
    assert J.shape == (*batch, 6, MIXED.dof)
    for idx in np.ndindex(*batch):
        np.testing.assert_allclose(J[idx], robot.jacobian(q[idx], frame=frame), atol=1e-15)  # type: ignore[arg-type]
        if frame == "base":
            np.testing.assert_allclose(
                J[idx], finite_difference_jacobian(MIXED, q[idx]), atol=FD_TOL
            )


@PROPERTY
@given(spec=robot_specs(), seed=seeds)
def test_joint_axes_lie_on_the_frames_z_axes(spec: RobotSpec, seed: int) -> None:
    # Joint i turns about (slides along) z of frame i-1 (standard) or of Craig's
    # frame i (modified), before any tool.
    robot = spec.build()
    q = random_q(spec, np.random.default_rng(seed), (2,))
    directions, points = robot.joint_axes(q)
    assert directions.shape == points.shape == (2, spec.dof, 3)
    for b in range(2):
        frames = spec.ref_frames(q[b])
        frames[-1] = frames[-2] @ spec.ref_links(q[b])[-1]  # frame n without the tool
        for i in range(spec.dof):
            F = frames[i] if spec.convention == "standard" else frames[i + 1]
            z, o = F[:3, 2], F[:3, 3]
            np.testing.assert_allclose(directions[b, i], z, atol=1e-12, err_msg=f"joint {i + 1}")
            np.testing.assert_allclose(
                np.cross(points[b, i] - o, z), 0.0, atol=1e-12, err_msg=f"joint {i + 1}"
            )


def test_joint_axes_default_to_zero_configuration() -> None:
    robot = MIXED.build()
    directions, points = robot.joint_axes()
    d0, p0 = robot.joint_axes(np.zeros(MIXED.dof))
    np.testing.assert_array_equal(directions, d0)
    np.testing.assert_array_equal(points, p0)
    assert directions.shape == (MIXED.dof, 3)


def test_jacobian_bad_input() -> None:
    robot = MIXED.build()
    with pytest.raises(
        KinematicaError, match="frame must be 'base', 'tool' or 'spatial', got 'world'"
    ):
        robot.jacobian(np.zeros(4), frame="world")  # type: ignore[arg-type]
    with pytest.raises(DimensionError, match="must hold 4 joint values"):
        robot.jacobian(np.zeros(3))
    with pytest.raises(DimensionError, match="NaN or inf"):
        robot.jacobian([0.0, math.nan, 0.0, 0.0])
    with pytest.raises(DimensionError, match="must hold 4 joint values"):
        robot.joint_axes(np.zeros((2, 5)))


def test_jacobian_batch_with_a_bad_row_returns_the_rest() -> None:
    robot = MIXED.build()
    q = np.zeros((3, 4))
    q[1, 2] = math.inf
    with pytest.warns(KinematicaWarning, match="1 row"):
        J = robot.jacobian(q)
    assert np.all(np.isnan(J[1])) and np.all(np.isfinite(J[[0, 2]]))
    np.testing.assert_array_equal(J[0], robot.jacobian(np.zeros(4)))
