"""6R arms near one of rank 5 everywhere: isolated solutions strung along a near-continuum.

An arm within a small distance of an arm of :mod:`kinematica.ik.rank_five` (its DH
values moved by 1e-12..1e-3 off four concurrent axes, a spherical shoulder and
wrist, ...) has isolated solutions, but σ6 / σ1 of its Jacobian stays below
:data:`~kinematica.ik.rank_five.RANK_NEAR_TOL` everywhere: the exact arm's continuum
through a pose is broken into a few solutions along it, each determined in its joints
only to about the tolerance over σ6. Every elimination of the general 6R is then
ill-posed, and one numeric search finds one solution of several (it answered 81 of
210 poses of such arms, the generating configuration often missed).

**The method.** A one-dimensional sweep along the near-continuum, every sub-problem in
closed form (:mod:`kinematica.ik.near_sweep`): a joint s that moves along it is held
at :data:`~kinematica.ik.near_sweep.SWEEP_SAMPLES` values across its turn, and each arm
so left, with a virtual joint at the tool, is solved in closed form for every solution:
configurations of the real arm with ``q_s`` at that value that miss the pose only by
the virtual joint's angle θ. Along each branch θ varies smoothly with ``q_s`` and the
real arm's solutions are its zeros. Where θ changes sign between two samples, the
configuration interpolated at θ = 0, and every sample where |θ| is at most its
neighbours', are guesses: off the near-continuum by the interval's square, or along it
up to half a step from the zero, each beyond the reach of Newton's method alone (its
step along the near-null direction, error over σ6, overshoots): :data:`MINIMA_STEPS`
steps of Newton's method in two scales (:func:`~kinematica.ik.near_manifold.slow_newton`:
onto the near-continuum, then along it) take each within it, and Newton's method, with
the general 6R's candidates (where it was built), to the real arm; the distinct
ones meeting the tolerance are kept. On an arm within round-off of the continuum (σ6
/ σ1 at most :data:`CONTINUUM_RATIO`) the pose is met within the tolerance along arcs:
the guesses that meet it are kept too, and the answer is ``singular``.

**Which joint, and what it costs.** The end joints are swept where they move along the
near-continuum (a spherical shoulder and wrist, three parallel axes and three
concurrent, four axes from the first or to the last): the arm left is then the same
for every value, built once per chain, and every sample of every target
is a moved target of one batch of the core. Where neither end joint moves (four
parallel or concurrent axes 2-5), the joint in the middle that moves most is swept on
the arm cut open at it (:mod:`kinematica.ik.near_cut`), built once per target. Near an
arm of rank 4 or less no sweep of one joint pierces the continua, and Newton's method in
two scales from random guesses answers (:mod:`kinematica.ik.near_manifold`); it is also
tried on a target the sweep found nothing for. Measured against the previous method
(two joints that move most, each value its own arm built: 48 builds a pose, then
Newton and the local search from every sample) on the same 30 poses of 10 random arms
near rank 5, in one run on a loaded machine (2 cores, load 10): 546 ms a pose (median),
1,424 ms (mean), 5.8 s (max) before; 22.8, 51.5 and 213 ms now, 2-25 ms on an arm's
second and later poses near rank 5 (the first builds the end joints' arms, 40-150 ms),
100-210 ms near rank 4 and 3 (the two-scale Newton from 64 guesses). The solutions found
include every one of the previous method's at every pose, and more at 6 poses; near
rank 4 and 3, 2-8 where it found none. ``benchmarks/ik_degenerate.py --tables 80``
(same run conditions): arms near rank 5, 39 poses, 0 false statuses and 0 generating
configurations missed, 93 ms a pose (mean, first poses included), against 2 false
(``not_found``) and 3,079 ms before. Against a search from 200 random starts on 84 poses
of 28 arms near rank 5: every solution it found is among ours at 83 poses, and at the
84th (σ6 / σ1 = 3e-9, just above :data:`CONTINUUM_RATIO`, both find 6) 2 of its 200
answers lie beyond the matching tolerance of ours (1e-4 rad plus the tolerance over σ6).

The sweep's samples are a grid: a zero close to a fold of its branch, or one θ only
touches, can be missed, so the answer is never marked complete, and it is marked
``near_singular`` (the note gives the conditioning).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from kinematica.core import Chain, resolve_workers
from kinematica.ik.near_cut import cut_sweep
from kinematica.ik.near_manifold import SLOW_SEEDS, slow_newton, slow_rank, slow_search
from kinematica.ik.near_sweep import (
    SWEEP_SAMPLES,
    end_samples,
    end_sweeps,
    moving_joints,
    newton,
    seeds_between,
)
from kinematica.ik.rank_five import (
    FREE_TOL,
    RankFive,
    free_motion,
    rank_size,
    relative_sigma,
    scaled_jacobian,
)
from kinematica.ik.result import IKBatchResult, IKResult
from kinematica.ik.stack import pose_residuals, solve_each
from kinematica.ik.status import IKStatus

if TYPE_CHECKING:
    from kinematica.ik.options import IKOptions
    from kinematica.ik.registry import ClosedForm
    from kinematica.ik.targets import Targets
    from kinematica.ik.tolerance import Tolerance

__all__ = [
    "CONTINUUM_RATIO",
    "METHOD",
    "SAME_TOL",
    "near_answer",
    "solve_near",
    "sweep_guesses",
]

FloatArray = NDArray[np.float64]
Solve = Callable[[Chain, FloatArray, "IKOptions"], "IKResult | IKBatchResult"]

#: What the answers' ``method`` says.
METHOD = "analytic:near-rank-5"
#: Two solutions are one when every joint agrees to this (rad, modulo 2π), or to the
#: tolerance over σ6 at them where that is more: a solution of a near-continuum is
#: determined only to that (1e-10 m / 2e-8 m/rad = 5e-3 rad on an arm moved by 1e-6 off
#: a spherical shoulder and wrist); distinct ones differ by far more (0.1 rad and more).
SAME_TOL = 1e-4
#: Where σ6 / σ1 is at most this at every solution found, the pose is reached within the
#: tolerance along arcs (a joint moved by δ along the near-null direction moves the tool
#: by about σ6 δ: 1e-10 m over 0.1 rad at this ratio and an arm of a metre), and the
#: answer is ``singular``, not isolated solutions.
CONTINUUM_RATIO = 1e-9
#: Two-scale steps (:func:`~kinematica.ik.near_manifold.slow_newton`) from each minimum
#: of |θ| before Newton's: a sample where |θ| is least lies on the near-continuum but up to half
#: a sample's step from the zero, beyond the reach of Newton's method alone.
MINIMA_STEPS = 3


def _distinct(chain: Chain, Q: FloatArray, tol: float) -> FloatArray:
    """The rows of ``Q (k, 6)`` but those as close to an earlier one as either is determined.

    A solution is determined to about ``tol`` (m) over σ6 of its Jacobian (m/rad, lengths
    of the arm's size): within that of an earlier row, or within SAME_TOL, it is that row.
    """
    if not len(Q):
        return Q
    size = max(rank_size(chain), 1e-300)
    sigma = np.linalg.svd(scaled_jacobian(chain, Q), compute_uv=False)[:, -1] * size
    spread = np.maximum(SAME_TOL, tol / np.maximum(sigma, 1e-300))
    kept: list[int] = []
    for i, row in enumerate(Q):
        if not any(
            np.abs(np.remainder(row - Q[k] + math.pi, 2 * math.pi) - math.pi).max()
            <= max(spread[i], spread[k])
            for k in kept
        ):
            kept.append(i)
    return Q[kept]


def sweep_guesses(
    chain: Chain,
    five: RankFive,
    closed: ClosedForm | None,
    poses: FloatArray,
    options: IKOptions,
) -> tuple[list[FloatArray], tuple[int, ...]]:
    """Per target of ``poses (k, 4, 4)``, the guesses of its solutions, and the joints swept.

    The end joints that move are swept for every target in one batch of the core
    (:func:`~kinematica.ik.near_sweep.end_samples`); where neither moves, the joint in
    the middle that moves most, on the arm cut open at it (:mod:`kinematica.ik.near_cut`,
    built per target); the general 6R's candidates join where
    it was built (a family's arm near rank 5).
    """
    from kinematica.ik.tolerance import parse_tolerance

    tol = parse_tolerance(options.tol)
    threads = resolve_workers(options.workers) if len(poses) > 1 else 1
    ends = end_sweeps(chain, five.rank)
    per: list[list[FloatArray]] = [[] for _ in range(len(poses))]
    least: list[list[FloatArray]] = [[] for _ in range(len(poses))]  # minima of |θ|
    for sweep in ends:
        for i, samples in enumerate(end_samples(chain, sweep, poses, tol, threads)):
            minima, brackets = seeds_between(samples)
            least[i].extend([minima, brackets.at_zero()])
    joints = tuple(e.joint for e in ends)
    if not ends:  # a joint in the middle: the arm cut open at it, built per target
        joints = tuple([j for j in moving_joints(chain, five.rank) if j not in (0, 5)][:1])
        for j in joints:
            for i, T in enumerate(poses):
                cut = cut_sweep(chain, j, T)
                if cut is None:
                    continue
                minima, brackets = seeds_between(end_samples(chain, cut, T[None], tol)[0])
                least[i].extend([minima, brackets.at_zero()])
    near = [np.concatenate(m) if m else np.zeros((0, 6)) for m in least]
    at = np.repeat(np.arange(len(poses)), [len(m) for m in near])
    if len(at):  # onto the near-continuum, and along it towards the zero
        onto = slow_newton(chain, np.concatenate(near), poses[at], 5, MINIMA_STEPS)
        for i in range(len(poses)):
            per[i].append(onto[at == i])
    if closed is not None:
        for i, T in enumerate(poses):
            C = np.asarray(closed.params.candidates(chain.core, T, None)[0])
            per[i].append(C[np.isfinite(C).all(axis=1)])
    return [np.concatenate(g) if g else np.zeros((0, 6)) for g in per], joints


def near_answer(
    chain: Chain,
    five: RankFive,
    guesses: FloatArray,
    taken: FloatArray,
    how: str,
    T: FloatArray,
    options: IKOptions,
) -> IKResult:
    """Every solution the sweep along the near-continuum finds for the pose ``T (4, 4)``.

    Args:
        chain: The 6R arm, near one of rank 5 everywhere (:func:`rank_five`, not exact).
        five: Its structure.
        guesses: ``(g, 6)`` its guesses (:func:`sweep_guesses`).
        taken: ``(g, 6)`` each after Newton's method on the arm
            (:func:`~kinematica.ik.near_sweep.newton`).
        how: How the guesses were found, for the note (``"found by ..."``).
        T: ``(4, 4)`` the target (base frame, m).
        options: The call's settings (``tol``, ``respect_limits``; ``q0`` orders the
            solutions).
    """
    from kinematica.ik.tolerance import parse_tolerance

    tol = parse_tolerance(options.tol)
    Q = taken
    if five.ratio <= CONTINUUM_RATIO:  # within round-off of a continuum: its points count too
        Q = np.concatenate([Q, guesses])
    Q = np.remainder(Q + math.pi, 2.0 * math.pi) - math.pi  # (wrapped first: then judged)
    Q = _distinct(chain, Q[_meets(chain, Q, T, tol)], tol.position)
    lim = chain.qlim
    inside = (
        ((lim[:, 0] <= Q) & (lim[:, 1] >= Q)).all(axis=1)
        if options.respect_limits
        else np.ones(len(Q), dtype=bool)
    )
    Q, outside = Q[inside], Q[~inside]
    if options.q0 is not None and len(Q):
        Q = Q[np.argsort(np.linalg.norm(Q - np.asarray(options.q0, dtype=float), axis=1))]
    ratio = float(np.max(relative_sigma(chain, Q))) if len(Q) else math.inf
    at_solutions = f", {ratio:.1e} at the solutions" if len(Q) else ""
    note = (
        f"the arm is near one of rank {five.rank} at every configuration ({five.structure}; "
        f"σ6/σ1 of its Jacobian at most {five.ratio:.1e} at every configuration sampled"
        f"{at_solutions}): its solutions are isolated but determined only "
        f"to about the tolerance over σ6; they were {how}; more may exist"
    )
    free: tuple[int, ...] = ()
    if len(Q) and ratio <= CONTINUUM_RATIO:  # within the tolerance, a continuum
        n = free_motion(chain, Q[0], five.rank)
        free = tuple(j for j in range(6) if abs(float(n[j])) > FREE_TOL)
        note = (
            f"the arm is within round-off of one of rank {five.rank} at every configuration "
            f"({five.structure}; σ6/σ1 of its Jacobian at most {ratio:.1e} at the solutions): "
            "the pose is reached within the tolerance along arcs of a continuum (joints "
            f"{', '.join(str(j + 1) for j in free)} move together); the solutions given are "
            f"points of them {how}"
        )
    if free:
        status = IKStatus.SINGULAR
    elif len(Q):
        status = IKStatus.OK
    elif len(outside):
        status = IKStatus.OUT_OF_LIMITS
    else:
        status = IKStatus.NOT_FOUND
        note += ": none was found, nothing was proven"
    return IKResult(
        solutions=Q,
        status=status,
        method=METHOD,
        residuals=pose_residuals(chain, Q, T),
        branches=tuple(f"solution #{k + 1}" for k in range(len(Q))),
        out_of_limits=outside,
        out_of_limits_branches=tuple(f"solution #{len(Q) + k + 1}" for k in range(len(outside))),
        free_joints=free,
        notes=(note,),
        complete=False,
        near_singular=True,
    )


def _newton_each(chain: Chain, guesses: list[FloatArray], poses: FloatArray) -> list[FloatArray]:
    """Each target's guesses after Newton's method (every guess of every target at once)."""
    sizes = [len(g) for g in guesses]
    rows = np.repeat(np.arange(len(poses)), sizes)
    every = np.concatenate(guesses) if guesses else np.zeros((0, 6))
    return list(np.split(newton(chain, every, poses[rows]), np.cumsum(sizes)[:-1]))


def _meets(chain: Chain, Q: FloatArray, T: FloatArray, tol: Tolerance) -> NDArray[np.bool_]:
    """``(k,)`` True where a row of ``Q (k, 6)`` meets ``T`` within the tolerance."""
    err = pose_residuals(chain, Q, T)
    return np.asarray((err[:, 0] <= tol.position) & (err[:, 1] <= tol.rotation), dtype=np.bool_)


def solve_near(
    chain: Chain,
    five: RankFive,
    closed: ClosedForm | None,
    targets: Targets,
    options: IKOptions,
    solve: Solve,
) -> IKResult | IKBatchResult:
    """:func:`near_answer` of each pose target (one, or a batch of any shape).

    The sweeps of every target are one batch of the core (:func:`sweep_guesses`), and
    Newton's method takes every guess of every target at once.
    """
    from kinematica.ik.tolerance import parse_tolerance

    tol = parse_tolerance(options.tol)
    valid = [i for i in range(targets.poses.shape[0]) if i not in targets.invalid]
    poses = targets.poses[valid]
    rank = slow_rank(chain) if five.rank < 5 else 5
    joints: tuple[int, ...] = ()
    if five.rank < 5:  # continua of 2 dimensions and more: no sweep pierces them
        guesses = [np.zeros((0, 6)) for _ in poses]
    else:
        guesses, joints = sweep_guesses(chain, five, closed, poses, options)
    taken = _newton_each(chain, guesses, poses)
    bare = [i for i, q in enumerate(taken) if not _meets(chain, q, poses[i], tol).any()]
    swept = " and ".join(f"q{j + 1}" for j in joints)
    hows = [
        f"found by sweeping {swept} over {SWEEP_SAMPLES} values each, every one solved in "
        "closed form with a virtual joint at the tool, and taken to the arm by Newton's method"
    ] * len(poses)
    slow = (
        f"found by Newton's method in two scales from {SLOW_SEEDS} "
        f"random guesses: its Jacobian has {6 - rank} small singular values"
        + (
            " (the nearby arm's continua have as many dimensions: no sweep of one joint "
            "pierces them)"
            if rank < 5
            else ", and the sweep found no solution"
        )
    )
    for i, q in zip(bare, slow_search(chain, poses[bare], rank), strict=True):
        guesses[i] = np.concatenate([guesses[i], q])
        taken[i] = np.concatenate([taken[i], newton(chain, q, poses[i])])
        hows[i] = slow
    ahead = iter(zip(guesses, taken, hows, strict=True))  # solve_each asks in this order

    def answer(T: FloatArray, opts: IKOptions) -> IKResult:
        g, q, how = next(ahead)
        return near_answer(chain, five, g, q, how, T, opts)

    return solve_each(answer, targets, options)
