"""Robot forward kinematics: every frame, link matrices, batches, conventions, bad input.

Expected values are the reference DH product of ``support/helpers.py`` (four elementary
matrices per link) and formulas derived by hand from the seeds.
"""

from __future__ import annotations

import math
import warnings
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from support.helpers import (
    PROPERTY,
    JointSpec,
    RobotSpec,
    assert_transform_close,
    random_q,
    robot_specs,
    rot_x,
    rot_z,
    seeds,
    transform_from,
    tras_x,
    tras_z,
)

import kinematica as km
from kinematica.dh import Prismatic, Revolute
from kinematica.errors import DimensionError, KinematicaError, KinematicaWarning
from kinematica.robot import Robot

BATCHES = [(), (1,), (3, 2)]
DEG = math.pi / 180

# PUMA 560 (standard DH, Corke) and Panda (modified DH, Franka) as plain specs.
PUMA = RobotSpec(
    tuple(
        JointSpec("R", d, a, alpha * DEG, 0.0)
        for d, a, alpha in [
            (0.0, 0.0, 90),
            (0.0, 0.4318, 0),
            (0.15005, 0.0203, -90),
            (0.4318, 0.0, 90),
            (0.0, 0.0, -90),
            (0.0, 0.0, 0),
        ]
    ),
    "standard",
)
PANDA = RobotSpec(
    tuple(
        JointSpec("R", d, a, alpha * DEG, 0.0)
        for a, d, alpha in [
            (0.0, 0.333, 0),
            (0.0, 0.0, -90),
            (0.0, 0.316, 90),
            (0.0825, 0.0, 90),
            (-0.0825, 0.384, -90),
            (0.0, 0.0, 90),
            (0.088, 0.0, 90),
        ]
    ),
    "modified",
    tool=tras_z(0.107),
)
# A mixed chain with everything switched on: prismatic joints, offsets, base, tool.
MIXED = RobotSpec(
    (
        JointSpec("R", 0.3, 0.1, 0.7, 0.2, (-2.0, 2.0)),
        JointSpec("P", 0.4, -0.2, -math.pi / 2, 0.1, (0.0, 0.5)),
        JointSpec("R", 0.0, 0.5, math.pi, -0.3),
        JointSpec("P", -1.1, 0.0, 0.0, -0.2),
        JointSpec("R", -0.25, 0.3, math.pi / 2, math.pi / 2),
    ),
    "standard",
    base=transform_from([0.9, 0.1, -0.3, 0.2], [0.1, -0.2, 0.3]),
    tool=transform_from([0.2, 0.7, 0.1, -0.4], [0.0, 0.05, 0.12]),
)
MIXED_MDH = RobotSpec(MIXED.joints, "modified", MIXED.base, MIXED.tool)
FIXED = {"puma": PUMA, "panda": PANDA, "mixed": MIXED, "mixed_mdh": MIXED_MDH}


#: A transform whose rotation part is off orthonormal by 1e-6.
SKEWED = rot_z(0.3)
SKEWED[0, 1] += 3e-6  # max|RᵀR - I| = 3e-6: beyond ORTHONORMAL_TOL (1e-6)


def seed000_arm(l1: float, l2: float, l3: float, l4: float) -> Robot:
    """Seed 000's 6-DOF table, typed as on the slide (degrees converted)."""
    rows = [  # theta, d, a, alpha
        Revolute(offset=0, d=l1, a=0, alpha=90 * DEG),  # q1,      l1, 0,  90
        Revolute(offset=90 * DEG, d=0, a=l2, alpha=0),  # q2 + 90, 0,  l2, 0
        Revolute(offset=-90 * DEG, d=0, a=0, alpha=-90 * DEG),  # q3 - 90, 0, 0, -90
        Revolute(offset=-90 * DEG, d=l3, a=0, alpha=-90 * DEG),  # q4 - 90, l3, 0, -90
        Revolute(offset=0, d=0, a=0, alpha=90 * DEG),  # q5, 0, 0, 90
        Revolute(offset=0, d=l4, a=0, alpha=0),  # q6, l4, 0, 0
    ]
    return Robot.from_dh(rows, convention="standard", name="seed 000 arm")


def homogeneous(R: list[list[float]], p: list[float]) -> np.ndarray:
    T = np.eye(4)
    T[:3, :3] = R
    T[:3, 3] = p
    return T


# ------------------------------------------------------- against the reference
@PROPERTY
@given(spec=robot_specs(), seed=seeds)
def test_fk_equals_reference_product(spec: RobotSpec, seed: int) -> None:
    robot = spec.build()
    q = random_q(spec, np.random.default_rng(seed), (4,))
    expected = np.array([spec.ref_fk(qi) for qi in q])
    assert_transform_close(robot.fk(q), expected, atol=1e-12)
    assert_transform_close(robot.fk(q[0]), expected[0], atol=1e-12)  # single-q fast path


@PROPERTY
@given(spec=robot_specs(), seed=seeds)
def test_all_frames_equal_reference_frames(spec: RobotSpec, seed: int) -> None:
    # Frame 0 is the base, frame i is 0Ti (Craig's frame i for "modified"),
    # frame n includes the tool, and the last frame is fk.
    robot = spec.build()
    q = random_q(spec, np.random.default_rng(seed), (3,))
    frames = robot.fk(q, all_frames=True)
    assert frames.shape == (3, spec.dof + 1, 4, 4)
    expected = np.array([spec.ref_frames(qi) for qi in q])
    assert_transform_close(frames, expected, atol=1e-12)
    base = np.broadcast_to(np.eye(4) if spec.base is None else spec.base, (3, 4, 4))
    assert_transform_close(frames[:, 0], base, atol=0.0)
    assert_transform_close(frames[:, -1], robot.fk(q), atol=1e-15)


@PROPERTY
@given(spec=robot_specs(), seed=seeds)
def test_link_matrices_equal_reference_links(spec: RobotSpec, seed: int) -> None:
    robot = spec.build()
    q = random_q(spec, np.random.default_rng(seed), (3,))
    A = robot.link_matrices(q)
    assert A.shape == (3, spec.dof, 4, 4)
    assert_transform_close(A, np.array([spec.ref_links(qi) for qi in q]), atol=1e-15)
    # Their product is base⁻¹ · T · tool⁻¹.
    product = A[:, 0]
    for i in range(1, spec.dof):
        product = product @ A[:, i]
    inner = np.linalg.inv(robot.base) @ robot.fk(q) @ np.linalg.inv(robot.tool)
    assert_transform_close(product, inner, atol=1e-11)


@pytest.mark.parametrize("name", FIXED)
def test_modified_frames_are_craigs_frames(name: str) -> None:
    # Explicitly for the fixed arms: frame i of a modified robot is Craig's
    # 0Ti = base · Π_k Rot(x, α_(k-1)) Tras(x, a_(k-1)) Rot(z, θ_k) Tras(z, d_k).
    spec = FIXED[name]
    robot = spec.build()
    q = random_q(spec, np.random.default_rng(10))
    T = np.eye(4) if spec.base is None else spec.base
    frames = robot.fk(q, all_frames=True)
    for i, (j, qi) in enumerate(zip(spec.joints, q, strict=True), start=1):
        theta, d, a, alpha = j.params(qi)
        if spec.convention == "modified":
            T = np.linalg.multi_dot([T, rot_x(alpha), tras_x(a), rot_z(theta), tras_z(d)])
        else:
            T = np.linalg.multi_dot([T, rot_z(theta), tras_z(d), tras_x(a), rot_x(alpha)])
        if i < spec.dof:
            assert_transform_close(frames[i], T, atol=1e-14, err_msg=f"frame {i}")
    tool = np.eye(4) if spec.tool is None else spec.tool
    assert_transform_close(frames[-1], T @ tool, atol=1e-14, err_msg="frame n")


# ------------------------------------------------------------------ batching
@PROPERTY
@given(spec=robot_specs(), seed=seeds)
def test_batch_equals_per_configuration_loop(spec: RobotSpec, seed: int) -> None:
    robot = spec.build()
    q = random_q(spec, np.random.default_rng(seed), (2, 3))
    T = robot.fk(q)
    F = robot.fk(q, all_frames=True)
    A = robot.link_matrices(q)
    for idx in np.ndindex(2, 3):
        assert_transform_close(T[idx], robot.fk(q[idx]), atol=1e-14)
        assert_transform_close(F[idx], robot.fk(q[idx], all_frames=True), atol=1e-15)
        assert_transform_close(A[idx], robot.link_matrices(q[idx]), atol=1e-15)


@pytest.mark.parametrize("batch", BATCHES)
@pytest.mark.parametrize("name", FIXED)
def test_batch_shapes(name: str, batch: tuple[int, ...]) -> None:
    spec = FIXED[name]
    robot = spec.build()
    n = spec.dof
    q = random_q(spec, np.random.default_rng(11), batch)
    T, F, A = robot.fk(q), robot.fk(q, all_frames=True), robot.link_matrices(q)
    assert T.shape == (*batch, 4, 4)
    assert F.shape == (*batch, n + 1, 4, 4)
    assert A.shape == (*batch, n, 4, 4)
    for idx in np.ndindex(*batch):
        frames = spec.ref_frames(q[idx])
        assert_transform_close(T[idx], frames[-1], atol=1e-13, err_msg=f"fk {idx}")
        assert_transform_close(F[idx], frames, atol=1e-13, err_msg=f"frames {idx}")
        assert_transform_close(A[idx], np.array(spec.ref_links(q[idx])), atol=1e-15)


@pytest.mark.parametrize("name", FIXED)
def test_empty_batch(name: str) -> None:
    robot = FIXED[name].build()
    n = robot.dof
    assert robot.fk(np.zeros((0, n))).shape == (0, 4, 4)
    assert robot.fk(np.zeros((0, n)), all_frames=True).shape == (0, n + 1, 4, 4)
    assert robot.link_matrices(np.zeros((2, 0, n))).shape == (2, 0, n, 4, 4)


@pytest.mark.parametrize("name", FIXED)
def test_single_configuration_forms_equal_batched_path(name: str) -> None:
    # list, tuple, (n,) float64/float32/int arrays take the fast path; each must
    # equal the batched path on the same values to 1e-15.
    spec = FIXED[name]
    robot = spec.build()
    rng = np.random.default_rng(12)
    for q in random_q(spec, rng, (20,)):
        batched = robot.fk(q[None])[0]
        for form in (q.tolist(), tuple(q.tolist()), q, [float(v) for v in q]):
            assert_transform_close(robot.fk(form), batched, atol=1e-15)
        q32 = q.astype(np.float32)
        assert_transform_close(robot.fk(q32), robot.fk(q32.astype(float)[None])[0], atol=1e-15)
    qi = rng.integers(-3, 4, spec.dof)
    for form in (qi, qi.astype(np.int32), qi.tolist(), tuple(int(v) for v in qi)):
        assert_transform_close(robot.fk(form), robot.fk(qi.astype(float)[None])[0], atol=1e-15)
        assert_transform_close(robot.fk(form), spec.ref_fk(qi.astype(float)), atol=1e-13)


@PROPERTY
@given(spec=robot_specs(), seed=seeds)
def test_single_path_equals_batched_path_random_robots(spec: RobotSpec, seed: int) -> None:
    robot = spec.build()
    for q in random_q(spec, np.random.default_rng(seed), (3,)):
        assert_transform_close(robot.fk(q.tolist()), robot.fk(q[None])[0], atol=1e-14)


def test_fk_does_not_modify_its_input() -> None:
    robot = MIXED.build()
    q = random_q(MIXED, np.random.default_rng(13), (4,))
    q_copy = q.copy()
    robot.fk(q)
    robot.fk(q, all_frames=True)
    robot.link_matrices(q)
    np.testing.assert_array_equal(q, q_copy)


# ---------------------------------------------------------------- conventions
@PROPERTY
@given(spec=robot_specs(), seed=seeds)
def test_to_convention_keeps_fk(spec: RobotSpec, seed: int) -> None:
    robot = spec.build()
    q = random_q(spec, np.random.default_rng(seed), (4,))
    T = robot.fk(q)
    for target in ("standard", "modified"):
        other = robot.to_convention(target)
        assert other.convention == target
        assert_transform_close(other.fk(q), T, atol=1e-12, err_msg=target)
        assert_transform_close(other.fk(q[0]), T[0], atol=1e-12, err_msg=target)


@PROPERTY
@given(spec=robot_specs(), seed=seeds)
def test_convention_round_trip(spec: RobotSpec, seed: int) -> None:
    # standard -> modified -> standard (and the reverse) gives the same FK, and
    # the same table: joint types, offsets, limits, every constant parameter,
    # except the one (a, α) pair the other convention cannot hold, which comes
    # back inside the base (from modified), or the tool (from standard) unless
    # that tool is Tras(x, a)·Rot(x, α) itself: then the pair, with it, comes
    # back to the last row (no tool: exactly the table it was).
    robot = spec.build()
    other = "modified" if spec.convention == "standard" else "standard"
    back = robot.to_convention(other).to_convention(spec.convention)
    assert back.convention == robot.convention
    assert back.joint_types == robot.joint_types
    np.testing.assert_array_equal(back.qlim, robot.qlim)
    q = random_q(spec, np.random.default_rng(seed), (4,))
    assert_transform_close(back.fk(q), robot.fk(q), atol=1e-12)
    moved = -1 if spec.convention == "standard" else 0
    tool = robot.tool
    on_x = np.allclose(tool[:3, 0], [1, 0, 0], atol=1e-12) and np.allclose(
        tool[1:3, 3], 0, atol=1e-12
    )
    to_row = spec.convention == "standard" and on_x
    for i, (got, want) in enumerate(zip(back.links, robot.links, strict=True)):
        if i != moved % spec.dof:
            assert got == want, f"joint {i + 1}"
            continue
        assert (got.theta, got.d, got.offset) == (want.theta, want.d, want.offset)
        if to_row:  # the tool's own a and α add to the row's
            assert got.a == pytest.approx(want.a + tool[0, 3], abs=1e-15)
            twist = math.atan2(tool[2, 1], tool[1, 1])
            assert math.remainder(got.alpha - want.alpha - twist, 2 * math.pi) == pytest.approx(
                0.0, abs=1e-15
            )
        else:
            assert (got.a, got.alpha) == (0.0, 0.0)
    pair = rot_x(robot.links[moved].alpha) @ tras_x(robot.links[moved].a)
    if to_row:
        assert_transform_close(back.base, robot.base, atol=1e-15)
        assert_transform_close(back.tool, np.eye(4), atol=1e-15)
        if spec.tool is None:  # the table it was, to the bit but for α's last digit
            assert back.links[:-1] == robot.links[:-1]
            np.testing.assert_array_equal(back.tool, np.eye(4))
    elif spec.convention == "standard":
        assert_transform_close(back.base, robot.base, atol=1e-15)
        assert_transform_close(back.tool, pair @ robot.tool, atol=1e-15)
    else:
        assert_transform_close(back.base, robot.base @ pair, atol=1e-15)
        assert_transform_close(back.tool, robot.tool, atol=1e-15)


def test_to_convention_unknown_name() -> None:
    with pytest.raises(KinematicaError, match="unknown DH convention 'euler'"):
        PUMA.build().to_convention("euler")


# --------------------------------------------------------------- seed formulas
def test_seed000_arm_at_zero_by_hand() -> None:
    # q = 0, l = (l1, l2, l3, l4); derived link by link (c = cos, s = sin):
    #   0T1 = Rot(z,0) Tras(z,l1) Rot(x,90):   R1 = [[1,0,0],[0,0,-1],[0,1,0]], p1 = (0,0,l1)
    #   1T2 = Rot(z,90) Tras(x,l2):            R2 = R1·Rz(90) = [[0,-1,0],[0,0,-1],[1,0,0]],
    #                                          p2 = p1 + l2·(R1 y) = (0, 0, l1 + l2)
    #   2T3 = Rot(z,-90) Rot(x,-90) = [[0,0,1],[-1,0,0],[0,-1,0]]:  R3 = R2·that = I, p3 = p2
    #   3T4 = same rotation, Tras(z,l3):      R4 = [[0,0,1],[-1,0,0],[0,-1,0]], p4 = p3 + l3·z3
    #   4T5 = Rot(x,90):                       R5 = R4·Rx(90) = [[0,1,0],[-1,0,0],[0,0,1]], p5 = p4
    #   5T6 = Tras(z,l4):                      R6 = R5, p6 = p5 + l4·z5
    # The arm stands straight up: T = [[0,1,0,0],[-1,0,0,0],[0,0,1,l1+l2+l3+l4],[0,0,0,1]].
    l1, l2, l3, l4 = 0.5, 0.4, 0.35, 0.1
    robot = seed000_arm(l1, l2, l3, l4)
    expected = homogeneous([[0, 1, 0], [-1, 0, 0], [0, 0, 1]], [0, 0, l1 + l2 + l3 + l4])
    assert_transform_close(robot.fk([0, 0, 0, 0, 0, 0]), expected, atol=1e-15)
    # The intermediate frames derived above.
    frames = robot.fk(np.zeros(6), all_frames=True)
    assert_transform_close(
        frames[1], homogeneous([[1, 0, 0], [0, 0, -1], [0, 1, 0]], [0, 0, l1]), atol=1e-15
    )
    assert_transform_close(
        frames[2], homogeneous([[0, -1, 0], [0, 0, -1], [1, 0, 0]], [0, 0, l1 + l2]), atol=1e-15
    )
    assert_transform_close(frames[3], homogeneous(np.eye(3).tolist(), [0, 0, l1 + l2]), atol=1e-15)
    assert_transform_close(
        frames[4],
        homogeneous([[0, 0, 1], [-1, 0, 0], [0, -1, 0]], [0, 0, l1 + l2 + l3]),
        atol=1e-15,
    )


def test_seed000_arm_shoulder_down_by_hand() -> None:
    # q2 = -90°: θ2 = 0, so 1T2 = Tras(x, l2) and the upper arm lies along x1 = x0:
    # p2 = (l2, 0, l1). R3 = R1·Rz(-90)Rx(-90) = [[0,0,1],[0,1,0],[-1,0,0]] (= Ry(90)),
    # so the forearm z3 points along +x; the wrist at zero adds Rz(-90) and l4 along z3:
    # R = Ry(90)·Rz(-90) = [[0,0,1],[-1,0,0],[0,-1,0]], p = (l2 + l3 + l4, 0, l1).
    # q1 = 90° turns all of it about z0: R -> Rz(90)·R, p -> (0, l2 + l3 + l4, l1).
    l1, l2, l3, l4 = 0.5, 0.4, 0.35, 0.1
    robot = seed000_arm(l1, l2, l3, l4)
    R = [[0, 0, 1], [-1, 0, 0], [0, -1, 0]]
    expected = homogeneous(R, [l2 + l3 + l4, 0, l1])
    assert_transform_close(robot.fk([0, -90 * DEG, 0, 0, 0, 0]), expected, atol=1e-15)
    expected_q1 = homogeneous((rot_z(90 * DEG)[:3, :3] @ R).tolist(), [0, l2 + l3 + l4, l1])
    assert_transform_close(robot.fk([90 * DEG, -90 * DEG, 0, 0, 0, 0]), expected_q1, atol=1e-15)


def test_seed000_arm_geometric_formula() -> None:
    # With q5 = 0 the wrist is straight: the tool lies on the forearm line whatever
    # q4 and q6. Joint 2 turns about z1 = Rz(q1)·(0,-1,0), so the upper arm points
    # along u = (-c1 s2, -s1 s2, c2) and the forearm along v = (-c1 s23, -s1 s23, c23):
    #   x = -c1 (l2 s2 + (l3 + l4) s23),  y = -s1 (l2 s2 + (l3 + l4) s23),
    #   z = l1 + l2 c2 + (l3 + l4) c23,   and the tool z axis is v.
    l1, l2, l3, l4 = 0.5, 0.4, 0.35, 0.1
    robot = seed000_arm(l1, l2, l3, l4)
    rng = np.random.default_rng(14)
    q = rng.uniform(-math.pi, math.pi, (50, 6))
    q[:, 4] = 0.0
    q1, q2, q23 = q[:, 0], q[:, 1], q[:, 1] + q[:, 2]
    r = l2 * np.sin(q2) + (l3 + l4) * np.sin(q23)
    p = np.stack(
        [-np.cos(q1) * r, -np.sin(q1) * r, l1 + l2 * np.cos(q2) + (l3 + l4) * np.cos(q23)], -1
    )
    v = np.stack([-np.cos(q1) * np.sin(q23), -np.sin(q1) * np.sin(q23), np.cos(q23)], -1)
    T = robot.fk(q)
    np.testing.assert_allclose(T[:, :3, 3], p, atol=1e-14)
    np.testing.assert_allclose(T[:, :3, 2], v, atol=1e-14)


def test_seed000_prismatic_revolute_example() -> None:
    # Seed 000's 2-DOF P-R mechanism: x = q1 + l1 + l2 cos q2, y = l2 sin q2.
    # DH: z0 on the slide axis (world x): base = Ry(90°); row 1 prismatic with
    # theta = 90°, alpha = -90° turns z1 onto world z (the revolute axis) and
    # x1 onto world y; row 2 revolute, a = l2, offset -90° so x2 = (c2, s2, 0).
    l1, l2 = 0.3, 0.25
    base = homogeneous([[0, 0, 1], [0, 1, 0], [-1, 0, 0]], [0, 0, 0])
    robot = Robot.from_dh(
        [
            Prismatic(theta=90 * DEG, alpha=-90 * DEG, offset=l1),
            Revolute(a=l2, offset=-90 * DEG),
        ],
        base=base,
        convention="standard",
    )
    q = np.random.default_rng(15).uniform([-0.2, -math.pi], [0.5, math.pi], (40, 2))
    p = robot.fk(q)[:, :3, 3]
    np.testing.assert_allclose(p[:, 0], q[:, 0] + l1 + l2 * np.cos(q[:, 1]), atol=1e-15)
    np.testing.assert_allclose(p[:, 1], l2 * np.sin(q[:, 1]), atol=1e-15)
    np.testing.assert_allclose(p[:, 2], 0.0, atol=1e-15)


def test_seed000_planar_prr_example() -> None:
    # Seed 000, geometric example 1 (1 prismatic + 2 revolute, in the x-z plane):
    #   z = q1 + l1 + l3 cos q2 + l4 cos(q2 + q3),  x = l2 + l3 sin q2 + l4 sin(q2 + q3),  y = 0.
    # DH: slide along z0; row 1 d = q1 + l1, a = l2, alpha = -90° (z1 = +y);
    # row 2 a = l3, offset -90° (x2 = (s2, 0, c2)); row 3 a = l4.
    l1, l2, l3, l4 = 0.4, 0.1, 0.3, 0.2
    robot = Robot.from_dh(
        [
            Prismatic(a=l2, alpha=-90 * DEG, offset=l1),
            Revolute(a=l3, offset=-90 * DEG),
            Revolute(a=l4),
        ],
        convention="standard",
    )
    q = np.random.default_rng(16).uniform(-math.pi, math.pi, (40, 3))
    q2, q23 = q[:, 1], q[:, 1] + q[:, 2]
    p = robot.fk(q)[:, :3, 3]
    np.testing.assert_allclose(
        p[:, 2], q[:, 0] + l1 + l3 * np.cos(q2) + l4 * np.cos(q23), atol=1e-15
    )
    np.testing.assert_allclose(p[:, 0], l2 + l3 * np.sin(q2) + l4 * np.sin(q23), atol=1e-15)
    np.testing.assert_allclose(p[:, 1], 0.0, atol=1e-15)
    # The same mechanism in Craig's convention gives the same tool pose (seed 001).
    mdh = robot.to_convention("modified")
    assert_transform_close(mdh.fk(q), robot.fk(q), atol=1e-15)


def test_seed001_planar_3r_example() -> None:
    # Seed 001, example 1: rows (θi, 0, li, 0). The tool is turned by q1 + q2 + q3
    # about z and sits at x = l1 c1 + l2 c12 + l3 c123, y = l1 s1 + l2 s12 + l3 s123, z = 0.
    lengths = (0.4, 0.3, 0.2)
    robot = Robot.from_dh([Revolute(a=a) for a in lengths], convention="standard")
    q = np.random.default_rng(17).uniform(-math.pi, math.pi, (40, 3))
    c = np.cumsum(q, axis=-1)
    expected = np.array([rot_z(ci) for ci in c[:, 2]])
    expected[:, 0, 3] = np.cos(c) @ lengths
    expected[:, 1, 3] = np.sin(c) @ lengths
    assert_transform_close(robot.fk(q), expected, atol=1e-15)


# ------------------------------------------------------- description, limits
def test_structure_and_limits() -> None:
    robot = MIXED.build()
    assert robot.dof == 5
    assert robot.joint_types == "RPRPR"
    np.testing.assert_array_equal(robot.is_prismatic, [False, True, False, True, False])
    np.testing.assert_array_equal(robot.has_limits, [True, True, False, False, False])
    np.testing.assert_array_equal(
        robot.qlim,
        [[-2.0, 2.0], [0.0, 0.5], [-math.pi, math.pi], [-math.inf, math.inf], [-math.pi, math.pi]],
    )
    assert robot.qlim.shape == (5, 2)


def test_with_limits_base_tool() -> None:
    robot = MIXED.build()
    limited = robot.with_limits([(-1, 1), None, (0, 1), (-0.5, 0.5), None])
    np.testing.assert_array_equal(limited.qlim[:, 0], [-1, -math.inf, 0, -0.5, -math.pi])
    with pytest.raises(DimensionError, match="qlim must have 5 rows, got 2"):
        robot.with_limits([(-1, 1), None])
    moved = robot.with_base(None).with_tool(None)
    q = random_q(MIXED, np.random.default_rng(18))
    expected = np.linalg.inv(robot.base) @ robot.fk(q) @ np.linalg.inv(robot.tool)
    assert_transform_close(moved.fk(q), expected, atol=1e-13)


def test_dh_table() -> None:
    robot = MIXED.build()
    q = [0.1, 0.2, 0.3, 0.4, 0.5]
    expected = [j.params(qi) for j, qi in zip(MIXED.joints, q, strict=True)]
    np.testing.assert_allclose(robot.dh_table(q), expected, atol=1e-15)


def test_robot_is_immutable() -> None:
    robot = MIXED.build()
    with pytest.raises(ValueError, match="read-only"):
        robot.base[0, 3] = 1.0
    with pytest.raises(AttributeError):
        robot.links = ()  # type: ignore[misc]


# --------------------------------------------------------------------- bad input
@pytest.fixture
def puma() -> Robot:
    return PUMA.build()


@pytest.mark.parametrize(
    ("q", "match"),
    [
        ([0.0] * 5, r"must hold 6 joint values .* got 5"),
        ([0.0] * 7, r"must hold 6 joint values .* got 7"),
        (np.zeros((3, 5)), r"must hold 6 joint values .* got 5 \(shape \(3, 5\)\)"),
        (0.0, "must hold 6 joint values .* got a scalar"),
        ([], r"must hold 6 joint values .* got 0"),
    ],
)
def test_wrong_number_of_joint_values(puma: Robot, q: object, match: str) -> None:
    for call in (puma.fk, lambda v: puma.fk(v, all_frames=True), puma.link_matrices):
        with pytest.raises(DimensionError, match=match):
            call(q)


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_non_finite_joint_values(puma: Robot, bad: float) -> None:
    q = [0.0, 0.1, 0.2, bad, 0.4, 0.5]
    for form in (q, tuple(q), np.array(q), np.array(q, dtype=np.float32)):
        with pytest.raises(DimensionError, match=r"q holds NaN or inf at index \(3,\)"):
            puma.fk(form)
    # A batch: the bad row is named in a warning and comes out NaN; the rest stands.
    batch = np.zeros((2, 3, 6))
    batch[1, 2, 4] = bad
    for call in (puma.fk, lambda b: puma.fk(b, all_frames=True), puma.link_matrices):
        with pytest.warns(KinematicaWarning, match=r"1 row\(s\) hold NaN or inf.*\(1, 2\)"):
            out = call(batch)
        assert np.all(np.isnan(out[1, 2]))
        good = np.ones((2, 3), dtype=bool)
        good[1, 2] = False
        assert np.all(np.isfinite(out[good]))
        clean = batch.copy()
        clean[1, 2] = 0.0
        np.testing.assert_array_equal(out[good], call(clean)[good])


@pytest.mark.parametrize(
    ("q", "match"),
    [
        ("abcdef", "q must be numbers, got 'abcdef'"),
        (["a", 0, 0, 0, 0, 0], r"q must be numbers, got \['a', 0"),
        ([1, 2, 3, 4, 5, "x"], r"q must be numbers, got \[1, 2, 3, 4, 5, 'x'\]"),
        ([[0.0] * 6, [0.0] * 5], "q must be numbers"),  # ragged
        ({"q1": 0.0}, "q must be numbers"),
        ([None] * 6, "q must be numbers"),
    ],
)
def test_joint_values_that_are_not_numbers(puma: Robot, q: object, match: str) -> None:
    with pytest.raises(DimensionError, match=match):
        puma.fk(q)  # type: ignore[arg-type]
    with pytest.raises(DimensionError, match=match):
        puma.jacobian(q)  # type: ignore[arg-type]


def test_numeric_strings_are_not_joint_values(puma: Robot) -> None:
    with pytest.raises(DimensionError, match="q must be numbers"):
        puma.fk(["0", "0.1", "0.2", "0.3", "0.4", "0.5"])


@pytest.mark.filterwarnings("ignore::numpy.exceptions.ComplexWarning")
def test_complex_joint_values_are_rejected(puma: Robot) -> None:
    with pytest.raises(DimensionError, match="q must be"):
        puma.fk(np.array([0, 0.1, 0.2, 0.3, 0.4, 0.5 + 1j]))


@pytest.mark.parametrize("which", ["base", "tool"])
@pytest.mark.parametrize(
    ("value", "match"),
    [
        (np.eye(3), r"must be a 4x4 homogeneous transform, got shape \(3, 3\)"),
        (np.eye(4)[:3], r"must be a 4x4 homogeneous transform, got shape \(3, 4\)"),
        (np.zeros((2, 4, 4)), r"must be a 4x4 homogeneous transform, got shape \(2, 4, 4\)"),
        (np.diag([1.0, 1.0, -1.0, 1.0]), r"rotation has det = -1.000, expected \+1"),
        (np.diag([2.0, 1.0, 1.0, 1.0]), "rotation is not orthonormal"),
        (SKEWED, "rotation is not orthonormal"),
        (np.diag([1.0, 1.0, 1.0, 2.0]), r"last row must be \[0, 0, 0, 1\]"),
        (np.full((4, 4), np.nan), "contains NaN or inf"),
    ],
)
def test_bad_base_and_tool(which: str, value: np.ndarray, match: str) -> None:
    rows = [Revolute(a=0.3), Prismatic(alpha=0.2)]
    with pytest.raises(DimensionError, match=f"{which} {match}"):
        Robot.from_dh(rows, convention="standard", **{which: value})
    robot = Robot.from_dh(rows, convention="standard")
    with pytest.raises(DimensionError, match=f"{which} {match}"):
        robot.with_base(value) if which == "base" else robot.with_tool(value)


@pytest.mark.parametrize("which", ["base", "tool"])
def test_base_or_tool_that_is_not_numbers(which: str) -> None:
    with pytest.raises(KinematicaError, match=which):
        Robot.from_dh([Revolute()], convention="standard", **{which: "identity"})


def test_bad_robot_descriptions() -> None:
    with pytest.raises(KinematicaError, match="at least one joint"):
        Robot.from_dh([], convention="standard")
    with pytest.raises(
        KinematicaError, match=r"joint 2: expected kinematica\.Revolute .* got tuple"
    ):
        Robot.from_dh([Revolute(), (0.0, 0.0, 0.0, 0.0)], convention="standard")  # type: ignore[list-item]
    with pytest.raises(KinematicaError, match="unknown DH convention 'sideways'"):
        Robot.from_dh([Revolute()], convention="sideways")


@pytest.mark.parametrize("name", ["puma560", "stanford", "panda", "scara"])
@pytest.mark.parametrize("suffix", [".json", ".toml", ".yaml"])
def test_robot_written_to_a_file_loads_back_identical(
    name: str, suffix: str, tmp_path: Path
) -> None:
    robot = km.load(name)
    path = tmp_path / f"arm{suffix}"
    km.write_robot_file(km.spec_from_robot(robot), path)
    again = km.load(path)
    q = np.random.default_rng(4).uniform(-1, 1, (20, robot.dof))
    np.testing.assert_array_equal(again.fk(q), robot.fk(q))
    np.testing.assert_array_equal(again.qlim, robot.qlim)
    assert again.convention == robot.convention and again.joint_types == robot.joint_types


def test_base_and_tool_written_with_seven_digits_are_accepted_and_made_rigid() -> None:
    # max|RᵀR - I| = 3e-7, inside ORTHONORMAL_TOL (1e-6): the same tolerance as a
    # robot file's; the robot keeps the nearest rotation, exactly rigid.
    R = rot_z(0.3)
    R[0, 1] += 3e-7
    for which in ("base", "tool"):
        robot = Robot.from_dh(
            [Revolute(a=0.3), Prismatic(alpha=0.2)], convention="standard", **{which: R}
        )
        M = getattr(robot, which)
        assert np.abs(M[:3, :3].T @ M[:3, :3] - np.eye(3)).max() < 1e-15
        assert np.abs(M - R).max() < 1e-6
        T = robot.fk([0.4, 0.1])
        assert np.abs(T[:3, :3].T @ T[:3, :3] - np.eye(3)).max() < 1e-15


def test_base_orthonormal_to_roundoff_is_kept_bit_for_bit() -> None:
    # ROUNDOFF_TOL (1e-14): a rotation computed in double precision is kept as
    # given; one 1e-12 off orthonormal (written with 12 digits) is projected.
    exact = rot_z(0.3) @ rot_x(1.1)
    assert 0 < np.abs(exact[:3, :3].T @ exact[:3, :3] - np.eye(3)).max() < 1e-15
    robot = Robot.from_dh([Revolute(a=0.3)], base=exact, convention="standard")
    np.testing.assert_array_equal(robot.base, exact)
    off = exact.copy()
    off[0, 0] += 1e-12
    robot = Robot.from_dh([Revolute(a=0.3)], base=off, convention="standard")
    assert not np.array_equal(robot.base, off)
    assert np.abs(robot.base[:3, :3].T @ robot.base[:3, :3] - np.eye(3)).max() < 1e-15


def test_degrees_given_to_the_radian_api_warn_without_limits() -> None:
    arm = km.load("arm6-dh")  # no joint limits: nothing else would say it
    with pytest.warns(km.UnitWarning, match=r"joint 1 = 30 rad is more than a full turn"):
        arm.fk([30, 40, -30, 10, 60, -20])
    with pytest.warns(km.UnitWarning, match=r"joint 2 \(row \(1,\)\) = 7 rad"):
        arm.fk(np.array([[0.0] * 6, [0.0, 7.0, 0, 0, 0, 0]]))
    with pytest.warns(km.UnitWarning, match="is it in degrees"):
        arm.jacobian([0, 0, 0, 0, 90, 0])
    assert issubclass(km.UnitWarning, km.KinematicaWarning)
    turn = 2 * np.pi  # the boundary, single call and batch (the core counts, numpy names) alike
    for q in ([turn * (1 - 1e-12), 0, 0, 0, 0, 0], [[-turn * (1 - 1e-12), 0, 0, 0, 0, 0]]):
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            arm.fk(q)
            arm.jacobian(q)
    for q in ([turn * (1 + 1e-12), 0, 0, 0, 0, 0], [[-turn * (1 + 1e-12), 0, 0, 0, 0, 0]]):
        with pytest.warns(km.UnitWarning):
            arm.fk(q)
    with warnings.catch_warnings():  # NaN and inf are said otherwise, not as a unit slip
        warnings.simplefilter("ignore", km.KinematicaWarning)
        warnings.simplefilter("error", km.UnitWarning)
        arm.fk([[np.inf, 0, 0, 0, 0, 0], [np.nan, 0, 0, 0, 0, 0]])
    # a joint with limits of its own is judged by them, a prismatic joint not at all
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        km.load("planar-prr").fk([0.1, 0.5, 0.5])
    with pytest.warns(km.KinematicaWarning, match="outside its limits") as caught:
        km.load("puma560").fk([30, 0, 0, 0, 0, 0])
    assert not any(issubclass(w.category, km.UnitWarning) for w in caught)


def test_a_batch_names_every_slip_of_a_row_that_has_several() -> None:
    # the core counts a row beyond a turn even when it is also outside the limits or
    # holds NaN, so that the batch names it (the first state of a row is not its only one)
    arm = Robot.from_dh([Revolute(a=0.3), Revolute(a=0.2, qlim=(-1.0, 1.0))], convention="standard")
    for rows, other in (([[7.0, 2.0]], "outside its limits"), ([[7.0, np.nan]], "NaN or inf")):
        for call in (arm.fk, arm.jacobian):
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                call(np.array([[0.0, 0.0], *rows]))
            said = [str(w.message) for w in caught]
            assert any("joint 1 (row (1,)) = 7 rad" in m for m in said), said
            if call == arm.fk or other.startswith("NaN"):  # a Jacobian ignores limits
                assert any(other in m for m in said), said


def test_the_limits_warning_of_a_large_batch_names_the_first_row_and_counts_all() -> None:
    arm = km.load("puma560")
    q = np.zeros((3, 5000, 6))
    q[1, 4321, 1] = 4.5  # joint 2's limits: [-45°, 225°]
    q[2, 17, 2] = -9.0
    q[2, 18, 0] = 9.0
    with pytest.warns(km.KinematicaWarning) as caught:
        arm.fk(q)
    (message,) = [str(w.message) for w in caught]
    assert message.startswith("q: joint 2 = 4.5 rad in row (1, 4321) is outside its limits")
    assert message.endswith("(3 configurations outside the limits)")


def test_nan_rows_are_counted_and_the_first_five_named() -> None:
    puma = km.load("puma560")
    q = np.zeros((3, 4000, 6))
    bad = [(0, 7), (1, 0), (1, 3999), (2, 5), (2, 6), (2, 3000), (2, 3999)]
    for i, j in bad:
        q[i, j, j % 6] = np.nan if j % 2 else np.inf
    with pytest.warns(km.KinematicaWarning) as seen:
        T = puma.fk(q)
    shown = ", ".join(str(b) for b in bad[:5])
    assert str(seen[0].message) == (
        f"q: 7 row(s) hold NaN or inf, their results are NaN: {shown} ..."
    )
    assert np.isnan(T[1, 3999]).all() and np.isfinite(T[1, 3998]).all()
    with pytest.warns(km.KinematicaWarning, match=r"2 row\(s\) .*: \(8,\), \(9999,\)$"):
        flat = np.zeros((10_000, 6))
        flat[[8, 9999], 0] = np.nan
        puma.jacobian(flat)


def test_a_batch_of_nan_rows_makes_no_object_per_row() -> None:
    """The warning of 200,000 NaN rows costs what that of a few does (it once made a
    Python tuple of every row to name five: 4-5x the time of the batch itself)."""
    import tracemalloc
    import warnings

    puma = km.load("puma560")
    n = 200_000
    finite, nan = np.zeros((n, 6)), np.full((n, 6), np.nan)
    peaks = {}
    for name, q in (("finite", finite), ("nan", nan)):
        for f in (puma.fk, puma.jacobian):
            tracemalloc.start()
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                f(q)
            peaks[name, f.__name__] = tracemalloc.get_traced_memory()[1]
            tracemalloc.stop()
    for f in ("fk", "jacobian"):  # the results themselves: 25.6 MB and 57.6 MB
        assert peaks["nan", f] - peaks["finite", f] < 1_000_000, peaks
