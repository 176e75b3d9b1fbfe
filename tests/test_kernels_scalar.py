"""The scalar building blocks of the kernels against the C library and by their definitions.

``sincos`` (fdlibm's scheme, vectorisable) against ``math.sin``/``math.cos`` on
millions of angles; ``block_trig`` (one flat vectorised loop over a block)
against ``sincos`` one angle at a time; ``wrap`` (no ``fmod`` one turn off)
against the definition; ``angle_between``'s division shortcut against
``atan2``; ``turn`` against Rodrigues' formula with numpy. The two constants
of this module are tested at their documented values, written as literals.
"""

from __future__ import annotations

import math

import numba
import numpy as np
import pytest

import kinematica as km
from kinematica.kernels.fk import block_trig
from kinematica.kernels.geometry import rotate, turn
from kinematica.kernels.so3 import angle_between, wrap
from kinematica.kernels.trig import sincos, sincos_reduced

#: Documented values (trig.py, so3.py).
REDUCTION_LIMIT = 1.0e6
ATAN_LINEAR = 1e-8


@numba.njit
def _sincos_all(x: np.ndarray, s: np.ndarray, c: np.ndarray) -> None:
    for i in range(x.shape[0]):
        s[i], c[i] = sincos(x[i])


@numba.njit
def _reduced_all(x: np.ndarray, s: np.ndarray, c: np.ndarray) -> None:
    for i in range(x.shape[0]):
        s[i], c[i] = sincos_reduced(x[i])


@numba.njit
def _wrap_all(x: np.ndarray, out: np.ndarray) -> None:
    for i in range(x.shape[0]):
        out[i] = wrap(x[i])


def _ulps(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """|a - b| in units of the last place of b (of the smallest normal near 0)."""
    return np.abs(a - b) / np.spacing(np.maximum(np.abs(b), np.finfo(float).tiny))


@pytest.mark.parametrize(("largest", "ulps"), [(10.0, 1.0), (REDUCTION_LIMIT, 2.0)])
def test_sincos_is_within_an_ulp_or_two_of_the_c_library(largest: float, ulps: float) -> None:
    rng = np.random.default_rng(1)
    sign = np.sign(rng.normal(size=500_000))
    x = np.concatenate(
        [
            rng.uniform(-largest, largest, 1_000_000),
            sign * 10 ** rng.uniform(-12, math.log10(largest), 500_000),
            np.arange(-6, 7) * (math.pi / 4),  # quadrant boundaries
        ]
    )
    s, c = np.empty_like(x), np.empty_like(x)
    _sincos_all(x, s, c)
    # near a zero of sin or cos the C library's own result is tiny: compare absolutely there
    for ours, ref in ((s, np.sin(x)), (c, np.cos(x))):
        err = np.where(np.abs(ref) > 1e-3, _ulps(ours, ref), np.abs(ours - ref) / np.spacing(1.0))
        assert err.max() <= ulps


def test_sincos_of_nan_and_inf_is_nan() -> None:
    x = np.array([math.nan, math.inf, -math.inf])
    s, c = np.empty(3), np.empty(3)
    _sincos_all(x, s, c)
    assert np.isnan(s).all() and np.isnan(c).all()


def test_reduction_limit_is_where_the_c_library_takes_over() -> None:
    # Beyond the limit the C library answers, bit for bit (a reduction 1000x
    # further would be inexact there: n P1 is exact only for n < 2**20).
    far = np.array([10.0, -10.0, 37.25]) * REDUCTION_LIMIT
    s, c = np.empty(3), np.empty(3)
    _sincos_all(far, s, c)
    assert np.array_equal(s, np.sin(far)) and np.array_equal(c, np.cos(far))
    # Within it, the polynomial answers: find angles where it differs from
    # the C library by an ulp, and see that sincos gives the polynomial's.
    rng = np.random.default_rng(2)
    near = rng.uniform(0.05, 0.1, 20_000) * REDUCTION_LIMIT
    rs, rc = np.empty_like(near), np.empty_like(near)
    _reduced_all(near, rs, rc)
    differs = (rs != np.sin(near)) | (rc != np.cos(near))
    assert differs.sum() > 10
    s, c = np.empty_like(near), np.empty_like(near)
    _sincos_all(near, s, c)
    assert np.array_equal(s[differs], rs[differs]) and np.array_equal(c[differs], rc[differs])


@pytest.mark.parametrize("rows", [1, 3, 8, 64])
def test_block_trig_equals_sincos_angle_by_angle(rows: int) -> None:
    robot = km.Robot.from_dh(
        [
            km.Revolute(d=0.3, alpha=math.pi / 2, offset=0.25),
            km.Prismatic(theta=0.7, alpha=-math.pi / 2),
            km.Revolute(a=0.4, offset=-1.0),
        ]
    )
    links = robot.chain.links
    rng = np.random.default_rng(rows)
    Q = rng.uniform(-7.0, 7.0, (rows + 2, 3))
    Q[0, 0] = 2.0e7  # beyond the reduction: the block takes the C library for every angle
    for b0, b1 in ((0, rows), (2, rows + 2)):
        C, S = np.empty((3, b1 - b0)), np.empty((3, b1 - b0))
        block_trig(links, Q, b0, b1, C, S)
        angles = Q[b0:b1] + np.array([0.25, 0.0, -1.0])
        s, c = np.empty(angles.size), np.empty(angles.size)
        _sincos_all(np.ascontiguousarray(angles.T).ravel(), s, c)
        for j in (0, 2):
            assert np.array_equal(C[j], c.reshape(3, -1)[j])
            assert np.array_equal(S[j], s.reshape(3, -1)[j])
        assert np.all(C[1] == math.cos(0.7)) and np.all(S[1] == math.sin(0.7))


def test_wrap_is_the_representative_in_minus_pi_pi() -> None:
    rng = np.random.default_rng(3)
    x = np.concatenate(
        [
            rng.uniform(-12.0, 12.0, 200_000),
            [math.pi, -math.pi, 3 * math.pi, -3 * math.pi, 2 * math.pi, 0.0, -0.0, 1e17],
            np.nextafter([math.pi, -math.pi, 3 * math.pi, -3 * math.pi], [9, -9, 99, -99]),
        ]
    )
    out = np.empty_like(x)
    _wrap_all(x, out)
    assert np.all((out > -math.pi) & (out <= math.pi))
    # congruent modulo 2π, to the rounding of one subtraction of 2π
    turns = np.round((x - out) / (2 * math.pi))
    small = np.abs(x) < 100.0
    assert np.all(np.abs(x - out - turns * 2 * math.pi)[small] <= 4 * np.spacing(10.0))
    inside = (x > -math.pi) & (x <= math.pi)
    assert np.array_equal(out[inside], x[inside])  # unchanged when already inside
    assert out[x == -math.pi][0] == math.pi


def test_wrap_of_nan_and_inf_is_nan() -> None:
    out = np.empty(3)
    _wrap_all(np.array([math.nan, math.inf, -math.inf]), out)
    assert np.isnan(out).all()


def _rz(theta: float) -> np.ndarray:
    T = np.eye(4)
    c, s = math.cos(theta), math.sin(theta)
    T[:2, :2] = [[c, -s], [s, c]]
    return T


@pytest.mark.parametrize("factor", [0.1, 10.0])
def test_atan_linear_is_where_the_ratio_is_the_angle(factor: float) -> None:
    theta = factor * ATAN_LINEAR
    got = angle_between(_rz(theta), np.eye(4))
    # Inside, the ratio sin/cos is θ to an ulp; outside, atan2 is. The ratio
    # there would be tan θ, θ³/3 (about 24 ulps) too large: a limit 1000x
    # larger fails here. (One 1000x smaller would only cost time: atan2 is
    # exact inside too.)
    assert abs(got - theta) <= np.spacing(theta)


def test_angle_between_is_the_rotation_angle() -> None:
    rng = np.random.default_rng(4)
    for theta in np.concatenate([rng.uniform(-math.pi, math.pi, 200), [0.0, 1e-12, 3.0]]):
        assert angle_between(_rz(theta), np.eye(4)) == pytest.approx(abs(theta), abs=1e-15)


def test_turn_is_rodrigues_and_rotate_is_turn() -> None:
    rng = np.random.default_rng(5)
    for _ in range(100):
        k = rng.normal(size=3)
        k /= np.linalg.norm(k)
        v = rng.normal(size=3)
        theta = rng.uniform(-4.0, 4.0)
        K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
        R = np.eye(3) + math.sin(theta) * K + (1 - math.cos(theta)) * K @ K
        got = np.array(turn(*k, math.cos(theta), math.sin(theta), *v))
        assert np.allclose(got, R @ v, rtol=0, atol=1e-14)
        out = np.empty(3)
        rotate(k, math.cos(theta), math.sin(theta), v, out)
        assert np.array_equal(out, got)
