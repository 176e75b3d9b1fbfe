"""Geometric subproblems (Paden-Kahan / IK-Geo) and the batched quartic solver.

Every instance is built from a known answer: pick the angles, rotate, and ask
the subproblem to find them again. Rotations come from scipy's ``Rotation``
(an independent implementation); instances without an exact solution are
built on purpose and their least-squares answers checked against a dense
search over the angle.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.typing import NDArray
from scipy.spatial.transform import Rotation

from kinematica.ik.analytic.subproblems import (
    cross,
    rotate,
    rotation_matrix,
    solve_quartic,
    solve_trig_linear,
    subproblem1,
    subproblem2,
    subproblem3,
    subproblem4,
)

FloatArray = NDArray[np.float64]
BATCHES = [(), (1,), (3, 2)]


def unit(rng: np.random.Generator, shape: tuple[int, ...]) -> FloatArray:
    v = rng.normal(size=(*shape, 3))
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def rot(k: FloatArray, theta: FloatArray, v: FloatArray) -> FloatArray:
    """Reference rotation by scipy (rotation vector k θ)."""
    rv = np.asarray(k) * np.asarray(theta)[..., None]
    shape = np.broadcast_shapes(rv.shape, np.shape(v))
    rv = np.array(np.broadcast_to(rv, shape)).reshape(-1, 3)
    vv = np.array(np.broadcast_to(v, shape)).reshape(-1, 3)
    return Rotation.from_rotvec(rv).apply(vv).reshape(shape)


def angle_diff(a: FloatArray, b: FloatArray) -> FloatArray:
    return np.abs(np.angle(np.exp(1j * (np.asarray(a) - np.asarray(b)))))


@pytest.mark.parametrize("batch", BATCHES)
def test_rotate_and_rotation_matrix_match_scipy(batch: tuple[int, ...]) -> None:
    rng = np.random.default_rng(1)
    k, v, t = unit(rng, batch), rng.normal(size=(*batch, 3)), rng.uniform(-4, 4, batch)
    expected = rot(k, t, v)
    np.testing.assert_allclose(rotate(k, t, v), expected, atol=1e-14)
    R = rotation_matrix(k, t)
    assert R.shape == (*batch, 3, 3)
    np.testing.assert_allclose((R @ v[..., None])[..., 0], expected, atol=1e-14)
    np.testing.assert_allclose(cross(k, v), np.cross(k, v), atol=1e-15)


@pytest.mark.parametrize("batch", BATCHES)
def test_subproblem1_recovers_the_angle(batch: tuple[int, ...]) -> None:
    rng = np.random.default_rng(2)
    k, p1, t = unit(rng, batch), rng.normal(size=(*batch, 3)), rng.uniform(-math.pi, math.pi, batch)
    theta = subproblem1(p1, rot(k, t, p1), k)
    assert theta.shape == batch
    assert np.all(angle_diff(theta, t) < 1e-12)


def test_subproblem1_least_squares_when_inconsistent() -> None:
    rng = np.random.default_rng(3)
    k, p1, p2 = unit(rng, ()), rng.normal(size=3), rng.normal(size=3)  # |p1| != |p2|
    theta = subproblem1(p1, p2, k)
    grid = np.linspace(-math.pi, math.pi, 200001)
    dist = np.linalg.norm(rot(np.broadcast_to(k, (len(grid), 3)), grid, p1) - p2, axis=-1)
    assert angle_diff(theta, grid[np.argmin(dist)]) < 1e-4


@pytest.mark.parametrize("batch", BATCHES)
def test_subproblem2_finds_the_constructed_pair(batch: tuple[int, ...]) -> None:
    rng = np.random.default_rng(4)
    k1, k2, p2 = unit(rng, batch), unit(rng, batch), rng.normal(size=(*batch, 3))
    t1, t2 = rng.uniform(-math.pi, math.pi, (2, *batch))
    p1 = rot(k1, -t1, rot(k2, t2, p2))  # so that R(k1, t1) p1 = R(k2, t2) p2
    th1, th2, exact = subproblem2(p1, p2, k1, k2)
    assert th1.shape == th2.shape == (*batch, 2) and exact.shape == batch
    assert exact.all()
    hit = (angle_diff(th1, t1[..., None]) < 1e-9) & (angle_diff(th2, t2[..., None]) < 1e-9)
    assert hit.any(axis=-1).all()
    for j in range(2):  # both solutions solve the equation
        lhs = rot(k1, th1[..., j], p1)
        rhs = rot(k2, th2[..., j], p2)
        np.testing.assert_allclose(lhs, rhs, atol=1e-12)


def test_subproblem2_without_solution() -> None:
    # R(k1, θ1) k1 = k1 always, and R(k2, θ2) k2 = k2: no θ makes them equal
    k1, k2 = np.array([0.0, 0.0, 1.0]), np.array([0.0, 1.0, 0.0])
    _, _, exact = subproblem2(k1, k2, k1, k2)
    assert not exact


@pytest.mark.parametrize("batch", BATCHES)
def test_subproblem3_distance(batch: tuple[int, ...]) -> None:
    rng = np.random.default_rng(5)
    k, p1, p2 = unit(rng, batch), rng.normal(size=(*batch, 3)), rng.normal(size=(*batch, 3))
    t = rng.uniform(-math.pi, math.pi, batch)
    d = np.linalg.norm(rot(k, t, p1) - p2, axis=-1)
    theta, exact = subproblem3(p1, p2, k, d)
    assert exact.all() and theta.shape == (*batch, 2)
    assert (angle_diff(theta, t[..., None]) < 1e-9).any(axis=-1).all()
    for j in range(2):
        got = np.linalg.norm(rot(k, theta[..., j], p1) - p2, axis=-1)
        np.testing.assert_allclose(got, d, atol=1e-12)


def test_subproblem3_too_far_is_least_squares() -> None:
    rng = np.random.default_rng(6)
    k, p1, p2 = unit(rng, ()), rng.normal(size=3), rng.normal(size=3)
    d = np.linalg.norm(p1) + np.linalg.norm(p2) + 1.0  # beyond any distance
    theta, exact = subproblem3(p1, p2, k, d)
    assert not exact
    grid = np.linspace(-math.pi, math.pi, 200001)
    dist = np.linalg.norm(rot(np.broadcast_to(k, (len(grid), 3)), grid, p1) - p2, axis=-1)
    assert (angle_diff(theta, grid[np.argmax(dist)]) < 1e-4).all()


@pytest.mark.parametrize("batch", BATCHES)
def test_subproblem4_projection(batch: tuple[int, ...]) -> None:
    rng = np.random.default_rng(7)
    h, k, p = rng.normal(size=(*batch, 3)), unit(rng, batch), rng.normal(size=(*batch, 3))
    t = rng.uniform(-math.pi, math.pi, batch)
    d = np.sum(h * rot(k, t, p), axis=-1)
    theta, exact = subproblem4(h, p, k, d)
    assert exact.all()
    assert (angle_diff(theta, t[..., None]) < 1e-9).any(axis=-1).all()
    for j in range(2):
        np.testing.assert_allclose(np.sum(h * rot(k, theta[..., j], p), axis=-1), d, atol=1e-12)


def test_subproblem4_out_of_range() -> None:
    h, k, p = np.array([1.0, 0, 0]), np.array([0, 0, 1.0]), np.array([1.0, 0, 0])
    _, exact = subproblem4(h, p, k, 1.5)  # hᵀ R p = cos θ never reaches 1.5
    assert not exact


def test_trig_linear_slots_tangent_and_degenerate() -> None:
    # 3 cos θ + 4 sin θ = c: two roots, one double root at c = 5, none beyond
    theta, exact = solve_trig_linear(3.0, 4.0, np.array([2.0, 5.0, 6.0]))
    assert exact.tolist() == [True, True, False]
    np.testing.assert_allclose(3 * np.cos(theta[0]) + 4 * np.sin(theta[0]), 2.0, atol=1e-14)
    assert abs(theta[0, 0] - theta[0, 1]) > 0.1
    np.testing.assert_allclose(theta[1], math.atan2(4, 3), atol=1e-7)
    theta, exact = solve_trig_linear(0.0, 0.0, np.array([0.0, 1.0]))
    assert exact.tolist() == [True, False]


def poly_from_roots(roots: NDArray[np.complex128]) -> FloatArray:
    return np.real(np.array([np.poly(r) for r in roots]))


def assert_roots_match(found: NDArray[np.complex128], expected: NDArray[np.complex128]) -> None:
    for f, e in zip(found, expected, strict=True):
        d = np.abs(f[:, None] - e[None, :])
        scale = 1.0 + np.abs(e)
        # every expected root has a found root nearby (multiple roots: sqrt-sized error)
        assert (d.min(axis=0) / scale < 1e-6).all(), (f, e)


def test_quartic_roots_known_by_construction() -> None:
    rng = np.random.default_rng(8)
    real = rng.uniform(-3, 3, (500, 4))
    pairs = rng.uniform(-3, 3, (500, 2)) + 1j * rng.uniform(0.1, 2, (500, 2))
    cases = [
        real.astype(complex),
        np.concatenate([real[:, :2], pairs[:, :1], pairs[:, :1].conj()], axis=1),
        np.concatenate([pairs, pairs.conj()], axis=1),
        np.concatenate([real[:, :1], real[:, :1], real[:, 2:]], axis=1),  # double root
        np.concatenate([real[:, :3] * 1e-3, real[:, 3:] * 1e3], axis=1),  # widely spread
    ]
    for roots in cases:
        coeffs = poly_from_roots(roots) * rng.uniform(0.5, 2, (500, 1))
        assert_roots_match(solve_quartic(coeffs), roots)


@pytest.mark.parametrize("batch", BATCHES)
def test_quartic_batch_shapes(batch: tuple[int, ...]) -> None:
    rng = np.random.default_rng(9)
    coeffs = rng.normal(size=(*batch, 5))
    roots = solve_quartic(coeffs)
    assert roots.shape == (*batch, 4)
    flat = coeffs.reshape(-1, 5)
    assert_roots_match(roots.reshape(-1, 4), np.array([np.roots(c) for c in flat]))
