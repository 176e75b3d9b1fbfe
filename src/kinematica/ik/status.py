"""The statuses of an IK answer, and the sentence each one gives people."""

from __future__ import annotations

import math
from enum import StrEnum

import kinematica._core as _core

__all__ = ["STATUS_NAMES", "IKStatus", "held", "status_message"]


class IKStatus(StrEnum):
    """What an IK answer is. Each compares equal to its string, e.g. ``"ok"``.

    Attributes:
        OK: Every solution found (a closed form), or one found (the numeric search:
            a local search, more may exist; the result's ``complete`` is False, and
            where ``method="auto"`` fell back to it, a note says why).
        SINGULAR: Infinitely many solutions; the rows are representatives and
            ``free_joints`` names the joints left free.
        OUT_OF_LIMITS: Solutions exist, none within the joint limits.
        UNREACHABLE: Provably no solution: the target is beyond a proven bound
            (``gap`` says how far), or a closed form has no real root where it
            is well conditioned.
        NOT_FOUND: A numeric search did not converge (or found solutions
            only just outside the limits), or a closed form near a singular set
            found no solution to tolerance: the target may still be reachable.
        INVALID: In a batch, a malformed target (its message says what is wrong).
    """

    OK = "ok"
    SINGULAR = "singular"
    OUT_OF_LIMITS = "out_of_limits"
    UNREACHABLE = "unreachable"
    NOT_FOUND = "not_found"
    INVALID = "invalid"


#: Status of each of the core's status codes (``kinematica._core.STATUS``).
STATUS_NAMES: dict[int, IKStatus] = {code: IKStatus(name) for name, code in _core.STATUS.items()}


def status_message(
    status: str,
    *,
    method: str,
    count: int,
    out_of_limits: int,
    free: tuple[int, ...],
    gap: float,
    nearest: tuple[float, float],
    complete: bool,
    near: bool = False,
    held: str | None = None,
) -> str:
    """One sentence for people about an IK outcome.

    Args:
        status: The status.
        method: The method name, e.g. ``"analytic:spherical-wrist"``.
        count: Solutions within limits.
        out_of_limits: Solutions outside the limits.
        free: 0-based indices of the free joints (singular case).
        gap: Distance outside the reach (m), NaN if unknown, inf when it
            overflows.
        nearest: Position (m) and rotation (rad) error of the closest
            candidate that was not a solution, NaN if none.
        complete: The method gives every solution (a closed form).
        near: The target is within round-off of a singular set (the closed
            form's solutions there may merge or be lost to round-off).
        held: The joint held at a value for this answer (``"q7 = 0.3"``,
            see :func:`held`): the outcome is said of the arm with it there.
    """
    text = _message(status, method, count, out_of_limits, free, gap, nearest, complete, near)
    if held is None or status == IKStatus.INVALID:
        return text
    if status in (IKStatus.OK, IKStatus.SINGULAR):
        return f"{text}, with {held}"
    head, _, rest = text.partition(": ")
    if not rest:  # "3 solutions exist, none within the joint limits"
        return f"with {held}: {text}; other values may do better"
    name = held.split(" = ")[0]
    return (
        f"{head} with {held}: {rest} (said of the arm with {name} held there; "
        f"other values of {name} may reach it)"
    )


def held(name: str, value: float) -> str:
    """How messages name a joint held at a value: ``"q7 = 0.3"`` (the API's units: rad, m)."""
    return f"{name} = {value:.6g}"


def _message(
    status: str,
    method: str,
    count: int,
    out_of_limits: int,
    free: tuple[int, ...],
    gap: float,
    nearest: tuple[float, float],
    complete: bool,
    near: bool,
) -> str:
    """:func:`status_message` of an answer with every joint free."""
    plural = "s" if count != 1 else ""
    if status == IKStatus.OK:
        extra = f"; {out_of_limits} more outside the joint limits" if out_of_limits else ""
        return f"{count} solution{plural} ({method}){extra}"
    if status == IKStatus.SINGULAR:
        names = ", ".join(f"q{v + 1}" for v in free)
        return (
            f"singular: infinitely many solutions ({names or 'some joints'} free); "
            f"{count} representative{plural} given"
        )
    if status == IKStatus.OUT_OF_LIMITS:
        s = "s" if out_of_limits != 1 else ""
        return f"{out_of_limits} solution{s} exist, none within the joint limits"
    pos, rot = nearest
    miss = f" (closest off by {pos:.3g} m, {rot:.3g} rad)" if math.isfinite(pos) else ""
    if status == IKStatus.UNREACHABLE:
        if gap > 0.0:
            return _beyond(gap)
        if not complete:  # a search proves nothing but a gap
            return "unreachable: the target is out of reach"
        if math.isfinite(pos):
            return (
                "unreachable: no configuration reaches this pose "
                f"(closest candidate off by {pos:.3g} m, {rot:.3g} rad)"
            )
        return "unreachable: the closed form has no real solution for this target"
    if status == IKStatus.INVALID:
        return "invalid target"
    if complete:
        if near:
            return (
                "not found: the target is within round-off of a singular set or a workspace "
                f"boundary, where closed-form solutions merge, and none meets the tolerance"
                f"{miss}; a looser tol may accept one"
            )
        return (
            f"not found: no configuration reaches this target within the tolerance{miss}: "
            "it is not exactly reachable; a looser tol accepts the closest if that is enough"
        )
    if out_of_limits:
        s = "s" if out_of_limits != 1 else ""
        return (
            f"not found: the numeric search found {out_of_limits} solution{s} just outside "
            "the joint limits and none within them; one may still exist within them"
        )
    return (
        f"not found: the numeric search did not converge{miss}; the target may still "
        "be reachable (another initial guess or seed may find it)"
    )


def _beyond(gap: float) -> str:
    """The message of a target proven out of reach by ``gap`` (m, > 0, maybe inf)."""
    if math.isinf(gap):
        return (
            "unreachable: the target is farther outside the reach than a float can hold "
            "(its distance overflows)"
        )
    return f"unreachable: the target is at least {gap:.6g} m outside the reach"
