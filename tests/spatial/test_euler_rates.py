"""Euler-rate matrix E (ω = E · angle rates) against finite differences of R(angles)."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

import kinematica as km
from kinematica.spatial import GIMBAL_LOCK_TOL, euler_rate_matrix, euler_rate_singular

PROPER = ["".join(s) for s in itertools.product("xyz", repeat=3) if s[0] == s[2] and s[0] != s[1]]
TAIT = ["".join(s) for s in itertools.permutations("xyz")]
ALL_SEQ = [s.upper() for s in PROPER + TAIT] + PROPER + TAIT


def omega_fd(angles: np.ndarray, rates: np.ndarray, seq: str, h: float = 1e-6) -> np.ndarray:
    """Angular velocity (fixed frame) from a central difference of R: [ω]× = Ṙ Rᵀ."""
    Rp = km.matrix_from_euler(angles + h * rates, seq)
    Rm = km.matrix_from_euler(angles - h * rates, seq)
    W = (Rp - Rm) / (2 * h) @ km.matrix_from_euler(angles, seq).T
    return np.array([W[2, 1] - W[1, 2], W[0, 2] - W[2, 0], W[1, 0] - W[0, 1]]) / 2


def test_twenty_four_sequences() -> None:
    assert len(set(ALL_SEQ)) == 24


@pytest.mark.parametrize("seq", ALL_SEQ)
def test_rate_matrix_maps_angle_rates_to_angular_velocity(seq: str) -> None:
    rng = np.random.default_rng(abs(hash(seq)) % 2**32)
    for _ in range(5):
        a = rng.uniform(-np.pi, np.pi, 3)
        a[1] = rng.uniform(0.2, 2.9) if seq[0].lower() == seq[2].lower() else rng.uniform(-1.4, 1.4)
        rates = rng.normal(size=3)
        assert np.allclose(euler_rate_matrix(a, seq) @ rates, omega_fd(a, rates, seq), atol=1e-8)


@pytest.mark.parametrize("seq", ALL_SEQ)
def test_determinant_is_sine_or_cosine_of_the_middle_angle(seq: str) -> None:
    b = np.linspace(-3.0, 3.0, 13)
    angles = np.stack([np.full_like(b, 0.4), b, np.full_like(b, -1.1)], axis=-1)
    det = np.linalg.det(euler_rate_matrix(angles, seq))
    expected = np.sin(b) if seq[0].lower() == seq[2].lower() else np.cos(b)
    assert np.allclose(np.abs(det), np.abs(expected), atol=1e-12)


def test_degrees_and_batch_shapes() -> None:
    a = np.array([10.0, 30.0, -20.0])
    assert np.allclose(euler_rate_matrix(a, "ZYZ", degrees=True), euler_rate_matrix(np.radians(a)))
    for batch in [(), (1,), (3, 2)]:
        angles = np.random.default_rng(0).uniform(-1, 1, (*batch, 3))
        assert euler_rate_matrix(angles, "xyz").shape == (*batch, 3, 3)
        assert euler_rate_singular(angles, "xyz").shape == batch


@pytest.mark.parametrize(("seq", "lock"), [("ZYZ", 0.0), ("ZYZ", np.pi), ("XYZ", np.pi / 2)])
def test_singular_band_is_the_gimbal_lock_band(seq: str, lock: float) -> None:
    sign = -1.0 if lock > 0 else 1.0  # stay inside the angle's range
    inside = np.array([0.3, lock + sign * 0.5 * GIMBAL_LOCK_TOL, 0.2])
    outside = np.array([0.3, lock + sign * 2.0 * GIMBAL_LOCK_TOL, 0.2])
    assert euler_rate_singular(inside, seq)
    assert not euler_rate_singular(outside, seq)
    # the same band as km.gimbal_locked on the rotation itself
    assert km.gimbal_locked(km.matrix_from_euler(inside, seq), seq)
    assert not km.gimbal_locked(km.matrix_from_euler(outside, seq), seq)


def test_bad_sequence() -> None:
    with pytest.raises(km.EulerSequenceError, match="Euler sequence"):
        euler_rate_matrix([0, 0, 0], "ZZY")
