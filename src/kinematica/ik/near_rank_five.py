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
closed form: each of the :data:`SWEEP_JOINTS` joints s that move most along the
near-null direction of the Jacobian (at the search's point, else at a random
configuration) is held at
:data:`SWEEP_SAMPLES` values across its turn, and each arm so left, with a virtual
joint at the tool, is solved in closed form for every solution
(:func:`kinematica.ik.continuum_6r.virtual_solutions`): configurations of the real arm
with ``q_s`` at that value that miss the pose only by the virtual joint's angle θ.
Along each branch θ varies smoothly with ``q_s`` and the real arm's solutions are its
zeros; every configuration of every sample, those interpolated at the zeros between
samples, the general 6R's candidates (where it was built) and the search's point are
guesses, each taken by Newton's method and by the Levenberg-Marquardt search from that
guess alone (no restarts) to the real arm's solution it leads to, and the distinct ones
meeting the tolerance are kept. On an arm within round-off of the continuum (σ6 / σ1 at
most :data:`CONTINUUM_RATIO`) the pose is met within the tolerance along arcs: the
guesses that meet it are kept too, and the answer is ``singular``.

The sweep's samples are a grid: a branch whose zero lies between samples is reached
by the local search from the samples on either side, but a zero too close to a fold
of its branch can be missed, so the answer is never marked complete, and it is
marked ``near_singular`` (the note gives the conditioning).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from kinematica.core import Chain
from kinematica.ik.continuum_6r import virtual_solutions
from kinematica.ik.rank_five import (
    FREE_TOL,
    RankFive,
    free_motion,
    relative_sigma,
    scaled_jacobian,
)
from kinematica.ik.result import IKBatchResult, IKResult
from kinematica.ik.stack import pose_residuals, solve_each
from kinematica.ik.status import IKStatus
from kinematica.ik.structure import features

if TYPE_CHECKING:
    from kinematica.ik.options import IKOptions
    from kinematica.ik.registry import ClosedForm
    from kinematica.ik.targets import Targets

__all__ = [
    "CONTINUUM_RATIO",
    "METHOD",
    "NEWTON_DONE",
    "NEWTON_STEPS",
    "SAME_TOL",
    "SWEEP_JOINTS",
    "SWEEP_SAMPLES",
    "near_answer",
    "newton",
    "searched_from",
    "solve_near",
    "sweep_seeds",
]

FloatArray = NDArray[np.float64]
Solve = Callable[[Chain, FloatArray, "IKOptions"], "IKResult | IKBatchResult"]

#: What the answers' ``method`` says.
METHOD = "analytic:near-rank-5"
#: Values of a swept joint, evenly across its turn.
SWEEP_SAMPLES = 24
#: Joints swept, those that move most along the near-null direction at the search's
#: point (the direction turns from one solution to another: one joint that moves much at
#: one may barely move at the next).
SWEEP_JOINTS = 2
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
#: Newton steps from each guess (quadratic convergence: a guess within reach settles in
#: 4-6).
NEWTON_STEPS = 12
#: Newton stops when every component of the pose error is below this (m, rad): a tenth
#: of the default tolerance, round-off's reach.
NEWTON_DONE = 1e-11


def searched_from(chain: Chain, seeds: FloatArray, T: FloatArray, options: IKOptions) -> FloatArray:
    """``(k, 6)`` the solutions the search reaches from each of ``seeds`` alone (no restarts)."""
    from kinematica.ik.numeric import numeric_solver
    from kinematica.ik.solvers import POSE_WEIGHTS, check_options
    from kinematica.ik.tolerance import parse_tolerance

    if not len(seeds):
        return np.zeros((0, 6))
    tol = parse_tolerance(options.tol)
    setup = numeric_solver(chain, tol, False, 0, POSE_WEIGHTS)[0]
    opts = check_options(tol, False, False, POSE_WEIGHTS)
    poses = np.ascontiguousarray(np.broadcast_to(T, (len(seeds), 4, 4)))
    raw = setup.quick.ik_batch(chain.core, poses, opts, np.ascontiguousarray(seeds), None, 1)
    Q = raw.q[:, 0]
    return Q[np.isfinite(Q).all(axis=1)]


def newton(chain: Chain, seeds: FloatArray, T: FloatArray) -> FloatArray:
    """``(k, 6)`` each of ``seeds (k, 6)`` after :data:`NEWTON_STEPS` Newton steps on the pose.

    Full (undamped) steps, the pose error's position (m) and rotation vector (rad) against
    the geometric Jacobian, solved by least squares: along the near-continuum the step is
    Newton's on the virtual angle's zero, however small σ6.
    """
    from kinematica.spatial import rotvec_from_matrix

    out = np.array(seeds, dtype=np.float64).reshape(-1, 6)
    for q in out:
        for _ in range(NEWTON_STEPS):
            F = chain.fk(np.ascontiguousarray(q))[0]
            e = np.concatenate([T[:3, 3] - F[:3, 3], rotvec_from_matrix(T[:3, :3] @ F[:3, :3].T)])
            if not np.isfinite(e).all() or np.abs(e).max() < NEWTON_DONE:
                break
            J = chain.jacobian(np.ascontiguousarray(q))[0]
            q += np.linalg.lstsq(J, e, rcond=None)[0]
    return out


def sweep_seeds(
    chain: Chain, joint: int, T: FloatArray, options: IKOptions, solve: Solve
) -> FloatArray:
    """``(k, 6)`` guesses of the solutions from the sweep of ``joint`` (see the module).

    Every configuration of every sample, and between two adjacent samples, for each of
    the first's configurations and the one of the second nearest it (the held joint's
    step and the others' change, wrapped), where their virtual angles θ change sign,
    the configuration interpolated linearly at θ = 0.
    """
    step = 2.0 * math.pi / SWEEP_SAMPLES
    samples: list[tuple[FloatArray, FloatArray]] = []
    for t in -math.pi + step * np.arange(SWEEP_SAMPLES):
        got = next(iter(virtual_solutions(chain, joint, float(t), T, options, solve)), None)
        samples.append((np.zeros((0, 6)), np.zeros(0)) if got is None else (got[0], got[1]))
    seeds = [Q for Q, _ in samples]
    for k in range(SWEEP_SAMPLES):
        (Qa, ta), (Qb, tb) = samples[k], samples[(k + 1) % SWEEP_SAMPLES]
        if not len(Qa) or not len(Qb):
            continue
        for qa, th_a in zip(Qa, ta, strict=True):
            d = np.remainder(Qb - qa + math.pi, 2.0 * math.pi) - math.pi
            b = int(np.argmin(np.abs(d).max(axis=1)))
            th_b = float(math.remainder(tb[b], 2.0 * math.pi))
            th_a = float(math.remainder(th_a, 2.0 * math.pi))
            if th_a * th_b > 0.0 or abs(th_a - th_b) > math.pi:
                continue
            w = th_a / (th_a - th_b)
            seeds.append((qa + w * d[b])[None])
    return np.concatenate(seeds) if seeds else np.zeros((0, 6))


def _distinct(chain: Chain, Q: FloatArray, tol: float) -> FloatArray:
    """The rows of ``Q (k, 6)`` but those as close to an earlier one as either is determined.

    A solution is determined to about ``tol`` (m) over σ6 of its Jacobian (m/rad, lengths
    of the arm's size): within that of an earlier row, or within SAME_TOL, it is that row.
    """
    if not len(Q):
        return Q
    size = max(features(chain).size, 1e-300)
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


def near_answer(
    chain: Chain,
    five: RankFive,
    closed: ClosedForm | None,
    T: FloatArray,
    options: IKOptions,
    solve: Solve,
) -> IKResult:
    """Every solution the sweep along the near-continuum finds for the pose ``T (4, 4)``.

    Args:
        chain: The 6R arm, near one of rank 5 everywhere (:func:`rank_five`, not exact).
        five: Its structure.
        closed: The general 6R's closed form of the arm, where it was built (its
            candidates are guesses too); else None.
        T: ``(4, 4)`` the target (base frame, m).
        options: The call's settings (``tol``, ``respect_limits``, ``seed``; ``q0``
            orders the solutions).
        solve: ``solve_ik``.
    """
    from kinematica.ik.tolerance import parse_tolerance

    tol = parse_tolerance(options.tol)
    searched = solve(chain, T, dataclasses.replace(options, method="numeric", q0=None))
    assert isinstance(searched, IKResult)
    found = np.concatenate([searched.solutions, searched.out_of_limits])
    start = found[0] if len(found) else np.random.default_rng(0).uniform(-math.pi, math.pi, 6)
    n = free_motion(chain, start, five.rank)
    joints = [int(j) for j in np.argsort(-n)[:SWEEP_JOINTS]]
    seeds = [found, *(sweep_seeds(chain, j, T, options, solve) for j in joints)]
    if closed is not None:
        C = np.asarray(closed.params.candidates(chain.core, T, None)[0])
        seeds.append(C[np.isfinite(C).all(axis=1)])
    guesses = np.concatenate(seeds)
    Q = np.concatenate([newton(chain, guesses, T), searched_from(chain, guesses, T, options)])
    if five.ratio <= CONTINUUM_RATIO:  # within round-off of a continuum: its points count too
        Q = np.concatenate([Q, guesses])
    Q = np.remainder(Q + math.pi, 2.0 * math.pi) - math.pi  # (wrapped first: then judged)
    err = pose_residuals(chain, Q, T)
    Q = _distinct(chain, Q[(err[:, 0] <= tol.position) & (err[:, 1] <= tol.rotation)], tol.position)
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
        "to about the tolerance over σ6; they were found by sweeping "
        f"{' and '.join(f'q{j + 1}' for j in joints)} over {SWEEP_SAMPLES} values each, every "
        "one solved in closed form with a "
        "virtual joint at the tool, and taken to the arm by a local search; more may exist"
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
            f"points of them found by sweeping {' and '.join(f'q{j + 1}' for j in joints)} over "
            f"{SWEEP_SAMPLES} values each, every one solved in closed form with a virtual "
            "joint at the tool"
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


def solve_near(
    chain: Chain,
    five: RankFive,
    closed: ClosedForm | None,
    targets: Targets,
    options: IKOptions,
    solve: Solve,
) -> IKResult | IKBatchResult:
    """:func:`near_answer` of each pose target (one, or a batch of any shape)."""
    return solve_each(lambda T, o: near_answer(chain, five, closed, T, o, solve), targets, options)
