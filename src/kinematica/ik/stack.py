"""Results of a locked arm made whole again, and batches put together from parts.

A locked arm's answer holds n - 1 joint values per solution: :func:`widen_result`
and :func:`widen_batch` insert the locked joint's value. :func:`stack_results` makes
one batch of single answers (targets solved one by one, each its own arm), and
:func:`replace_rows` puts another method's answers in some rows of a batch (the
redundant arm's numeric search over every joint where the lock found nothing), and
:func:`solve_each` answers a batch target by target (the continua of 6R arms).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Mapping, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

import kinematica._core as _core
from kinematica.core import Chain
from kinematica.ik.result import IKBatchResult, IKResult, amended, replaced

__all__ = [
    "pose_residuals",
    "replace_rows",
    "solve_each",
    "stack_results",
    "widen_batch",
    "widen_result",
]

if TYPE_CHECKING:
    from kinematica.ik.options import IKOptions
    from kinematica.ik.targets import Targets

FloatArray = NDArray[np.float64]

_INVALID = _core.STATUS["invalid"]


def pose_residuals(chain: Chain, q: FloatArray, T: FloatArray) -> FloatArray:
    """``(k, 2)`` position (m) and rotation (rad) errors of each row of ``q (k, n)``.

    Against the target ``T (4, 4)`` (base frame), as a result's ``residuals`` hold them:
    the answers assembled in Python (continua, coaxial pairs, sweeps) measure theirs here.
    """
    if not len(q):
        return np.zeros((0, 2))
    from kinematica.spatial import rotation_angle

    F = chain.fk(np.ascontiguousarray(q))[0]
    pos = np.linalg.norm(F[:, :3, 3] - T[:3, 3], axis=1)
    rot = np.asarray(rotation_angle(F[:, :3, :3], T[:3, :3]))
    return np.stack([pos, rot], axis=1)


def widen_result(
    res: IKResult, joint: int, value: float, parameter: tuple[str, float] | None
) -> IKResult:
    """The answer of an arm locked at joint ``joint``, with that joint's ``value`` put back.

    Args:
        res: The locked (n - 1)-joint arm's answer.
        joint: The locked joint, 0-based, in the whole arm.
        value: Its value (rad or m).
        parameter: What the result names as its parameter (``("q7", 0.3)``).
    """
    return amended(
        res,
        solutions=_with_column(res.solutions, joint, value),
        out_of_limits=_with_column(res.out_of_limits, joint, value),
        free_joints=tuple(j + (j >= joint) for j in res.free_joints),  # the whole arm's indices
        parameter=parameter,
    )


def _with_column(q: FloatArray, joint: int, value: float) -> FloatArray:
    """``(k, n - 1)`` rows with a column of ``value`` put in at ``joint``: ``(k, n)``."""
    out = np.empty((q.shape[0], q.shape[1] + 1))
    if not q.shape[0]:
        return out
    if joint:  # the first and last joints (the usual parameters) skip an empty copy
        out[:, :joint] = q[:, :joint]
    out[:, joint] = value
    if joint < q.shape[1]:
        out[:, joint + 1 :] = q[:, joint:]
    return out


def widen_batch(res: IKBatchResult, joint: int, values: FloatArray, name: str) -> IKBatchResult:
    """:func:`widen_result` of a batch; ``values`` ``(N,)`` the joint's value per target."""
    raw = res.raw
    q = raw.q
    column = np.where(np.isnan(q[..., :1]), np.nan, values[:, None, None])
    wide = np.concatenate([q[..., :joint], column, q[..., joint:]], axis=-1)
    free = np.insert(raw.free, joint, False, axis=1)
    parameter = (name, values.reshape(res.shape) if res.shape else values.reshape(()))
    return dataclasses.replace(res, raw=replaced(raw, q=wide, free=free), parameter=parameter)


def _where(shape: tuple[int, ...], i: int) -> tuple[int, ...]:
    return tuple(int(v) for v in np.unravel_index(i, shape))


def stack_results(
    results: Mapping[int, IKResult],
    targets: Targets,
    n: int,
    name: str | None,
    values: FloatArray | None,
) -> IKBatchResult:
    """One batch of single answers (flat target index -> answer); the others are invalid.

    Args:
        results: The answer of each valid target (already whole: n joint values).
        targets: The parsed targets (shape, invalid rows and their messages, notes).
        n: Joints of the arm.
        name: The parameter's name (None: every joint was free).
        values: ``(N,)`` its value per target (None with ``name`` None).
    """
    N = targets.poses.shape[0]
    labels: list[str] = []
    for r in results.values():
        for b in (*r.branches, *r.out_of_limits_branches):
            if b not in labels:
                labels.append(b)
    m = max((r.count + r.out_of_limits.shape[0] for r in results.values()), default=1) or 1
    q = np.full((N, m, n), np.nan)
    slot = np.full((N, m), -1, dtype=np.int64)
    res = np.full((N, m, 2), np.nan)
    status = np.full(N, _INVALID, dtype=np.int64)
    count = np.zeros(N, dtype=np.int64)
    out_count = np.zeros(N, dtype=np.int64)
    gap = np.full(N, np.nan)
    nearest = np.full((N, 2), np.nan)
    near = np.zeros(N, dtype=bool)
    free = np.zeros((N, n), dtype=bool)
    methods: dict[tuple[int, ...], str] = {}
    notes: dict[tuple[int, ...], tuple[str, ...]] = {}
    first = next(iter(results.values()), None)
    method = first.method if first is not None else "none"
    complete = first.complete if first is not None else True
    for i, r in results.items():
        c, o = r.count, r.out_of_limits.shape[0]
        q[i, :c] = r.solutions
        q[i, c : c + o] = r.out_of_limits
        res[i, :c] = r.residuals
        slot[i, : c + o] = [labels.index(b) for b in (*r.branches, *r.out_of_limits_branches)]
        status[i] = _core.STATUS[str(r.status)]
        count[i], out_count[i] = c, o
        gap[i] = np.nan if r.gap is None else r.gap
        nearest[i] = r.nearest_error
        near[i] = r.near_singular
        free[i, list(r.free_joints)] = True
        idx = _where(targets.shape, i)
        if r.method != method or r.complete != complete:
            methods[idx] = r.method
        if r.notes:
            notes[idx] = r.notes
    raw = _core.BatchAnswer(q, slot, res, status, count, out_count, gap, nearest, near, free)
    return IKBatchResult(
        raw=raw,
        method=method,
        labels=tuple(labels),
        shape=targets.shape,
        errors={_where(targets.shape, i): msg for i, msg in targets.invalid.items()},
        notes=notes,
        complete=complete,
        methods=methods,
        parameter=None if name is None or values is None else (name, values.reshape(targets.shape)),
    )


def replace_rows(
    batch: IKBatchResult,
    rows: NDArray[np.intp],
    other: IKBatchResult,
    notes_of: Sequence[str] | None,
) -> IKBatchResult:
    """``batch`` with the flat rows ``rows`` answered by ``other`` (one target per row).

    With ``notes_of`` (one note per row, in the order of ``rows``) those rows are
    answered with every joint free: they lose the batch's parameter (NaN) and take
    ``other``'s method, its notes and the note. Without, they keep the parameter (the
    same question answered again) and take ``other``'s method and notes. Either way
    the replaced answer's method and notes are gone: ``other``'s rows hold any notes on
    how their targets were read.
    """
    a, b = batch.raw, other.raw
    m = a.q.shape[1]
    mb = b.q.shape[1]
    M = max(m, mb)

    def padded(x: NDArray[Any], fill: Any) -> NDArray[Any]:
        out = np.full((x.shape[0], M, *x.shape[2:]), fill, dtype=x.dtype)
        out[:, : x.shape[1]] = x
        return out

    q, res, slot = padded(a.q, np.nan), padded(a.res, np.nan), padded(a.slot, -1)
    q[rows] = padded(b.q, np.nan)
    res[rows] = padded(b.res, np.nan)
    slot[rows] = np.where(padded(b.slot, -1) >= 0, padded(b.slot, -1) + len(batch.labels), -1)
    fields: dict[str, Any] = {"q": q, "res": res, "slot": slot}
    for key in ("status", "count", "out_count", "gap", "nearest", "near", "free"):
        merged = np.array(getattr(a, key), copy=True)
        merged[rows] = getattr(b, key)
        fields[key] = merged
    shape = batch.shape
    methods = dict(batch.methods)
    notes = dict(batch.notes)
    for j, i in enumerate(rows.tolist()):
        idx = _where(shape, i)
        mine = other[j]
        if notes_of is not None:
            methods[idx] = mine.method
            notes[idx] = (*mine.notes, notes_of[j])
            continue
        # the row's answer is other's alone: none of the replaced answer's method or notes
        if mine.method != batch.method or not mine.complete:
            methods[idx] = mine.method
        else:
            methods.pop(idx, None)
        if mine.notes:
            notes[idx] = mine.notes
        else:
            notes.pop(idx, None)
    parameter = batch.parameter
    if parameter is not None and notes_of is not None:
        values = np.array(parameter[1], dtype=float).reshape(-1)
        values[rows] = np.nan
        parameter = (parameter[0], values.reshape(shape))
    return dataclasses.replace(
        batch,
        raw=_core.BatchAnswer(**fields),
        labels=(*batch.labels, *other.labels),
        methods=methods,
        notes=notes,
        parameter=parameter,
    )


def solve_each(
    answer: Callable[[FloatArray, IKOptions], IKResult], targets: Targets, options: IKOptions
) -> IKResult | IKBatchResult:
    """``answer(T, options)`` of each pose target (one, or a batch of any shape).

    The targets' notes (how each was read) come first in each answer's; a batch's
    ``q0`` rows are given to their targets.
    """
    if targets.single:
        one = answer(targets.poses[0], options)
        notes = targets.notes.get(0, ()) if targets.notes else ()
        return dataclasses.replace(one, notes=(*notes, *one.notes)) if notes else one
    q0 = options.q0
    rows = (
        None
        if q0 is None
        else np.broadcast_to(np.asarray(q0, dtype=float), (*targets.shape, 6)).reshape(-1, 6)
    )
    results: dict[int, IKResult] = {}
    for i in range(targets.poses.shape[0]):
        if i in targets.invalid:
            continue
        opts = options if rows is None else dataclasses.replace(options, q0=rows[i])
        results[i] = answer(targets.poses[i], opts)
    out = stack_results(results, targets, 6, None, None)
    if targets.notes:
        where = {tuple(int(v) for v in np.unravel_index(i, targets.shape)): n
                 for i, n in targets.notes.items()}  # fmt: skip
        merged = dict(out.notes)
        for idx, n in where.items():
            merged[idx] = (*n, *merged.get(idx, ()))
        out = dataclasses.replace(out, notes=merged)
    return out
