"""6R arms of rank 5 everywhere: every pose they reach is reached along a continuum.

An arm of :mod:`kinematica.ik.rank_five` (four concurrent or four parallel axes, a
spherical shoulder and wrist, three parallel axes and three concurrent) has no
isolated solutions: through each solution runs a curve of configurations (the
self-motion, along the Jacobian's null direction) with the same tool pose. The
honest answer is ``singular``, with the joints that move along it named, and
representatives: points of the continua, each exact.

**The method.** The search (:mod:`kinematica.ik.numeric`) finds one point q* of a
continuum (or nothing). The joint j that moves most along the self-motion there is
held at its value ``q*_j``: the 5R arm left is regular at q* (the held joint's column
was the one the null direction needed), so its solutions are isolated, and the
closed form of the 6R arm made by a virtual joint at the tool
(:func:`kinematica.ik.coaxial.with_virtual_joint`, as for a coaxial pair) gives every
one of them: the representatives are every configuration of the arm with ``q_j =
q*_j`` that reaches the pose, one on each branch of the continua through that value
(the search's among them).

This was preferred to a closed form per structure (the shoulder-wrist arm's turn about
the line through its centres, the planar chain of the parallel axes): one method for
every arm of rank 5, whatever makes it so, whose accuracy is the closed form's. It does
not prove that every continuum passes through ``q_j = q*_j`` (a continuum along which
joint j keeps within a narrower range may not), so the answer is marked incomplete.

**Poses out of reach.** Where the structure keeps one quantity of the pose fixed (the
distance between a spherical shoulder's and wrist's centres; the wrist centre's height
along three parallel axes), a target whose value misses it by more than the tolerance
carried to it is ``unreachable``, proved (:mod:`kinematica.ik.rank_five_reach`), before
any search.

**Which solutions are kept.** As for the coaxial pair: a solution of the virtual arm is
put on the real arm with θ dropped and ``q_j`` put back, and kept when its forward
kinematics meets the target within the call's tolerance.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Iterator
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from kinematica.core import Chain
from kinematica.ik.coaxial import VIRTUAL_LINES, frame_on, with_virtual_joint
from kinematica.ik.rank_five import FREE_TOL, RankFive, free_motion, rank_five
from kinematica.ik.rank_five_reach import invariant_miss
from kinematica.ik.result import IKBatchResult, IKResult
from kinematica.ik.stack import pose_residuals, solve_each
from kinematica.ik.status import IKStatus
from kinematica.ik.structure import features

if TYPE_CHECKING:
    from kinematica.ik.options import IKOptions
    from kinematica.ik.targets import Targets

__all__ = [
    "DUPLICATE_TOL",
    "METHOD",
    "continuum_answer",
    "distinct",
    "exact_rank_five",
    "held_solutions",
    "solve_continuum",
    "virtual_solutions",
]

FloatArray = NDArray[np.float64]
Solve = Callable[[Chain, FloatArray, "IKOptions"], "IKResult | IKBatchResult"]

#: What the answers' ``method`` says.
METHOD = "analytic:rank-5"
#: Two representatives are one when every joint agrees to this (rad, modulo 2π): the
#: closed forms give a solution to round-off over the arm's conditioning (1e-12 rad and
#: better on the arms of the tests), and distinct representatives differ by far more.
DUPLICATE_TOL = 1e-9


def held_solutions(
    chain: Chain, joint: int, value: float, T: FloatArray, options: IKOptions, solve: Solve
) -> tuple[FloatArray, bool] | None:
    """Every configuration with joint ``joint`` at ``value`` that reaches ``T``, and whether all.

    Args:
        chain: The 6R arm.
        joint: The held joint (0-based).
        value: Its value (rad).
        T: ``(4, 4)`` the target (base frame, m).
        options: The call's settings (``tol``; limits are not applied here).
        solve: ``solve_ik``.

    Returns:
        ``((k, 6) configurations, complete)``: the rows meet the target within the call's
        tolerance on the real arm; ``complete`` when the virtual arm's closed form gave
        every solution it has. None when no virtual arm has a closed form.
    """
    from kinematica.ik.tolerance import parse_tolerance

    tol = parse_tolerance(options.tol)
    first: tuple[FloatArray, bool] | None = None
    for Q, _, decided in virtual_solutions(chain, joint, value, T, options, solve):
        err = pose_residuals(chain, Q, T)
        Q = Q[(err[:, 0] <= tol.position) & (err[:, 1] <= tol.rotation)]
        if decided:
            return Q, True
        if first is None or len(Q) > len(first[0]):
            first = (Q, False)
    return first


def virtual_solutions(
    chain: Chain, joint: int, value: float, T: FloatArray, options: IKOptions, solve: Solve
) -> Iterator[tuple[FloatArray, FloatArray, bool]]:
    """Per virtual line with a closed form: the virtual arm's solutions on the real arm.

    The arm with joint ``joint`` held at ``value`` and a virtual joint at the tool
    (:func:`~kinematica.ik.coaxial.with_virtual_joint`, about each of
    :data:`~kinematica.ik.coaxial.VIRTUAL_LINES`) is solved in closed form; each
    solution is put on the real arm (``(k, 6)``: θ dropped, ``value`` put back), with
    its θ (``(k,)``, rad) and whether that closed form gave every solution it has (a
    complete answer away from a singular set). The rows reach T where θ is 0. A virtual
    arm still of rank 5, or near one (the held joint did not break the self-motion), is
    passed over: it is not regular, and its own answer would come back here.
    """
    from kinematica.ik.solvers import closed_form

    locked = chain.locked(joint, value)
    limits = np.array(locked.own_limits, dtype=np.float64)
    size = features(chain).size
    opts = dataclasses.replace(
        options, q0=None, fixed=None, arm_angle=None, mask=None, respect_limits=False
    )
    for direction, point in VIRTUAL_LINES:
        W = frame_on(np.array(direction), size * np.array(point))
        arm = with_virtual_joint(locked, W, limits)
        if closed_form(arm, "pose") is None or rank_five(arm) is not None:
            continue
        res = solve(arm, T, opts)
        assert isinstance(res, IKResult)
        found = np.concatenate([res.solutions, res.out_of_limits])
        Q = np.insert(found[:, :5], joint, value, axis=1) if len(found) else np.zeros((0, 6))
        decided = (
            res.complete
            and str(res.status) in (IKStatus.OK, IKStatus.UNREACHABLE)
            and not res.near_singular
        )
        yield Q, found[:, 5] if len(found) else np.zeros(0), decided


def continuum_answer(
    chain: Chain, five: RankFive, T: FloatArray, options: IKOptions, solve: Solve
) -> IKResult:
    """Representatives of the continua reaching the pose ``T (4, 4)``, or why none.

    Args:
        chain: The 6R arm, of rank 5 everywhere (:func:`rank_five`).
        five: Its structure.
        T: ``(4, 4)`` the target (base frame, m).
        options: The call's settings (``tol``, ``respect_limits``, ``seed``; ``q0``
            starts the search and orders the representatives).
        solve: ``solve_ik``.
    """
    from kinematica.ik.tolerance import parse_tolerance

    tol = parse_tolerance(options.tol)
    why = f"{five.structure}: the arm has rank {five.rank} at every configuration"
    miss = invariant_miss(chain, five, T, tol.position, tol.rotation)
    if miss is not None:  # proved out of reach by what the structure keeps fixed
        return IKResult(
            solutions=np.zeros((0, 6)),
            status=IKStatus.UNREACHABLE,
            method=METHOD,
            residuals=np.zeros((0, 2)),
            branches=(),
            out_of_limits=np.zeros((0, 6)),
            out_of_limits_branches=(),
            notes=(f"{why}: {miss.note()}: no configuration reaches this pose",),
        )
    searched = solve(chain, T, dataclasses.replace(options, method="numeric"))
    assert isinstance(searched, IKResult)
    found = np.concatenate([searched.solutions, searched.out_of_limits])
    if not len(found):
        status = (
            IKStatus.UNREACHABLE
            if str(searched.status) == IKStatus.UNREACHABLE
            else IKStatus.NOT_FOUND
        )
        note = (
            f"{why}, and reaches only a {five.rank}-dimensional set of poses; the search "
            "found no configuration reaching this one"
            + ("" if status == IKStatus.NOT_FOUND else " (beyond the reach within the limits)")
            + ": nothing more was proven"
        )
        return dataclasses.replace(
            searched, status=status, method=METHOD, notes=(note,), complete=False
        )
    q = found[0]
    n = free_motion(chain, q, five.rank)
    free = tuple(j for j in range(6) if abs(float(n[j])) > FREE_TOL)
    reps, held = q[None], None
    for j in sorted(free, key=lambda j: -abs(float(n[j]))):
        got = held_solutions(chain, j, float(q[j]), T, options, solve)
        if got is not None and len(got[0]):
            reps, held = got[0], j
            break
    reps = _within_turn(chain, reps)
    inside = _inside(chain, reps) if options.respect_limits else np.ones(len(reps), dtype=bool)
    Q, outside = reps[inside], reps[~inside]
    if options.q0 is not None and len(Q):
        Q = Q[np.argsort(np.linalg.norm(Q - np.asarray(options.q0, dtype=float), axis=1))]
    if not len(Q) and not len(outside):  # the closed forms lost the search's own point
        Q = q[None]
    err = pose_residuals(chain, Q, T)
    keep = (err[:, 0] <= tol.position) & (err[:, 1] <= tol.rotation)
    Q, err = Q[keep], err[keep]
    joints = ", ".join(str(j + 1) for j in free)
    how = (
        "the search's point, the one representative found (no arm with one of them held "
        "has a closed form)"
        if held is None
        else f"its representatives with q{held + 1} at {float(q[held]):.6g}, where the search "
        f"met it, every one the closed form of the arm with q{held + 1} held gives (a "
        "continuum not passing through that value is not represented)"
    )
    note = (
        f"{why}, and reaches this pose along a continuum (joints {joints} move together): "
        f"the solutions given are {how}"
    )
    return IKResult(
        solutions=Q,
        status=IKStatus.SINGULAR if len(Q) else IKStatus.OUT_OF_LIMITS,
        method=METHOD,
        residuals=err,
        branches=tuple(f"representative #{k + 1}" for k in range(len(Q))),
        out_of_limits=outside,
        out_of_limits_branches=tuple(
            f"representative #{len(Q) + k + 1}" for k in range(len(outside))
        ),
        free_joints=free,
        notes=(note,),
        complete=False,
    )


def _within_turn(chain: Chain, Q: FloatArray) -> FloatArray:
    """``Q (k, 6)`` with joints without limits of their own wrapped to (-π, π]; duplicates out."""
    own = chain.own_limits
    free = ~(np.isfinite(own[:, 0]) | np.isfinite(own[:, 1]))
    out = np.array(Q, dtype=np.float64)
    out[:, free] = np.remainder(out[:, free] + math.pi, 2.0 * math.pi) - math.pi
    return distinct(out, DUPLICATE_TOL)


def distinct(Q: FloatArray, tol: float) -> FloatArray:
    """The rows of ``Q (k, 6)`` but those within ``tol`` (rad, modulo 2π) of an earlier one."""
    kept: list[FloatArray] = []
    for row in Q:
        if not any(
            np.max(np.abs(np.remainder(row - k + math.pi, 2 * math.pi) - math.pi)) <= tol
            for k in kept
        ):
            kept.append(row)
    return np.array(kept).reshape(-1, Q.shape[1])


def _inside(chain: Chain, Q: FloatArray) -> NDArray[np.bool_]:
    """``(k,)`` True where each row of ``Q (k, 6)`` keeps within the joints' limits."""
    lim = chain.qlim
    return np.asarray(((lim[:, 0] <= Q) & (lim[:, 1] >= Q)).all(axis=1), dtype=np.bool_)


def solve_continuum(
    chain: Chain, five: RankFive, targets: Targets, options: IKOptions, solve: Solve
) -> IKResult | IKBatchResult:
    """:func:`continuum_answer` of each pose target (one, or a batch of any shape)."""
    return solve_each(lambda T, o: continuum_answer(chain, five, T, o, solve), targets, options)


def exact_rank_five(chain: Chain) -> RankFive | None:
    """The arm's rank-5 structure where it is exact (a continuum at every pose), else None."""
    five = rank_five(chain)
    return five if five is not None and five.exact else None
