"""The core's singular values (``singular.hpp``, one-sided Jacobi), against LAPACK's.

numpy's ``linalg.svd`` (LAPACK's dgesdd) is the independent reference: on thousands of
random Jacobians of random arms (through :meth:`kinematica.core.Chain.singular_values`,
which never stores the Jacobian), on random matrices of every shape the core takes, on
matrices of known rank built from chosen singular values, and at the singular
configurations of real arms. Both methods are backward stable, so each value agrees to
a few round-offs of the largest one, zero values included.
"""

from __future__ import annotations

import kinematica._core as _core
import numpy as np
import pytest

import kinematica as km
from kinematica.core import singular_values

#: Singular values agree to this times the largest one (both methods backward stable).
AGREE = 1e-12


def _worst(ours: np.ndarray, ref: np.ndarray) -> float:
    """The largest difference, relative to each matrix's largest singular value."""
    scale = np.maximum(ref[..., :1], np.finfo(float).tiny)
    return float(np.max(np.abs(ours - ref) / scale))


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


@pytest.mark.parametrize("n", [2, 3, 5, 6, 7, 9])
def test_random_jacobians_match_lapack(n: int) -> None:
    """1,000 configurations of 4 random arms per joint count, every row set measured."""
    rng = np.random.default_rng(n)
    worst = 0.0
    for _ in range(4):
        arm = _random_arm(rng, n)
        q = rng.uniform(-np.pi, np.pi, (250, n))
        J = arm.jacobian(q)
        for rows in [(0, 1, 2), (3, 4, 5), (0, 1, 2, 3, 4, 5), (0, 2, 4, 5), (1,)]:
            ours = arm.chain.singular_values(q, rows)
            ref = np.linalg.svd(J[:, rows, :], compute_uv=False)
            assert ours.shape == ref.shape == (250, min(len(rows), n))
            worst = max(worst, _worst(ours, ref))
    assert worst <= AGREE


@pytest.mark.parametrize(
    "shape", [(1, 1), (1, 9), (9, 1), (2, 2), (3, 6), (6, 3), (6, 6), (6, 7), (5, 40), (40, 6)]
)
def test_random_matrices_match_lapack(shape: tuple[int, int]) -> None:
    rng = np.random.default_rng(sum(shape))
    A = rng.standard_normal((500, *shape)) * rng.uniform(1e-3, 1e3, (500, 1, 1))
    assert _worst(singular_values(A), np.linalg.svd(A, compute_uv=False)) <= AGREE


@pytest.mark.parametrize(("m", "n"), [(6, 6), (6, 7), (3, 6), (6, 4)])
def test_rank_deficient_matrices(m: int, n: int) -> None:
    """``U diag(σ) Vᵀ`` of chosen σ, some exactly 0, some tiny: each value to AGREE·σ1."""
    rng = np.random.default_rng(m * n)
    k = min(m, n)
    for rank in range(k):
        for _ in range(100):
            U = np.linalg.qr(rng.standard_normal((m, m)))[0]
            V = np.linalg.qr(rng.standard_normal((n, n)))[0]
            s = np.zeros(k)
            s[:rank] = np.sort(rng.uniform(0.1, 10.0, rank))[::-1]
            A = U[:, :k] @ np.diag(s) @ V[:, :k].T
            ours = singular_values(A[None])[0]
            ref = np.linalg.svd(A, compute_uv=False)
            scale = max(s[0], 1.0)
            assert np.max(np.abs(ours - ref)) <= AGREE * scale
            assert np.max(np.abs(ours - s)) <= AGREE * scale  # and the chosen values
            assert np.all(ours[rank:] <= AGREE * scale)


def test_singular_configurations_of_real_arms() -> None:
    """The PUMA's wrist (q5 = 0) and the planar 3R stretched: a value 0 to round-off."""
    puma = km.load("puma560")
    rng = np.random.default_rng(3)
    q = rng.uniform(-2.0, 2.0, (300, 6))
    q[:, 4] = 0.0
    ours = puma.chain.singular_values(q)
    ref = np.linalg.svd(puma.jacobian(q), compute_uv=False)
    assert _worst(ours, ref) <= AGREE
    assert np.all(ours[:, -1] <= AGREE * ours[:, 0])
    planar = km.load("planar-3r")
    stretched = np.column_stack([rng.uniform(-3, 3, 300), np.zeros(300), np.zeros(300)])
    s = planar.chain.singular_values(stretched, (0, 1))
    assert np.all(s[:, 1] <= AGREE * s[:, 0])


def test_values_by_hand() -> None:
    """[[1, 1], [0, 1]]: the golden ratio φ and 1/φ; a diagonal: its entries, sorted."""
    phi = (1.0 + np.sqrt(5.0)) / 2.0
    got = singular_values(np.array([[[1.0, 1.0], [0.0, 1.0]]]))[0]
    assert np.max(np.abs(got - [phi, 1.0 / phi])) <= AGREE
    D = np.diag([0.5, -3.0, 0.0, 2.0, 1e-150, 7.0])
    assert singular_values(D[None])[0].tolist() == [7.0, 3.0, 2.0, 0.5, 1e-150, 0.0]


def test_agreement_tolerance_boundary() -> None:
    """A matrix changed by 1e3·AGREE (relative) is told apart; the same one is not."""
    rng = np.random.default_rng(9)
    A = rng.standard_normal((200, 6, 6))
    ref = np.linalg.svd(A, compute_uv=False)
    assert _worst(singular_values(A), ref) <= AGREE
    B = A * (1.0 + 1e3 * AGREE)  # every singular value scaled by the same factor
    assert _worst(singular_values(B), ref) > AGREE


def test_nan_and_bad_input() -> None:
    A = np.random.default_rng(0).standard_normal((3, 4, 6))
    A[1, 2, 3] = np.nan
    s = singular_values(A)
    assert np.isnan(s[1]).all() and np.isfinite(s[[0, 2]]).all()
    puma = km.load("puma560")
    q = np.zeros((2, 6))
    q[1, 0] = np.inf
    s = puma.chain.singular_values(q)
    assert np.isfinite(s[0]).all() and np.isnan(s[1]).all()
    with pytest.raises(ValueError, match="at most 6 rows or 6 columns"):
        singular_values(np.zeros((1, 7, 7)))
    with pytest.raises(ValueError, match="matrices"):
        singular_values(np.zeros(3))
    with pytest.raises(ValueError, match="bit mask"):
        puma.chain.core.jacobian_singular_values(q, 0, 1)
    with pytest.raises(ValueError, match="bit mask"):
        puma.chain.core.jacobian_singular_values(q, 64, 1)
    assert _core.singular_values(np.zeros((0, 6, 6)), 1).shape == (0, 6)


def test_batch_shapes_and_threads() -> None:
    puma = km.load("puma560")
    q = np.random.default_rng(1).uniform(-1, 1, (4, 5, 6))
    one = puma.chain.singular_values(q, (0, 1, 2), workers=1)
    assert one.shape == (4, 5, 3)
    assert np.array_equal(one, puma.chain.singular_values(q, (2, 0, 1), workers=2))
    big = np.random.default_rng(2).uniform(-1, 1, (3000, 6))
    assert np.array_equal(
        puma.chain.singular_values(big, workers=1), puma.chain.singular_values(big, workers=2)
    )


@pytest.mark.parametrize("scale", [1e-200, 1e200, 2.0**200, 2.0**201, 2.0**-201, 2.0**-202])
def test_far_scales(scale: float) -> None:
    """Matrices far from unit size (scaled exactly by a power of 2 inside) keep their values."""
    A = np.random.default_rng(4).standard_normal((50, 6, 6))
    ref = np.linalg.svd(A, compute_uv=False) * scale
    assert _worst(singular_values(A * scale), ref) <= AGREE


def test_a_wrist_flip_shares_its_twins_values_within_the_tolerance() -> None:
    """Rows in groups: a wrist flip's Jacobian (column 5 negated) takes its twin's values.

    The PUMA's flip (q4 + π, −q5, q6 + π) reaches the same pose with J·diag(1, 1, 1, 1,
    −1, 1). A flip moved by 1e-15 rad (its Jacobian within SAME_COLUMNS_TOL = 1e-14 of
    the twin's, up to sign) takes the twin's values bit for bit; one moved by 1e-11 rad
    (outside it) has its own, which differ from the twin's.
    """
    puma = km.load("puma560")
    q = np.array([0.3, -0.4, 0.5, 0.7, 0.9, -1.1])
    flip = q + np.array([0.0, 0.0, 0.0, np.pi, -2 * q[4], np.pi])
    J, Jf = puma.jacobian(q), puma.jacobian(flip)
    np.testing.assert_allclose(Jf * [1, 1, 1, 1, -1, 1], J, atol=1e-15)
    for delta, shared in [(1e-15, True), (1e-11, False)]:
        near = flip + np.array(
            [0, delta, 0, 0, 0, 0]
        )  # q2: the arm itself moves (q1 only turns it)
        Q = np.array([q, near, [np.nan] * 6, q + 0.2])
        grouped = puma.chain.singular_values(Q, group=4)
        alone = puma.chain.singular_values(Q)
        assert np.array_equal(grouped[1], grouped[0]) is shared
        assert np.all(np.abs(grouped - alone)[[0, 1, 3]] <= AGREE * grouped[0, 0])
        assert np.isnan(grouped[2]).all()
        assert np.array_equal(grouped[3], alone[3])
    with pytest.raises(ValueError, match="group"):
        puma.chain.singular_values(Q[:3], group=2)
    with pytest.raises(ValueError, match="group"):
        puma.chain.singular_values(np.zeros((17, 6)), group=17)
