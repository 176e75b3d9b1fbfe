"""The core's geometry the closed forms are built of: rotations, SP1, ``a cos + b sin = c``,
and the quartic's roots.

Every instance is built from a known answer (scipy's ``Rotation`` for the
rotations, polynomials from chosen roots), or checked against a dense search
where no exact answer exists.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from kinematica._core_testing import internals
from numpy.typing import NDArray
from scipy.spatial.transform import Rotation

FloatArray = NDArray[np.float64]

TRIG_TOL = internals.TRIG_TOL
subproblem1 = internals.subproblem1


def trig_linear(a: float, b: float, c: float, out: FloatArray) -> int:
    code, out[0], out[1] = internals.trig_linear(a, b, c)
    return int(code)


def quartic_roots(k: FloatArray, roots: NDArray[np.complex128]) -> None:
    roots[:] = internals.quartic_roots(np.asarray(k, dtype=float).tolist())


def unit(rng: np.random.Generator) -> FloatArray:
    v = rng.normal(size=3)
    return v / np.linalg.norm(v)


def angle_diff(a: float, b: float) -> float:
    return abs(math.remainder(a - b, 2 * math.pi))


def test_rotate_matches_scipy() -> None:
    rng = np.random.default_rng(61)
    for _ in range(200):
        k, v, t = unit(rng), rng.normal(size=3), rng.uniform(-4, 4)
        out = internals.rotate_about(k, math.cos(t), math.sin(t), v)
        np.testing.assert_allclose(out, Rotation.from_rotvec(k * t).apply(v), atol=1e-14)


def test_subproblem1_recovers_the_angle_and_is_least_squares_otherwise() -> None:
    rng = np.random.default_rng(62)
    for _ in range(200):
        k, p1, t = unit(rng), rng.normal(size=3), rng.uniform(-math.pi, math.pi)
        p2 = Rotation.from_rotvec(k * t).apply(p1)
        assert angle_diff(subproblem1(p1, p2, k), t) < 1e-12
    k, p1, p2 = unit(rng), rng.normal(size=3), rng.normal(size=3)  # |p1| != |p2|
    grid = np.linspace(-math.pi, math.pi, 200001)
    dist = np.linalg.norm(Rotation.from_rotvec(np.outer(grid, k)).apply(p1) - p2, axis=-1)
    assert angle_diff(subproblem1(p1, p2, k), grid[np.argmin(dist)]) < 1e-4
    z = np.array([0.0, 0.0, 1.0])
    assert math.isfinite(subproblem1(2.0 * z, p2, z))  # p1 on the axis: any angle will do


def test_trig_linear_two_roots_a_double_root_and_none() -> None:
    out = np.empty(2)
    assert trig_linear(3.0, 4.0, 2.0, out) == 1
    for t in out:
        assert 3 * math.cos(t) + 4 * math.sin(t) == pytest.approx(2.0, abs=1e-14)
    assert abs(out[0] - out[1]) > 0.1
    assert trig_linear(3.0, 4.0, 5.0, out) == 1  # touching: one double root
    assert out[0] == pytest.approx(math.atan2(4, 3), abs=1e-7) and out[0] == out[1]
    assert trig_linear(3.0, 4.0, 6.0, out) == 0
    assert trig_linear(0.0, 0.0, 1.0, out) == -1


@pytest.mark.parametrize(("factor", "exact"), [(0.5, 1), (2.0, 0)])
def test_trig_tol(factor: float, exact: int) -> None:
    """|c| above hypot(a, b) by up to TRIG_TOL (relative) is a double root."""
    r = 5.0
    c = r * math.sqrt(1.0 + 2.0 * factor * TRIG_TOL)  # r² - c² = -2 factor TRIG_TOL r²
    assert trig_linear(3.0, 4.0, c, np.empty(2)) == exact


def assert_roots(found: NDArray[np.complex128], expected: FloatArray, tol: float) -> None:
    d = np.abs(found[:, None] - expected[None, :])
    assert (d.min(axis=0) / (1.0 + np.abs(expected)) < tol).all(), (found, expected)


def test_quartic_roots_known_by_construction() -> None:
    rng = np.random.default_rng(63)
    roots = np.empty(4, dtype=np.complex128)
    for case in range(5):
        for _ in range(200):
            real = rng.uniform(-3, 3, 4)
            pair = complex(rng.uniform(-3, 3), rng.uniform(0.1, 2))
            expected = [
                real.astype(complex),
                np.array([real[0], real[1], pair, pair.conjugate()]),
                np.array([pair, pair.conjugate(), pair * 0.5 + 1, (pair * 0.5 + 1).conjugate()]),
                np.array([real[0], real[0], real[2], real[3]], dtype=complex),  # double root
                np.concatenate([real[:3] * 1e-3, real[3:] * 1e3]).astype(complex),  # spread
            ][case]
            k = np.real(np.poly(expected)) * rng.uniform(0.5, 2.0)
            quartic_roots(k, roots)
            assert_roots(roots, expected, 1e-6 if case == 3 else 1e-9)


def test_quartic_roots_of_non_finite_coefficients_are_nan() -> None:
    roots = np.empty(4, dtype=np.complex128)
    quartic_roots(np.array([1.0, np.inf, 0.0, 0.0, 1.0]), roots)
    assert np.isnan(roots).all()
