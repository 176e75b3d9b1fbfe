"""Pose targets of arms with fewer than 6 joints: over-determined, and often printed.

An arm with n < 6 joints reaches an n-dimensional set of poses; a pose target is 6
numbers' worth of conditions. A pose computed by forward kinematics lies on that set
to round-off, but the same pose printed with 5 digits (``kinematica fk --precision
5``) and pasted back lies off it by about the last digit: no configuration reaches it
to 1e-10, and the closed form's candidates, each polished by the check to its
least-squares point, miss by a few 1e-6. Two things follow.

- The answer to an over-determined target is the closest configuration (the
  polished candidate, least squares over the whole pose): its residual is the
  "closest off by" a failure reports, and it is the solution given when a
  tolerance (or the precision below) accepts it, not a farther candidate that a
  looser tolerance let through unpolished.
- A target whose numbers carry fewer digits than a double's is read as printed:
  N significant digits (the most any of its 12 numbers shows), so each entry is
  known to half a unit in the N-th digit of the largest entry of its block
  (position column, rotation block). The closest configuration answers it when
  it misses the target by no more than rounding to that precision can move a
  pose the arm reaches (:func:`rounding_miss`); the note says which precision
  was assumed. Components the arm cannot control are thereby checked against its
  reachable set to the precision the numbers carry.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from decimal import Decimal

import numpy as np
from numpy.typing import ArrayLike, NDArray

import kinematica._core as _core
from kinematica.core import Chain
from kinematica.ik.options import IKOptions
from kinematica.ik.result import IKBatchResult, IKResult, arrays_of
from kinematica.ik.status import IKStatus
from kinematica.ik.tolerance import parse_tolerance

__all__ = [
    "PRINTED_DIGITS_MAX",
    "PRINTED_DIGITS_MIN",
    "answer_overdetermined",
    "half_unit",
    "overdetermined_rows",
    "printed_digits",
    "printed_precision",
    "rounding_miss",
    "significant_digits",
]

FloatArray = NDArray[np.float64]
Solve = Callable[[Chain, ArrayLike, IKOptions], "IKResult | IKBatchResult"]

#: Numbers showing more significant digits than this were computed, not printed (a
#: double shows up to 17): no precision is assumed for them.
PRINTED_DIGITS_MAX = 12
#: Numbers showing fewer than this were typed (0.5, 1e200), not printed from a pose:
#: they are taken as exact.
PRINTED_DIGITS_MIN = 3
_NOT_FOUND = _core.STATUS["not_found"]
_UNREACHABLE = _core.STATUS["unreachable"]
#: A tolerance a hair above the closest candidate's residual accepts it alone.
_JUST_ABOVE = 1.0 + 1e-9


def significant_digits(value: float) -> int:
    """Significant digits of the shortest decimal that reads back as ``value`` (0 for 0)."""
    if value == 0.0 or not math.isfinite(value):
        return 0
    digits = Decimal(repr(float(value))).normalize().as_tuple().digits
    return len(digits)


def printed_digits(values: ArrayLike) -> int | None:
    """The most significant digits any of ``values`` shows; None unless printed.

    None for computed numbers (more than :data:`PRINTED_DIGITS_MAX`) and typed ones
    (fewer than :data:`PRINTED_DIGITS_MIN`, all 0 included).
    """
    n = max((significant_digits(float(v)) for v in np.ravel(values)), default=0)
    return None if n < PRINTED_DIGITS_MIN or n > PRINTED_DIGITS_MAX else n


def half_unit(values: ArrayLike, digits: int) -> float:
    """Half a unit in the ``digits``-th significant digit of the largest of ``values``."""
    big = float(np.abs(np.asarray(values, dtype=float)).max())
    return 0.0 if big == 0.0 else 0.5 * 10.0 ** (math.floor(math.log10(big)) - digits + 1)


def printed_precision(T: ArrayLike) -> tuple[float, float] | None:
    """Half a unit in the last printed digit of a pose's position and rotation entries.

    Args:
        T: ``(4, 4)`` the target as given (before any projection onto SO(3)).

    Returns:
        ``(position, rotation)``: the precision (m; unitless) of the position
        column and of the rotation block read as printed with N significant
        digits, N the most any of the 12 numbers shows; None when they show more
        than :data:`PRINTED_DIGITS_MAX` (computed numbers) or fewer than
        :data:`PRINTED_DIGITS_MIN` (typed ones).
    """
    block = np.asarray(T, dtype=float)[:3, :4]
    n = printed_digits(block)
    if n is None:
        return None
    return half_unit(block[:, 3], n), half_unit(block[:, :3], n)


def rounding_miss(precision: tuple[float, float]) -> float:
    """How far (m and rad together) rounding to ``precision`` can move a pose.

    Entries off by at most ε_p (position) move the position by at most √3·ε_p;
    rotation entries off by at most ε_R, once projected onto SO(3), turn it by at
    most ‖E‖_F/√2 <= 3ε_R/√2 (to first order: the skew part of RᵀE). So a pose
    printed from one the arm reaches lies within ``√(3ε_p² + 4.5ε_R²)`` of it, and
    the closest configuration (least squares over p² + r²) misses it by no more.
    """
    p, r = precision
    return math.sqrt(3.0 * p * p + 4.5 * r * r)


def _note(chain: Chain, precision: tuple[float, float], digits: int | None, accepted: bool) -> str:
    p, r = precision
    within = f"±{p:.1g} m in position, ±{r:.1g} in the rotation entries"
    read = (
        f"target read as printed with {digits} significant digits ({within})"
        if digits
        else f"target taken to the precision its numbers carry ({within})"
    )
    over = f"a pose is over-determined for this {chain.dof}-joint arm"
    if accepted:
        return (
            f"{read}: {over}, and the closest configuration misses it by no more than rounding "
            "to that precision can"
        )
    return f"{read}: {over}, and the closest configuration misses it by more than rounding can"


def _unproven(res: IKResult) -> bool:
    """An "unreachable" without a gap: no candidate within reach of polishing, nothing proven.

    For an over-determined target the closest candidate may still reproduce its
    printed numbers (one printed with 3 or 4 digits misses by more than the check
    polishes).
    """
    return res.status == IKStatus.UNREACHABLE and res.gap is None


def _past_the_boundary(
    chain: Chain,
    target: ArrayLike,
    options: IKOptions,
    first: IKResult,
    solve: Solve,
    precision: tuple[float, float] | None,
) -> IKResult:
    """A printed target proven out of reach by less than its rounding can account for.

    Printed from a pose at the workspace boundary (arm stretched or folded), its
    rounding may put it just outside: the closest candidate then answers it when it
    misses by no more than the rounding can (:func:`rounding_miss`).
    """
    raw = np.asarray(target, dtype=float)
    digits = None
    if precision is None:
        precision, digits = printed_precision(raw), printed_digits(raw[:3, :4])
    if precision is None or first.gap is None:
        return first
    bound = rounding_miss(precision) * _JUST_ABOVE
    if not math.isfinite(bound) or first.gap > bound:
        return first
    near = solve(chain, raw, dataclasses.replace(options, tol=(bound, bound)))
    assert isinstance(near, IKResult)  # one target, one result
    misses = [math.hypot(*res) for res in near.residuals]
    if not misses or min(misses) > bound:
        return first
    keep = int(np.argmin(misses))
    best = dataclasses.replace(
        near,
        solutions=near.solutions[keep : keep + 1],
        residuals=near.residuals[keep : keep + 1],
        branches=near.branches[keep : keep + 1],
    )
    note = _note(chain, precision, digits, accepted=True)
    gap = f"it lies {first.gap:.3g} m past the reach, no farther than its rounding can move a pose"
    return dataclasses.replace(best, notes=(*best.notes, f"{note}; {gap}"))


def answer_overdetermined(
    chain: Chain,
    target: ArrayLike,
    options: IKOptions,
    first: IKResult,
    solve: Solve,
    precision: tuple[float, float] | None = None,
) -> IKResult:
    """The answer to one pose target of an arm with fewer than 6 joints (module docstring).

    Args:
        chain: The chain (``dof < 6``).
        target: ``(4, 4)`` the pose as given.
        options: The call's options (no mask).
        first: What the solver answered with these options.
        solve: The solver (``solve_ik``'s single-target path), called again with
            other tolerances.
        precision: ``(position m, rotation entries)`` the target's numbers carry;
            None: read from their digits (:func:`printed_precision`).

    Returns:
        ``first`` when the default tolerance answered it or nothing was close;
        else the closest configuration, accepted when within the tolerance asked
        for or the target's printed precision (with a note).
    """
    if first.status == IKStatus.UNREACHABLE and first.gap is not None:
        return _past_the_boundary(chain, target, options, first, solve, precision)
    solved = first.status in (IKStatus.OK, IKStatus.SINGULAR)
    if solved and (options.tol is None or first.count == 0):
        return first  # the default tolerance polished what it took
    if not solved and first.status != IKStatus.NOT_FOUND and not _unproven(first):
        return first
    raw = np.asarray(target, dtype=float)
    digits = None
    if not solved and precision is None:  # computed numbers: nothing more to read
        precision = printed_precision(raw)
        digits = printed_digits(raw[:3, :4])
        if precision is None:
            return first
    tol = parse_tolerance(options.tol)

    def within_asked(res: IKResult) -> bool:
        return res.count > 0 and bool(
            np.all(res.residuals[:, 0] <= tol.position)
            and np.all(res.residuals[:, 1] <= tol.rotation)
        )

    tight = first
    if options.tol is not None:
        # every candidate polished to its least-squares point: the closest one's miss
        again = solve(chain, raw, dataclasses.replace(options, tol=None))
        assert isinstance(again, IKResult)  # one target, one result
        tight = again
    if tight.status in (IKStatus.OK, IKStatus.SINGULAR):  # reached to 1e-10 after all
        return tight if solved and within_asked(tight) else first
    if tight.status != IKStatus.NOT_FOUND and not _unproven(tight):
        return first
    p, r = tight.nearest_error
    if not (math.isfinite(p) and math.isfinite(r)):
        return first
    closest = (max(p * _JUST_ABOVE, 1e-300), max(r * _JUST_ABOVE, 1e-300))
    best = solve(chain, raw, dataclasses.replace(options, tol=closest))
    assert isinstance(best, IKResult)
    if best.count == 0 and best.out_of_limits.shape[0] == 0:
        return first
    if solved:  # the tolerance asked for took a farther candidate: the closest instead
        # (when it took several, each is another branch: they stay as they are)
        return best if first.count == 1 and within_asked(best) else first
    assert precision is not None
    miss = best.residuals[0] if best.count else tight.nearest_error
    if math.hypot(*miss) > rounding_miss(precision) * _JUST_ABOVE:
        note = _note(chain, precision, digits, accepted=False)
        return dataclasses.replace(first, notes=(*first.notes, note))
    note = _note(chain, precision, digits, accepted=True)
    return dataclasses.replace(best, notes=(*best.notes, note))


def overdetermined_rows(
    chain: Chain,
    target: ArrayLike,
    options: IKOptions,
    raw: _core.BatchAnswer,
    labels: tuple[str, ...],
    q0s: FloatArray | None,
    solve_one: Solve,
) -> tuple[_core.BatchAnswer, dict[int, tuple[str, ...]]]:
    """A batch's unanswered pose targets (``dof < 6``), each answered as one target.

    Args:
        chain: The chain.
        target: ``(..., 4, 4)`` the targets as given.
        options: The call's options.
        raw: The batch's check output (arrays over the N flat targets).
        labels: The branch labels of the batch's slots.
        q0s: ``(N, n)`` q0 per target, or None.
        solve_one: ``solve_ik`` (one target, the over-determined look included).

    Returns:
        ``(raw, notes)``: the arrays with those rows replaced where the one-target
        answer found solutions, and flat index -> its notes.
    """
    flat = np.asarray(target, dtype=float).reshape(-1, 4, 4)
    rows = np.flatnonzero((raw.status == _NOT_FOUND) | (raw.status == _UNREACHABLE))
    notes: dict[int, tuple[str, ...]] = {}
    if rows.size == 0:
        return raw, notes
    out = arrays_of(raw)
    for i in rows.tolist():
        if options.precision is None and printed_precision(flat[i]) is None:
            continue  # computed numbers: the batch's answer stands
        q0 = None if q0s is None else q0s[i]
        one = solve_one(chain, flat[i], dataclasses.replace(options, q0=q0, workers=None))
        assert isinstance(one, IKResult)  # one target, one result
        found = np.vstack([one.solutions, one.out_of_limits])
        branches = (*one.branches, *one.out_of_limits_branches)
        if found.shape[0] == 0 or any(b not in labels for b in branches):
            continue
        out["q"][i], out["res"][i], out["slot"][i] = np.nan, np.nan, -1
        out["q"][i, : found.shape[0]] = found
        out["res"][i, : one.count] = one.residuals
        out["slot"][i, : found.shape[0]] = [labels.index(b) for b in branches]
        out["status"][i] = _core.STATUS[str(one.status)]
        out["count"][i], out["out_count"][i] = one.count, one.out_of_limits.shape[0]
        out["gap"][i] = np.nan
        notes[i] = one.notes
    return _core.BatchAnswer(**out), notes
