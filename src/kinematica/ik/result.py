"""IK results: every solution with its branch, residuals and an honest status."""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np
from numpy.typing import NDArray

import kinematica._core as _core
from kinematica.errors import UnreachableError
from kinematica.ik.status import STATUS_NAMES, IKStatus, held, status_message
from kinematica.spatial import ROUNDOFF_TOL

__all__ = [
    "BATCH_FIELDS",
    "NEAR_NOTE",
    "IKBatchResult",
    "IKResult",
    "amended",
    "arrays_of",
    "prepared",
    "replaced",
    "result_of",
]

FloatArray = NDArray[np.float64]

#: Said of solutions found for a target within round-off of a singular set.
NEAR_NOTE = (
    "the target is within round-off of a singular set, where solutions merge or form a "
    "continuum within the tolerance: solutions that merge there are given once, and "
    "others may lie along it"
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
        free_joints: 0-based indices of the joints left free in a singular case
            (:attr:`free_names` names them as the messages do: ``("q4", "q6")``).
        gap: For ``"unreachable"``, a lower bound of the distance between the
            target and the reachable set (m), when one is known; else None.
        nearest_error: Position (m) and rotation (rad) error of the closest
            candidate that was not a solution (NaN if none).
        notes: Remarks on how the target was read or solved (a rotation
            projected onto SO(3), a target near a singular set...).
        complete: True when the method gives every solution (a closed form).
        near_singular: True when the target lies within round-off of a singular
            set or a workspace boundary, where closed-form solutions merge or form
            a continuum within the tolerance (a spherical wrist aligned to within
            1e-7 rad; two branches under 1e-5 rad apart whose midpoint also
            reaches the target, reported as one). Without it, the solutions of a
            closed form are exact to round-off over the arm's conditioning
            (docs/inverse-kinematics.md, "Near a singular set").
        parameter: ``(name, value)`` of the joint held at a value for this answer
            (``robot.ik(T, fixed=...)``, or a redundant arm's ``method="auto"``):
            every solution has that value, and the status is relative to it
            ("unreachable" with that joint there); None when every joint was free.
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
    parameter: tuple[str, float] | None = None

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
            held=None if self.parameter is None else held(*self.parameter),
        )
        notes = self.notes
        if self.near_singular and self.status in (IKStatus.OK, IKStatus.SINGULAR):
            notes = (*notes, NEAR_NOTE)
        return "; ".join((text, *notes))

    @property
    def letters(self) -> tuple[str, ...]:
        """``(k,)`` the branch labels in the Robotics Toolbox's letters (``"ruf"``...).

        ``l/r`` shoulder, ``u/d`` elbow, ``n/f`` wrist in the Toolbox's meaning,
        where ``f`` is kinematica's ``"wrist no-flip"``
        (see :mod:`kinematica.ik.letters`).
        """
        from kinematica.ik.letters import toolbox_letters  # asked for by some only

        return tuple(toolbox_letters(b) for b in self.branches)

    @property
    def free_names(self) -> tuple[str, ...]:
        """The free joints as the messages and tables name them, 1-based: ``("q4", "q6")``.

        Each is accepted where a joint is asked for (``fixed={"q4": ...}``).
        """
        return tuple(f"q{i + 1}" for i in self.free_joints)

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

    def _repr_html_(self) -> str:
        """The solutions as an HTML table, with their branches and residuals (Jupyter)."""
        from kinematica.ik.display import result_html

        return result_html(self)


@dataclass(frozen=True, eq=False)
class IKBatchResult:
    """IK results for a batch of targets of any shape ``(...)``, as arrays.

    Index it with a batch index (``res[i]``, ``res[i, j]``) for one
    :class:`IKResult`; iterating yields one per target in C order. The arrays
    below are derived from the core's check output on first access.

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
        near_singular: ``(...)`` see :attr:`IKResult.near_singular`.
        message: ``(...)`` one sentence per target, as :attr:`IKResult.message`.
        errors: Batch index -> what is wrong with that target, for the
            targets whose status is ``"invalid"``.
        notes: Batch index -> remarks on that target (e.g. its rotation was
            projected onto SO(3)).
        complete: True when the method gives every solution (a closed form).
        methods: Batch index -> the method of a target solved by another than
            ``method`` (a near-degenerate arm's targets the numeric search
            answered; their results are not complete).
        parameter: ``(name, values (...))``: the joint held at a value per
            target (see :attr:`IKResult.parameter`), NaN for a target answered
            with every joint free; None when no joint was held.
    """

    raw: _core.BatchAnswer = field(repr=False)
    method: str
    labels: tuple[str, ...] = field(repr=False)
    shape: tuple[int, ...]
    errors: Mapping[tuple[int, ...], str] = field(default_factory=dict)
    notes: Mapping[tuple[int, ...], tuple[str, ...]] = field(default_factory=dict)
    complete: bool = True
    methods: Mapping[tuple[int, ...], str] = field(default_factory=dict)
    parameter: tuple[str, FloatArray] | None = None

    @property
    def size(self) -> int:
        """The number of targets."""
        return int(self.raw.status.shape[0])

    def __len__(self) -> int:
        return self.shape[0] if self.shape else 1

    # -------------------------------------------------------------- the arrays
    def _shaped(self, a: NDArray[Any]) -> NDArray[Any]:
        return a.reshape(*self.shape, *a.shape[1:])

    @cached_property
    def _counts(self) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
        return self.raw.count, self.raw.out_count

    @cached_property
    def count(self) -> NDArray[np.int64]:
        """``(...)`` number of solutions per target."""
        return self._shaped(self._counts[0])

    @cached_property
    def out_of_limits_count(self) -> NDArray[np.int64]:
        """``(...)`` number of solutions outside the joint limits per target."""
        return self._shaped(self._counts[1])

    def _rows(self, first: bool) -> tuple[NDArray[np.intp], NDArray[np.bool_]]:
        """Slot index and mask of the solutions within (``first``) or outside the limits."""
        count, out = self._counts
        m = self.raw.slot.shape[1]
        k = int((count if first else out).max(initial=0))
        cols = np.arange(k)[None, :]
        idx = cols if first else np.minimum(count[:, None] + cols, m - 1)
        mask = cols < (count if first else out)[:, None]
        return np.broadcast_to(idx, mask.shape), mask

    def _gather(self, values: NDArray[Any], first: bool, fill: Any) -> NDArray[Any]:
        idx, mask = self._rows(first)
        if first:  # the slots within the limits come first: the leading ones, a slice
            got = values[:, : idx.shape[1]]
        else:
            at = idx.reshape(*idx.shape, *([1] * (values.ndim - 2)))
            got = np.take_along_axis(values, at, 1)
        mask = mask.reshape(*mask.shape, *([1] * (values.ndim - 2)))
        return self._shaped(np.where(mask, got, fill))

    def _names(self, first: bool, letters: bool = False) -> NDArray[np.str_]:
        from kinematica.ik.letters import toolbox_letters  # asked for by some only

        labels = [toolbox_letters(b) for b in self.labels] if letters else self.labels
        names = np.array([*labels, ""], dtype=str)  # slot -1 -> ""
        idx, mask = self._rows(first)
        slots = np.take_along_axis(self.raw.slot, idx, 1)
        return self._shaped(np.where(mask, names[slots], ""))

    @cached_property
    def solutions(self) -> FloatArray:
        """``(..., k, n)`` solutions within the limits, NaN-padded."""
        return self._gather(self.raw.q, True, np.nan)

    @cached_property
    def residuals(self) -> FloatArray:
        """``(..., k, 2)`` their position (m) and rotation (rad) errors, NaN-padded."""
        return self._gather(self.raw.res, True, np.nan)

    @cached_property
    def branches(self) -> NDArray[np.str_]:
        """``(..., k)`` their branch labels, ``""`` where padded."""
        return self._names(True)

    @cached_property
    def letters(self) -> NDArray[np.str_]:
        """``(..., k)`` the branch labels in the Robotics Toolbox's letters, ``""`` where padded.

        See :attr:`IKResult.letters`.
        """
        return self._names(True, letters=True)

    @cached_property
    def out_of_limits(self) -> FloatArray:
        """``(..., j, n)`` solutions outside the joint limits, NaN-padded."""
        return self._gather(self.raw.q, False, np.nan)

    @cached_property
    def out_of_limits_branches(self) -> NDArray[np.str_]:
        """``(..., j)`` their branch labels."""
        return self._names(False)

    @cached_property
    def status(self) -> NDArray[np.str_]:
        """``(...)`` status per target (strings)."""
        names = np.array([str(STATUS_NAMES[c]) for c in sorted(STATUS_NAMES)], dtype=str)
        return self._shaped(names[self.raw.status])

    @cached_property
    def free(self) -> NDArray[np.bool_]:
        """``(..., n)`` True for the joints left free, where the status is singular."""
        singular = self.raw.status == _SINGULAR
        return self._shaped(self.raw.free & singular[:, None])

    @cached_property
    def gap(self) -> FloatArray:
        """``(...)`` distance outside the reach for unreachable targets (m), else NaN."""
        return self._shaped(self.raw.gap.copy())

    @cached_property
    def nearest_error(self) -> FloatArray:
        """``(..., 2)`` the closest miss among candidates that were not solutions."""
        return self._shaped(self.raw.nearest.copy())

    @cached_property
    def near_singular(self) -> NDArray[np.bool_]:
        """``(...)`` True where the target is within round-off of a singular set."""
        return self._shaped(self.raw.near.copy())

    # -------------------------------------------------------------- one target
    def _index(self, i: int | tuple[int, ...]) -> tuple[int, ...]:
        idx = (i,) if isinstance(i, int | np.integer) else tuple(i)
        if len(idx) != len(self.shape):
            raise IndexError(
                f"a batch of shape {self.shape} takes {len(self.shape)} indices, got {len(idx)}"
            )
        return tuple(int(v) % s for v, s in zip(idx, self.shape, strict=True))

    def __getitem__(self, i: int | tuple[int, ...]) -> IKResult:
        idx = self._index(i)
        flat = int(np.ravel_multi_index(idx, self.shape)) if self.shape else 0
        notes = self.notes.get(idx, ())
        if idx in self.errors:
            notes = (self.errors[idx], *notes)
        raw = self.raw
        count, out = int(raw.count[flat]), int(raw.out_count[flat])
        code = int(raw.status[flat])
        free: tuple[int, ...] = ()
        if code == _SINGULAR:
            free = tuple(j for j, v in enumerate(raw.free[flat].tolist()) if v)
        gap = float(raw.gap[flat])
        labels = self.labels
        branches = tuple(labels[j] for j in raw.slot[flat, : count + out].tolist())
        q = raw.q[flat]
        parameter = None
        if self.parameter is not None:
            value = float(np.asarray(self.parameter[1]).reshape(-1)[flat])
            parameter = None if value != value else (self.parameter[0], value)
        res = _new(IKResult)
        res.__dict__.update(
            solutions=q[:count], status=STATUS_NAMES[code], residuals=raw.res[flat, :count],
            branches=branches[:count], out_of_limits=q[count : count + out],
            out_of_limits_branches=branches[count:], free_joints=free,
            gap=None if gap != gap else gap,
            nearest_error=(float(raw.nearest[flat, 0]), float(raw.nearest[flat, 1])),
            notes=notes, method=self.methods.get(idx, self.method),
            complete=self.complete and idx not in self.methods,
            near_singular=bool(raw.near[flat]), parameter=parameter,
        )  # fmt: skip
        return res

    @cached_property
    def message(self) -> NDArray[np.str_]:
        """``(...)`` one sentence per target, as :attr:`IKResult.message`."""
        out = np.empty(self.shape, dtype=object)
        for idx in np.ndindex(*self.shape):
            out[idx] = self[idx].message
        return out.astype(str)

    def __iter__(self) -> Iterator[IKResult]:
        return (self[idx] for idx in np.ndindex(*self.shape))

    def _repr_html_(self) -> str:
        """One row per target, with its status and message, as HTML (Jupyter)."""
        from kinematica.ik.display import batch_html

        return batch_html(self)


#: The arrays of a batch's answer (the core's ``BatchAnswer``), in its constructor's order:
#: ``q (N, m, n)`` solutions within the limits then those outside, NaN after; ``slot
#: (N, m)`` the candidate slot (branch) of each row, -1 after; ``res (N, m, 2)``
#: residuals; ``status``, ``count``, ``out_count``, ``gap (N,)``; ``nearest (N, 2)``;
#: ``near (N,)``; ``free (N, n)``.
BATCH_FIELDS = ("q", "slot", "res", "status", "count", "out_count", "gap", "nearest", "near",
                "free")  # fmt: skip

#: A new object without its class's ``__init__`` (see :func:`result_of`).
_new = object.__new__

#: The core's code of the singular status.
_SINGULAR = next(code for code, name in STATUS_NAMES.items() if name is IKStatus.SINGULAR)
#: The status of each core code, by code.
_STATUSES = tuple(STATUS_NAMES[code] for code in range(len(STATUS_NAMES)))


def result_of(
    answer: _core.Answer,
    method: str,
    complete: bool,
    notes: tuple[str, ...],
    parameter: tuple[str, float] | None = None,
) -> IKResult:
    """The :class:`IKResult` of one target from the core's answer to it.

    Args:
        answer: The core's check of the target (its solutions, residuals, branches and
            report, by the result's names).
        method: The method name.
        complete: The method gives every solution.
        notes: Remarks on the target.
        parameter: The joint held at a value, ``(name, value)``, or None.

    Built by the core without the frozen dataclass's ``__init__``: its fields stored
    straight into the new object's ``__dict__``.
    """
    fields = {"method": method, "complete": complete, "notes": notes, "parameter": parameter}
    made: IKResult = answer.result(IKResult, fields, _STATUSES)  # type: ignore[assignment]
    return made


def prepared(
    solver: Any,
    core: _core.Chain,
    options: _core.CheckOptions,
    labels: tuple[str, ...],
    method: str,
    complete: bool,
    notes: tuple[str, ...],
    final: frozenset[int],
) -> _core.Prepared:
    """A closed form's ``Params`` made ready for one target at a time (the core's ``prepare``).

    Called with a ``(4, 4)`` float target and ``q0``, ``(n,)`` float or None (the solutions
    sorted nearest it), it gives None where the target is not rigid to round-off as the
    core reads it, or ``q0`` holds NaN or inf; else the :class:`IKResult` (as
    :func:`result_of` makes it) where the status is one of ``final``, the core's answer
    otherwise.
    """
    fields = {"method": method, "complete": complete, "notes": notes, "parameter": None}
    bits = sum(1 << code for code in final)
    return solver.prepare(core, options, ROUNDOFF_TOL, labels, IKResult, fields, _STATUSES, bits)


def replaced(raw: _core.BatchAnswer, **changes: Any) -> _core.BatchAnswer:
    """``raw`` with some of its arrays (:data:`BATCH_FIELDS`) changed."""
    return _core.BatchAnswer(
        **{name: changes.get(name, getattr(raw, name)) for name in BATCH_FIELDS}
    )


def arrays_of(raw: _core.BatchAnswer) -> dict[str, NDArray[Any]]:
    """Writable copies of ``raw``'s arrays, by name (:data:`BATCH_FIELDS`)."""
    return {name: np.array(getattr(raw, name)) for name in BATCH_FIELDS}


def amended(res: IKResult, **fields: Any) -> IKResult:
    """``res`` with ``fields`` changed, as ``dataclasses.replace`` gives it.

    Built as :func:`result_of` builds one; its message (a cached property) is said again.
    """
    out = _new(IKResult)
    d = out.__dict__
    d.update(res.__dict__)
    d.pop("message", None)
    d.update(fields)
    return out
