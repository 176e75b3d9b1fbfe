"""The orientation sets: rotations, spread evenly, deterministic, as documented."""

from __future__ import annotations

import math

import numpy as np
import pytest

from kinematica.errors import ArgumentError
from kinematica.reach.orientations import MAX_ORIENTATIONS, cone_set, planar_set, so3_set

ROUND_OFF = 1e-12


def _are_rotations(R: np.ndarray) -> None:
    eye = np.broadcast_to(np.eye(3), R.shape)
    np.testing.assert_allclose(np.swapaxes(R, -1, -2) @ R, eye, atol=ROUND_OFF)
    np.testing.assert_allclose(np.linalg.det(R), 1.0, atol=ROUND_OFF)


@pytest.mark.parametrize("n", [1, 2, 64, 1000])
def test_so3_set_has_equal_area_bands_of_tool_axes(n: int) -> None:
    R = so3_set(n)
    assert R.shape == (n, 3, 3)
    _are_rotations(R)
    # z axis of rotation i: cos θ = 1 − (2i + 1)/n, the Fibonacci lattice's bands
    np.testing.assert_allclose(R[:, 2, 2], 1 - (2 * np.arange(n) + 1) / n, atol=ROUND_OFF)
    np.testing.assert_array_equal(so3_set(n), R)  # deterministic


def test_so3_set_is_spread_over_so3() -> None:
    # Haar measure: E[R] = 0 and E[R_ij R_kl] = δ_ik δ_jl / 3; a set of n evenly spread
    # rotations gets both within a few 1/n (a random set: 1/sqrt(n), 40 times worse at 1e4).
    n = 10_000
    R = so3_set(n)
    assert np.abs(R.mean(axis=0)).max() < 5.0 / n
    second = np.einsum("nij,nkl->ijkl", R, R) / n
    expected = np.einsum("ik,jl->ijkl", np.eye(3), np.eye(3)) / 3
    assert np.abs(second - expected).max() < 5.0 / n
    # the spins do not follow the longitudes: the x axes are spread too
    assert np.abs(R[:, :, 0].mean(axis=0)).max() < 5.0 / n


def test_cone_keeps_every_tool_axis_within_its_half_angle() -> None:
    axis = np.array([0.0, 0.0, -1.0])
    R = cone_set(50, [0, 0, -2], 0.3)
    _are_rotations(R)
    angles = np.arccos(np.clip(R[:, :, 2] @ axis, -1, 1))
    assert angles.max() <= 0.3 + ROUND_OFF
    assert angles.max() > 0.25  # the cap is filled, not a point
    R0 = cone_set(8, [1, 1, 0], 0.0)
    np.testing.assert_allclose(R0[:, :, 2], np.tile([2**-0.5, 2**-0.5, 0], (8, 1)), atol=1e-15)
    spins = np.arctan2(R0[:, 2, 0], -R0[:, 2, 1])  # distinct spins about the axis
    assert np.unique(np.round(spins, 9)).size == 8
    np.testing.assert_allclose(cone_set(16, [0, 0, 1], math.pi), so3_set(16), atol=ROUND_OFF)


def test_planar_set_turns_about_the_normal() -> None:
    R = planar_set(4, [0, 0, 1])
    _are_rotations(R)
    phi = np.arctan2(R[:, 1, 0], R[:, 0, 0])
    np.testing.assert_allclose(phi, np.radians([45, 135, -135, -45]), atol=ROUND_OFF)


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (lambda: so3_set(0), "orientations"),
        (lambda: so3_set(MAX_ORIENTATIONS + 1), "orientations"),
        (lambda: so3_set(2.5), "orientations"),  # type: ignore[arg-type]
        (lambda: cone_set(4, [0, 0, 0], 0.1), "zero vector"),
        (lambda: cone_set(4, [0, 1], 0.1), "3 finite numbers"),
        (lambda: cone_set(4, [0, 0, 1], 4.0), "half_angle"),
        (lambda: cone_set(4, "up", 0.1), "approach"),
    ],
)
def test_bad_sets_are_refused(call, match: str) -> None:  # type: ignore[no-untyped-def]
    with pytest.raises(ArgumentError, match=match):
        call()
