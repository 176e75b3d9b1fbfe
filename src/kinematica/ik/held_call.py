"""``robot.ik(T, fixed={joint: value})`` of one pose, a new value on every call: one core call.

``robot.ik`` reads such a call into a :class:`~kinematica.ik.request.HeldCall` (the request
of its other settings, kept, and the joint and value as given); :func:`held_one` reads the
joint once per chain and checks the value as :func:`~kinematica.ik.fixed.solve_fixed`
does, and the arm its lock leaves answers in one core call
(:meth:`~kinematica.ik.parameter.JointParameter.lean`). Any other call, or an answer that
is not final, goes :func:`~kinematica.ik.fixed.solve_fixed`'s way.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from kinematica.core import Chain
from kinematica.ik.fixed import joint_parameter
from kinematica.ik.moved import LOCKED_CACHE, held_at
from kinematica.ik.parameter import JointParameter
from kinematica.ik.request import HeldCall
from kinematica.ik.result import IKResult

__all__ = ["held_one"]


def held_one(
    chain: Chain, target: object, call: HeldCall, names: tuple[str, ...] | None
) -> IKResult | None:
    """``robot.ik(T, fixed={joint: value})`` of one pose as one core call, or None.

    The joint is read once per chain, settings and key; its value is checked as
    :func:`~kinematica.ik.fixed.solve_fixed` checks it (a number within the limits
    passes as it is). None where the joint's lock has no lean call
    (:meth:`~kinematica.ik.parameter.JointParameter.lean`) or the target is not one pose
    as the core reads it: the general path answers.
    """
    q0 = call.q0  # the whole arm's (n,), or None
    if chain.dof < 7 or target.__class__ is not np.ndarray:
        return None
    if q0 is not None and q0.shape != (chain.dof,):  # the general path explains it
        return None
    memo: dict[tuple[object, ...], tuple[JointParameter, Any, float, float, bool]]
    memo = chain.memo.setdefault("held calls", {})  # type: ignore[assignment]
    key = (call.request.key, call.joint, call.joint.__class__, names)
    try:
        found = memo.get(key)
    except TypeError:  # an unhashable key: the general path refuses it
        return None
    if found is None:
        joint = joint_parameter(chain, call.joint, names)
        lo, hi = joint.span(chain)
        kept = joint.prismatic or bool(np.isfinite(chain.own_limits[joint.index]).any())
        if len(memo) >= LOCKED_CACHE:
            memo.clear()
        found = memo[key] = (joint, joint.lean(chain, call.request), lo, hi, kept)
    joint, ready, lo, hi, kept = found
    if ready is None:
        return None
    v = call.value
    if not (kept and v.__class__ is float and lo <= v <= hi):
        v = joint.check(chain, v, bool(call.request.respect_limits))
    return held_at(chain, joint.index, joint.name, call.request, ready, target, v, q0)
