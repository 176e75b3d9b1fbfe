"""Euler angles: all 24 sequence forms against scipy, batches, gimbal lock, bad input."""

from __future__ import annotations

import re
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose
from scipy.spatial.transform import Rotation

from kinematica.errors import DimensionError, KinematicaError
from kinematica.spatial import (
    GIMBAL_LOCK_TOL,
    EulerSequenceError,
    euler_from_matrix,
    gimbal_locked,
    matrix_from_euler,
)

PROPER = ["XYX", "XZX", "YXY", "YZY", "ZXZ", "ZYZ"]
TAIT_BRYAN = ["XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX"]
INTRINSIC = PROPER + TAIT_BRYAN
SEQUENCES = INTRINSIC + [s.lower() for s in INTRINSIC]  # all 24 forms
BATCHES = [(), (1,), (3, 2)]
ATOL = 1e-12


def is_proper(seq: str) -> bool:
    return seq[0].lower() == seq[2].lower()


def angle_gap(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """|a − b| modulo 2π: ±π are the same angle (scipy returns −π, we return +π)."""
    return np.abs(np.angle(np.exp(1j * (np.asarray(a) - np.asarray(b)))))


def scipy_euler(R: np.ndarray, seq: str) -> np.ndarray:
    """scipy's angles, its gimbal-lock warning silenced (we test the values)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        return np.asarray(Rotation.from_matrix(R).as_euler(seq))


def random_angles(rng: np.random.Generator, n: int) -> np.ndarray:
    return rng.uniform(-2.0 * np.pi, 2.0 * np.pi, size=(n, 3))


def locked_angles(seq: str, offset: float, rng: np.random.Generator, n: int) -> np.ndarray:
    """Angles whose middle one is ``offset`` away from each singular value."""
    angles = rng.uniform(-np.pi, np.pi, size=(2 * n, 3))
    if is_proper(seq):
        middles = [0.0 + offset, np.pi - offset]
    else:
        middles = [np.pi / 2 - offset, -np.pi / 2 + offset]
    angles[:n, 1], angles[n:, 1] = middles
    return angles


@pytest.fixture(scope="module")
def rotations() -> Rotation:
    return Rotation.from_quat(np.random.default_rng(7).normal(size=(300, 4)))


# --- against scipy ------------------------------------------------------------------


@pytest.mark.parametrize("seq", SEQUENCES)
def test_matrix_from_euler_matches_scipy(seq: str) -> None:
    angles = random_angles(np.random.default_rng(1), 300)
    expected = Rotation.from_euler(seq, angles).as_matrix()
    assert_allclose(matrix_from_euler(angles, seq), expected, rtol=0, atol=ATOL)


@pytest.mark.parametrize("seq", SEQUENCES)
def test_euler_from_matrix_matches_scipy(seq: str, rotations: Rotation) -> None:
    angles = euler_from_matrix(rotations.as_matrix(), seq)
    assert angle_gap(angles, rotations.as_euler(seq)).max() < ATOL


@pytest.mark.parametrize("seq", SEQUENCES)
def test_ranges(seq: str, rotations: Rotation) -> None:
    angles = euler_from_matrix(rotations.as_matrix(), seq)
    outer = angles[:, [0, 2]]
    assert np.all((outer > -np.pi) & (outer <= np.pi))
    low, high = (0.0, np.pi) if is_proper(seq) else (-np.pi / 2, np.pi / 2)
    assert np.all((angles[:, 1] >= low) & (angles[:, 1] <= high))


@pytest.mark.parametrize("seq", SEQUENCES)
def test_round_trips(seq: str, rotations: Rotation) -> None:
    R = rotations.as_matrix()
    assert_allclose(matrix_from_euler(euler_from_matrix(R, seq), seq), R, rtol=0, atol=ATOL)
    angles = euler_from_matrix(R, seq)  # in range and away from the lock: a unique triple
    assert_allclose(euler_from_matrix(matrix_from_euler(angles, seq), seq), angles, atol=ATOL)


@pytest.mark.parametrize("seq", SEQUENCES)
def test_degrees(seq: str, rotations: Rotation) -> None:
    R = rotations.as_matrix()[:20]
    deg = euler_from_matrix(R, seq, degrees=True)
    assert angle_gap(np.deg2rad(deg), euler_from_matrix(R, seq)).max() < ATOL
    scipy_deg = rotations[:20].as_euler(seq, degrees=True)
    assert angle_gap(np.deg2rad(deg), np.deg2rad(scipy_deg)).max() < ATOL
    assert_allclose(matrix_from_euler(deg, seq, degrees=True), R, rtol=0, atol=ATOL)


def test_default_sequence_is_intrinsic_zyz() -> None:
    a, b, c = 0.3, 1.1, -2.0
    R = matrix_from_euler([a, b, c])
    expected = Rotation.from_euler("ZYZ", [a, b, c]).as_matrix()
    assert_allclose(R, expected, rtol=0, atol=ATOL)
    assert_allclose(euler_from_matrix(R), [a, b, c], atol=ATOL)


def test_intrinsic_is_reversed_extrinsic() -> None:
    angles = np.array([0.4, -0.7, 2.5])
    assert_allclose(
        matrix_from_euler(angles, "XYZ"),
        matrix_from_euler(angles[::-1], "zyx"),
        rtol=0,
        atol=ATOL,
    )


# --- batch shapes -------------------------------------------------------------------


@pytest.mark.parametrize("batch", BATCHES)
@pytest.mark.parametrize("seq", ["ZYZ", "xyz", "YXY", "zxy"])
def test_batch_shapes_match_loop(seq: str, batch: tuple[int, ...]) -> None:
    rng = np.random.default_rng(3)
    angles = rng.uniform(-np.pi, np.pi, size=(*batch, 3))
    R = matrix_from_euler(angles, seq)
    assert R.shape == (*batch, 3, 3)
    back = euler_from_matrix(R, seq)
    locked = gimbal_locked(R, seq)
    assert back.shape == (*batch, 3)
    assert locked.shape == batch
    for index in np.ndindex(*batch):
        assert_allclose(R[index], matrix_from_euler(angles[index], seq), rtol=0, atol=0)
        assert_allclose(back[index], euler_from_matrix(R[index], seq), rtol=0, atol=0)
        assert locked[index] == gimbal_locked(R[index], seq)


def test_batch_includes_locked_and_regular_rows() -> None:
    angles = np.array([[0.5, 0.0, 0.25], [0.5, 1.0, 0.25]])
    R = matrix_from_euler(angles, "ZYZ")
    assert gimbal_locked(R, "ZYZ").tolist() == [True, False]
    assert_allclose(euler_from_matrix(R, "ZYZ"), [[0.75, 0.0, 0.0], [0.5, 1.0, 0.25]], atol=ATOL)


# --- gimbal lock --------------------------------------------------------------------


@pytest.mark.parametrize("seq", SEQUENCES)
def test_gimbal_lock_exact(seq: str) -> None:
    R = matrix_from_euler(locked_angles(seq, 0.0, np.random.default_rng(4), 25), seq)
    angles = euler_from_matrix(R, seq)
    assert np.isfinite(angles).all()
    assert gimbal_locked(R, seq).all()
    assert np.all(angles[:, 2] == 0.0)  # scipy's choice: the third angle is zero
    assert_allclose(matrix_from_euler(angles, seq), R, rtol=0, atol=ATOL)
    assert angle_gap(angles, scipy_euler(R, seq)).max() < ATOL


@pytest.mark.parametrize("offset", [1e-12, 1e-9, -1e-9])
@pytest.mark.parametrize("seq", SEQUENCES)
def test_gimbal_lock_nearby(seq: str, offset: float) -> None:
    R = matrix_from_euler(locked_angles(seq, offset, np.random.default_rng(5), 25), seq)
    angles = euler_from_matrix(R, seq)
    assert np.isfinite(angles).all()
    assert gimbal_locked(R, seq).all()
    assert angle_gap(angles, scipy_euler(R, seq)).max() < ATOL
    # With the third angle fixed at 0, the middle angle's distance δ from the
    # lock can no longer be absorbed: R is reproduced to about 2δ, not 1e-12.
    assert_allclose(matrix_from_euler(angles, seq), R, rtol=0, atol=ATOL + 2 * abs(offset))


@pytest.mark.parametrize("seq", SEQUENCES)
def test_not_locked_just_outside_the_band(seq: str) -> None:
    R = matrix_from_euler(
        locked_angles(seq, 10 * GIMBAL_LOCK_TOL, np.random.default_rng(6), 5), seq
    )
    assert not gimbal_locked(R, seq).any()
    assert_allclose(matrix_from_euler(euler_from_matrix(R, seq), seq), R, rtol=0, atol=ATOL)


def test_extrinsic_lock_sets_the_last_applied_angle_to_zero() -> None:
    # "xyz" at b = π/2: R = Rz(c) Ry(π/2) Rx(a) depends on a − c only.
    R = matrix_from_euler([0.9, np.pi / 2, 0.3], "xyz")
    assert_allclose(euler_from_matrix(R, "xyz"), [0.6, np.pi / 2, 0.0], atol=ATOL)
    # "XYZ" at b = π/2: R = Rx(a) Ry(π/2) Rz(c) depends on a + c only.
    R = matrix_from_euler([0.9, np.pi / 2, 0.3], "XYZ")
    assert_allclose(euler_from_matrix(R, "XYZ"), [1.2, np.pi / 2, 0.0], atol=ATOL)


def test_no_negative_zero() -> None:
    R = matrix_from_euler([0.4, -np.pi / 2, 0.0], "zyx")  # scipy gives third = -0.0 here
    assert not np.signbit(euler_from_matrix(R, "zyx")[2])


@settings(max_examples=60, deadline=None, database=None)
@given(
    seq=st.sampled_from(SEQUENCES),
    angles=st.lists(
        st.floats(-4.0, 4.0, allow_nan=False, allow_infinity=False), min_size=3, max_size=3
    ),
)
def test_round_trip_property(seq: str, angles: list[float]) -> None:
    R = matrix_from_euler(angles, seq)
    back = euler_from_matrix(R, seq)
    assert np.isfinite(back).all()
    atol = 4 * GIMBAL_LOCK_TOL if gimbal_locked(R, seq) else ATOL
    assert_allclose(matrix_from_euler(back, seq), R, rtol=0, atol=atol)


# --- bad input ----------------------------------------------------------------------


@pytest.mark.parametrize("seq", ["XyZ", "zYz", "XXY", "xyy", "XY", "XYZX", "ABC", "", "x y"])
def test_bad_sequence(seq: str) -> None:
    with pytest.raises(EulerSequenceError, match=r"upper case .*lower case"):
        matrix_from_euler([0.0, 0.0, 0.0], seq)
    with pytest.raises(EulerSequenceError, match=re.escape(repr(seq))):
        euler_from_matrix(np.eye(3), seq)
    with pytest.raises(EulerSequenceError):
        gimbal_locked(np.eye(3), seq)


def test_sequence_error_is_a_kinematica_value_error() -> None:
    assert issubclass(EulerSequenceError, KinematicaError)
    assert issubclass(EulerSequenceError, ValueError)


def test_bad_shapes_and_values() -> None:
    with pytest.raises(DimensionError, match=r"angles must have shape \(\.\.\., 3\), got \(2,\)"):
        matrix_from_euler([0.0, 1.0])
    with pytest.raises(DimensionError, match=r"R must have shape \(\.\.\., 3, 3\), got \(3, 4\)"):
        euler_from_matrix(np.zeros((3, 4)))
    angles = np.zeros((4, 3))
    angles[2, 1] = np.nan
    with pytest.raises(DimensionError, match=r"angles\[2\] contains NaN or inf"):
        matrix_from_euler(angles)
    R = np.tile(np.eye(3), (2, 1, 1))
    R[1, 0, 0] = np.inf
    with pytest.raises(DimensionError, match=r"R\[1\] contains NaN or inf"):
        euler_from_matrix(R)
    with pytest.raises(DimensionError, match="array of numbers"):
        matrix_from_euler(["a", "b", "c"])


@pytest.mark.parametrize(("delta", "locked"), [(1e-8, True), (2e-6, False)])
def test_gimbal_lock_tol_is_1e_7(delta: float, locked: bool) -> None:
    # ZYZ: the middle angle delta from 0 is in the lock band (1e-7) or not.
    R = matrix_from_euler([0.3, delta, -0.2], "ZYZ")
    assert bool(gimbal_locked(R, "ZYZ")) is locked
    angles = euler_from_matrix(R, "ZYZ")
    assert bool(angles[2] == 0.0) == locked  # the lock sets the third angle to 0
