"""How ``robot.ik`` is asked to solve: one object from the command line to the core."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike

from kinematica.ik.tolerance import Tolerance

__all__ = ["IKOptions", "Method"]

Method = Literal["auto", "analytic", "numeric"]


@dataclass(frozen=True, slots=True, eq=False)
class IKOptions:
    """The settings of an IK call (see :meth:`kinematica.Robot.ik` for each one).

    Attributes:
        method: ``"auto"`` (closed form when the structure allows), ``"analytic"``
            or ``"numeric"``.
        tol: Acceptance tolerance: one number for both, a pair (position m,
            rotation rad), a :class:`Tolerance`, or ``None`` (1e-10 m, 1e-10 rad).
        respect_limits: Keep solutions outside the joint limits apart.
        q0: ``(n,)`` or ``(..., n)``: the numeric initial guess, and the
            configuration solutions are sorted by distance to.
        mask: ``(6,)`` weights of x, y, z, rx, ry, rz (numeric only).
        seed: Seed of the numeric restarts.
        workers: Threads for a batch (None: the library default).
        precision: ``(position m, rotation entries)``: half a unit in the last
            digit a pose target's numbers were printed with, for arms with fewer
            than 6 joints (:mod:`kinematica.ik.printed`); None: read from the
            numbers' own digits.
        fixed: ``{joint: value}``: solve with that joint held at the value (rad or
            m), the joint named by its 0-based index or its name (or ``"qN"``,
            1-based); every solution has that value (:mod:`kinematica.ik.parameter`).
        arm_angle: The arm angle (rad) of an SRS 7R arm's solutions
            (:mod:`kinematica.ik.analytic.srs`): one value, or one per target;
            None: no parameter.
    """

    method: Method = "auto"
    tol: float | tuple[float, float] | Tolerance | None = None
    respect_limits: bool = True
    q0: ArrayLike | None = None
    mask: ArrayLike | None = None
    seed: int | np.random.Generator | None = None
    workers: int | None = None
    precision: tuple[float, float] | None = None
    fixed: Mapping[int | str, float] | None = None
    arm_angle: ArrayLike | None = None


#: The options of a call that gives none.
DEFAULT = IKOptions()
