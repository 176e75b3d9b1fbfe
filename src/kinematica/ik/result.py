"""IK results: every solution with its branch, residuals and an honest status."""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from kinematica.errors import UnreachableError
from kinematica.ik.status import IKStatus, status_message

__all__ = ["NEAR_NOTE", "IKBatchResult", "IKResult"]

FloatArray = NDArray[np.float64]

#: Said of solutions found for a target within round-off of a singular set.
NEAR_NOTE = (
    "the target is within round-off of a singular set, where solutions merge: "
    "solutions that merge there are given once"
)


@dataclass(frozen=True, eq=False)
class IKResult:
    """All inverse-kinematics solutions of one target.

    Attributes:
        solutions: ``(k, n)`` distinct solutions, each checked by forward
            kinematics; within the joint limits when limits were respected.
            Revolute angles wrapped to (−π, π] (or into the limit window).
            Sorted by distance to ``q0`` when one was given.
        status: An :class:`IKStatus` (compares equal to ``"ok"``,
            ``"singular"``, ``"out_of_limits"``, ``"unreachable"``,
            ``"not_found"``, ``"invalid"``).
        method: How it was solved, e.g. ``"analytic:spherical-wrist"``, ``"numeric:lm"``.
        residuals: ``(k, 2)`` per solution: position error (m), rotation error (rad).
        branches: ``(k,)`` branch label of each solution (e.g. ``"elbow up"``).
        out_of_limits: ``(j, n)`` solutions that reach the target but violate limits.
        out_of_limits_branches: ``(j,)`` their branch labels.
        free_joints: 0-based indices of the joints left free in a singular case.
        gap: For ``"unreachable"``, a lower bound of the distance between the
            target and the reachable set (m), when one is known; else None.
        nearest_error: Position (m) and rotation (rad) error of the closest
            candidate that was not a solution (NaN if none).
        notes: Remarks on how the target was read or solved (a rotation
            projected onto SO(3), a target near a singular set...).
        complete: True when the method gives every solution (a closed form).
        near_singular: True when the target lies within round-off of a singular
            set or a workspace boundary, where closed-form solutions merge (the
            solutions given reach the target; some that merge there may be
            reported as one).
    """

    solutions: FloatArray
    status: IKStatus
    method: str
    residuals: FloatArray
    branches: tuple[str, ...]
    out_of_limits: FloatArray
    out_of_limits_branches: tuple[str, ...]
    free_joints: tuple[int, ...] = ()
    gap: float | None = None
    nearest_error: tuple[float, float] = (math.nan, math.nan)
    notes: tuple[str, ...] = ()
    complete: bool = True
    near_singular: bool = False

    @cached_property
    def message(self) -> str:
        """One sentence (and the notes) saying what happened."""
        text = status_message(
            self.status,
            method=self.method,
            count=self.count,
            out_of_limits=int(self.out_of_limits.shape[0]),
            free=self.free_joints,
            gap=math.nan if self.gap is None else self.gap,
            nearest=self.nearest_error,
            complete=self.complete,
            near=self.near_singular,
        )
        notes = self.notes
        if self.near_singular and self.status in (IKStatus.OK, IKStatus.SINGULAR):
            notes = (*notes, NEAR_NOTE)
        return "; ".join((text, *notes))

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
            raise UnreachableError(self.message)
        return self.solutions[0]

    def __len__(self) -> int:
        return self.count

    def __iter__(self) -> Iterator[FloatArray]:
        return iter(self.solutions)


@dataclass(frozen=True, eq=False)
class IKBatchResult:
    """IK results for a batch of targets of any shape ``(...)``, as arrays.

    Index it with a batch index (``res[i]``, ``res[i, j]``) for one
    :class:`IKResult`; iterating yields one per target in C order.

    Attributes:
        solutions: ``(..., k, n)`` solutions, NaN-padded (see :class:`IKResult`).
        count: ``(...)`` number of solutions per target.
        status: ``(...)`` status per target (strings, see :class:`IKStatus`).
        method: How they were solved.
        residuals: ``(..., k, 2)`` position (m) and rotation (rad) errors, NaN-padded.
        branches: ``(..., k)`` branch labels, ``""`` where padded.
        out_of_limits: ``(..., j, n)`` solutions outside the joint limits, NaN-padded.
        out_of_limits_count: ``(...)``.
        out_of_limits_branches: ``(..., j)``.
        free: ``(..., n)`` True for joints left free in a singular case.
        gap: ``(...)`` distance outside the reach for unreachable targets (m), else NaN.
        nearest_error: ``(..., 2)`` smallest position (m) and rotation (rad)
            residual among candidates that were not solutions, NaN if none.
        errors: Batch index -> what is wrong with that target, for the
            targets whose status is ``"invalid"``.
        notes: Batch index -> remarks on that target (e.g. its rotation was
            projected onto SO(3)).
        complete: True when the method gives every solution (a closed form).
        near_singular: ``(...)`` see :attr:`IKResult.near_singular`.
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
    errors: Mapping[tuple[int, ...], str] = field(default_factory=dict)
    notes: Mapping[tuple[int, ...], tuple[str, ...]] = field(default_factory=dict)
    complete: bool = True
    near_singular: NDArray[np.bool_] | None = None

    @property
    def shape(self) -> tuple[int, ...]:
        """The batch shape ``(...)``."""
        return tuple(self.count.shape)

    @property
    def size(self) -> int:
        """The number of targets."""
        return int(self.count.size)

    def __len__(self) -> int:
        return self.shape[0] if self.shape else 1

    def _index(self, i: int | tuple[int, ...]) -> tuple[int, ...]:
        idx = (i,) if isinstance(i, int | np.integer) else tuple(i)
        if len(idx) != len(self.shape):
            raise IndexError(
                f"a batch of shape {self.shape} takes {len(self.shape)} indices, got {len(idx)}"
            )
        return tuple(int(v) % s for v, s in zip(idx, self.shape, strict=True))

    def __getitem__(self, i: int | tuple[int, ...]) -> IKResult:
        idx = self._index(i)
        k = int(self.count[idx])
        j = int(self.out_of_limits_count[idx])
        gap = float(self.gap[idx])
        notes = self.notes.get(idx, ())
        if idx in self.errors:
            notes = (self.errors[idx], *notes)
        return IKResult(
            solutions=self.solutions[idx][:k].copy(),
            status=IKStatus(str(self.status[idx])),
            method=self.method,
            residuals=self.residuals[idx][:k].copy(),
            branches=tuple(str(b) for b in self.branches[idx][:k]),
            out_of_limits=self.out_of_limits[idx][:j].copy(),
            out_of_limits_branches=tuple(str(b) for b in self.out_of_limits_branches[idx][:j]),
            free_joints=tuple(int(v) for v in np.flatnonzero(self.free[idx])),
            gap=None if math.isnan(gap) else gap,
            nearest_error=(float(self.nearest_error[idx][0]), float(self.nearest_error[idx][1])),
            notes=notes,
            complete=self.complete,
            near_singular=bool(self.near_singular[idx])
            if self.near_singular is not None
            else False,
        )

    @cached_property
    def message(self) -> NDArray[np.str_]:
        """``(...)`` one sentence per target, as :attr:`IKResult.message`."""
        out = np.empty(self.shape, dtype=object)
        for idx in np.ndindex(*self.shape):
            out[idx] = self[idx].message
        return out.astype(str)

    def __iter__(self) -> Iterator[IKResult]:
        return (self[idx] for idx in np.ndindex(*self.shape))
