"""A joint held where the arm left is nearly a continuum: its solutions along the self-motion.

Holding the elbow of a 7R arm that is SRS but for offsets of micrometres (the Realman
RM75) or a fraction of a millimetre (rtb-data's iiwa 14 URDF) leaves a 6R arm that
is nearly a continuum: the exact SRS arm reaches the pose along the whole circle of
its arm angle, and the offsets break that circle into a few isolated solutions, each
determined in its joints only to round-off over σ6/σ1 of the arm's Jacobian there
(1e-13..1e-7). No elimination of the general 6R is accurate on such an arm (every
labelling misses its probes by 1e-6..1e-3 rad), and the numeric search would give
one solution of several.

**The method.** The 7R arm's own self-motion at the pose, followed by a closed form:
an end joint s (the first, else the last) is held at values t across its turn, each
arm so left solved by its closed form for every solution (one locked arm for all t,
the targets moved: :meth:`~kinematica.ik.parameter.JointParameter.solve`), and the
solutions of adjacent samples are linked into branches (each to the nearest, within
:data:`SWEEP_JUMP`). Along a branch the held joint's value q_k(t) varies smoothly (by
the offsets' size on a near-continuum); a solution of the held arm is a t where
q_k(t) equals the value held. Each sign change of q_k(t) - value between adjacent
samples is narrowed by regula falsi (Illinois) on t, every step a closed-form
solve, and the configuration found is taken to the held arm's solution by the core's
repair (the check's damped Gauss-Newton, :func:`repaired`), kept when its forward
kinematics meets the tolerance.

This is a one-dimensional search with every sub-problem in closed form: a branch
that touches the value without crossing it between two samples (a tangency), or
folds back between them, can be missed, so the answer is never marked complete,
and the note gives the arm's conditioning σ6/σ1 at the solutions found: the solution
set is a near-continuum, and the rows are exact (forward kinematics within the
tolerance) but determined only to about the tolerance over σ6 in the joints.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

import kinematica._core as _core
from kinematica.core import Chain
from kinematica.ik.result import IKBatchResult, IKResult
from kinematica.ik.stack import pose_residuals
from kinematica.ik.status import IKStatus

if TYPE_CHECKING:
    from kinematica.ik.options import IKOptions
    from kinematica.ik.registry import ClosedForm
    from kinematica.ik.tolerance import Tolerance

__all__ = [
    "HUG_G",
    "MAX_CROSSINGS",
    "ROOT_STEPS",
    "ROUNDOFF_G",
    "SAME_TOL",
    "SWEEP_JUMP",
    "SWEEP_SAMPLES",
    "SWEEP_TRIES",
    "TOUCH_G",
    "crossings",
    "held_sweep",
    "polished",
    "repaired",
    "sweep_joints",
    "sweep_result",
    "touches",
]

FloatArray = NDArray[np.float64]
Hold = Callable[[int, FloatArray, "FloatArray | float", "IKOptions"], "IKResult | IKBatchResult"]

#: Values of the swept joint over its turn (every 5°).
SWEEP_SAMPLES = 72
#: Two solutions of adjacent samples are one branch when no joint differs by more (rad):
#: :data:`kinematica.robot.self_motion.MAX_JUMP`'s value, for the same sampling.
SWEEP_JUMP = 0.5
#: A branch whose held joint is within this of the value at two adjacent samples (on
#: either side) is taken to the held arm's solution by the repair from a sample,
#: without narrowing: the held arm is a continuum to within round-off over σ6 there
#: (rad; rtb-data's iiwa URDF with q4 at 0: the branches stay within 1e-10 of it).
HUG_G = 1e-9
#: More crossings than this (the general 6R's most solutions) along a sweep are not
#: isolated solutions but a continuum within round-off: none is narrowed, and the
#: samples nearest the value are the repair's starts.
MAX_CROSSINGS = 16
#: A branch's sample nearer the value than its neighbours (on the same side) and within
#: this of it (rad) is the repair's start for a solution where the branch touches the value.
TOUCH_G = 1e-3
#: Regula falsi steps on the swept joint's value, at most.
ROOT_STEPS = 16
#: Joints tried as the sweep's (those moving most along the near-continuum), at most.
SWEEP_TRIES = 2
#: Two solutions whose joints all differ by less than this are one (rad).
SAME_TOL = 1e-6
#: A branch whose held joint is within this of the value at two adjacent samples keeps
#: it all along (an exact continuum, the held_continuum module's): one point of it is
#: the sweep's answer, for that module's test (rad).
ROUNDOFF_G = 1e-12


def _wrap(x: FloatArray | float) -> FloatArray:
    return np.remainder(np.asarray(x) + math.pi, 2.0 * math.pi) - math.pi


def _solutions(res: IKResult | IKBatchResult, i: int | None) -> FloatArray:
    """``(k, n)`` every solution of target i of a batch (or of one result)."""
    if isinstance(res, IKResult):
        return np.concatenate([res.solutions, res.out_of_limits])
    q = res.raw.q[i]
    return np.asarray(q[np.isfinite(q).all(axis=1)])


def sweep_joints(locked: Chain, joint: int, q: FloatArray | None) -> tuple[int, ...]:
    """The whole arm's joints to sweep, best first: those that move most along the near-continuum.

    At a solution ``q (7,)`` of the held arm (the search's), the right singular vector
    of its Jacobian's smallest singular value is the near-continuum's direction; its
    largest entries name the joints that move most along it. Then the end joints (one
    locked arm serves every value), and without q every other joint.
    """
    order: list[int] = []
    if q is not None and np.isfinite(q).all():
        J = locked.jacobian(np.ascontiguousarray(np.delete(q, joint)))[0]
        v = np.linalg.svd(J)[2][-1]
        order = [int(j) + (int(j) >= joint) for j in np.argsort(-np.abs(v))[:SWEEP_TRIES]]
    for end in (0, locked.dof):
        if end != joint and end not in order:
            order.append(end)
    if q is None or not np.isfinite(q).all():  # no direction known: the middle joints too
        order += [j for j in range(1, locked.dof) if j != joint and j not in order]
    return tuple(order)


def held_sweep(
    chain: Chain,
    joint: int,
    value: float,
    T: FloatArray,
    options: IKOptions,
    hold: Hold,
    q: FloatArray | None = None,
) -> tuple[FloatArray, str, str] | None:
    """The held arm's solutions found along the self-motion, or None (no end joint to sweep).

    Args:
        chain: The 7R arm.
        joint: The held joint (0-based).
        value: Its value (rad).
        T: ``(4, 4)`` the target (base frame, m).
        options: The call's settings (``tol``).
        hold: ``(s, target(s), value(s), options)``: the whole arm's answer with joint s
            held at the value (one per target): ``JointParameter(s).solve``.
        q: ``(7,)`` a solution of the held arm (the search's), which names the joints to
            sweep (:func:`sweep_joints`); None: the end joints.

    Returns:
        ``(solutions (k, 7), method, note)``: every solution found (the held joint at
        ``value``, forward kinematics within the tolerance), the closed form the sweep
        stood on, and what the answer says of it.
    """
    from kinematica.ik.moved import locked_chain
    from kinematica.ik.solvers import closed_form
    from kinematica.ik.tolerance import parse_tolerance

    if chain.dof != 7 or bool(chain.prismatic.any()):
        return None
    tol = parse_tolerance(options.tol)
    opts = dataclasses.replace(
        options, q0=None, fixed=None, arm_angle=None, mask=None, respect_limits=False
    )
    locked = chain.locked(joint, value)
    sweeps: dict[int, ClosedForm | None]
    sweeps = chain.memo.setdefault("sweep closed forms", {})  # type: ignore[assignment]
    for s in sweep_joints(locked, joint, q):
        if s not in sweeps:  # once per chain and joint (a locked arm's cache turns over)
            sweeps[s] = closed_form(locked_chain(chain, s, 0.0), "pose")
        closed = sweeps[s]
        if closed is None:
            continue
        grid = np.linspace(-math.pi, math.pi, SWEEP_SAMPLES, endpoint=False)

        def at(t: float, s: int = s) -> FloatArray:
            return _solutions(hold(s, T, float(t), opts), None)

        batch = hold(s, np.broadcast_to(T, (SWEEP_SAMPLES, 4, 4)).copy(), grid, opts)
        rows = [_solutions(batch, i) for i in range(SWEEP_SAMPLES)]
        seeds = crossings(rows, grid, joint, value, at)
        found = polished(locked, joint, value, seeds, T, tol.position, tol.rotation)
        if not len(found):
            continue
        ratio = _conditioning(locked, np.delete(found, joint, axis=1))
        note = (
            f"with q{joint + 1} held at {value:.6g} the arm left is nearly a continuum "
            f"(σ6/σ1 of its Jacobian {ratio:.1e} at these solutions: each meets the "
            "tolerance but is determined in its joints only to about the tolerance over "
            f"σ6): found along the self-motion by holding q{s + 1} at {SWEEP_SAMPLES} values "
            f"across its turn, each solved by the closed form ({closed.name}), and the "
            f"values where q{joint + 1} crosses {value:.6g} narrowed; a branch touching "
            "that value between two samples may be missed"
        )
        return found, f"sweep:{closed.name}", note
    return None


def crossings(
    rows: list[FloatArray],
    grid: FloatArray,
    joint: int,
    value: float,
    at: object,
) -> list[FloatArray]:
    """Configurations where a branch's held joint crosses ``value``, narrowed on t."""
    seeds: list[FloatArray] = []
    brackets: list[tuple[float, float, FloatArray, FloatArray, float, float]] = []
    n = len(grid)
    step = 2.0 * math.pi / n
    for i in range(n):
        here, there = rows[i], rows[(i + 1) % n]
        if not len(here) or not len(there):
            continue
        t0 = float(grid[i])
        for x in here:
            d = np.abs(_wrap(there - x)).max(axis=1)
            j = int(np.argmin(d))
            if d[j] > SWEEP_JUMP:
                continue
            y = there[j]
            gx, gy = float(_wrap(x[joint] - value)), float(_wrap(y[joint] - value))
            if max(abs(gx), abs(gy)) <= ROUNDOFF_G:  # held all along: a continuum, one point
                return [x]
            if abs(gx) > 1.0 or abs(gy) > 1.0 or gx * gy > 0.0:
                continue
            if max(abs(gx), abs(gy)) <= HUG_G:  # the branch hugs the value: the repair's from x
                seeds.append(x)
                continue
            brackets.append((t0, t0 + step, x, y, gx, gy))
    seeds += touches(rows, joint, value)
    if len(brackets) > MAX_CROSSINGS:  # crossing everywhere: a continuum within round-off
        return seeds + [b[2] if abs(b[4]) <= abs(b[5]) else b[3] for b in brackets][:MAX_CROSSINGS]
    return seeds + [_narrowed(*b, joint, value, at) for b in brackets]


def touches(rows: list[FloatArray], joint: int, value: float) -> list[FloatArray]:
    """Samples where a branch comes nearest the value without crossing it (within TOUCH_G).

    A branch that touches the value between samples (the held arm's solutions there a
    double root) has no sign change to narrow: its sample nearest the value is
    the repair's start, and the repair on the held arm decides whether a solution
    is there.
    """
    seeds: list[FloatArray] = []
    n = len(rows)

    def match(x: FloatArray, there: FloatArray) -> FloatArray | None:
        if not len(there):
            return None
        d = np.abs(_wrap(there - x)).max(axis=1)
        j = int(np.argmin(d))
        return there[j] if d[j] <= SWEEP_JUMP else None

    for i in range(n):
        for x in rows[i]:
            g = float(_wrap(x[joint] - value))
            if abs(g) > TOUCH_G:
                continue
            before, after = match(x, rows[i - 1]), match(x, rows[(i + 1) % n])
            if before is None or after is None:
                continue
            gb, ga = float(_wrap(before[joint] - value)), float(_wrap(after[joint] - value))
            if gb * g > 0.0 and ga * g > 0.0 and abs(g) <= min(abs(gb), abs(ga)):
                seeds.append(x)
    return seeds


def _narrowed(
    ta: float,
    tb: float,
    xa: FloatArray,
    xb: FloatArray,
    ga: float,
    gb: float,
    joint: int,
    value: float,
    at: object,
) -> FloatArray:
    """The branch's configuration where its held joint is ``value`` (Illinois on t)."""
    assert callable(at)
    best = xa if abs(ga) <= abs(gb) else xb
    side = 0
    for _ in range(ROOT_STEPS):
        if ga == 0.0 or gb == 0.0 or tb - ta <= 1e-15:
            break
        t = (ta * gb - tb * ga) / (gb - ga)
        w = (t - ta) / (tb - ta)
        guess = xa + w * _wrap(xb - xa)
        Q = at(t)
        if not len(Q):
            break
        x = Q[int(np.argmin(np.abs(_wrap(Q - guess)).max(axis=1)))]
        g = float(_wrap(x[joint] - value))
        best = x if abs(g) < abs(float(_wrap(best[joint] - value))) else best
        if g * ga > 0.0:
            ta, xa, ga = t, x, g
            if side == -1:
                gb *= 0.5
            side = -1
        else:
            tb, xb, gb = t, x, g
            if side == 1:
                ga *= 0.5
            side = 1
        if abs(g) <= ROUNDOFF_G:  # the repair on the held arm does the rest
            break
    return np.asarray(best)


def repaired(
    arm: Chain, T: FloatArray, Q: FloatArray, tol: Tolerance
) -> tuple[FloatArray, NDArray[np.bool_]]:
    """The rows of ``Q (m, n)`` taken by the core's repair to ``T``, and which meet ``tol``.

    The check's repair (``cpp/include/kinematica/check.hpp``: Gauss-Newton steps damped
    by the residual, the best point kept), for every row whatever its residual
    (``_core.repair_candidates``). ``T``: ``(4, 4)``, or ``(m, 4, 4)`` one per row.

    Returns:
        ``(m, n)`` the rows reached, and ``(m,)`` True where forward kinematics there
        meets the tolerance.
    """
    from kinematica.ik.solvers import POSE_WEIGHTS, check_options

    opts = check_options(tol, False, False, POSE_WEIGHTS)
    targets = np.ascontiguousarray(np.broadcast_to(T, (len(Q), 4, 4)))
    rows = np.ascontiguousarray(np.reshape(Q, (len(Q), arm.dof)), dtype=float)
    out, res = _core.repair_candidates(arm.core, targets, rows, opts)
    return out, (res[:, 0] <= tol.position) & (res[:, 1] <= tol.rotation)


def polished(
    locked: Chain,
    joint: int,
    value: float,
    seeds: list[FloatArray],
    T: FloatArray,
    tol_position: float,
    tol_rotation: float,
) -> FloatArray:
    """``(k, 7)`` the seeds (held joint put at its value) repaired on the held arm, distinct.

    Each is taken to the held arm's solution by the core's repair (:func:`repaired`)
    and kept when its forward kinematics meets the tolerance.
    """
    from kinematica.ik.tolerance import Tolerance

    if not len(seeds):
        return np.zeros((0, locked.dof + 1))
    Q = np.delete(np.array(seeds, dtype=float).reshape(len(seeds), -1), joint, axis=1)
    out, ok = repaired(locked, T, Q, Tolerance(tol_position, tol_rotation))
    found: list[FloatArray] = []
    for q in out[ok]:
        full = _wrap(np.insert(q, joint, value))
        full[joint] = value
        if all(np.abs(_wrap(full - o)).max() > SAME_TOL for o in found):
            found.append(full)
    return np.array(found).reshape(-1, locked.dof + 1)


def _conditioning(locked: Chain, Q: FloatArray) -> float:
    """The smallest σ6/σ1 of the held arm's Jacobian at the rows of Q."""
    J = locked.jacobian(np.ascontiguousarray(Q))[0]
    s = np.linalg.svd(J, compute_uv=False)
    return float(np.min(s[:, -1] / s[:, 0]))


def sweep_result(
    chain: Chain,
    found: FloatArray,
    method: str,
    note: str,
    T: FloatArray,
    respect_limits: bool,
    parameter: tuple[str, float],
) -> IKResult:
    """The held arm's answer from the sweep's solutions (``found (k, 7)``)."""
    lo, hi = chain.qlim[:, 0], chain.qlim[:, 1]
    inside = (
        np.all((found >= lo) & (found <= hi), axis=1)
        if respect_limits
        else np.ones(len(found), dtype=bool)
    )
    residuals = pose_residuals(chain, found, T)
    k = int(inside.sum())
    return IKResult(
        solutions=found[inside],
        status=IKStatus.OK if k else IKStatus.OUT_OF_LIMITS,
        method=method,
        residuals=residuals[inside],
        branches=tuple(f"along the self-motion #{i + 1}" for i in range(k)),
        out_of_limits=found[~inside],
        out_of_limits_branches=tuple(
            f"along the self-motion #{k + i + 1}" for i in range(len(found) - k)
        ),
        notes=(note,),
        complete=False,
        near_singular=True,
        parameter=parameter,
    )
