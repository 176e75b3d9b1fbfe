"""The error model (calibration/model.py) and its analytic Jacobian (residuals.py)."""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
from support.calibration import NOISE, perturbed
from support.helpers import assert_transform_close

import kinematica as km
from kinematica.calibration.model import (
    SMALL_ANGLE,
    ErrorModel,
    inv_left_coefficient,
    log_rotation,
)
from kinematica.calibration.residuals import Measurements, jacobian, residuals
from kinematica.spatial import matrix_from_rotvec


@pytest.mark.parametrize("name", ["puma560", "ur5", "stanford", "kr6", "planar-prr"])
def test_nominal_model_is_the_robot(name):
    robot = km.load(name)
    model = ErrorModel.of(robot.chain)
    q = robot.random_q(7, seed=1)
    assert_transform_close(model.fk(np.zeros(model.size), q), robot.fk(q), atol=1e-13)


@pytest.mark.parametrize("convention", ["standard", "modified"])
def test_link_components_are_the_dh_values_they_are_named_after(convention):
    # d, theta, a, alpha of a link moved alone are exactly that DH value changed
    robot = km.load("puma560").to_convention(convention)
    model = ErrorModel.of(robot.chain)
    q = robot.random_q(5, seed=2)
    joint = 3  # 1-based
    for component, eps in (("d", 2e-3), ("theta", 1e-2), ("a", -3e-3), ("alpha", 2e-2)):
        delta = np.zeros(model.size)
        delta[model.names.index(f"{component}{joint}")] = eps
        rows = list(robot.links)
        # Craig's a_i, alpha_i sit in row i + 1
        k = joint if convention == "modified" and component in ("a", "alpha") else joint - 1
        link = rows[k]
        field = {"theta": "offset"}.get(component, component)
        rows[k] = type(link)(**{**link.__dict__, field: getattr(link, field) + eps})
        moved = km.Robot.from_dh(rows, convention=convention, base=robot.base, tool=robot.tool)
        assert_transform_close(model.fk(delta, q), moved.fk(q), atol=1e-13)


def test_base_and_tool_components_move_the_ends():
    robot = km.load("ur5")
    model = ErrorModel.of(robot.chain)
    q = robot.random_q(3, seed=3)
    delta = np.zeros(model.size)
    delta[model.names.index("base_z")] = 0.01
    delta[model.names.index("tool_rx")] = 0.2
    T = robot.fk(q)
    expected = km.transl(0, 0, 0.01) @ T @ km.make_transform(km.rotx(0.2), np.zeros(3))
    assert_transform_close(model.fk(delta, q), expected, atol=1e-13)


def _data(kind, seed=4):
    robot = km.load("puma560")
    true = perturbed(robot, seed)
    q = robot.random_q(6, seed=seed)
    T = true.fk(q)
    measured = T if kind == "pose" else T[:, :3, 3]
    return robot, Measurements(q, measured, kind, NOISE)


@pytest.mark.parametrize("kind", ["pose", "position"])
def test_analytic_jacobian_equals_finite_differences(kind):
    # away from the solution (the arm as it is differs from the nominal: rotation residuals
    # of 0.1 degree) and at a nonzero delta, so that every term of the Jacobian counts
    robot, data = _data(kind)
    model = ErrorModel.of(robot.chain)
    rng = np.random.default_rng(5)
    delta = rng.uniform(-1e-2, 1e-2, model.size)
    r, J = jacobian(model, delta, data)
    np.testing.assert_allclose(r, residuals(model, delta, data), rtol=0, atol=1e-9)
    h = 1e-7
    fd = np.empty_like(J)
    for k in range(model.size):
        e = np.zeros(model.size)
        e[k] = h
        fd[:, k] = (residuals(model, delta + e, data) - residuals(model, delta - e, data)) / (2 * h)
    scale = np.abs(J).max()
    assert np.abs(J - fd).max() < 1e-6 * scale


def test_jacobian_columns_subset():
    robot, data = _data("pose")
    model = ErrorModel.of(robot.chain)
    cols = np.array([0, 7, 20, model.size - 1])
    _, J = jacobian(model, np.zeros(model.size), data)
    _, Js = jacobian(model, np.zeros(model.size), data, cols)
    np.testing.assert_array_equal(Js, J[:, cols])


@pytest.mark.parametrize("theta", [0.0, 1e-9, 0.5 * SMALL_ANGLE, 2 * SMALL_ANGLE, 0.3, 2.0])
def test_log_rotation_inverts_the_exponential(theta):
    axis = np.array([0.3, -0.5, 0.81])
    v = theta * axis / np.linalg.norm(axis)
    np.testing.assert_allclose(log_rotation(matrix_from_rotvec(v)), v, rtol=0, atol=2e-15)


def _reference_coefficient(theta):
    with mpmath.workdps(50):
        t = mpmath.mpf(theta)
        return float(1 / t**2 - (1 + mpmath.cos(t)) / (2 * t * mpmath.sin(t)))


@pytest.mark.parametrize("factor", [0.5, 0.99, 1.01, 2.0, 300.0])
def test_inverse_left_jacobian_coefficient_either_side_of_small_angle(factor):
    # series below SMALL_ANGLE, closed form above: both within 1e-9 of the exact value.
    # SMALL_ANGLE 1000x smaller: the closed form's cancellation (1/θ² - ...) errs by 1e-5
    # there; 1000x larger (10 rad): the series is far off at 10 rad.
    theta = factor * SMALL_ANGLE
    got = float(inv_left_coefficient(np.array(theta)))
    assert got == pytest.approx(_reference_coefficient(theta), rel=1e-9)


def test_inverse_left_jacobian_is_the_derivative_of_the_log():
    rng = np.random.default_rng(6)
    phi = rng.normal(size=3) * 0.7
    w = rng.normal(size=3)
    h = 1e-6
    R = matrix_from_rotvec(phi)
    fd = (
        log_rotation(matrix_from_rotvec(h * w) @ R) - log_rotation(matrix_from_rotvec(-h * w) @ R)
    ) / (2 * h)
    from kinematica.calibration.model import inv_left_jacobian

    np.testing.assert_allclose(inv_left_jacobian(phi) @ w, fd, atol=1e-8)
    assert math.isclose(float(np.linalg.norm(phi)), np.linalg.norm(log_rotation(R)), rel_tol=1e-14)
