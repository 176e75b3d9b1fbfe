"""One pose of a redundant arm at one value of its parameter, straight to the core.

``robot.ik(T, fixed={k: v})``, ``robot.ik(T, arm_angle=psi)`` and ``robot.ik(T)`` of a
7-joint arm (``auto`` holds its parameter: :mod:`kinematica.ik.redundancy`), for one
pose rigid to round-off with every other setting at its default, as a 6R arm's one
pose goes (``Robot._fast``): the solver the general path picks, at the same value,
with the same check, giving the same answer field by field
(:func:`~kinematica.ik.parameter.solve_fixed`,
:meth:`~kinematica.ik.arm_angle.ArmAngleParameter.solve`), without the general
path's parsing, options and copies. A locked arm's
:class:`~kinematica.ik.solve.PoseSolver` is built once per locked chain; the first
joint's value moves the target instead (:mod:`kinematica.ik.moved`), as the general
path does. Whatever the general path adds to an answer or explains (a pose not rigid
to round-off, an answer that proves nothing, ``auto``'s search over every joint where
the lock finds no solution, a bad key or value) is left to it: the methods here
return None.
"""

from __future__ import annotations

import math
import weakref
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
from kinematica.ik.solve import PoseSolver, closed_form, pose_solver
from kinematica.ik.stack import widen_answer
from kinematica.spatial import ROUNDOFF_TOL

__all__ = ["DirectParameter"]

FloatArray = NDArray[np.float64]

_ARM_ANGLE = ArmAngleParameter()
#: ``auto``'s plan: its parameter, the value held without q0, the note, the SRS solver at it.
_Plan = tuple[JointParameter | ArmAngleParameter, float, str, Any]
#: The joints a locked arm keeps for the paths here: a pose's six (fewer: the
#: over-determined arm's own reading, :mod:`kinematica.ik.printed`).
_POSE_DOF = 6

#: The first joint's values whose target move (:func:`~kinematica.ik.moved.base_move`)
#: an arm keeps (a sweep of many values starts again past it).
_MOVES = 16

# One solver per locked arm: a locked arm lives in parameter.LOCKED_CACHE (or in
# moved.end_arm's), and its solver goes with it.
_SOLVERS: weakref.WeakKeyDictionary[Chain, PoseSolver] = weakref.WeakKeyDictionary()


def _solver(arm: Chain) -> PoseSolver:
    """The solver ``solve_ik`` runs on ``arm`` for one pose with the default options."""
    found = _SOLVERS.get(arm)
    if found is None:
        found = _SOLVERS[arm] = pose_solver(arm)
    return found


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
        self._joints: dict[int | str, JointParameter] = {}
        self._moves: dict[float, FloatArray] = {}  # the first joint's value -> base_move

    def fixed(self, pose: FloatArray, fixed: object) -> IKResult | None:
        """``robot.ik(pose, fixed={key: value})``, or None (the general path answers).

        Args:
            pose: ``(4, 4)`` float target.
            fixed: As ``robot.ik`` takes it; a dict of one joint (its 0-based index
                or a name) and a value within its limits is answered here.
        """
        chain = self._chain
        if type(fixed) is not dict or len(fixed) != 1 or chain.dof - 1 < _POSE_DOF:
            return None
        ((key, value),) = fixed.items()
        if type(key) is not int and type(key) is not str:  # True == 1: never a cached key
            return None
        joint = self._joints.get(key)
        try:
            if joint is None:
                joint = self._joints[key] = joint_parameter(chain, key, self._names)
            v = joint.check(chain, value)
        except KinematicaError:
            return None  # the general path says what is wrong
        return self._held(pose, joint, v, ())

    def arm_angle(self, pose: FloatArray, value: object) -> IKResult | None:
        """``robot.ik(pose, arm_angle=value)`` of an SRS arm, or None (the general path).

        Args:
            pose: ``(4, 4)`` float target.
            value: One finite number (rad).
        """
        kind = type(value)
        if kind is not float and kind is not int and kind is not np.float64:
            return None
        v = float(value)  # type: ignore[arg-type]
        srs = self._srs
        if srs is None or not math.isfinite(v):
            return None
        params, fast = srs
        return self._at_angle(pose, params.at(v), fast, v, ())

    def auto(self, pose: FloatArray) -> IKResult | None:
        """``robot.ik(pose)`` of a 7-joint arm: every solution at ``auto``'s parameter value.

        None where the general path answers: an arm ``auto`` holds nothing of, and a
        pose without a solution at that value (it searches every joint then).
        """
        plan = self._auto_plan
        if plan is None:
            return None
        joint, value, note, at = plan
        if isinstance(joint, ArmAngleParameter):
            assert self._srs is not None
            res = self._at_angle(pose, at, self._srs[1], value, (note,))
        else:
            res = self._held(pose, joint, value, (note,))
        return res if res is not None and res.count else None

    # ---------------------------------------------------------------- the paths
    def _held(
        self, pose: FloatArray, joint: JointParameter, v: float, notes: tuple[str, ...]
    ) -> IKResult | None:
        """Every solution with ``joint`` at ``v``, as ``JointParameter.solve`` gives it."""
        chain = self._chain
        k = joint.index
        if k == 0:  # the base turned by the value: the target moved, one locked arm
            if not _rigid(pose):
                return None
            arm, G, G_inv = end_arm(chain, 0)
            move = self._moves.get(v)
            if move is None:
                if len(self._moves) >= _MOVES:
                    self._moves.clear()
                move = self._moves[v] = base_move(chain.prismatic[0], G, G_inv, v)
            target = move @ pose
        else:
            arm, target = locked_chain(chain, k, v), pose
        fast = _solver(arm)
        if not fast.direct:
            return None
        out: CoreAnswer | None = fast.ik_rigid(
            arm.core, target, fast.options, ROUNDOFF_TOL, fast.labels
        )
        if out is None or needs_proof(out[-1][0], out[-1][1]):
            return None  # not rigid to round-off, or proving nothing: the general path
        return result_of(
            *widen_answer(out, k, v), fast.method, fast.complete, notes, (joint.name, v)
        )

    def _at_angle(
        self, pose: FloatArray, params: Any, fast: PoseSolver, v: float, notes: tuple[str, ...]
    ) -> IKResult | None:
        """All 8 solutions at the arm angle ``v`` (``params``: the closed form at it)."""
        core = self._chain.core
        out: CoreAnswer | None = params.ik_rigid(
            core, pose, fast.options, ROUNDOFF_TOL, fast.labels
        )
        if out is None or needs_proof(out[-1][0], out[-1][1]):
            return None
        return result_of(*out, fast.method, fast.complete, notes, (_ARM_ANGLE.name, v))

    @cached_property
    def _srs(self) -> tuple[Any, PoseSolver] | None:
        """The SRS closed form's ``Params`` and its one-pose settings, or None (not SRS)."""
        closed = closed_form(self._chain, "pose", "arm_angle")
        if closed is None:
            return None
        fast = pose_solver(self._chain, "pose", "arm_angle")
        return (closed.params, fast) if fast.direct else None

    @cached_property
    def _auto_plan(self) -> _Plan | None:
        """``auto``'s parameter, its value without q0, its note, and the SRS solver at it."""
        chain = self._chain
        joint = choose(chain, self._names) if chain.dof == REDUNDANT_DOF else None
        if not isinstance(joint, JointParameter | ArmAngleParameter):
            return None
        value, why = default_value(chain, joint)
        at = None
        if isinstance(joint, ArmAngleParameter):
            if self._srs is None:
                return None
            at = self._srs[0].at(value)
        return joint, value, held_note(chain, joint, value, why), at
