"""Hessian, J̇, spatial and exponential-coordinate Jacobians, manipulability measures, ellipsoids.

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
    arm = km.Robot.from_dh([km.Revolute(a=l1), km.Revolute(a=l2)])
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
    arm = km.Robot.from_dh([km.Revolute(a=0.5), km.Revolute(a=0.3)], base=km.transl(1.0, 2.0, 0.0))
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
    arm = km.Robot.from_dh([km.Revolute(a=1.0), km.Revolute(a=1.0)])
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


# ------------------------------------------------------------ ellipsoids
def test_ellipsoid_radii_are_the_singular_values() -> None:
    puma = km.load("puma560")
    q = puma.random_q(8, seed=7)
    for axes, rows in (("trans", slice(0, 3)), ("rot", slice(3, 6)), ("all", slice(None))):
        J = puma.jacobian(q)[:, rows]
        s = np.linalg.svd(J, compute_uv=False)
        vel = km.ellipsoid(puma, q, "velocity", axes)
        force = km.ellipsoid(puma, q, "force", axes)
        assert np.allclose(vel.radii, s, rtol=1e-12)
        assert np.allclose(force.radii, 1.0 / s, rtol=1e-12)
        # directions: orthonormal and J Jᵀ u_k = σ_k² u_k
        D = vel.directions
        m = D.shape[-1]
        assert np.allclose(np.swapaxes(D, -1, -2) @ D, np.eye(m), atol=1e-12)
        JJt = J @ np.swapaxes(J, -1, -2)
        assert np.allclose(JJt @ D, D * s[:, None, :] ** 2, atol=1e-10)
        assert np.allclose(vel.center, puma.fk(q)[:, :3, 3])


def test_ellipsoid_of_a_2_joint_arm_in_3_rows_is_flat() -> None:
    arm = km.Robot.from_dh([km.Revolute(a=1.0), km.Revolute(a=1.0)])
    vel = km.ellipsoid(arm, [0.0, math.pi / 2])
    force = km.ellipsoid(arm, [0.0, math.pi / 2], "force")
    golden = (1 + math.sqrt(5)) / 2
    assert np.allclose(vel.radii, [golden, 1 / golden, 0.0], atol=1e-15)
    assert np.allclose(force.radii[:2], [1 / golden, golden]) and force.radii[2] == np.inf
    assert np.allclose(np.abs(vel.directions[:, 2]), [0, 0, 1])  # the flat axis is z
    with pytest.raises(km.KinematicaError, match="infinite radius"):
        force.surface()


def test_ellipsoid_surface_points_satisfy_the_quadric() -> None:
    puma = km.load("puma560")
    q = puma.random_q(2, seed=8)
    e = km.ellipsoid(puma, q)
    pts = e.surface(resolution=9)
    assert pts.shape == (2, 9, 9, 3)
    local = np.einsum("bji,buvj->buvi", e.directions, pts - e.center[:, None, None, :])
    assert np.allclose(((local / e.radii[:, None, None, :]) ** 2).sum(-1), 1.0, atol=1e-12)


def test_ellipsoid_bad_input() -> None:
    puma = km.load("puma560")
    with pytest.raises(km.KinematicaError, match="kind must be"):
        km.ellipsoid(puma, np.zeros(6), "torque")  # type: ignore[arg-type]
    with pytest.raises(km.KinematicaError, match="3-D"):
        km.ellipsoid(puma, np.zeros(6), axes="all").surface()


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


# ------------------------------------------------------------ drawn ellipsoids
def test_drawn_ellipsoid_points_are_the_scaled_quadric() -> None:
    pytest.importorskip("matplotlib")
    from kinematica.viz.ellipsoid import ELLIPSOID_SIZE, ellipsoid_points
    from kinematica.viz.geometry import robot_scale

    puma = km.load("puma560")
    q = np.radians([10, -30, 40, 20, 50, 0])
    pts, scale, radii = ellipsoid_points(puma, q, "force")
    e = km.ellipsoid(puma, q, "force")
    assert np.allclose(radii, e.radii)
    assert scale * radii.max() == pytest.approx(ELLIPSOID_SIZE * robot_scale(puma))
    local = (pts - e.center) @ e.directions / (e.radii * scale)
    assert np.allclose((local**2).sum(-1), 1.0, atol=1e-12)
    # a planar arm: the ellipse in its plane, J's rows of those axes
    arm = km.Robot.from_dh([km.Revolute(a=1.0), km.Revolute(a=1.0)])
    pts2, scale2, radii2 = ellipsoid_points(arm, [0.0, np.pi / 2], plane=(0, 1))
    golden = (1 + np.sqrt(5)) / 2
    assert np.allclose(radii2, [golden, 1 / golden])
    assert np.allclose(pts2[:, 2], 0.0)
    J = arm.jacobian([0.0, np.pi / 2])[:2]
    centre = arm.fk([0.0, np.pi / 2])[:2, 3]
    # points x = c + s·J u with |u| = 1: |J⁻¹ (x − c)| = s
    u = np.linalg.solve(J, (pts2[:, :2] - centre).T)
    assert np.allclose(np.linalg.norm(u, axis=0), scale2, rtol=1e-12)
