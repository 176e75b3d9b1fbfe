"""Geometric subproblems (Paden-Kahan / IK-Geo) and the batched quartic solver (numpy).

What the numpy solvers still being ported use; the kernel versions are
tested in ``test_kernels_geometry.py``.

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
    rotation_matrix,
    solve_quartic,
    subproblem1,
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
def test_rotation_matrix_matches_scipy(batch: tuple[int, ...]) -> None:
    rng = np.random.default_rng(1)
    k, v, t = unit(rng, batch), rng.normal(size=(*batch, 3)), rng.uniform(-4, 4, batch)
    expected = rot(k, t, v)
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
