"""A joint held where the arm left reaches every pose along a continuum.

Holding a joint of a 7-joint arm at some values leaves a 6-joint arm with no isolated
solutions at all: the iiwa's or any SRS arm's elbow (q4) held leaves a spherical
shoulder and a spherical wrist, whose distance is then fixed, so every pose it reaches
is reached along the circle of the arm angle; its q2 held at 0 makes axes 1 and 3 one
line, and only q1 + q3 counts. No closed form is built for such an arm (each
elimination degenerates), and the numeric search would answer one point of the
continuum as if it were the answer.

Here the search's point is tested for a self-motion by the general 6R's test in the
core (``general_6r.hpp``, ``self_motion``: the locked arm's Jacobian rank-deficient
there, a step along its null direction, the loop closed again with one joint held).
On a continuum, the answer is ``singular`` with the free joints named, and its
representatives are every solution with the held joint at its value among those of
the arm with the free joint that moved most held at the search point's value instead:
that arm is regular there, and its closed form gives all of them (every branch of the
continuum through that value, not only the search's).
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
from kinematica.ik.result import IKResult
from kinematica.ik.solvers import closed_form
from kinematica.ik.stack import pose_residuals, widen_result
from kinematica.ik.status import IKStatus

if TYPE_CHECKING:
    from kinematica.ik.options import IKOptions

__all__ = ["HELD_MATCH_TOL", "continuum_answer", "holds_value"]

FloatArray = NDArray[np.float64]

#: A representative of the continuum (a solution of the arm with another joint held) has
#: the held joint at its value when they differ by at most this (rad, or m for a slide).
#: That arm is regular there, so its closed form gives the held joint to round-off
#: (within 3.6e-14 on 60 poses of the iiwa and the Panda); the other branches of that
#: arm's solutions have it elsewhere (0.025 rad and more away on those poses).
HELD_MATCH_TOL = 1e-8


def holds_value(q: float, value: float, prismatic: bool) -> bool:
    """True when a joint at ``q`` is at the held ``value`` (HELD_MATCH_TOL; modulo 2π)."""
    d = q - value if prismatic else math.remainder(q - value, 2.0 * math.pi)
    return abs(d) <= HELD_MATCH_TOL


def continuum_answer(
    chain: Chain,
    joint: int,
    value: float,
    name: str,
    T: FloatArray,
    answer: IKResult,
    options: IKOptions,
    lock: Callable[[Chain, int, float], Chain],
    solve: Callable[[Chain, FloatArray, IKOptions], object],
) -> IKResult:
    """``answer`` (the numeric search's, joint ``joint`` held) as a continuum where it is one.

    Args:
        chain: The whole arm.
        joint: The held joint (0-based).
        value: Its value (rad or m).
        name: Its name, as results name the parameter.
        T: ``(4, 4)`` the target (base frame, m).
        answer: The whole arm's answer with the joint held (the search's point in it).
        options: The IK settings of the call.
        lock: ``(chain, joint, value)`` -> the arm with that joint held (the kept one).
        solve: ``(arm, T, options)`` -> its answer (``solve_ik``).

    Returns:
        ``answer`` as it is when its solution is not on a continuum (or none was found);
        else ``singular``: the free joints named and every representative with another
        free joint held at the search point's value.
    """
    found = np.concatenate([answer.solutions, answer.out_of_limits])
    if not len(found):
        return answer
    q = found[0]
    locked = lock(chain, joint, value)
    # the locked arm's joints free along a continuum through its solution, most moved first
    free_locked = tuple(_core.general6r.free_joints(locked.core, T, np.delete(q, joint)))
    if not free_locked:
        return answer
    free = tuple(j if j < joint else j + 1 for j in free_locked)
    # hold the free joint whose locked arm has a closed form (those that moved most first)
    for other in free:
        arm = lock(chain, other, float(q[other]))
        if closed_form(arm, "pose") is None:
            continue
        opts = dataclasses.replace(options, q0=None, fixed=None)
        res = solve(arm, T, opts)
        assert isinstance(res, IKResult)
        wide = widen_result(res, other, float(q[other]), None)
        slide = bool(chain.prismatic[joint])
        keep = [holds_value(float(s[joint]), value, slide) for s in wide.solutions]
        keep_out = [holds_value(float(s[joint]), value, slide) for s in wide.out_of_limits]
        if not any(keep) and not any(keep_out):
            continue
        solutions, exact = _exact(locked, joint, value, wide.solutions[keep], T, options)
        outside, exact_out = _exact(locked, joint, value, wide.out_of_limits[keep_out], T, options)
        if not len(solutions) and not len(outside):
            continue
        residuals = pose_residuals(chain, solutions, T)
        branches = [b for b, k in zip(wide.branches, keep, strict=True) if k]
        out_branches = [b for b, k in zip(wide.out_of_limits_branches, keep_out, strict=True) if k]
        note = (
            f"with {name} held at {value:.6g} the pose is reached along a continuum "
            f"(joints {', '.join(str(j + 1) for j in sorted(free))} move together, the arm left "
            f"has rank 5 all along it): the solutions given are its representatives with "
            f"joint {other + 1} at {float(q[other]):.6g}, where the search met it"
        )
        return IKResult(
            solutions=solutions,
            status=IKStatus.SINGULAR if len(solutions) else IKStatus.OUT_OF_LIMITS,
            method=res.method,
            residuals=residuals,
            branches=tuple(b for b, k in zip(branches, exact, strict=True) if k),
            out_of_limits=outside,
            out_of_limits_branches=tuple(
                b for b, k in zip(out_branches, exact_out, strict=True) if k
            ),
            free_joints=tuple(sorted(free)),
            notes=(note,),
            complete=False,
            parameter=(name, value),
        )
    return answer


def _exact(
    locked: Chain, joint: int, value: float, Q: FloatArray, T: FloatArray, options: IKOptions
) -> tuple[FloatArray, list[bool]]:
    """The rows of ``Q (k, n)`` with the held joint put at its value, each exact; which kept.

    A row whose held joint was off its value by up to HELD_MATCH_TOL misses the target
    by up to that times the arm's size once the joint is put there (1.7e-9 m was seen
    on rtb-data's iiwa URDF with q4 held at 1e-6): such a row is taken by the core's repair
    on the held arm back to the target (:func:`kinematica.ik.held_sweep.polished`),
    and dropped where it cannot be.
    """
    from kinematica.ik.held_sweep import polished
    from kinematica.ik.tolerance import parse_tolerance

    tol = parse_tolerance(options.tol)
    rows: list[FloatArray] = []
    kept: list[bool] = []
    for row in np.array(Q, dtype=float):
        row[joint] = value
        err = pose_residuals(locked, np.ascontiguousarray(np.delete(row, joint))[None], T)[0]
        if not (err[0] <= tol.position and err[1] <= tol.rotation):
            again = polished(locked, joint, value, [row], T, tol.position, tol.rotation)
            if not len(again):
                kept.append(False)
                continue
            row = again[0]
        rows.append(row)
        kept.append(True)
    return np.array(rows).reshape(-1, Q.shape[1]), kept
