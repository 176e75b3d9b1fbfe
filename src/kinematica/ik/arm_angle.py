"""An SRS arm's arm angle as its redundancy parameter (for ``auto`` and self-motion).

An SRS 7R arm (iiwa type: axes 1-3 meet at the shoulder, axes 5-7 at the wrist)
holding a pose keeps its shoulder and wrist centres still; its elbow swings on a
circle about the line between them. The arm angle (:func:`kinematica.ik.analytic.srs.arm_angle`)
says where on that circle, and ``robot.ik(T, arm_angle=psi)`` gives all 8
solutions there in closed form. :class:`ArmAngleParameter` is that angle as a
:class:`~kinematica.ik.parameter.Parameter`: the one ``method="auto"`` holds on an
SRS arm (every joint keeps its own range, where holding a joint would not), and
one that :meth:`kinematica.Robot.self_motion` sweeps.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, ClassVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.core import Chain
from kinematica.ik.analytic.srs import arm_angle
from kinematica.ik.at_values import parameter_values
from kinematica.ik.request import IKRequest
from kinematica.ik.result import IKBatchResult, IKResult, amended
from kinematica.ik.solve import solve_ik
from kinematica.ik.solvers import closed_form
from kinematica.ik.targets import parse_targets

__all__ = ["ARM_ANGLE_NAMES", "ArmAngleParameter", "arm_angle_parameter"]

if TYPE_CHECKING:
    from kinematica.ik.options import IKOptions

FloatArray = NDArray[np.float64]

#: The words that name the arm angle where a parameter is asked for (``self_motion``,
#: ``--parameter``): no joint of a robot file may be so named without a clash, and none
#: of the built-in arms' is.
ARM_ANGLE_NAMES = ("arm_angle", "arm angle", "arm-angle", "psi")


@dataclass(frozen=True, slots=True)
class ArmAngleParameter:
    """The arm angle ψ of an SRS 7R arm (rad), as a redundancy parameter."""

    name: str = "arm angle"
    unit: str = "rad"
    #: A value costs its closed form in a batch (about 2 µs) where a round costs about
    #: 130 µs (a request, the targets read, the batch's result): one round of one target
    #: tries every value of the sweep but the few past 64.
    round_values: ClassVar[int] = 64
    keyword: ClassVar[str] = "arm_angle="

    def span(self, chain: Chain) -> tuple[float, float]:
        """``(-π, π)``: every elbow position on its circle, once."""
        return -math.pi, math.pi

    def default(self, chain: Chain) -> float:
        """0: the elbow in the plane of axis 1 and the shoulder-wrist line.

        On the iiwa, the plane of q3 = 0, elbow up.
        """
        return 0.0

    def default_reason(self, chain: Chain) -> str:
        """Where the elbow is at the default, 0."""
        return "0: the elbow in the plane of axis 1 and the shoulder-wrist line"

    def value_of(self, chain: Chain, q: FloatArray) -> FloatArray:
        """``(N,)`` the arm angle of each configuration ``q (N, 7)``."""
        return np.asarray(arm_angle(chain, q), dtype=float).reshape(-1)

    def describe(self, value: float) -> str:
        """``"arm angle = 0.3 rad"``."""
        return f"{self.name} = {value:.6g} {self.unit}"

    def solve(
        self, chain: Chain, target: ArrayLike, values: ArrayLike, options: IKOptions
    ) -> IKResult | IKBatchResult:
        """All 8 solutions of each target at its arm angle (one value, or one per target).

        Args:
            chain: The SRS arm.
            target: As :func:`~kinematica.ik.solve_ik` takes it (pose targets).
            values: One angle, or ``(N,)`` one per target of a batch (C order).
            options: The IK settings (``fixed`` and ``arm_angle`` are replaced).
        """
        if type(values) is float and type(target) is np.ndarray and target.shape == (4, 4):
            one = solve_ik(chain, target, IKRequest.of(options).but(arm_angle=values, fixed=None))
            assert isinstance(one, IKResult)  # one pose: read as the general path reads it
            return amended(one, parameter=(self.name, values))
        targets = parse_targets(target)
        angle: ArrayLike = values
        if isinstance(values, np.ndarray) and values.ndim == 1:
            if targets.single and values.size == 1:
                angle = float(values[0])
            elif not targets.single and values.size == math.prod(targets.shape):
                angle = values.reshape(targets.shape)  # one per target, C order
        opts = IKRequest.of(options).but(arm_angle=angle, fixed=None)
        res = solve_ik(chain, target if targets.single else targets, opts)
        if isinstance(res, IKResult) and type(angle) is float:
            return amended(res, parameter=(self.name, angle))
        given = parameter_values("arm_angle", angle, targets.shape)  # (N,), checked
        if isinstance(res, IKResult):
            return amended(res, parameter=(self.name, float(given[0])))
        return dataclasses.replace(res, parameter=(self.name, given.reshape(res.shape)))


def arm_angle_parameter(chain: Chain) -> ArmAngleParameter | None:
    """The arm angle when ``chain`` is an SRS arm (its closed form needs one), else None."""
    if chain.dof != 7 or closed_form(chain, "pose", "arm_angle") is None:
        return None
    return _ARM_ANGLE


_ARM_ANGLE = ArmAngleParameter()
