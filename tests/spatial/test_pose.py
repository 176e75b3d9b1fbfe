"""Pose vectors, the IK pose error, validation messages, and the spatial namespace."""

from __future__ import annotations

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.spatial.transform import Rotation

import kinematica.spatial as spatial
from kinematica.errors import DimensionError
from kinematica.spatial import (
    EulerSequenceError,
    check_rotation,
    check_transform,
    euler_from_matrix,
    from_pose,
    make_transform,
    matrix_from_axis_angle,
    matrix_from_rotvec,
    rotx,
    roty,
    rotz,
    se3_error,
    to_pose,
)

ATOL = 1e-12
BATCHES = [(), (1,), (3, 2)]


def random_transforms(batch: tuple[int, ...], seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    R = Rotation.from_quat(rng.normal(size=(*batch, 4)).reshape(-1, 4)).as_matrix()
    p = rng.uniform(-2.0, 2.0, size=(*batch, 3))
    return make_transform(R.reshape(*batch, 3, 3), p)


def test_namespace_exports_exist() -> None:
    for name in spatial.__all__:
        assert hasattr(spatial, name), name
    for name in ["compose", "inv_transform", "make_transform", "rotx", "roty", "rotz", "transl"]:
        assert name in spatial.__all__


def test_to_pose_by_hand() -> None:
    # ZYZ of a pure z rotation is gimbal locked: everything goes in the first angle.
    T = make_transform(rotz(0.3), [1.0, 2.0, 3.0])
    assert_allclose(to_pose(T), [1.0, 2.0, 3.0, 0.3, 0.0, 0.0], atol=ATOL)
    # Extrinsic roll-pitch-yaw: R = Rz(yaw) Ry(pitch) Rx(roll).
    T = make_transform(rotz(0.5) @ roty(-0.4) @ rotx(0.2), [0.1, 0.0, -0.2])
    assert_allclose(to_pose(T, euler="xyz"), [0.1, 0.0, -0.2, 0.2, -0.4, 0.5], atol=ATOL)
    deg = to_pose(T, euler="xyz", degrees=True)
    assert_allclose(deg, [0.1, 0.0, -0.2, *np.rad2deg([0.2, -0.4, 0.5])], atol=1e-10)


@pytest.mark.parametrize("euler", ["ZYZ", "zyz", "XYZ", "zyx", "YXY"])
def test_round_trip(euler: str) -> None:
    T = random_transforms((50,), 31)
    p = to_pose(T, euler)
    assert_allclose(p[:, 3:], euler_from_matrix(T[:, :3, :3], euler), atol=0)
    assert_allclose(from_pose(p, euler), T, rtol=0, atol=ATOL)
    assert_allclose(from_pose(to_pose(T, euler, degrees=True), euler, degrees=True), T, atol=ATOL)
    assert_allclose(to_pose(from_pose(p, euler), euler), p, rtol=0, atol=ATOL)


def test_from_pose_by_hand() -> None:
    T = from_pose([1.0, -2.0, 0.5, 0.1, 0.2, 0.3], euler="ZYZ")
    assert_allclose(T[:3, :3], rotz(0.1) @ roty(0.2) @ rotz(0.3), rtol=0, atol=ATOL)
    assert_allclose(T[:3, 3], [1.0, -2.0, 0.5], atol=0)
    assert_allclose(T[3], [0.0, 0.0, 0.0, 1.0], atol=0)


@pytest.mark.parametrize("batch", BATCHES)
def test_batch_shapes_match_loop(batch: tuple[int, ...]) -> None:
    T = random_transforms(batch, 32)
    target = random_transforms(batch, 33)
    p = to_pose(T)
    back = from_pose(p)
    err = se3_error(T, target)
    assert p.shape == err.shape == (*batch, 6)
    assert back.shape == (*batch, 4, 4)
    for i in np.ndindex(*batch):
        assert_allclose(p[i], to_pose(T[i]), rtol=0, atol=0)
        assert_allclose(back[i], from_pose(p[i]), rtol=0, atol=0)
        assert_allclose(err[i], se3_error(T[i], target[i]), rtol=0, atol=0)


def test_se3_error_convention() -> None:
    # Target rotated by +0.1 about base z from the current pose, and moved +x.
    current = make_transform(roty(0.7), [1.0, 0.0, 0.0])
    target = make_transform(rotz(0.1) @ roty(0.7), [1.5, 0.0, 0.0])
    assert_allclose(se3_error(current, target), [0.5, 0, 0, 0, 0, 0.1], atol=ATOL)
    assert_allclose(se3_error(target, target), 0.0, atol=0)


def test_se3_error_is_base_frame_rotation_vector() -> None:
    rng = np.random.default_rng(34)
    current = random_transforms((100,), 35)
    w = rng.normal(size=(100, 3))
    w *= rng.uniform(0.0, 3.0, size=(100, 1)) / np.linalg.norm(w, axis=-1, keepdims=True)
    dp = rng.normal(size=(100, 3))
    target = make_transform(matrix_from_rotvec(w) @ current[:, :3, :3], current[:, :3, 3] + dp)
    assert_allclose(se3_error(current, target), np.concatenate([dp, w], -1), atol=ATOL)


def test_se3_error_resolves_tiny_errors() -> None:
    current = random_transforms((20,), 36)
    axis = np.random.default_rng(37).normal(size=(20, 3))
    axis /= np.linalg.norm(axis, axis=-1, keepdims=True)
    target = current.copy()
    target[:, :3, :3] = matrix_from_axis_angle(axis, 1e-12) @ current[:, :3, :3]
    err = se3_error(current, target)
    assert_allclose(np.linalg.norm(err[:, 3:], axis=-1), 1e-12, rtol=1e-3)


def test_se3_error_broadcasts() -> None:
    current = random_transforms((3, 1), 38)
    target = random_transforms((4,), 39)
    assert se3_error(current, target).shape == (3, 4, 6)


# --- validation ---------------------------------------------------------------------


def test_check_transform_accepts_and_returns_float_array() -> None:
    T = random_transforms((2, 3), 40)
    assert check_transform(T) is T
    out = check_transform(np.eye(4, dtype=int).tolist())
    assert out.dtype == np.float64
    assert_allclose(check_rotation(rotx(0.3)), rotx(0.3), atol=0)


def test_check_transform_messages() -> None:
    with pytest.raises(DimensionError, match=r"T must have shape \(\.\.\., 4, 4\), got \(3, 3\)"):
        check_transform(np.eye(3))
    with pytest.raises(DimensionError, match=r"pose must have shape \(\.\.\., 4, 4\), got \(4,\)"):
        check_transform(np.zeros(4), name="pose")
    T = np.tile(np.eye(4), (2, 3, 1, 1))
    T[1, 2, 0, 3] = np.nan
    with pytest.raises(DimensionError, match=r"T\[1, 2\] contains NaN or inf"):
        check_transform(T)
    T = np.tile(np.eye(4), (2, 1, 1))
    T[1, 3, 0] = 0.5
    with pytest.raises(DimensionError, match=r"T\[1\] last row must be \[0, 0, 0, 1\], got \[0\.5"):
        check_transform(T)
    T = np.tile(np.eye(4), (2, 3, 1, 1))
    T[0, 1, :3, :3] *= 1.01
    with pytest.raises(
        DimensionError, match=r"T\[0, 1\] rotation is not orthonormal: max \|RᵀR − I\| = 2\.0e-02"
    ):
        check_transform(T)
    with pytest.raises(DimensionError, match=r"T rotation has det = -1\.000, expected \+1"):
        check_transform(np.diag([1.0, 1.0, -1.0, 1.0]))


def test_check_rotation_messages_and_tolerance() -> None:
    with pytest.raises(DimensionError, match=r"R must have shape \(\.\.\., 3, 3\), got \(4, 4\)"):
        check_rotation(np.eye(4))
    slightly_off = rotz(0.3) + 1e-9
    check_rotation(slightly_off)  # within the default tolerance
    with pytest.raises(DimensionError, match=r"R_tool rotation is not orthonormal"):
        check_rotation(slightly_off, name="R_tool", tol=1e-12)
    with pytest.raises(DimensionError, match=r"R rotation has det = -1\.000"):
        check_rotation(-np.eye(3))


def test_to_pose_validates() -> None:
    with pytest.raises(DimensionError, match=r"T must have shape \(\.\.\., 4, 4\), got \(3, 3\)"):
        to_pose(np.eye(3))
    sheared = np.eye(4)
    sheared[0, 1] = 0.1
    with pytest.raises(DimensionError, match=r"not orthonormal"):
        to_pose(sheared)
    with pytest.raises(EulerSequenceError):
        to_pose(np.eye(4), euler="XYx")


def test_from_pose_and_se3_error_validate() -> None:
    with pytest.raises(DimensionError, match=r"p must have shape \(\.\.\., 6\), got \(2, 3\)"):
        from_pose(np.zeros((2, 3)))
    with pytest.raises(DimensionError, match=r"p\[1\] contains NaN or inf"):
        from_pose([[0.0] * 6, [0.0, 0.0, 0.0, np.inf, 0.0, 0.0]])
    with pytest.raises(DimensionError, match=r"T_target must have shape"):
        se3_error(np.eye(4), np.eye(3))
