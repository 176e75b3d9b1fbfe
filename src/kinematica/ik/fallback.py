"""Closed forms that may miss a solution: their answers, completed by the numeric search.

An arm whose axes are parallel, perpendicular or meeting only to within the line
geometry's tolerances (:mod:`kinematica.dh.lines`) is solved by the closed form of
the family it nearly belongs to, and every candidate is checked, and polished, on
the real arm. The closed form then knows the real arm only approximately, so it
cannot promise every solution, nor prove a target out of reach by less than the
difference (:attr:`~kinematica.ik.structure.Features.slack`). So its results are
marked incomplete, "unreachable" needs a gap beyond that slack, and a target
for which no candidate survives the check goes to the numeric search, whose
answer, whatever it is, is about the real arm. The search starts from the closed
form's candidate that comes closest on the real arm (:func:`seeds`), unless the
caller gave a first guess.

A partial closed form (position targets of longer arms: its candidates hold joints
4..n at 0) may miss a target that other values of those joints reach: a target
none of its candidates solved goes to the numeric search too.
"""

from __future__ import annotations

from typing import Any

import numpy as np

import kinematica._core as _core
from kinematica.core import Chain
from kinematica.ik.local_search import LOCAL_SEARCH
from kinematica.ik.registry import ClosedForm
from kinematica.spatial import rotation_angle

__all__ = [
    "FALLBACK_NOTE",
    "INCOMPLETE_NOTE",
    "PARTIAL_NOTE",
    "merge_batch",
    "needs_search",
    "searched_note",
    "seeds",
]

#: Said of a closed form's result on a near-degenerate arm.
INCOMPLETE_NOTE = (
    "the arm's axes have this structure only to within the tolerances of the line "
    "geometry: the closed form's solutions are exact for this arm, but it may not give all"
)
#: Said of a target the closed form found nothing for, answered by the numeric search.
FALLBACK_NOTE = (
    "the arm's axes have its closed form's structure only to within the tolerances of the "
    "line geometry, and no candidate of the closed form solved this target: "
    f"the numeric search answered, {LOCAL_SEARCH}"
)

#: Said of a target a partial closed form found nothing for, answered by the numeric search.
PARTIAL_NOTE = (
    "no configuration of the closed form (joints 4 onwards at 0) reaches this target: "
    f"the numeric search answered, {LOCAL_SEARCH}"
)

_NOT_FOUND = _core.STATUS["not_found"]


def searched_note(closed_note: str) -> str:
    """The note of a target a closed form's ``search_note`` names, answered by the search."""
    return f"{closed_note}, {LOCAL_SEARCH}"


def needs_search(status: Any) -> Any:
    """Where (``(N,)`` bools, or one bool) the closed form found nothing on the real arm."""
    return status == _NOT_FOUND


def seeds(closed: ClosedForm, chain: Chain, poses: Any, position: bool, default: Any) -> Any:
    """``(k, n)`` first guesses of the search: per target, the closed form's closest candidate.

    Args:
        closed: The closed form whose candidates missed.
        chain: The real arm.
        poses: ``(k, 4, 4)`` the targets (a position target's origin only counts).
        position: The targets are positions.
        default: ``(n,)`` the guess of a target without any candidate.

    Returns:
        ``(k, n)``: the candidate whose forward kinematics on the real arm lies
        nearest the target (the larger of its position error in m and rotation
        error in rad).
    """
    out = np.empty((len(poses), chain.dof))
    for i, T in enumerate(poses):
        Q = np.asarray(closed.params.candidates(chain.core, T, None)[0])
        Q = np.ascontiguousarray(Q[np.isfinite(Q).all(axis=1)])
        if not len(Q):
            out[i] = default
            continue
        F = chain.fk(Q)[0]
        err = np.linalg.norm(F[:, :3, 3] - T[:3, 3], axis=1)
        if not position:
            err = np.maximum(err, rotation_angle(F[:, :3, :3], T[:3, :3]))
        out[i] = Q[int(np.argmin(err))]
    return out


def merge_batch(
    raw: _core.BatchAnswer,
    rows: Any,
    searched: _core.BatchAnswer,
    closed: ClosedForm | None,
    poses: Any,
) -> _core.BatchAnswer:
    """The closed form's batch ``raw`` with rows ``rows`` replaced by the search's answers.

    Args:
        raw: The closed form's ``ik_batch`` answer (arrays with ``m`` slots).
        rows: ``(k,)`` indices of the targets the search answered.
        searched: The numeric ``ik_batch`` answer for those targets (1 slot).
        closed: The closed form, whose ``mark_searched`` (if any) says of the search's
            answers what it says of its own.
        poses: ``(k, 4, 4)`` those targets.

    Returns:
        The arrays with one more slot, ``m``, the search's; its label follows the
        closed form's labels.
    """
    N, m, n = raw.q.shape
    found = {key: np.array(getattr(searched, key)) for key in ("status", "free")}
    if closed is not None and closed.mark_searched is not None:
        closed.mark_searched(poses, searched.q[:, 0], found["status"], found["free"])
    q = np.full((N, m + 1, n), np.nan)
    q[:, :m] = raw.q
    res = np.full((N, m + 1, 2), np.nan)
    res[:, :m] = raw.res
    slot = np.full((N, m + 1), -1, dtype=np.int64)
    slot[:, :m] = raw.slot
    q[rows] = np.nan
    res[rows] = np.nan
    slot[rows] = -1
    q[rows, 0] = searched.q[:, 0]
    res[rows, 0] = searched.res[:, 0]
    slot[rows, 0] = np.where(searched.slot[:, 0] >= 0, m, -1)
    out: dict[str, Any] = {"q": q, "res": res, "slot": slot}
    for key in ("status", "count", "out_count", "gap", "nearest", "near", "free"):
        merged = np.array(getattr(raw, key), copy=True)
        merged[rows] = found.get(key, getattr(searched, key))
        out[key] = merged
    return _core.BatchAnswer(**out)
