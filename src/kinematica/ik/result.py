"""IK results: every solution with its branch, residuals and an honest status."""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from kinematica.errors import UnreachableError

__all__ = ["IKBatchResult", "IKResult", "Status", "status_message"]

FloatArray = NDArray[np.float64]

Status = Literal["ok", "unreachable", "singular", "out_of_limits", "not_found", "invalid"]

#: Statuses for which ``solutions`` is not empty.
SOLVED: frozenset[str] = frozenset({"ok", "singular"})


def status_message(
    status: str,
    *,
    method: str,
    count: int,
    out_of_limits: int,
    free: tuple[int, ...],
    gap: float,
    nearest: tuple[float, float],
) -> str:
    """One sentence for people about an IK outcome.

    Args:
        status: The status.
        method: The method name.
        count: Solutions within limits.
        out_of_limits: Solutions outside the limits.
        free: 0-based indices of the free joints (singular case).
        gap: Distance outside the reach (m), NaN if unknown.
        nearest: Position (m) and rotation (rad) error of the closest
            candidate that was not a solution, NaN if none.
    """
    plural = "s" if count != 1 else ""
    if status == "ok":
        extra = f"; {out_of_limits} more outside the joint limits" if out_of_limits else ""
        return f"{count} solution{plural} ({method}){extra}"
    if status == "singular":
        names = ", ".join(f"q{v + 1}" for v in free)
        return (
            f"singular: infinitely many solutions ({names or 'some joints'} free); "
            f"{count} representative{plural} given"
        )
    if status == "out_of_limits":
        s = "s" if out_of_limits != 1 else ""
        return f"{out_of_limits} solution{s} exist, none within the joint limits"
    if status == "unreachable":
        if math.isfinite(gap) and gap > 0:
            return f"unreachable: the target is at least {gap:.6g} m outside the reach"
        pos, rot = nearest
        if math.isfinite(pos):
            return (
                "unreachable: no configuration reaches this pose "
                f"(closest candidate off by {pos:.3g} m, {rot:.3g} rad)"
            )
        return "unreachable: the closed form has no real solution for this target"
    return "not found: the numeric search did not converge (the target may still be reachable)"


@dataclass(frozen=True)
class IKResult:
    """All inverse-kinematics solutions of one target.

    Attributes:
        solutions: ``(k, n)`` distinct solutions, each checked by forward
            kinematics; within the joint limits when limits were respected.
            Revolute angles wrapped to (−π, π] (or into the limit window).
            Sorted by distance to ``q0`` when one was given.
        status: ``"ok"``; ``"singular"`` (infinitely many solutions: the
            rows are representatives, ``free_joints`` names the free ones);
            ``"out_of_limits"`` (solutions exist, none within limits: see
            ``out_of_limits``); ``"unreachable"`` (provably no solution:
            ``gap`` says how far); ``"not_found"`` (a numeric search did not
            converge: the target may still be reachable); ``"invalid"`` (in a
            batch, a malformed target: the message says what is wrong).
        method: How it was solved, e.g. ``"analytic:spherical-wrist"``, ``"numeric:lm"``.
        residuals: ``(k, 2)`` per solution: position error (m), rotation error (rad).
        branches: ``(k,)`` branch label of each solution (e.g. ``"elbow up"``).
        out_of_limits: ``(j, n)`` solutions that reach the target but violate limits.
        out_of_limits_branches: ``(j,)`` their branch labels.
        free_joints: 0-based indices of the joints left free in a singular case.
        gap: For ``"unreachable"``, a lower bound of the distance between the
            target and the reachable set (m), when the solver knows one.
        message: One sentence for people.
    """

    solutions: FloatArray
    status: Status
    method: str
    residuals: FloatArray
    branches: tuple[str, ...]
    out_of_limits: FloatArray
    out_of_limits_branches: tuple[str, ...]
    free_joints: tuple[int, ...] = ()
    gap: float | None = None
    message: str = ""

    @property
    def count(self) -> int:
        """Number of solutions (within limits when they were respected)."""
        return int(self.solutions.shape[0])

    @property
    def success(self) -> bool:
        """True when there is at least one solution."""
        return self.count > 0

    @property
    def q(self) -> FloatArray:
        """The first solution ``(n,)`` (nearest to ``q0`` when given).

        Raises:
            UnreachableError: When there is no solution (the message says why).
        """
        if not self.success:
            raise UnreachableError(self.message or f"no IK solution ({self.status})")
        return self.solutions[0]

    def __len__(self) -> int:
        return self.count

    def __iter__(self) -> Iterator[FloatArray]:
        return iter(self.solutions)


@dataclass(frozen=True)
class IKBatchResult:
    """IK results for N targets, as arrays (index it for one :class:`IKResult`).

    Attributes:
        solutions: ``(N, k, n)`` solutions, NaN-padded (see :class:`IKResult`).
        count: ``(N,)`` number of solutions per target.
        status: ``(N,)`` status per target.
        method: How they were solved.
        residuals: ``(N, k, 2)`` position (m) and rotation (rad) errors, NaN-padded.
        branches: ``(N, k)`` branch labels, ``""`` where padded.
        out_of_limits: ``(N, j, n)`` solutions outside the joint limits, NaN-padded.
        out_of_limits_count: ``(N,)``.
        out_of_limits_branches: ``(N, j)``.
        free: ``(N, n)`` True for joints left free in a singular case.
        gap: ``(N,)`` distance outside the reach for unreachable targets (m), else NaN.
        nearest_error: ``(N, 2)`` smallest position (m) and rotation (rad)
            residual among candidates that were not solutions, NaN if none.
        errors: Row -> what is wrong with that row's target, for the rows whose
            status is ``"invalid"`` (malformed targets in a batch).
    """

    solutions: FloatArray
    count: NDArray[np.int64]
    status: NDArray[np.str_]
    method: str
    residuals: FloatArray
    branches: NDArray[np.str_]
    out_of_limits: FloatArray
    out_of_limits_count: NDArray[np.int64]
    out_of_limits_branches: NDArray[np.str_]
    free: NDArray[np.bool_]
    gap: FloatArray
    nearest_error: FloatArray
    errors: Mapping[int, str] = field(default_factory=dict)

    def __len__(self) -> int:
        return int(self.count.shape[0])

    def __getitem__(self, i: int) -> IKResult:
        k = int(self.count[i])
        j = int(self.out_of_limits_count[i])
        gap = float(self.gap[i])
        return IKResult(
            solutions=self.solutions[i, :k].copy(),
            status=str(self.status[i]),  # type: ignore[arg-type]
            method=self.method,
            residuals=self.residuals[i, :k].copy(),
            branches=tuple(str(b) for b in self.branches[i, :k]),
            out_of_limits=self.out_of_limits[i, :j].copy(),
            out_of_limits_branches=tuple(str(b) for b in self.out_of_limits_branches[i, :j]),
            free_joints=tuple(int(v) for v in np.flatnonzero(self.free[i])),
            gap=None if np.isnan(gap) else gap,
            message=self.message(i),
        )

    def message(self, i: int) -> str:
        """One sentence saying what happened to target ``i``."""
        if i in self.errors:
            return f"invalid target: {self.errors[i]}"
        return status_message(
            str(self.status[i]),
            method=self.method,
            count=int(self.count[i]),
            out_of_limits=int(self.out_of_limits_count[i]),
            free=tuple(int(v) for v in np.flatnonzero(self.free[i])),
            gap=float(self.gap[i]),
            nearest=(float(self.nearest_error[i, 0]), float(self.nearest_error[i, 1])),
        )

    def __iter__(self) -> Iterator[IKResult]:
        return (self[i] for i in range(len(self)))
