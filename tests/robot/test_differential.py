"""Hessian, J̇, spatial and exponential-coordinate Jacobians (``robot/differential.py``).

References: central finite differences of the Jacobian and of the pose, the
adjoint map written out in the test, numpy's SVD and a Bernoulli series.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st
from support.helpers import PROPERTY, RobotSpec, random_q, robot_specs, seeds

import kinematica as km
from kinematica.robot.differential import EXP_SERIES_ANGLE, left_jacobian_inverse_coefficient

H = 1e-6
#: Finite differences of step H agree with an exact derivative to ~H² plus
#: round-off ~eps/H, i.e. ~1e-10 on arms of unit size; the contract is 1e-6.
FD_TOL = 1e-6

frames = st.sampled_from(["base", "tool", "spatial"])


def free(spec: RobotSpec) -> km.Robot:
    """The spec's robot without joint limits: random q beyond them are meant."""
    robot = spec.build()
    return robot.with_limits([None] * robot.dof)


def fd_hessian(robot: km.Robot, q: np.ndarray, frame: str) -> np.ndarray:
    out = np.empty((6, robot.dof, robot.dof))
    for j in range(robot.dof):
        dq = np.zeros(robot.dof)
        dq[j] = H
        out[:, :, j] = (robot.jacobian(q + dq, frame) - robot.jacobian(q - dq, frame)) / (2 * H)
    return out


@PROPERTY
@given(spec=robot_specs(max_dof=7), seed=seeds, frame=frames)
def test_hessian_equals_finite_differences(spec: RobotSpec, seed: int, frame: str) -> None:
    robot = free(spec)
    q = random_q(spec, np.random.default_rng(seed))
    Hq = km.hessian(robot, q, frame)
    assert Hq.shape == (6, robot.dof, robot.dof)
    scale = 1.0 + np.abs(Hq).max()
    assert np.abs(Hq - fd_hessian(robot, q, frame)).max() < FD_TOL * scale
    # the position rows of the base-frame Hessian are second derivatives: symmetric
    if frame == "base":
        assert np.allclose(Hq[:3], np.swapaxes(Hq[:3], -1, -2), atol=1e-12 * scale)


@PROPERTY
@given(spec=robot_specs(max_dof=7), seed=seeds, frame=frames)
def test_jacobian_dot_equals_finite_differences_along_the_motion(
    spec: RobotSpec, seed: int, frame: str
) -> None:
    robot = free(spec)
    rng = np.random.default_rng(seed)
    q, qd = random_q(spec, rng), rng.uniform(-1, 1, spec.dof)
    Jd = km.jacobian_dot(robot, q, qd, frame)
    fd = (robot.jacobian(q + H * qd, frame) - robot.jacobian(q - H * qd, frame)) / (2 * H)
    assert np.abs(Jd - fd).max() < FD_TOL * (1.0 + np.abs(Jd).max())


def test_hessian_of_planar_2r_by_hand() -> None:
    """x = l1 c1 + l2 c12, y = l1 s1 + l2 s12: every second derivative written out."""
    l1, l2, q1, q2 = 0.7, 0.4, 0.3, -1.1
    arm = km.Robot.from_dh([km.Revolute(a=l1), km.Revolute(a=l2)], convention="standard")
    c1, s1, c12, s12 = math.cos(q1), math.sin(q1), math.cos(q1 + q2), math.sin(q1 + q2)
    Hq = km.hessian(arm, [q1, q2])
    d11 = [-l1 * c1 - l2 * c12, -l1 * s1 - l2 * s12]  # ∂²(x, y)/∂q1²
    d12 = [-l2 * c12, -l2 * s12]
    assert np.allclose(Hq[:2, 0, 0], d11, atol=1e-15)
    assert np.allclose(Hq[:2, 0, 1], d12, atol=1e-15)
    assert np.allclose(Hq[:2, 1, 0], d12, atol=1e-15)
    assert np.allclose(Hq[:2, 1, 1], d12, atol=1e-15)
    assert np.all(Hq[2:] == 0.0)  # planar: no z motion, ω constant along z


def test_jacobian_dot_is_linear_in_qd_and_zero_at_rest() -> None:
    puma = km.load("puma560")
    q = puma.random_q(1, seed=3)[0]
    a, b = np.arange(1.0, 7.0), np.linspace(-1, 1, 6)
    assert np.allclose(
        km.jacobian_dot(puma, q, 2 * a - b),
        2 * km.jacobian_dot(puma, q, a) - km.jacobian_dot(puma, q, b),
        atol=1e-13,
    )
    assert np.all(km.jacobian_dot(puma, q, np.zeros(6)) == 0.0)


def adjoint(T: np.ndarray) -> np.ndarray:
    """Ad_T in the (v, ω) row order: [[R, [p]× R], [0, R]]."""
    R, p = T[:3, :3], T[:3, 3]
    px = np.array([[0, -p[2], p[1]], [p[2], 0, -p[0]], [-p[1], p[0], 0]])
    return np.block([[R, px @ R], [np.zeros((3, 3)), R]])


@PROPERTY
@given(spec=robot_specs(max_dof=7), seed=seeds)
def test_spatial_jacobian_is_the_adjoint_of_the_body_one(spec: RobotSpec, seed: int) -> None:
    robot = free(spec)
    rng = np.random.default_rng(seed)
    q, qd = random_q(spec, rng), rng.uniform(-1, 1, spec.dof)
    T = robot.fk(q)
    Js = robot.jacobian(q, "spatial")
    scale = 1.0 + np.abs(Js).max()
    assert np.allclose(Js, adjoint(T) @ robot.jacobian(q, "tool"), atol=1e-12 * scale)
    # V_s = (Ṫ T⁻¹)^∨ from finite differences of the pose along q̇
    Td = (robot.fk(q + H * qd) - robot.fk(q - H * qd)) / (2 * H)
    S = Td @ np.linalg.inv(T)
    Vs = np.r_[S[:3, 3], S[2, 1], S[0, 2], S[1, 0]]
    assert np.allclose(Js @ qd, Vs, atol=FD_TOL * scale)


def test_spatial_jacobian_column_of_a_revolute_joint_is_o_cross_z() -> None:
    arm = km.Robot.from_dh(
        [km.Revolute(a=0.5), km.Revolute(a=0.3)],
        base=km.transl(1.0, 2.0, 0.0),
        convention="standard",
    )
    Js = arm.jacobian([0.0, 0.0], "spatial")
    # joint 1: axis z through (1, 2, 0); joint 2: through (1.5, 2, 0)
    assert np.allclose(Js[:, 0], [2.0, -1.0, 0.0, 0.0, 0.0, 1.0], atol=1e-15)
    assert np.allclose(Js[:, 1], [2.0, -1.5, 0.0, 0.0, 0.0, 1.0], atol=1e-15)


@PROPERTY
@given(spec=robot_specs(max_dof=7), seed=seeds)
def test_exp_jacobian_equals_finite_differences_of_the_log(spec: RobotSpec, seed: int) -> None:
    robot = free(spec)
    q = random_q(spec, np.random.default_rng(seed))
    theta = float(np.linalg.norm(km.rotvec_from_matrix(robot.fk(q)[:3, :3])))
    assume(theta < math.pi - 0.05)  # the rotation vector jumps sign at π
    Ja = robot.jacobian(q, euler="exp")
    fd = np.empty_like(Ja)
    for i in range(robot.dof):
        dq = np.zeros(robot.dof)
        dq[i] = H
        Tp, Tm = robot.fk(q + dq), robot.fk(q - dq)
        fd[:3, i] = (Tp[:3, 3] - Tm[:3, 3]) / (2 * H)
        fd[3:, i] = (km.rotvec_from_matrix(Tp[:3, :3]) - km.rotvec_from_matrix(Tm[:3, :3])) / (
            2 * H
        )
    scale = (1.0 + np.abs(Ja).max()) / (math.pi - theta)
    assert np.abs(Ja - fd).max() < FD_TOL * scale


def bernoulli_coefficient(theta: float, terms: int = 40) -> float:
    """Σ_k |B_2k| θ^(2k−2)/(2k)!, Bernoulli numbers exact (Fractions), summed in floats."""
    B = [Fraction(1)]
    for m in range(1, 2 * terms + 1):
        B.append(-sum(math.comb(m + 1, k) * B[k] for k in range(m)) / (m + 1))
    total = 0.0
    for k in range(terms, 0, -1):  # smallest terms first
        total += float(abs(B[2 * k]) / math.factorial(2 * k)) * theta ** (2 * k - 2)
    return total


@pytest.mark.parametrize(
    ("theta", "rtol"),
    [
        (1e-9, 1e-15),
        (0.99 * EXP_SERIES_ANGLE, 1e-14),  # the series, just inside: the closed form is 3e-13 off
        (1.01 * EXP_SERIES_ANGLE, 1e-12),  # the closed form, just outside
        (1.0, 1e-14),
        (3.0, 1e-14),  # the truncated series would be far off here
    ],
)
def test_left_jacobian_inverse_coefficient(theta: float, rtol: float) -> None:
    got = float(left_jacobian_inverse_coefficient(theta))
    assert abs(got / bernoulli_coefficient(theta) - 1.0) < rtol


def test_exp_jacobian_rates_satisfy_omega_equals_left_jacobian_times_rates() -> None:
    """ω = J_l(φ) φ̇ with J_l = I + (1 − cos θ)/θ² [φ]× + (θ − sin θ)/θ³ [φ]×² (forward map)."""
    ur5 = km.load("ur5")
    for q in ur5.random_q(5, seed=4):
        phi = km.rotvec_from_matrix(ur5.fk(q)[:3, :3])
        t = float(np.linalg.norm(phi))
        K = np.array([[0, -phi[2], phi[1]], [phi[2], 0, -phi[0]], [-phi[1], phi[0], 0]])
        Jl = np.eye(3) + (1 - math.cos(t)) / t**2 * K + (t - math.sin(t)) / t**3 * K @ K
        assert np.allclose(Jl @ ur5.jacobian(q, euler="exp")[3:], ur5.jacobian(q)[3:], atol=1e-12)


@pytest.mark.parametrize("batch", [(), (1,), (3, 2)])
def test_batch_shapes(batch: tuple[int, ...]) -> None:
    puma = km.load("puma560")
    q = np.random.default_rng(0).uniform(-0.7, 0.7, (*batch, 6))
    assert km.hessian(puma, q, "tool").shape == (*batch, 6, 6, 6)
    assert km.jacobian_dot(puma, q, q).shape == (*batch, 6, 6)
    assert puma.jacobian(q, "spatial").shape == (*batch, 6, 6)
    assert puma.jacobian(q, euler="exp").shape == (*batch, 6, 6)
    e = km.ellipsoid(puma, q)
    assert e.radii.shape == (*batch, 3) and e.directions.shape == (*batch, 3, 3)
    for method in ("yoshikawa", "inverse_condition", "min_singular"):
        assert km.manipulability(puma, q, method=method).shape == batch  # type: ignore[arg-type]
    assert km.motion.manipulability_gradient(puma, q).shape == (*batch, 6)


def test_bad_frame() -> None:
    puma = km.load("puma560")
    with pytest.raises(km.KinematicaError, match="'spatial'"):
        km.hessian(puma, np.zeros(6), "world")  # type: ignore[arg-type]
    with pytest.raises(km.KinematicaError, match="'spatial'"):
        puma.jacobian(np.zeros(6), "world")  # type: ignore[arg-type]
