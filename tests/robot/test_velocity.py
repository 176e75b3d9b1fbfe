"""Analytic Jacobian, manipulability and condition number against independent references."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st
from support.helpers import PROPERTY, RobotSpec, random_q, robot_specs, seeds

import kinematica as km
from kinematica.errors import KinematicaWarning
from kinematica.motion import manipulability
from kinematica.spatial import GIMBAL_LOCK_TOL

H = 1e-6


def fd_pose_jacobian(robot: km.Robot, q: np.ndarray, seq: str) -> np.ndarray:
    """Central differences of to_pose (angles wrapped) column by column."""
    cols = []
    for i in range(robot.dof):
        dq = np.zeros(robot.dof)
        dq[i] = H
        diff = km.to_pose(robot.fk(q + dq), seq) - km.to_pose(robot.fk(q - dq), seq)
        diff[3:] = km.wrap_angle(diff[3:])
        cols.append(diff / (2 * H))
    return np.array(cols).T


def fd_geometric_jacobian(robot: km.Robot, q: np.ndarray) -> np.ndarray:
    cols = []
    for i in range(robot.dof):
        dq = np.zeros(robot.dof)
        dq[i] = H
        Tp, Tm = robot.fk(q + dq), robot.fk(q - dq)
        v = (Tp[:3, 3] - Tm[:3, 3]) / (2 * H)
        w = km.rotvec_from_matrix(Tp[:3, :3] @ Tm[:3, :3].T) / (2 * H)
        cols.append(np.r_[v, w])
    return np.array(cols).T


@PROPERTY
@given(spec=robot_specs(max_dof=7), seed=seeds, seq=st.sampled_from(["ZYZ", "xyz", "XZX", "zyx"]))
def test_analytic_jacobian_equals_finite_differences(spec: RobotSpec, seed: int, seq: str) -> None:
    robot = spec.build()
    q = random_q(spec, np.random.default_rng(seed))
    angles = km.to_pose(robot.fk(q), seq)[3:]
    b = angles[1]
    far = abs(math.sin(b)) if seq[0].lower() == seq[2].lower() else abs(math.cos(b))
    assume(far > 0.05)  # finite differences of angles are poor next to gimbal lock
    Ja = robot.jacobian(q, euler=seq)
    scale = 1.0 + np.abs(Ja).max()
    assert np.allclose(Ja, fd_pose_jacobian(robot, q, seq), atol=2e-6 * scale / far)
    # and the geometric Jacobian it is built from equals finite differences too
    assert np.allclose(robot.jacobian(q), fd_geometric_jacobian(robot, q), atol=1e-6 * scale)


def test_analytic_jacobian_in_gimbal_lock_is_nan_and_warned() -> None:
    puma = km.load("puma560")
    # Tool z axis along the base z axis (ZYZ middle angle 0), wrist not singular.
    q = np.array([0.0, 0.0, -np.pi / 2, 0.0, np.pi / 2, 0.0])
    R = puma.fk(q)[:3, :3]
    assert km.gimbal_locked(R, "ZYZ")
    with pytest.warns(km.KinematicaWarning, match="gimbal lock"):
        Ja = puma.jacobian(q, euler="ZYZ")
    assert np.isnan(Ja[3:]).all()
    assert np.allclose(Ja[:3], puma.jacobian(q)[:3])
    # another sequence is regular there
    assert np.isfinite(puma.jacobian(q, euler="XYZ")).all()


def test_analytic_jacobian_just_outside_the_lock_is_finite() -> None:
    puma = km.load("puma560")
    q = np.array([0.0, 0.0, -np.pi / 2, 0.0, np.pi / 2 + 3 * GIMBAL_LOCK_TOL, 0.0])
    assert not km.gimbal_locked(puma.fk(q)[:3, :3], "ZYZ")
    assert np.isfinite(puma.jacobian(q, euler="ZYZ")).all()


def test_analytic_jacobian_batch_marks_only_locked_rows() -> None:
    puma = km.load("puma560")
    q = np.array([[0.0, 0.0, -np.pi / 2, 0.0, np.pi / 2, 0.0], [0.1, 0.2, 0.3, 0.4, 0.5, 0.6]])
    with pytest.warns(km.KinematicaWarning, match="1 configuration"):
        Ja = km.analytic_jacobian(puma, q, "ZYZ")
    assert np.isnan(Ja[0, 3:]).all() and np.isfinite(Ja[1]).all()


def test_analytic_jacobian_rejects_tool_frame() -> None:
    with pytest.raises(km.KinematicaError, match="base frame"):
        km.load("puma560").jacobian(np.zeros(6), frame="tool", euler="ZYZ")


def planar_2r(l1: float, l2: float) -> km.Robot:
    return km.Robot.from_dh([km.Revolute(a=l1), km.Revolute(a=l2)], convention="standard")


def test_manipulability_of_planar_2r_by_hand() -> None:
    l1, l2 = 0.7, 0.4
    q2 = np.linspace(-3, 3, 25)
    q = np.stack([np.full_like(q2, 0.3), q2], axis=-1)
    w = km.manipulability(planar_2r(l1, l2), q, axes="trans")
    assert np.allclose(w, l1 * l2 * np.abs(np.sin(q2)), atol=1e-14)


def test_manipulability_of_anthropomorphic_arm_by_hand() -> None:
    arm = km.load("anthropomorphic-3r")  # L2 = 0.4, L3 = 0.3 (seed 002)
    rng = np.random.default_rng(3)
    q = rng.uniform(-3, 3, (50, 3))
    c2, c23, s3 = np.cos(q[:, 1]), np.cos(q[:, 1] + q[:, 2]), np.sin(q[:, 2])
    expected = 0.4 * 0.3 * np.abs(s3) * np.abs(0.4 * c2 + 0.3 * c23)
    assert np.allclose(km.manipulability(arm, q, axes="trans"), expected, atol=1e-14)
    # "task" picks the position rows for such an arm
    assert np.allclose(km.manipulability(arm, q, axes="task"), expected, atol=1e-14)


def test_manipulability_is_yoshikawa_sqrt_det_on_6r() -> None:
    puma = km.load("puma560")
    q = puma.random_q(20, seed=1)
    J = puma.jacobian(q)
    yoshikawa = np.sqrt(np.linalg.det(J @ np.swapaxes(J, -1, -2)))
    assert np.allclose(km.manipulability(puma, q), yoshikawa, rtol=1e-9)
    # rotation rows only
    Jr = J[:, 3:]
    assert np.allclose(
        km.manipulability(puma, q, axes="rot"),
        np.sqrt(np.linalg.det(Jr @ np.swapaxes(Jr, -1, -2))),
        rtol=1e-9,
    )


def test_condition_number_against_numpy_cond() -> None:
    ur5 = km.load("ur5")
    q = ur5.random_q(20, seed=2)
    assert np.allclose(km.condition_number(ur5, q), np.linalg.cond(ur5.jacobian(q)), rtol=1e-9)
    l1, l2 = 1.0, 1.0
    # planar 2R at q2 = 90°: Jv = [[-1, -1], [1, 0]]·... -> cond of a known 2x2
    Jv = np.array([[-l1 * 0 - l2 * 1, -l2 * 1], [l1 * 1 + l2 * 0, 0.0]])
    got = km.condition_number(planar_2r(l1, l2), [0.0, np.pi / 2], axes=[0, 1])
    assert np.isclose(got, np.linalg.cond(Jv))


def test_singular_configuration_measures() -> None:
    puma = km.load("puma560")
    q = np.array([0.1, 0.2, 0.3, 0.4, 0.0, 0.5])  # wrist singular
    assert km.manipulability(puma, q) < 1e-12
    assert km.condition_number(puma, q) > 1e12


@pytest.mark.parametrize("batch", [(), (1,), (3, 2)])
def test_batch_shapes(batch: tuple[int, ...]) -> None:
    puma = km.load("puma560")
    q = np.random.default_rng(0).uniform(-1, 1, (*batch, 6))
    assert km.manipulability(puma, q).shape == batch
    assert km.condition_number(puma, q).shape == batch
    assert puma.jacobian(q, euler="XYZ").shape == (*batch, 6, 6)


def test_bad_axes() -> None:
    puma = km.load("puma560")
    with pytest.raises(km.KinematicaError, match="axes"):
        km.manipulability(puma, np.zeros(6), axes="linear")  # type: ignore[arg-type]
    with pytest.raises(km.KinematicaError, match="row indices"):
        km.manipulability(puma, np.zeros(6), axes=[0, 7])
    with pytest.raises(km.DimensionError, match="6 joint values"):
        km.manipulability(puma, np.zeros(5))


def _arm() -> km.Robot:
    return km.load("planar-3r")


def test_manipulability_of_a_batch_with_nan_rows_is_nan_there() -> None:
    arm = _arm()
    with pytest.warns(KinematicaWarning, match="1 row"):
        w = manipulability(arm, [[0.0, 0.5, 0.5], [0.0, math.nan, 0.0]], axes="trans")
    assert np.isnan(w[1])
    assert w[0] == pytest.approx(float(manipulability(arm, [0.0, 0.5, 0.5], axes="trans")))


#: Finite differences of step H agree with an exact derivative to ~H² plus
#: round-off ~eps/H, i.e. ~1e-10 on arms of unit size; the contract is 1e-6.
FD_TOL = 1e-6


# ------------------------------------------------------------ measures
def test_manipulability_methods_from_singular_values() -> None:
    ur5 = km.load("ur5")
    q = ur5.random_q(10, seed=5)
    for axes, rows in (("all", slice(None)), ("trans", slice(0, 3)), ("rot", slice(3, 6))):
        s = np.linalg.svd(ur5.jacobian(q)[:, rows], compute_uv=False)
        inv = km.manipulability(ur5, q, axes, method="inverse_condition")
        assert np.allclose(inv, s[:, -1] / s[:, 0], rtol=1e-12)
        assert np.allclose(inv, 1.0 / km.condition_number(ur5, q, axes), rtol=1e-12)
        mins = km.manipulability(ur5, q, axes, method="min_singular")
        assert np.allclose(mins, s[:, -1], rtol=1e-12)
        assert np.allclose(
            km.manipulability(ur5, q, axes, method="yoshikawa"), s.prod(axis=-1), rtol=1e-12
        )


def test_manipulability_methods_of_planar_2r_by_hand() -> None:
    """Jv = [[-l1 s1 - l2 s12, -l2 s12], [l1 c1 + l2 c12, l2 c12]]; at q1 = 0, q2 = 90°
    with l1 = l2 = 1: [[-1, -1], [1, 0]], singular values √((3 ± √5)/2) = φ and 1/φ."""
    arm = km.Robot.from_dh([km.Revolute(a=1.0), km.Revolute(a=1.0)], convention="standard")
    golden = (1 + math.sqrt(5)) / 2
    q = [0.0, math.pi / 2]
    assert math.isclose(km.manipulability(arm, q, [0, 1], "min_singular"), 1 / golden)
    assert math.isclose(km.manipulability(arm, q, [0, 1], "inverse_condition"), 1 / golden**2)
    stretched = [0.3, 0.0]
    assert km.manipulability(arm, stretched, [0, 1], "inverse_condition") < 1e-15
    assert km.manipulability(arm, stretched, [0, 1], "min_singular") < 1e-15


def test_manipulability_rejects_an_unknown_method() -> None:
    with pytest.raises(km.KinematicaError, match="method must be"):
        km.manipulability(km.load("puma560"), np.zeros(6), method="volume")  # type: ignore[arg-type]


@pytest.mark.parametrize("axes", ["all", "trans"])
def test_manipulability_gradient_equals_finite_differences(axes: str) -> None:
    panda = km.load("panda")
    for q in panda.random_q(4, seed=6):
        g = km.motion.manipulability_gradient(panda, q, axes)
        fd = np.array(
            [
                (
                    km.manipulability(panda, q + H * e, axes)
                    - km.manipulability(panda, q - H * e, axes)
                )
                / (2 * H)
                for e in np.eye(7)
            ]
        )
        assert np.allclose(g, fd, atol=FD_TOL * (1.0 + np.abs(g).max()))
