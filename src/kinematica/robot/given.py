"""Values given to IK and self-motion checked for units as forward kinematics checks q.

``robot.fk(q)`` warns of a configuration beyond a joint's own limits, and of a free
revolute joint beyond a full turn (degrees given to the radian API?). The same
values given as ``q0``, ``fixed=``, ``arm_angle=`` or ``self_motion(values=)`` get
the same warnings, named after the argument.
"""

from __future__ import annotations

import re
import warnings
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike

from kinematica.errors import UnitWarning
from kinematica.io.plausible import PLAUSIBLE_ANGLE, check_angle

if TYPE_CHECKING:
    from kinematica.robot.kinematics import RobotKinematics

__all__ = ["check_given", "check_joint_values"]

_Q_NAME = re.compile(r"q([1-9][0-9]*)")
_FLOAT64 = np.dtype(np.float64)
#: Where a warning of check_given points: the caller of robot.ik (check_given, ik, caller).
_STACK = 3


def _joint(robot: RobotKinematics, key: Any) -> int | None:
    """The 0-based joint a key names (index, ``"qN"`` or a joint name), or None."""
    if isinstance(key, int | np.integer) and not isinstance(key, bool):
        return int(key) if 0 <= int(key) < robot.dof else None
    if isinstance(key, str):
        m = _Q_NAME.fullmatch(key)
        if m is not None and int(m.group(1)) <= robot.dof:
            return int(m.group(1)) - 1
        if key in robot.joint_names:
            return robot.joint_names.index(key)
    return None


def check_joint_values(
    robot: RobotKinematics, key: Any, values: ArrayLike, name: str, stacklevel: int = _STACK
) -> None:
    """Warn (:class:`UnitWarning`) of values of a free revolute joint beyond a full turn.

    ``stacklevel``: as :func:`warnings.warn`'s, from this function (3: its caller's caller).
    """
    from kinematica.ik.arm_angle import ARM_ANGLE_NAMES  # loaded by the solver anyway

    j = _joint(robot, key)
    angle = isinstance(key, str) and key.strip().lower() in ARM_ANGLE_NAMES
    if not angle and (j is None or robot.chain.prismatic[j] or robot._own[j]):
        return  # a joint's own limits judge its values (the solver says so)
    try:
        a = np.asarray(values, dtype=float).ravel()
    except (TypeError, ValueError):
        return  # not numbers: the solver's own check says so
    with np.errstate(invalid="ignore"):
        beyond = a[np.isfinite(a) & (np.abs(a) > PLAUSIBLE_ANGLE)]
    if beyond.size:
        text = check_angle(float(beyond[0]))
        what = "the arm angle" if angle or j is None else f"joint {j + 1}"
        warnings.warn(f"{name}: {what} = {text}", UnitWarning, stacklevel=stacklevel)


def check_given(
    robot: RobotKinematics, q0: ArrayLike | None, fixed: Mapping[Any, float] | None, arm_angle: Any
) -> None:
    """Warn of ``q0``, ``fixed`` and ``arm_angle`` values as ``fk`` warns of ``q``."""
    if (
        type(q0) is np.ndarray
        and q0.dtype is _FLOAT64
        and q0.shape == robot._single
        and robot.chain.core.fk(q0)[1] == 0
    ):
        q0 = None  # finite, within its own limits, no free joint beyond a turn: nothing to say
    if q0 is not None:
        try:
            qa = np.asarray(q0, dtype=float)
        except (TypeError, ValueError):
            qa = None  # not numbers: the solver's own check says so
        if qa is not None and qa.ndim and qa.shape[-1] == robot.dof:
            own, qlim = robot._own, robot.chain.qlim  # read-only: not copied
            flat = qa.reshape(-1, robot.dof)
            with np.errstate(invalid="ignore"):
                outside = own & ((flat < qlim[:, 0]) | (flat > qlim[:, 1]))
            count = int(np.sum(outside.any(axis=-1)))
            if count:
                warning = robot._limits_message(qa, "q0", count)
                warnings.warn(warning, stacklevel=_STACK)
            robot._check_turns(qa, "q0")
    if fixed is not None and (type(fixed) is dict or isinstance(fixed, Mapping)):
        for key, value in fixed.items():
            check_joint_values(robot, key, value, "fixed", _STACK + 1)
    if arm_angle is not None:
        try:
            psi = np.asarray(arm_angle, dtype=float).ravel()
        except (TypeError, ValueError):
            return
        with np.errstate(invalid="ignore"):
            beyond = psi[np.isfinite(psi) & (np.abs(psi) > PLAUSIBLE_ANGLE)]
        if beyond.size:
            text = check_angle(float(beyond[0]))
            warnings.warn(f"arm_angle: {text}", UnitWarning, stacklevel=_STACK)
