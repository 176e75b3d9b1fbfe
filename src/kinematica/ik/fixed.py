"""``robot.ik(T, fixed={joint: value})``: the joint a key names, its value checked, solved.

A key is a 0-based index, the joint's name, or ``"qN"`` (1-based) (:func:`joint_parameter`,
also read by ``robot.self_motion`` and the command line's joint options); the value is
checked against the joint's limits (:meth:`~kinematica.ik.parameter.JointParameter.check`)
and every solution with the joint there is the answer (:func:`solve_fixed`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from kinematica.core import Chain
from kinematica.errors import KinematicaError
from kinematica.ik.parameter import JointParameter, joint_names
from kinematica.ik.result import IKBatchResult, IKResult

if TYPE_CHECKING:
    from kinematica.ik.options import IKOptions

__all__ = ["joint_parameter", "solve_fixed"]


def joint_parameter(
    chain: Chain, key: object, names: Sequence[str] | None = None, arg: str = "fixed"
) -> JointParameter:
    """The joint a key names: a 0-based index, the joint's name, or ``"qN"`` (1-based).

    Args:
        chain: The arm.
        key: The key.
        names: The joints' display names (``q1..qn`` when None).
        arg: The argument messages name.

    Raises:
        KinematicaError: (``arg=arg``) an index out of range, an unknown name,
            or a key of another type; the message lists what is accepted.
    """
    n = chain.dof
    shown = joint_names(chain, names)
    index: int | None = None
    if isinstance(key, int | np.integer) and not isinstance(key, bool):
        if not 0 <= int(key) < n:
            raise KinematicaError(
                f"{arg}: joint index {int(key)} is out of range: 0..{n - 1} (0-based) "
                f"for an arm of {n} joints",
                arg=arg,
            )
        index = int(key)
    elif isinstance(key, str):
        if key in shown:
            index = shown.index(key)
        else:
            q = key.strip().lower()
            if q.startswith("q") and q[1:].isdigit() and 1 <= int(q[1:]) <= n:
                index = int(q[1:]) - 1
        if index is None:
            raise KinematicaError(
                f"{arg}: no joint is named {key!r}: give a 0-based index 0..{n - 1}, "
                f"q1..q{n}, or one of {', '.join(shown)}",
                arg=arg,
            )
    else:
        raise KinematicaError(
            f"{arg}: a joint is named by a 0-based index or a name, got {key!r}", arg=arg
        )
    return JointParameter(index, shown[index], bool(chain.prismatic[index]))


def solve_fixed(
    chain: Chain,
    target: ArrayLike,
    options: IKOptions,
    names: Sequence[str] | None = None,
) -> IKResult | IKBatchResult:
    """``robot.ik(T, fixed={joint: value})``: every solution with that joint held at the value.

    Raises:
        KinematicaError: (``arg="fixed"``) not a mapping of one joint, a bad key or value,
            or an arm of one joint.
    """
    fixed = options.fixed
    if not (type(fixed) is dict or isinstance(fixed, Mapping)) or len(fixed) != 1:
        got = f"{len(fixed)} entries" if isinstance(fixed, Mapping) else repr(fixed)
        raise KinematicaError(
            f"fixed must hold one joint and its value, e.g. {{6: 0.3}}, got {got}", arg="fixed"
        )
    if chain.dof < 2:
        raise KinematicaError(
            "fixed: an arm of one joint has no joint left to solve once it is locked", arg="fixed"
        )
    ((key, value),) = fixed.items()
    joint = joint_parameter(chain, key, names)
    v = joint.check(chain, value, bool(options.respect_limits))
    return joint.solve(chain, target, v, options)
