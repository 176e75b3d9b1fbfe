"""The core's Jacobian volumes (``volume.hpp``: σ1···σk from a determinant), checked.

References: the product of LAPACK's singular values (numpy's ``linalg.svd``) of the same
Jacobians, for random arms and every row set; a planar 2R arm's ``l1·l2·|sin q2|`` worked
by hand; zero exactly at a singular configuration; NaN for a configuration holding NaN.
"""

from __future__ import annotations

import numpy as np
import pytest

import kinematica as km

#: The product agrees with LAPACK's to this times σ1^k (both backward stable).
AGREE = 1e-12


def _random_arm(rng: np.random.Generator, n: int) -> km.Robot:
    joints = []
    for _ in range(n):
        a, d = rng.uniform(-0.6, 0.6, 2)
        alpha = rng.choice([0.0, np.pi / 2, -np.pi / 2, rng.uniform(-np.pi, np.pi)])
        if rng.random() < 0.15:
            joints.append(km.Prismatic(a=a, alpha=alpha, theta=rng.uniform(-1, 1)))
        else:
            joints.append(km.Revolute(a=a, d=d, alpha=alpha))
    return km.Robot.from_dh(joints, name=f"random {n}", convention="standard")


@pytest.mark.parametrize("n", [2, 3, 6, 7])
def test_volumes_match_the_product_of_lapacks_singular_values(n: int) -> None:
    rng = np.random.default_rng(10 + n)
    for _ in range(3):
        arm = _random_arm(rng, n)
        q = rng.uniform(-np.pi, np.pi, (200, n))
        J = arm.jacobian(q)
        for rows in [(0, 1, 2), (0, 1, 2, 3, 4, 5), (3, 4, 5), (0, 2, 4, 5), (1,)]:
            s = np.linalg.svd(J[:, rows, :], compute_uv=False)
            ours = arm.chain.volumes(q, rows)
            assert ours.shape == (200,)
            scale = s[:, 0] ** s.shape[1]
            assert np.all(np.abs(ours - np.prod(s, axis=-1)) <= AGREE * scale)


def test_planar_2r_by_hand() -> None:
    """Position rows x, y of a planar 2R: w = l1·l2·|sin q2| (square 2 x 2)."""
    l1, l2 = 0.7, 0.4
    arm = km.Robot.from_dh([km.Revolute(a=l1), km.Revolute(a=l2)], name="2R", convention="standard")
    q = np.random.default_rng(3).uniform(-np.pi, np.pi, (100, 2))
    hand = l1 * l2 * np.abs(np.sin(q[:, 1]))
    assert np.allclose(arm.chain.volumes(q, (0, 1)), hand, rtol=1e-13, atol=1e-15)
    # stretched out: exactly zero, as the LU meets a zero pivot
    assert arm.chain.volumes(np.array([[0.3, 0.0]]), (0, 1))[0] == 0.0


def test_nan_rows_and_batch_shapes() -> None:
    arm = km.load("puma560")
    q = np.random.default_rng(4).uniform(-1, 1, (3, 2, 6))
    q[1, 0, 2] = np.nan
    v = arm.chain.volumes(q)
    assert v.shape == (3, 2)
    assert np.isnan(v[1, 0]) and np.all(np.isfinite(np.delete(v.reshape(-1), 2)))
    flat = arm.chain.volumes(q.reshape(-1, 6))
    assert np.array_equal(flat.reshape(3, 2), v, equal_nan=True)
    # threads change nothing: each row is computed alone
    assert np.array_equal(arm.chain.volumes(q, workers=2), v, equal_nan=True)
