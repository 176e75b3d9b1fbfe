"""``robot.ik``'s one door: :func:`solve` takes every target and setting.

``Robot.ik`` reads its settings into an :class:`~kinematica.ik.request.IKRequest`
(:meth:`~kinematica.ik.request.IKRequest.parse`) and hands it here with the target. A
redundant arm with a parameter to hold (``fixed=``, ``arm_angle=``, or ``auto`` on a
7-joint arm) goes to :func:`kinematica.ik.redundancy.solve_arm`, which holds it and
solves the arm the lock leaves; every other arm to :func:`kinematica.ik.solve.solve_ik`.
Either way the targets are solved by ``solve_ik``'s one path; one pose target as the
core reads it, with nothing held, goes straight to the plan's prepared call
(:attr:`~kinematica.ik.solvers.Plan.prepared`), which gives its result; with ``q0``,
``robot.ik`` tries that call first (:func:`lean_q0`).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.core import Chain
from kinematica.ik.request import HeldCall, IKRequest, Q0Call
from kinematica.ik.result import IKBatchResult, IKResult
from kinematica.ik.solve import REDUNDANT_DOF, answered, solve_ik
from kinematica.ik.solvers import Plan

__all__ = ["lean_q0", "solve"]

FloatArray = NDArray[np.float64]


def solve(
    chain: Chain,
    target: ArrayLike,
    request: IKRequest | HeldCall | Q0Call,
    names: tuple[str, ...] | None = None,
) -> IKResult | IKBatchResult:
    """``robot.ik``: every inverse-kinematics solution of a target, or an honest status.

    See :meth:`kinematica.Robot.ik` for the arguments and what comes back.

    Args:
        chain: The arm.
        target: As ``robot.ik`` takes it.
        request: The call's settings (:meth:`IKRequest.parse`); a :class:`HeldCall`: one
            joint held at a value, tried as one core call first
            (:func:`kinematica.ik.held_call.held_one`); a :class:`Q0Call`: ``q0`` beside
            the request (its one call is :func:`lean_q0`'s, tried before this).
        names: The joints' display names (``result.parameter`` names a held joint so).
    """
    if type(request) is HeldCall:
        got = (_held_one or _redundancy()[1])(chain, target, request, names)
        if got is not None:
            return got
        request = request.full()
    elif type(request) is Q0Call:  # its one core call: lean_q0, tried first by robot.ik
        request = request.full()
    elif type(request) is IKRequest:
        got = _lean(chain, target, request, None)
        if got is not None:
            return got
    assert type(request) is IKRequest
    if not request.holds and (not request.may_hold or chain.dof != REDUNDANT_DOF):
        return solve_ik(chain, target, request)
    return (_solve_arm or _redundancy()[0])(chain, target, request, names)


def lean_q0(chain: Chain, target: ArrayLike, call: Q0Call) -> IKResult | None:
    """One pose target with ``q0`` by the plan's one call, or None for :func:`solve`.

    The core answers where ``q0`` is ``(n,)`` finite values within the joints' own limits
    and a turn (a ``q0`` of which ``robot.ik`` has nothing to say), the target a rigid
    pose it reads in place and the call's other settings lean; else None, and
    ``robot.ik`` warns of ``q0`` and hands the call to :func:`solve`.
    """
    if call.q0.shape != (chain.dof,):
        return None
    return _lean(chain, target, call.request, call.q0)


def _lean(
    chain: Chain, target: ArrayLike, request: IKRequest, q0: FloatArray | None
) -> IKResult | None:
    """One pose target as the core reads it, by the plan's one call (q0 ``(n,)`` or None).

    None where the request or the plan is not lean, or the core does not read the target
    or q0 as they are: the general path answers.
    """
    lean = request.lean
    if lean is None:
        return None
    plan: Plan | None = chain.memo.get(lean)  # type: ignore[assignment]
    if plan is None or not plan.lean:
        return None
    got = plan.prepared(target, q0)
    if got is None or got.__class__ is IKResult:
        return got
    # an answer to complete (a search, the limited reach)
    return answered(chain, plan, request, target, "pose", got, (), q0)  # type: ignore[arg-type]


#: :func:`kinematica.ik.redundancy.solve_arm` and :func:`kinematica.ik.held_call.held_one`,
#: once loaded (:func:`_redundancy`).
_solve_arm: Any = None
_held_one: Any = None


def _redundancy() -> tuple[Any, Any]:
    """The redundancy layer's doors, loaded when a redundant arm is first solved."""
    global _solve_arm, _held_one
    from kinematica.ik.held_call import held_one
    from kinematica.ik.redundancy import solve_arm

    _solve_arm, _held_one = solve_arm, held_one
    return solve_arm, held_one
