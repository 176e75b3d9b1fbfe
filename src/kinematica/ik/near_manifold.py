"""Newton's method in two scales, for arms near one of rank 4 or less at every configuration.

An arm near one of rank r < 5 (six axes nearly through one point: rank 3; four axes
nearly parallel beside two more nearly so: rank 4) keeps 6 - r singular values of its
Jacobian small everywhere: the nearby arm's continua have 6 - r dimensions, and a sweep
of one joint (:mod:`kinematica.ik.near_sweep`) leaves an arm still near a continuum, so
no closed form pierces them. Newton's method from a random guess fails there (0 of 300
guesses on such arms): its step along the small directions, error over σ, is thrown
far off by the error the large directions leave at second order. The search fails too
(0 of 200 starts): its damping stalls it along the flat directions.

**The method.** Each step splits the Jacobian's singular directions in two: the r large
ones, whose error is cancelled first by :data:`CORRECT_STEPS` Gauss-Newton steps
restricted to them (well conditioned: the guess is pulled onto the slow manifold, where
the large errors vanish), then one step along the 6 - r small ones, at most
:data:`TRUST` rad long. On the slow manifold the error left lies along the small
directions and is linear in the step to second order of the manifold's own curvature,
so the step is Newton's in the manifold's coordinates: it converges from a guess far
off along the manifold. Every guess of every target at once (numpy).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from kinematica.core import Chain

__all__ = [
    "CORRECT_STEPS",
    "SLOW_GAP",
    "SLOW_SEED",
    "SLOW_SEEDS",
    "SLOW_STEPS",
    "TRUST",
    "slow_newton",
    "slow_rank",
    "slow_search",
]

FloatArray = NDArray[np.float64]

#: A singular value is small when σ_i / σ1 is below this at some configuration sampled:
#: the small ones of the arms of the tests are 1e-5 and less, the large ones 0.1 and more.
SLOW_GAP = 1e-3
#: Random guesses per target (found 2-6 distinct solutions of each of 6 poses of arms
#: near rank 3 from 100, the generating one every time; the 200-start search, none).
SLOW_SEEDS = 64
#: Their seed.
SLOW_SEED = 7
#: Outer steps (a corrector and a predictor each).
SLOW_STEPS = 40
#: Gauss-Newton steps onto the slow manifold in each outer step.
CORRECT_STEPS = 2
#: The longest step along the small directions (rad): beyond, the manifold's curvature
#: makes the linear model wrong.
TRUST = 0.2


def _error(chain: Chain, q: FloatArray, T: FloatArray) -> tuple[FloatArray, FloatArray]:
    """``((k, 6) pose error, (k, 6, 6) Jacobian)``: position (m), rotation vector (rad)."""
    from kinematica.spatial import rotvec_from_matrix

    Q = np.ascontiguousarray(q)
    F = np.asarray(chain.fk(Q)[0])
    R = T[:, :3, :3] @ np.swapaxes(F[:, :3, :3], 1, 2)
    e = np.concatenate([T[:, :3, 3] - F[:, :3, 3], rotvec_from_matrix(R)], axis=1)
    return e, np.asarray(chain.jacobian(Q)[0])


def slow_newton(
    chain: Chain, seeds: FloatArray, T: FloatArray, rank: int, steps: int = SLOW_STEPS
) -> FloatArray:
    """``(k, 6)`` each of ``seeds (k, 6)`` after ``steps`` two-scale steps.

    Args:
        chain: The 6R arm.
        seeds: ``(k, 6)`` the guesses (rad).
        T: ``(4, 4)`` the target, or ``(k, 4, 4)`` one per guess (base frame, m).
        rank: The rank r of the nearby arm: r large singular directions, 6 - r small.
        steps: Outer steps (:data:`SLOW_STEPS`).

    Returns:
        The configurations reached (rows whose error grew non-finite keep their last
        finite value); the caller judges them by their residuals.
    """
    q = np.array(seeds, dtype=np.float64).reshape(-1, 6)
    T = np.ascontiguousarray(np.broadcast_to(T, (len(q), 4, 4)))
    for _ in range(steps):
        for _ in range(CORRECT_STEPS):  # onto the slow manifold: the large directions only
            e, J = _error(chain, q, T)
            U, s, Vt = np.linalg.svd(J)
            c = np.einsum("kji,kj->ki", U[:, :, :rank], e) / s[:, :rank]
            step = np.einsum("kji,kj->ki", Vt[:, :rank], c)
            q = np.where(np.isfinite(step).all(axis=1)[:, None], q + step, q)
        e, J = _error(chain, q, T)
        U, s, Vt = np.linalg.svd(J)
        c = np.einsum("kji,kj->ki", U[:, :, rank:], e) / s[:, rank:]
        step = np.einsum("kji,kj->ki", Vt[:, rank:], c)
        size = np.linalg.norm(step, axis=1)
        scale = np.minimum(1.0, TRUST / np.maximum(size, 1e-300))
        q = np.where(np.isfinite(step).all(axis=1)[:, None], q + scale[:, None] * step, q)
    return q


def slow_rank(chain: Chain) -> int:
    """The number of the Jacobian's singular values not small: σ_i / σ1 above :data:`SLOW_GAP`.

    The smallest over :data:`~kinematica.ik.rank_five.RANK_SAMPLES` random configurations
    (the same as the rank's), made once per chain: 5 on an arm near rank 5, 3 on one whose
    six axes nearly meet at one point, whatever the small ones' size.
    """
    key = ("near-manifold", "rank")
    if key not in chain.memo:
        from kinematica.ik.rank_five import RANK_SAMPLES, RANK_SEED, scaled_jacobian

        Q = np.random.default_rng(RANK_SEED).uniform(-np.pi, np.pi, (RANK_SAMPLES, 6))
        s = np.linalg.svd(scaled_jacobian(chain, Q), compute_uv=False)
        chain.memo[key] = int(np.count_nonzero((s / s[:, :1]).min(axis=0) > SLOW_GAP))
    got: int = chain.memo[key]  # type: ignore[assignment]
    return got


def slow_search(chain: Chain, poses: FloatArray, rank: int) -> list[FloatArray]:
    """Per target of ``poses (k, 4, 4)``: :func:`slow_newton` from :data:`SLOW_SEEDS` guesses.

    The guesses are random (a fixed seed: the same answer every call), the same for every
    target; the rows returned are not judged (the caller keeps those meeting the target).
    """
    if not len(poses):
        return []
    seeds = np.random.default_rng(SLOW_SEED).uniform(-np.pi, np.pi, (SLOW_SEEDS, 6))
    Q = slow_newton(chain, np.tile(seeds, (len(poses), 1)), np.repeat(poses, SLOW_SEEDS, 0), rank)
    return list(Q.reshape(len(poses), SLOW_SEEDS, 6))
