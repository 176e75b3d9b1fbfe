"""Quaternions against scipy: conversions, canonical sign, product, slerp, bad input."""

from __future__ import annotations

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.spatial.transform import Rotation, Slerp

from kinematica.errors import DimensionError
from kinematica.spatial import (
    matrix_from_axis_angle,
    matrix_from_quat,
    quat_conjugate,
    quat_from_matrix,
    quat_multiply,
    quat_slerp,
)

ATOL = 1e-12
BATCHES = [(), (1,), (3, 2)]


def same_rotation(q1: np.ndarray, q2: np.ndarray) -> np.ndarray:
    """Distance between quaternions up to sign (q and −q are one rotation)."""
    return np.minimum(
        np.abs(q1 - q2).max(axis=-1),
        np.abs(q1 + q2).max(axis=-1),
    )


@pytest.fixture(scope="module")
def rotations() -> Rotation:
    return Rotation.from_quat(np.random.default_rng(11).normal(size=(300, 4)))


def test_quat_from_matrix_matches_scipy(rotations: Rotation) -> None:
    q = quat_from_matrix(rotations.as_matrix())
    assert_allclose(q, rotations.as_quat(canonical=True), rtol=0, atol=ATOL)
    assert np.all(q[:, 3] >= 0.0)
    assert_allclose(np.linalg.norm(q, axis=-1), 1.0, rtol=0, atol=ATOL)


def test_quat_from_matrix_scalar_first(rotations: Rotation) -> None:
    R = rotations.as_matrix()
    assert_allclose(
        quat_from_matrix(R, scalar_first=True),
        rotations.as_quat(canonical=True, scalar_first=True),
        rtol=0,
        atol=ATOL,
    )


@pytest.mark.parametrize("axis", [*np.eye(3).tolist(), [1.0, -1.0, 0.0], [-1.0, 2.0, -3.0]])
@pytest.mark.parametrize("angle", [np.pi, np.pi - 1e-9, 1e-12, 0.0])
def test_quat_from_matrix_near_half_turn_and_identity(axis: list[float], angle: float) -> None:
    # Each Shepperd branch is exercised: the largest of trace, R_xx, R_yy, R_zz.
    R = matrix_from_axis_angle(axis, angle)
    q = quat_from_matrix(R)
    expected = Rotation.from_matrix(R).as_quat(canonical=True)
    assert_allclose(q, expected, rtol=0, atol=ATOL)
    assert_allclose(matrix_from_quat(q), R, rtol=0, atol=ATOL)


def test_canonical_sign_at_half_turns() -> None:
    # w == 0: the first nonzero of x, y, z is made positive, as scipy does.
    assert_allclose(quat_from_matrix(np.diag([1.0, -1.0, -1.0])), [1, 0, 0, 0], atol=0)
    assert_allclose(quat_from_matrix(np.diag([-1.0, -1.0, 1.0])), [0, 0, 1, 0], atol=0)
    half = np.array([[0.0, -1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, -1.0]])  # π about x − y
    q = quat_from_matrix(half)
    assert q[3] == 0.0
    assert q[0] > 0.0
    assert_allclose(q, Rotation.from_matrix(half).as_quat(canonical=True), rtol=0, atol=ATOL)


def test_matrix_from_quat_matches_scipy_and_normalises(rotations: Rotation) -> None:
    q = rotations.as_quat()
    scale = np.random.default_rng(12).uniform(0.1, 10.0, size=(len(q), 1))
    expected = rotations.as_matrix()
    assert_allclose(matrix_from_quat(q * scale), expected, rtol=0, atol=ATOL)
    assert_allclose(matrix_from_quat(-q), expected, rtol=0, atol=ATOL)
    q_first = rotations.as_quat(scalar_first=True)
    assert_allclose(matrix_from_quat(q_first, scalar_first=True), expected, rtol=0, atol=ATOL)


@pytest.mark.parametrize("batch", BATCHES)
def test_batch_shapes_match_loop(batch: tuple[int, ...]) -> None:
    q = np.random.default_rng(13).normal(size=(*batch, 4))
    R = matrix_from_quat(q)
    back = quat_from_matrix(R)
    conj = quat_conjugate(q)
    assert R.shape == (*batch, 3, 3)
    assert back.shape == conj.shape == (*batch, 4)
    for index in np.ndindex(*batch):
        assert_allclose(R[index], matrix_from_quat(q[index]), rtol=0, atol=0)
        assert_allclose(back[index], quat_from_matrix(R[index]), rtol=0, atol=0)
        assert_allclose(conj[index], quat_conjugate(q[index]), rtol=0, atol=0)


def test_multiply_is_matrix_product(rotations: Rotation) -> None:
    q1, q2 = rotations.as_quat()[:150], rotations.as_quat()[150:]
    q = quat_multiply(q1, q2)
    assert_allclose(
        matrix_from_quat(q), matrix_from_quat(q1) @ matrix_from_quat(q2), rtol=0, atol=ATOL
    )
    assert same_rotation(q, (rotations[:150] * rotations[150:]).as_quat()).max() < ATOL
    q1f, q2f = q1[:, [3, 0, 1, 2]], q2[:, [3, 0, 1, 2]]
    assert_allclose(quat_multiply(q1f, q2f, scalar_first=True), q[:, [3, 0, 1, 2]], atol=0)


def test_multiply_broadcasts() -> None:
    rng = np.random.default_rng(14)
    q1, q2 = rng.normal(size=(3, 1, 4)), rng.normal(size=(1, 2, 4))
    q = quat_multiply(q1, q2)
    assert q.shape == (3, 2, 4)
    for i, j in np.ndindex(3, 2):
        assert_allclose(q[i, j], quat_multiply(q1[i, 0], q2[0, j]), rtol=0, atol=0)


def test_conjugate_is_inverse(rotations: Rotation) -> None:
    q = rotations.as_quat()
    identity = quat_multiply(q, quat_conjugate(q))
    assert_allclose(identity, np.broadcast_to([0.0, 0.0, 0.0, 1.0], q.shape), atol=ATOL)
    assert_allclose(quat_conjugate([1.0, 2.0, 3.0, 4.0], scalar_first=True), [1, -2, -3, -4])


def test_slerp_endpoints_and_midpoint_match_scipy(rotations: Rotation) -> None:
    q1, q2 = rotations.as_quat()[:100], rotations.as_quat()[100:200]
    for t in [0.0, 0.25, 0.5, 0.9, 1.0]:
        q = quat_slerp(q1, q2, t)
        expected = np.stack(
            [
                Slerp([0.0, 1.0], Rotation.from_quat([a, b]))(t).as_quat()
                for a, b in zip(q1, q2, strict=True)
            ]
        )
        assert same_rotation(q, expected).max() < ATOL, t
    assert_allclose(quat_slerp(q1, q2, 0.0), q1, rtol=0, atol=ATOL)
    assert same_rotation(quat_slerp(q1, q2, 1.0), q2).max() < ATOL


def test_slerp_takes_the_short_way() -> None:
    q1 = quat_from_matrix(np.eye(3))
    q2 = -quat_from_matrix(matrix_from_axis_angle([0.0, 0.0, 1.0], 0.2))  # same rotation, far sign
    mid = quat_slerp(q1, q2, 0.5)
    expected = matrix_from_axis_angle([0.0, 0.0, 1.0], 0.1)
    assert_allclose(matrix_from_quat(mid), expected, rtol=0, atol=ATOL)


@pytest.mark.parametrize("gap", [0.0, 1e-15, 1e-12, 1e-8])
def test_slerp_near_parallel(gap: float) -> None:
    rng = np.random.default_rng(15)
    axis = rng.normal(size=3)
    R1 = Rotation.from_quat(rng.normal(size=4)).as_matrix()
    R2 = R1 @ matrix_from_axis_angle(axis, gap)
    ts = np.linspace(-0.5, 1.5, 9)
    q = quat_slerp(quat_from_matrix(R1), quat_from_matrix(R2), ts)
    assert np.isfinite(q).all()
    expected = R1 @ matrix_from_axis_angle(axis, ts * gap)
    assert_allclose(matrix_from_quat(q), expected, rtol=0, atol=ATOL)
    assert_allclose(np.linalg.norm(q, axis=-1), 1.0, rtol=0, atol=ATOL)


def test_slerp_broadcasts_t() -> None:
    rng = np.random.default_rng(16)
    q1, q2 = rng.normal(size=(3, 1, 4)), rng.normal(size=(3, 1, 4))
    t = np.linspace(0.0, 1.0, 5)
    q = quat_slerp(q1, q2, t)
    assert q.shape == (3, 5, 4)
    for i, j in np.ndindex(3, 5):
        assert_allclose(q[i, j], quat_slerp(q1[i, 0], q2[i, 0], t[j]), rtol=0, atol=ATOL)
    qf = quat_slerp(q1[..., [3, 0, 1, 2]], q2[..., [3, 0, 1, 2]], t, scalar_first=True)
    assert_allclose(qf, q[..., [3, 0, 1, 2]], rtol=0, atol=ATOL)


def test_bad_input() -> None:
    with pytest.raises(DimensionError, match=r"q must have shape \(\.\.\., 4\), got \(3,\)"):
        matrix_from_quat([0.0, 0.0, 1.0])
    q = np.tile([0.0, 0.0, 0.0, 1.0], (3, 1))
    q[1] = 0.0
    with pytest.raises(DimensionError, match=r"q\[1\] has zero norm"):
        matrix_from_quat(q)
    with pytest.raises(DimensionError, match=r"q2 has zero norm"):
        quat_slerp([0.0, 0.0, 0.0, 1.0], [0.0, 0.0, 0.0, 0.0], 0.5)
    with pytest.raises(DimensionError, match=r"q1 contains NaN or inf"):
        quat_multiply([np.nan, 0.0, 0.0, 1.0], [0.0, 0.0, 0.0, 1.0])
    with pytest.raises(DimensionError, match=r"R must have shape \(\.\.\., 3, 3\), got \(4, 4\)"):
        quat_from_matrix(np.eye(4))
