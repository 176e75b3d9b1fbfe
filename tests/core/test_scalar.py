"""The core's scalar building blocks against the C library and by their definitions.

``sincos`` (fdlibm's scheme, vectorisable) against ``math.sin``/``math.cos`` on
millions of angles; ``sincos_block`` (the vectorised loop every FK and check
runs) against ``sincos`` one angle at a time; ``wrap`` (no ``fmod`` one turn
off) against the definition; ``angle_between``'s division shortcut against
``atan2``; ``rotate_about`` against Rodrigues' formula with numpy. The two
constants are tested at their documented values, written as literals.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from kinematica._core_testing import internals

import kinematica as km

#: Documented values (trig.hpp, so3.hpp).
REDUCTION_LIMIT = 1.0e6
ATAN_LINEAR = 1e-8


def test_documented_constants() -> None:
    assert internals.REDUCTION_LIMIT == REDUCTION_LIMIT
    assert internals.ATAN_LINEAR == ATAN_LINEAR


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
    s, c = internals.sincos_block(x)
    # near a zero of sin or cos the C library's own result is tiny: compare absolutely there
    for ours, ref in ((s, np.sin(x)), (c, np.cos(x))):
        err = np.where(np.abs(ref) > 1e-3, _ulps(ours, ref), np.abs(ours - ref) / np.spacing(1.0))
        assert err.max() <= ulps


def test_block_equals_one_angle_at_a_time() -> None:
    # The vectorised loop and the scalar function are the same arithmetic, bit for bit.
    rng = np.random.default_rng(6)
    x = np.concatenate([rng.uniform(-7.0, 7.0, 3000), [2.0e7, -3.5e9, math.nan, math.inf]])
    s, c = internals.sincos_block(x)
    one = np.array([internals.sincos(v) for v in x])
    assert np.array_equal(s, one[:, 0], equal_nan=True)
    assert np.array_equal(c, one[:, 1], equal_nan=True)


def test_sincos_of_nan_and_inf_is_nan() -> None:
    for v in (math.nan, math.inf, -math.inf):
        assert all(math.isnan(t) for t in internals.sincos(v))
        assert all(math.isnan(t) for t in internals.sincos_reduced(v))


def test_reduction_limit_is_where_the_c_library_takes_over() -> None:
    # Beyond the limit the C library answers, bit for bit (a reduction 1000x
    # further would be inexact there: n P1 is exact only for n < 2**20).
    far = np.array([10.0, -10.0, 37.25]) * REDUCTION_LIMIT
    s, c = internals.sincos_block(far)
    assert np.array_equal(s, np.sin(far)) and np.array_equal(c, np.cos(far))
    # Within it, the polynomial answers: find angles where it differs from
    # the C library by an ulp, and see that sincos gives the polynomial's.
    rng = np.random.default_rng(2)
    near = rng.uniform(0.05, 0.1, 20_000) * REDUCTION_LIMIT
    reduced = np.array([internals.sincos_reduced(v) for v in near])
    differs = (reduced[:, 0] != np.sin(near)) | (reduced[:, 1] != np.cos(near))
    assert differs.sum() > 10
    s, c = internals.sincos_block(near)
    assert np.array_equal(s[differs], reduced[differs, 0])
    assert np.array_equal(c[differs], reduced[differs, 1])


@pytest.mark.parametrize("rows", [1, 3, 8, 300])
def test_fk_of_a_batch_equals_single_calls_beyond_the_reduction(rows: int) -> None:
    # A batch's trigonometry is one pass over all its angles (joint offsets added),
    # with angles beyond the reduction taken by the C library: each row as alone.
    robot = km.Robot.from_dh(
        [
            km.Revolute(d=0.3, alpha=math.pi / 2, offset=0.25),
            km.Prismatic(theta=0.7, alpha=-math.pi / 2),
            km.Revolute(a=0.4, offset=-1.0),
        ],
        convention="standard",
    )
    rng = np.random.default_rng(rows)
    Q = rng.uniform(-7.0, 7.0, (rows, 3))
    Q[0, 0] = 2.0e7
    T = robot.fk(Q)
    for i in range(rows):
        assert np.array_equal(T[i], robot.fk(Q[i]))


@pytest.mark.parametrize("name", ["puma560", "panda", "stanford"])
def test_batches_are_the_same_with_one_worker_or_several(name: str) -> None:
    # Blocks go to threads in any order; each row is computed by the same code either
    # way, so the results are equal to the last bit (several blocks of each kind).
    robot = km.load(name)
    rng = np.random.default_rng(11)
    lo, hi = np.maximum(robot.qlim[:, 0], -3.0), np.minimum(robot.qlim[:, 1], 3.0)
    Q = rng.uniform(lo, hi, (1000, robot.dof))
    for w in (2, 3):
        assert np.array_equal(robot.fk(Q, workers=1), robot.fk(Q, workers=w))
        assert np.array_equal(
            robot.fk(Q, all_frames=True, workers=1), robot.fk(Q, all_frames=True, workers=w)
        )
        assert np.array_equal(robot.jacobian(Q, workers=1), robot.jacobian(Q, workers=w))
    T = robot.fk(Q[:300])
    one, many = robot.ik(T, workers=1), robot.ik(T, workers=2)
    assert np.array_equal(one.raw.q, many.raw.q, equal_nan=True)
    assert np.array_equal(one.raw.status, many.raw.status)


def test_wrap_is_the_representative_in_minus_pi_pi() -> None:
    rng = np.random.default_rng(3)
    x = np.concatenate(
        [
            rng.uniform(-12.0, 12.0, 200_000),
            [math.pi, -math.pi, 3 * math.pi, -3 * math.pi, 2 * math.pi, 0.0, -0.0, 1e17],
            np.nextafter([math.pi, -math.pi, 3 * math.pi, -3 * math.pi], [9, -9, 99, -99]),
        ]
    )
    out = km._core.wrap(x)
    assert np.all((out > -math.pi) & (out <= math.pi))
    # congruent modulo 2π, to the rounding of one subtraction of 2π
    turns = np.round((x - out) / (2 * math.pi))
    small = np.abs(x) < 100.0
    assert np.all(np.abs(x - out - turns * 2 * math.pi)[small] <= 4 * np.spacing(10.0))
    inside = (x > -math.pi) & (x <= math.pi)
    assert np.array_equal(out[inside], x[inside])  # unchanged when already inside
    assert out[x == -math.pi][0] == math.pi
    assert np.array_equal(out[:500], [internals.wrap(v) for v in x[:500]])


def test_wrap_of_nan_and_inf_is_nan() -> None:
    assert np.isnan(km._core.wrap(np.array([math.nan, math.inf, -math.inf]))).all()


def test_floor_mod_is_pythons_modulo() -> None:
    rng = np.random.default_rng(7)
    for a, b in zip(rng.normal(0, 20, 500), rng.choice([2 * math.pi, -3.0, 0.7], 500), strict=True):
        assert internals.floor_mod(a, b) == a % b
    assert math.copysign(1.0, internals.floor_mod(-0.0, 2.0)) == 1.0


def _rz(theta: float) -> np.ndarray:
    T = np.eye(4)
    c, s = math.cos(theta), math.sin(theta)
    T[:2, :2] = [[c, -s], [s, c]]
    return T


@pytest.mark.parametrize("factor", [0.1, 10.0])
def test_atan_linear_is_where_the_ratio_is_the_angle(factor: float) -> None:
    theta = factor * ATAN_LINEAR
    got = internals.angle_between(_rz(theta), np.eye(4))
    # Inside, the ratio sin/cos is θ to an ulp; outside, atan2 is. The ratio
    # there would be tan θ, θ³/3 (about 24 ulps) too large: a limit 1000x
    # larger fails here. (One 1000x smaller would only cost time: atan2 is
    # exact inside too.)
    assert abs(got - theta) <= np.spacing(theta)


def test_angle_between_is_the_rotation_angle() -> None:
    rng = np.random.default_rng(4)
    for theta in np.concatenate([rng.uniform(-math.pi, math.pi, 200), [0.0, 1e-12, 3.0]]):
        got = internals.angle_between(_rz(theta), np.eye(4))
        assert got == pytest.approx(abs(theta), abs=1e-15)


def test_rotate_about_is_rodrigues() -> None:
    rng = np.random.default_rng(5)
    for _ in range(100):
        k = rng.normal(size=3)
        k /= np.linalg.norm(k)
        v = rng.normal(size=3)
        theta = rng.uniform(-4.0, 4.0)
        K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
        R = np.eye(3) + math.sin(theta) * K + (1 - math.cos(theta)) * K @ K
        got = internals.rotate_about(k, math.cos(theta), math.sin(theta), v)
        assert np.allclose(got, R @ v, rtol=0, atol=1e-14)
