"""Axis-angle, rotation vectors and the geodesic angle, near 0 and near π included."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose
from scipy.spatial.transform import Rotation

import kinematica as km
from kinematica.errors import DimensionError
from kinematica.spatial import (
    axis_angle_from_matrix,
    matrix_from_axis_angle,
    matrix_from_rotvec,
    rotation_angle,
    rotvec_from_matrix,
)

ATOL = 1e-12
BATCHES = [(), (1,), (3, 2)]


def unit_axes(n: int, seed: int) -> np.ndarray:
    v = np.random.default_rng(seed).normal(size=(n, 3))
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def exact_rotation(axis: np.ndarray, angle: float) -> np.ndarray:
    """Rodrigues written out independently of the code under test (unit axes)."""
    x, y, z = np.moveaxis(axis, -1, 0)
    o = np.zeros_like(x)
    K = np.stack([np.stack(row, axis=-1) for row in ([o, -z, y], [z, o, -x], [-y, x, o])], -2)
    return np.eye(3) + np.sin(angle) * K + (1.0 - np.cos(angle)) * (K @ K)


@pytest.fixture(scope="module")
def rotations() -> Rotation:
    return Rotation.from_quat(np.random.default_rng(21).normal(size=(300, 4)))


def test_matrix_from_axis_angle_matches_scipy() -> None:
    rng = np.random.default_rng(22)
    axis = rng.normal(size=(200, 3))  # not unit: normalised by the function
    angle = rng.uniform(-2 * np.pi, 2 * np.pi, size=200)
    n = axis / np.linalg.norm(axis, axis=-1, keepdims=True)
    expected = Rotation.from_rotvec(n * angle[:, None]).as_matrix()
    assert_allclose(matrix_from_axis_angle(axis, angle), expected, rtol=0, atol=ATOL)
    got = matrix_from_axis_angle(axis, np.rad2deg(angle), degrees=True)
    assert_allclose(got, expected, rtol=0, atol=ATOL)


def test_matrix_from_rotvec_matches_scipy(rotations: Rotation) -> None:
    v = rotations.as_rotvec()
    assert_allclose(matrix_from_rotvec(v), rotations.as_matrix(), rtol=0, atol=ATOL)
    deg = rotations.as_rotvec(degrees=True)
    assert_allclose(matrix_from_rotvec(deg, degrees=True), rotations.as_matrix(), atol=ATOL)


def test_rotvec_from_matrix_matches_scipy(rotations: Rotation) -> None:
    R = rotations.as_matrix()
    assert_allclose(rotvec_from_matrix(R), rotations.as_rotvec(), rtol=0, atol=ATOL)
    deg = rotvec_from_matrix(R, degrees=True)
    assert_allclose(deg, rotations.as_rotvec(degrees=True), rtol=0, atol=1e-10)


def test_round_trips(rotations: Rotation) -> None:
    R = rotations.as_matrix()
    assert_allclose(matrix_from_rotvec(rotvec_from_matrix(R)), R, rtol=0, atol=ATOL)
    axis, angle = axis_angle_from_matrix(R)
    assert np.all((angle >= 0.0) & (angle <= np.pi))
    assert_allclose(np.linalg.norm(axis, axis=-1), 1.0, rtol=0, atol=ATOL)
    assert_allclose(matrix_from_axis_angle(axis, angle), R, rtol=0, atol=ATOL)
    _, deg = axis_angle_from_matrix(R, degrees=True)
    assert_allclose(deg, np.rad2deg(angle), rtol=1e-14)


@pytest.mark.parametrize("angle", [1e-12, 1e-9, 1e-6])
def test_tiny_angles(angle: float) -> None:
    n = unit_axes(50, 23)
    R = exact_rotation(n, angle)
    assert_allclose(matrix_from_axis_angle(n, angle), R, rtol=0, atol=1e-15)
    axis, got = axis_angle_from_matrix(R)
    assert_allclose(got, angle, rtol=1e-9, atol=0)
    assert_allclose(axis, n, rtol=0, atol=1e-3)  # direction of a 1e-12 turn: ~1e-4
    # The rotation vector itself is exact to round-off: no cut-off near 0.
    assert_allclose(rotvec_from_matrix(R), n * angle, rtol=0, atol=1e-16 * 5)
    assert_allclose(matrix_from_rotvec(n * angle), R, rtol=0, atol=1e-16 * 5)


def test_identity_axis_is_z_by_convention() -> None:
    axis, angle = axis_angle_from_matrix(np.eye(3))
    assert_allclose(axis, [0.0, 0.0, 1.0], atol=0)
    assert angle == 0.0
    assert_allclose(rotvec_from_matrix(np.eye(3)), 0.0, atol=0)
    assert_allclose(matrix_from_rotvec(np.zeros(3)), np.eye(3), atol=0)


@pytest.mark.parametrize("gap", [1e-9, 1e-6, 1e-3])
def test_near_half_turn(gap: float) -> None:
    n = unit_axes(100, 24)
    angle = np.pi - gap
    R = exact_rotation(n, angle)
    axis, got = axis_angle_from_matrix(R)
    assert_allclose(got, angle, rtol=0, atol=ATOL)
    assert_allclose(axis, n, rtol=0, atol=ATOL)  # sign too: taken from the skew part
    assert_allclose(rotvec_from_matrix(R), n * angle, rtol=0, atol=ATOL)


def test_exact_half_turn() -> None:
    n = unit_axes(100, 25)
    R = exact_rotation(n, np.pi)
    axis, angle = axis_angle_from_matrix(R)
    assert_allclose(angle, np.pi, rtol=0, atol=ATOL)
    # n and −n are the same half turn; either may come back.
    assert_allclose(np.abs(np.sum(axis * n, axis=-1)), 1.0, rtol=0, atol=ATOL)
    assert_allclose(matrix_from_axis_angle(axis, angle), R, rtol=0, atol=ATOL)
    assert_allclose(matrix_from_rotvec(rotvec_from_matrix(R)), R, rtol=0, atol=ATOL)
    coordinate = axis_angle_from_matrix(np.diag([-1.0, 1.0, -1.0]))
    assert_allclose(coordinate[0], [0.0, 1.0, 0.0], atol=0)


@pytest.mark.parametrize("angle", [1e-12, 1e-10, 3e-8, 0.5, np.pi - 1e-9, np.pi])
def test_rotation_angle_against_a_known_angle(angle: float) -> None:
    rng = np.random.default_rng(26)
    R_a = Rotation.from_quat(rng.normal(size=(100, 4))).as_matrix()
    R_b = R_a @ exact_rotation(unit_axes(100, 27), angle)
    got = rotation_angle(R_a, R_b)
    # Absolute accuracy ~1e-16: products of O(1) entries; arccos alone gives ~1e-8.
    assert_allclose(got, angle, rtol=0, atol=1e-15 if angle < 1.0 else ATOL)
    assert_allclose(rotation_angle(R_b, R_a), got, rtol=0, atol=1e-15)


def test_rotation_angle_matches_scipy_and_degrees(rotations: Rotation) -> None:
    a, b = rotations[:150], rotations[150:]
    expected = (a.inv() * b).magnitude()
    got = rotation_angle(a.as_matrix(), b.as_matrix())
    assert_allclose(got, expected, rtol=0, atol=ATOL)
    got_deg = rotation_angle(a.as_matrix(), b.as_matrix(), degrees=True)
    assert_allclose(got_deg, np.rad2deg(expected), rtol=0, atol=1e-10)
    assert_allclose(rotation_angle(a.as_matrix(), a.as_matrix()), 0.0, atol=1e-15)


@pytest.mark.parametrize("batch", BATCHES)
def test_batch_shapes_match_loop(batch: tuple[int, ...]) -> None:
    rng = np.random.default_rng(28)
    v = rng.normal(size=(*batch, 3))
    R = matrix_from_rotvec(v)
    axis, angle = axis_angle_from_matrix(R)
    rv = rotvec_from_matrix(R)
    R2 = matrix_from_axis_angle(v, angle)
    dist = rotation_angle(R, R2)
    assert R.shape == R2.shape == (*batch, 3, 3)
    assert axis.shape == rv.shape == (*batch, 3)
    assert angle.shape == dist.shape == batch
    for i in np.ndindex(*batch):
        assert_allclose(R[i], matrix_from_rotvec(v[i]), rtol=0, atol=0)
        assert_allclose(axis[i], axis_angle_from_matrix(R[i])[0], rtol=0, atol=0)
        assert_allclose(angle[i], axis_angle_from_matrix(R[i])[1], rtol=0, atol=0)
        assert_allclose(rv[i], rotvec_from_matrix(R[i]), rtol=0, atol=0)
        assert_allclose(R2[i], matrix_from_axis_angle(v[i], angle[i]), rtol=0, atol=0)
        assert_allclose(dist[i], rotation_angle(R[i], R2[i]), rtol=0, atol=0)


def test_axis_angle_broadcasts() -> None:
    R = matrix_from_axis_angle([0.0, 0.0, 2.0], np.linspace(0.0, 1.0, 4))
    assert R.shape == (4, 3, 3)
    assert_allclose(rotation_angle(R[0], R), np.linspace(0.0, 1.0, 4), rtol=0, atol=ATOL)


@settings(max_examples=60, deadline=None, database=None)
@given(
    st.lists(st.floats(-1.0, 1.0, allow_nan=False), min_size=3, max_size=3).filter(
        lambda v: np.linalg.norm(v) > 1e-3
    ),
    st.floats(0.0, np.pi, allow_nan=False),
)
def test_log_inverts_exp(axis: list[float], angle: float) -> None:
    R = matrix_from_axis_angle(axis, angle)
    assert_allclose(matrix_from_rotvec(rotvec_from_matrix(R)), R, rtol=0, atol=ATOL)
    assert_allclose(axis_angle_from_matrix(R)[1], angle, rtol=0, atol=1e-11)


def test_bad_input() -> None:
    with pytest.raises(DimensionError, match=r"axis is the zero vector"):
        matrix_from_axis_angle([0.0, 0.0, 0.0], 1.0)
    with pytest.raises(DimensionError, match=r"axis\[1\] is the zero vector"):
        matrix_from_axis_angle([[1.0, 0.0, 0.0], [0.0, 0.0, 0.0]], 1.0)
    with pytest.raises(DimensionError, match=r"axis must have shape \(\.\.\., 3\), got \(2,\)"):
        matrix_from_axis_angle([1.0, 0.0], 1.0)
    with pytest.raises(DimensionError, match=r"angle contains NaN or inf"):
        matrix_from_axis_angle([1.0, 0.0, 0.0], np.nan)
    with pytest.raises(DimensionError, match=r"rotvec must have shape"):
        matrix_from_rotvec(np.zeros((2, 4)))
    with pytest.raises(DimensionError, match=r"R_b must have shape \(\.\.\., 3, 3\), got \(3,\)"):
        rotation_angle(np.eye(3), np.zeros(3))
    with pytest.raises(DimensionError, match=r"R contains NaN or inf"):
        rotvec_from_matrix(np.full((3, 3), np.nan))


IDENTITY_ANGLE_TOL = 10.0 * np.finfo(np.float64).eps  # spatial/axis_angle.py


#: A case a factor 10 inside a tolerance, and one a factor 10 outside it.
FACTORS = [(0.1, True), (10.0, False)]


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_identity_angle_tol_gives_the_conventional_axis(factor: float, inside: bool) -> None:
    """IDENTITY_ANGLE_TOL: below this angle the axis of R is round-off, and
    axis_angle_from_matrix returns the z axis by convention.

    A rotation about x by a tiny angle ``e`` has the exact skew part
    ``sin e`` ~ ``e``, so its angle is recovered; its axis is x above the
    tolerance and z (the convention) below it.
    """
    e = factor * IDENTITY_ANGLE_TOL
    axis, angle = km.axis_angle_from_matrix(km.matrix_from_axis_angle([1.0, 0.0, 0.0], e))
    assert float(angle) == pytest.approx(e, rel=1e-6)
    expected = [0.0, 0.0, 1.0] if inside else [1.0, 0.0, 0.0]
    assert np.array_equal(axis, expected)
