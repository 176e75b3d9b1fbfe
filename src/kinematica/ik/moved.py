"""The arms a held joint leaves, kept by the chain; the first or last joint's, moved targets.

A joint held at a value leaves a locked arm (:meth:`kinematica.core.Chain.locked`),
built once per value and kept (:func:`locked_chain`). For the first and last joints
one serves every value (:func:`end_arm`): the first joint's value only turns (or
slides) the base, the last's only the tool, so the arm locked at 0 takes each target
moved instead (``T' = G₀ M(v)⁻¹ G₀⁻¹ T`` for the first joint, ``T G⁻¹ M(v)⁻¹ G`` for
the last, ``G₀`` the chain's start, ``G`` its last fixed part times the tool). The
first joint's move keeps distances and angles: the same problem; so does the last
joint's where the tool point is on its axis (:func:`on_axis`, the makers' 7R arms).
Else the last joint's moves the tool point, and the locked arm is checked against a
narrower position tolerance (:func:`narrowed_tolerance`).
"""

from __future__ import annotations

import math
from collections import OrderedDict
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

import kinematica._core as _core
from kinematica.core import Chain
from kinematica.ik.rank_five import RANK_FIVE_HELD, held_rank_five
from kinematica.ik.result import IKResult
from kinematica.ik.solve import answered
from kinematica.ik.solvers import plan_of
from kinematica.ik.stack import widen_result
from kinematica.ik.tolerance import parse_tolerance

if TYPE_CHECKING:
    from kinematica.ik.request import IKRequest

__all__ = [
    "LOCKED_CACHE",
    "NARROWEST",
    "ON_AXIS_TOL",
    "end_arm",
    "held_at",
    "held_completed",
    "held_prepared",
    "lever",
    "locked_chain",
    "move_parts",
    "moved_targets",
    "narrowed_tolerance",
    "on_axis",
]

FloatArray = NDArray[np.float64]

#: The least share of the position tolerance a target moved past the last joint may
#: be held to (:func:`narrowed_tolerance`); below it (with equal position and rotation
#: tolerances: the tool point moved by more than 0.5 m) the targets are solved on one
#: locked arm per value instead.
NARROWEST = 0.5
#: How far from the last joint's axis the tool point may lie (m) for the last joint's
#: value to move the target without moving the tool point (:func:`on_axis`): round-off
#: of a tool transform read from a file.
ON_AXIS_TOL = 1e-12


#: Locked arms kept per chain, least recently used first out (a sweep over a middle
#: joint's values builds one per value; the first and last joints' are kept apart,
#: :func:`end_arm`).
LOCKED_CACHE = 16


def locked_chain(chain: Chain, joint: int, value: float) -> Chain:
    """``chain.locked(joint, value)``, built once and kept (:data:`LOCKED_CACHE` per chain).

    An arm of rank 5 whatever the value (:func:`~kinematica.ik.rank_five.held_rank_five`)
    is marked so (:data:`RANK_FIVE_HELD` in its memo).
    """
    if value == 0.0 and joint in (0, chain.dof - 1):
        return end_arm(chain, joint)  # the first or last joint's: kept apart
    per: OrderedDict[tuple[int, float], Chain]
    per = chain.memo.setdefault("locked arms", OrderedDict())  # type: ignore[assignment]
    key = (joint, float(value))
    found = per.get(key)
    if found is None:
        found = per[key] = chain.locked(joint, value)
        if held_rank_five(chain, joint) is not None:
            found.memo[RANK_FIVE_HELD] = True
        if len(per) > LOCKED_CACHE:
            per.popitem(last=False)
    else:
        per.move_to_end(key)
    return found


def end_arm(chain: Chain, k: int) -> Chain:
    """The arm with its first (k = 0) or last joint locked at 0, made once per chain."""
    return _end(chain, k)[0]


def move_parts(chain: Chain, k: int) -> tuple[FloatArray, bool]:
    """``(A, after)``: the parts ``(3, 4, 4)`` of the move of a held first (k = 0) or last joint.

    A pose T of the whole arm, the joint at v, is the target ``M(v) T`` (first) or
    ``T M(v)`` (last, ``after``) of :func:`end_arm`'s arm, ``M(v) = A₀ + f₁ A₁ + f₂ A₂``
    (``km::moved_pose``, ``cpp/include/kinematica/moved.hpp``).
    """
    return _end(chain, k)[1], k != 0


def _end(chain: Chain, k: int) -> tuple[Chain, FloatArray]:
    """:func:`end_arm` and ``(3, 4, 4)`` the move's parts ``A``, made once per chain.

    ``M(v)⁻¹ = E₀ + f₁(v) E₁ + f₂(v) E₂`` (``f = (cos v, sin v)`` for a turn about z,
    ``(-v, 0)`` for a slide along it), so the move is ``A₀ + f₁ A₁ + f₂ A₂`` with
    ``A_i = G E_i G⁻¹`` before the target (k = 0) or ``G⁻¹ E_i G`` after it; ``G`` the
    chain's start (k = 0), or its last fixed part times the tool.
    """
    per: dict[int, tuple[Chain, FloatArray]]
    per = chain.memo.setdefault("end arms", {})  # type: ignore[assignment]
    found = per.get(k)
    if found is None:
        G = np.array(chain.start if k == 0 else chain.fixed_parts[-1] @ chain.tool)
        G_inv = np.eye(4)
        G_inv[:3, :3] = G[:3, :3].T
        G_inv[:3, 3] = -G[:3, :3].T @ G[:3, 3]
        E = np.zeros((3, 4, 4))
        if chain.prismatic[k]:
            E[0] = np.eye(4)
            E[1, 2, 3] = 1.0
        else:
            E[0, 2, 2] = E[0, 3, 3] = E[1, 0, 0] = E[1, 1, 1] = E[2, 0, 1] = 1.0
            E[2, 1, 0] = -1.0
        A = G @ E @ G_inv if k == 0 else G_inv @ E @ G
        found = per[k] = (chain.locked(k, 0.0), A)
    return found


def on_axis(chain: Chain) -> bool:
    """Whether the last joint turns about an axis through the tool point.

    Then ``T G⁻¹ M(v)⁻¹ G`` keeps the target's position (``G``'s translation is on the
    axis ``M`` turns about): a target moved past the last joint is the same problem,
    checked against the same tolerance, whatever the value (:data:`ON_AXIS_TOL`).
    """
    found = chain.memo.get("tool on last axis")
    if found is None:
        G = chain.fixed_parts[-1] @ chain.tool
        found = chain.memo["tool on last axis"] = not bool(chain.prismatic[-1]) and bool(
            math.hypot(G[0, 3], G[1, 3]) <= ON_AXIS_TOL
        )
    return bool(found)


def moved_targets(chain: Chain, k: int, poses: FloatArray, v: FloatArray) -> FloatArray:
    """``(N, 4, 4)`` targets of the arm locked at 0 that are ``poses`` with joint k at ``v``."""
    A = _end(chain, k)[1]
    v = np.asarray(v, dtype=float)
    return _core.moved_poses(A, poses, v, k != 0, bool(chain.prismatic[k]))


def held_prepared(chain: Chain, k: int, request: IKRequest, name: str) -> Any:
    """The arm locked at 0 at end joint k made ready for one pose at any value, or None.

    The plan's prepared call of that arm (:attr:`~kinematica.ik.solvers.Plan.prepared`,
    for ``request``'s settings) held at joint k (``Prepared.held``): called as
    ``at(T, value)``, the core moves the pose by the value, solves and checks it, and
    gives the whole arm's result (the joint's column put back, ``parameter`` ``(name,
    value)``), else the locked arm's answer to complete (:func:`held_at`); None for a pose
    to read otherwise. None where the plan has no core's prepared call (a coaxial pair,
    rank 5, the numeric search).
    Made once per chain, settings, joint and name.
    """
    per: dict[tuple[int | None, int, str], Any]
    per = chain.memo.setdefault("held prepared", {})  # type: ignore[assignment]
    key = (request.key, k, name)
    found = per.get(key, per)
    if found is per:
        if len(per) >= LOCKED_CACHE:
            per.clear()
        arm, A = _end(chain, k)
        ready = plan_of(arm, "pose", request).prepared  # the search's is Python's: not held
        slides = bool(chain.prismatic[k])
        held = type(ready) is _core.Prepared
        found = per[key] = ready.held(k, A, k != 0, slides, name) if held else None
    return found


def held_at(
    chain: Chain,
    k: int,
    name: str,
    request: IKRequest,
    ready: Any,
    T: object,
    value: float,
    q0: FloatArray | None = None,
) -> IKResult | None:
    """One pose ``T`` with end joint k at ``value``: ``ready``'s (:func:`held_prepared`) call.

    The core's final answer is the result; any other is completed as the arm locked at 0
    completes its answers (:func:`~kinematica.ik.solve.answered`: the search where its
    closed form found nothing, the limited reach), then widened. ``q0``: the whole arm's
    ``(n,)`` (its solutions sorted nearest it), or None. None where ``ready`` is None or
    the core does not read ``T`` as one rigid pose, or ``q0`` as finite values.
    """
    got = None if ready is None else ready.at(T, value, q0)
    if got is None or got.__class__ is IKResult:
        return got
    return held_completed(chain, k, name, request, T, value, got, q0)


def held_completed(
    chain: Chain,
    k: int,
    name: str,
    request: IKRequest,
    T: object,
    value: float,
    got: Any,
    q0: FloatArray | None = None,
) -> IKResult:
    """:func:`held_at`'s answer from the core's answer ``got`` to complete (not a result)."""
    arm = _end(chain, k)[0]
    pose = moved_targets(chain, k, np.asarray(T)[None], np.array([value]))[0]
    locked = None if q0 is None else np.delete(q0, k)
    res = answered(arm, plan_of(arm, "pose", request), request, pose, "pose", got, (), locked)
    return widen_result(res, k, value, (name, value))


def narrowed_tolerance(
    tol: object, chain: Chain, k: int, v: FloatArray
) -> tuple[float, float] | None:
    """The position tolerance a target moved past the last joint is held to, or None.

    The arm's pose is ``F = L Y⁻¹`` for the locked arm's ``L`` checked against
    ``T Y``: its position error is at most the locked arm's plus its rotation error
    times ``|t_Y|`` (``(I - R) x`` is at most ``θ |x|``), so ``P - R max|t_Y|``
    keeps every accepted solution within ``P`` of the real target. None when that
    leaves less than :data:`NARROWEST` of ``P`` (solve those targets as they are).

    Args:
        tol: The tolerance as ``robot.ik`` takes it (None: the defaults).
        chain: The arm.
        k: Its last joint's index.
        v: ``(N,)`` the values the targets are moved by.

    Returns:
        ``(position m, rotation rad)``, or None.
    """
    given = parse_tolerance(tol)  # type: ignore[arg-type]
    position = given.position - given.rotation * lever(chain, k, v)
    return (position, given.rotation) if position >= NARROWEST * given.position else None


def lever(chain: Chain, k: int, v: FloatArray) -> float:
    """``max |t_Y|`` (m) over the values ``v`` ``(N,)`` of the last joint (index ``k``).

    A target moved past the last joint is ``T Y`` (:func:`moved_targets`); a pose within
    ``(P, R)`` of ``T`` is within ``(P + R |t_Y|, R)`` of ``T Y`` (the error conjugated by
    ``Y``: ``(I - R) t_Y`` is at most ``θ |t_Y|``). 0 with the tool point on the axis.
    """
    if not v.size:
        return 0.0
    Y = moved_targets(chain, k, np.broadcast_to(np.eye(4), (v.size, 4, 4)), v)
    return float(np.linalg.norm(Y[:, :3, 3], axis=1).max())
