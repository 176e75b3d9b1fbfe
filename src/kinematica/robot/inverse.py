"""A robot's inverse kinematics: ``robot.ik``, one door into :func:`kinematica.ik.door.solve`."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import TYPE_CHECKING, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.robot.kinematics import RobotKinematics

# The IK layer loads when a method first needs it: a robot that only answers FK
# (`kinematica fk`) never imports it.
if TYPE_CHECKING:
    from kinematica.ik import IKBatchResult, IKOptions, IKResult, Tolerance
    from kinematica.ik.request import HeldCall, IKRequest, Q0Call

__all__ = ["RobotIK"]

FloatArray = NDArray[np.float64]


#: ``(IKRequest.parse, solve, check_given, lean_q0, Q0Call)``, once the IK layer is loaded
#: (:func:`_door`).
_Door = tuple[
    Callable[..., "IKRequest | HeldCall | Q0Call"],
    Callable[..., "IKResult | IKBatchResult"],
    Callable[..., None],
    Callable[..., "IKResult | None"],
    type,
]
_DOOR: _Door | None = None


def _door() -> _Door:
    """The IK layer's door, loaded when a robot first solves IK (``kinematica fk`` never does)."""
    global _DOOR
    from kinematica.ik.door import lean_q0, solve
    from kinematica.ik.request import IKRequest, Q0Call
    from kinematica.robot.given import check_given  # degrees given for radians?

    _DOOR = (IKRequest.parse, solve, check_given, lean_q0, Q0Call)
    return _DOOR


class RobotIK(RobotKinematics):
    """A robot's kinematics with its inverse kinematics (see :class:`~kinematica.Robot`)."""

    def ik(
        self,
        target: ArrayLike,
        *,
        method: Literal["auto", "analytic", "numeric"] = "auto",
        respect_limits: bool = True,
        q0: ArrayLike | None = None,
        mask: ArrayLike | None = None,
        seed: int | np.random.Generator | None = None,
        tol: float | tuple[float, float] | Tolerance | None = None,
        workers: int | None = None,
        precision: tuple[float, float] | None = None,
        fixed: Mapping[int | str, float] | None = None,
        arm_angle: ArrayLike | None = None,
        options: IKOptions | None = None,
    ) -> IKResult | IKBatchResult:
        """Every inverse-kinematics solution of a target, or an honest status.

        Args:
            target: A pose ``(4, 4)`` (tool in the base frame), a position
                ``(3,)`` (tool origin; orientation free), or batches of any
                shape ``(..., 4, 4)`` / ``(..., 3)``. A rotation orthonormal
                to within ``PROJECTION_TOL`` (2e-4: any copy with 4 decimals)
                is projected onto SO(3), with a note in the result.
            method: ``"auto"`` (closed form when the structure allows, else
                numeric, with a note saying why), ``"analytic"`` or ``"numeric"``.
                The numeric search is local: it gives one solution, where more may
                exist (``complete`` False).
            respect_limits: Keep solutions outside the joint limits apart
                (``out_of_limits``) rather than among ``solutions``.
            q0: ``(n,)`` or ``(..., n)``: the numeric initial guess, and the
                configuration solutions are sorted by distance to.
            mask: ``(6,)`` weights of the error components x, y, z, rx, ry, rz
                (numeric only); e.g. ``[1, 1, 1, 0, 0, 1]``.
            seed: Seed of the numeric restarts (a whole number or a Generator).
            tol: Acceptance tolerance: one number for both, or a pair
                (position m, rotation rad); default 1e-10 m and 1e-10 rad.
            workers: Threads for a batch (None: the library default).
            precision: For a pose target of an arm with fewer than 6 joints
                (over-determined): ``(position m, rotation entries)``, half a
                unit in the last digit its numbers were printed with; None: read
                from their digits. The closest configuration answers a target
                it reproduces to that precision (a note says which was assumed).
            fixed: ``{joint: value}``: every solution with that joint held at the
                value (rad or m; the joint by its 0-based index, its name, or
                ``"qN"``); the status is relative to it and ``result.parameter``
                names it. A value outside the joint's limits is an error unless
                ``respect_limits=False``. Without it, ``method="auto"`` on a
                7-joint arm holds a joint whose locked arm has a closed form (at
                q0's value, else the middle of its limits) and says which; see
                :mod:`kinematica.ik.redundancy`.
            arm_angle: For an SRS 7R arm (iiwa type): the arm angle (rad) of the
                solutions, one value or one per target; all 8 solutions at it
                (see :mod:`kinematica.ik.analytic.srs` and :meth:`arm_angle`).
            options: All of the above as one :class:`~kinematica.ik.IKOptions`
                (then give none of them as keywords).

        Returns:
            An :class:`IKResult` for one target, an :class:`IKBatchResult`
            (arrays with the targets' batch shape) for a batch. In a batch, a
            malformed target gets the status ``"invalid"``; the others are solved.
        """
        parse, solve, check_given, lean_q0, q0_call = _DOOR or _door()
        request = parse(method, tol, respect_limits, q0, mask, seed, workers, precision, fixed,
                        arm_angle, options)  # fmt: skip
        if request.__class__ is q0_call:  # one core call where q0 needs no word of warning
            got = lean_q0(self.chain, target, request)
            if got is not None:
                return got
        if request.given:
            check_given(self, request.q0, request.fixed, request.arm_angle)
        return solve(self.chain, target, request, self.joint_names)

    def arm_angle(self, q: ArrayLike) -> FloatArray:
        """The arm angle (rad) of configurations of an SRS 7R arm (iiwa type).

        The parameter of ``ik(T, arm_angle=...)``: the angle about the line from
        the shoulder centre to the wrist centre from the plane through that line
        and axis 1 to the plane of the elbow (:mod:`kinematica.ik.analytic.srs`).

        Args:
            q: ``(..., 7)`` joint angles (rad).

        Returns:
            ``(...)`` angles in (-π, π]; NaN where undefined (the elbow stretched
            or folded onto the shoulder-wrist line, or that line along axis 1).

        Raises:
            KinematicaError: The arm is not an SRS 7R arm.
        """
        from kinematica.ik.analytic.srs import arm_angle

        return arm_angle(self.chain, self.check_q(q))
