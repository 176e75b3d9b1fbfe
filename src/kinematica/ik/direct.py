"""One pose of a redundant arm at one value of its parameter, straight to the core.

``robot.ik(T, fixed={k: v})``, ``robot.ik(T, arm_angle=psi)`` and ``robot.ik(T)`` of a
7-joint arm (``auto`` holds its parameter: :mod:`kinematica.ik.redundancy`), for one
pose rigid to round-off with every other setting at its default, as a 6R arm's one
pose goes (``Robot._fast``): the solver the general path picks, at the same value,
with the same check, giving the same answer field by field
(:func:`~kinematica.ik.parameter.solve_fixed`,
:meth:`~kinematica.ik.arm_angle.ArmAngleParameter.solve`), without the general
path's parsing, options and copies. A joint held at a value is looked up once per
(joint, value): the arm locked there and its :class:`~kinematica.ik.solvers.PoseSolver`
(the first joint's value moves the target instead, :mod:`kinematica.ik.moved`, as
the general path does). Whatever the general path adds to an answer or explains (a
pose not rigid to round-off, an answer that proves nothing, ``auto``'s search over
every joint where the lock finds no solution, a bad key or value) is left to it:
the methods here return None.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from functools import cached_property
from typing import Any

import numpy as np
from numpy.typing import NDArray

import kinematica._core as _core
from kinematica.core import Chain
from kinematica.errors import KinematicaError
from kinematica.ik.arm_angle import ArmAngleParameter
from kinematica.ik.moved import base_move, end_arm
from kinematica.ik.parameter import JointParameter, joint_parameter, locked_chain
from kinematica.ik.reach import needs_proof
from kinematica.ik.redundancy import REDUNDANT_DOF, choose, default_value, held_note
from kinematica.ik.result import CoreAnswer, IKResult, result_of
from kinematica.ik.solvers import PoseSolver, closed_form, pose_solver
from kinematica.ik.stack import widen_answer
from kinematica.spatial import ROUNDOFF_TOL

__all__ = ["HELD_CACHE", "DirectParameter"]

FloatArray = NDArray[np.float64]

#: The (joint, value) pairs an arm keeps ready (:class:`Held`); past it they are
#: made again (a sweep over many values), as the general path makes them.
HELD_CACHE = 16
#: The joints a locked arm keeps for the paths here: a pose's six (fewer: the
#: over-determined arm's own reading, :mod:`kinematica.ik.printed`).
_POSE_DOF = 6
_ARM_ANGLE = ArmAngleParameter()
#: The value types a joint's value is looked up by (a bool is not one: True == 1).
_VALUE_TYPES = (float, int, np.float64)


class Held:
    """A joint held at a value, ready for one pose.

    Plain classes here (a named tuple's class took 0.15 ms to make, at the first
    ``robot.ik`` of a redundant arm).

    Attributes:
        joint: The joint.
        value: Its value, checked (:meth:`JointParameter.check`).
        arm: The arm locked there (the first joint: locked at 0, the target moved).
        solver: The arm's solver for one pose with the default options.
        move: ``(4, 4)`` what a target is multiplied by (the first joint), else None.
    """

    __slots__ = ("arm", "joint", "move", "solver", "value")

    def __init__(
        self,
        joint: JointParameter,
        value: float,
        arm: Chain,
        solver: PoseSolver,
        move: FloatArray | None,
    ) -> None:
        self.joint = joint
        self.value = value
        self.arm = arm
        self.solver = solver
        self.move = move


class _Auto:
    """``auto``'s parameter at its value without q0: held (a joint) or the SRS solver.

    Attributes:
        held: The joint held, or None (the arm angle).
        angle: The SRS closed form's Params at the value, when the arm angle is held.
        value: The value.
        note: The note of the answers.
    """

    __slots__ = ("angle", "held", "note", "value")

    def __init__(self, held: Held | None, angle: Any, value: float, note: str) -> None:
        self.held = held
        self.angle = angle
        self.value = value
        self.note = note


def _rigid(pose: FloatArray) -> bool:
    """The pose is a rigid transform to round-off, as ``parse_targets`` reads it silently."""
    finite, last, ortho, det = _core.pose_defects(pose)
    return bool(finite and ortho <= ROUNDOFF_TOL and last == 0.0 and det > 0.0)


class DirectParameter:
    """The one-pose paths of one arm at one parameter value (built once per robot).

    Args:
        chain: The arm.
        names: Its joints' display names (as ``result.parameter`` names them).
    """

    def __init__(self, chain: Chain, names: Sequence[str]) -> None:
        self._chain = chain
        self._names = tuple(names)
        self._held: dict[tuple[int | str, float], Held] = {}

    def fixed(self, pose: FloatArray, fixed: object) -> IKResult | None:
        """``robot.ik(pose, fixed={key: value})``, or None (the general path answers).

        Args:
            pose: ``(4, 4)`` float target.
            fixed: As ``robot.ik`` takes it; a dict of one joint (its 0-based index
                or a name) and a value within its limits is answered here.
        """
        if type(fixed) is not dict or len(fixed) != 1:
            return None
        ((key, value),) = fixed.items()
        kind = type(key)  # before the look-up: True == 1 and hash(True) == hash(1)
        if (kind is not int and kind is not str) or type(value) not in _VALUE_TYPES:
            return None
        held = self._held.get((key, value))
        if held is None:
            chain = self._chain
            if chain.dof - 1 < _POSE_DOF:
                return None
            try:
                joint = joint_parameter(chain, key, self._names)
                held = self._hold(joint, joint.check(chain, value))
            except KinematicaError:
                return None  # the general path says what is wrong
            if len(self._held) >= HELD_CACHE:
                self._held.clear()
            self._held[key, value] = held
        if not held.solver.complete and held.arm.dof == _POSE_DOF:
            return None  # no closed form there: perhaps a continuum (held_continuum)
        return self._at_joint(pose, held, ())

    def arm_angle(self, pose: FloatArray, value: object) -> IKResult | None:
        """``robot.ik(pose, arm_angle=value)`` of an SRS arm, or None (the general path).

        Args:
            pose: ``(4, 4)`` float target.
            value: One finite number (rad).
        """
        if type(value) not in _VALUE_TYPES:
            return None
        v = float(value)  # type: ignore[arg-type]
        srs = self._srs
        if srs is None or not math.isfinite(v):
            return None
        return self._at_angle(pose, srs[0].at(v), v, ())

    def auto(self, pose: FloatArray) -> IKResult | None:
        """``robot.ik(pose)`` of a 7-joint arm: every solution at ``auto``'s parameter value.

        None where the general path answers: an arm ``auto`` holds nothing of, and a
        pose without a solution at that value (it searches every joint then).
        """
        plan = self._auto
        if plan is None:
            return None
        if plan.held is not None:
            res = self._at_joint(pose, plan.held, (plan.note,))
        else:
            res = self._at_angle(pose, plan.angle, plan.value, (plan.note,))
        return res if res is not None and res.count else None

    # ---------------------------------------------------------------- the paths
    def _at_joint(self, pose: FloatArray, held: Held, notes: tuple[str, ...]) -> IKResult | None:
        """Every solution with the joint at its value, as ``JointParameter.solve`` gives it."""
        fast = held.solver
        if not fast.direct:
            return None
        target = pose
        if held.move is not None:  # the base turned by the value: the target moved
            if not _rigid(pose):
                return None
            target = held.move @ pose
        out: CoreAnswer | None = fast.ik_rigid(
            held.arm.core, target, fast.options, ROUNDOFF_TOL, fast.labels
        )
        if out is None or needs_proof(out[-1][0], out[-1][1]):
            return None  # not rigid to round-off, or proving nothing: the general path
        v = held.value
        k = held.joint.index
        return result_of(
            *widen_answer(out, k, v),
            fast.method,
            fast.complete,
            (*fast.notes, *notes),  # the search's note first, as the general path has it
            (held.joint.name, v),
        )

    def _at_angle(
        self, pose: FloatArray, params: Any, v: float, notes: tuple[str, ...]
    ) -> IKResult | None:
        """All 8 solutions at the arm angle ``v`` (``params``: the closed form at it)."""
        assert self._srs is not None
        fast = self._srs[1]
        core = self._chain.core
        out: CoreAnswer | None = params.ik_rigid(
            core, pose, fast.options, ROUNDOFF_TOL, fast.labels
        )
        if out is None or needs_proof(out[-1][0], out[-1][1]):
            return None
        return result_of(*out, fast.method, fast.complete, notes, (_ARM_ANGLE.name, v))

    # ---------------------------------------------------------------- made once
    def _hold(self, joint: JointParameter, v: float) -> Held:
        """``joint`` held at ``v``: the arm and target move ``JointParameter.solve`` uses."""
        chain = self._chain
        if joint.index == 0:  # the first joint: the arm locked at 0 serves every value
            arm, G, G_inv = end_arm(chain, 0)
            return Held(joint, v, arm, pose_solver(arm), base_move(chain.prismatic[0], G, G_inv, v))
        arm = locked_chain(chain, joint.index, v)
        return Held(joint, v, arm, pose_solver(arm), None)

    @cached_property
    def _srs(self) -> tuple[Any, PoseSolver] | None:
        """The SRS closed form's ``Params`` and its one-pose settings, or None (not SRS)."""
        closed = closed_form(self._chain, "pose", "arm_angle")
        if closed is None:
            return None
        fast = pose_solver(self._chain, "pose", "arm_angle")
        return (closed.params, fast) if fast.direct else None

    @cached_property
    def _auto(self) -> _Auto | None:
        """``auto``'s parameter held at its value without q0, with its note; None: none."""
        chain = self._chain
        joint = choose(chain, self._names) if chain.dof == REDUNDANT_DOF else None
        if joint is None:
            return None
        value, why = default_value(chain, joint)
        note = held_note(chain, joint, value, why)
        if isinstance(joint, JointParameter):
            return _Auto(self._hold(joint, value), None, value, note)
        if isinstance(joint, ArmAngleParameter) and self._srs is not None:
            return _Auto(None, self._srs[0].at(value), value, note)
        return None
