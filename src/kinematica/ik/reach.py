"""A target beyond the arm's reach within its joint limits: "unreachable", with its gap.

A closed form works on the arm without its limits (the check sorts its solutions by
them afterwards), so for an arm with a slide it can prove nothing about distance: an
unlimited slide reaches any distance. Far beyond any arm (a target at 1e200 m) it
computes no candidate at all, and nearer (1e50 m) only candidates that round-off has
put far off the target; either way "not found" or a gapless "unreachable" followed.
When the limits are respected, the slide's limits bound the reach
(:func:`~kinematica.ik.numeric.reach_bound`, the numeric search's own bound): a
target farther than that from the base is out of reach by at least the difference,
as every arm of revolute joints answers.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

import kinematica._core as _core
from kinematica.core import Chain

__all__ = ["ANSWERED", "beyond_limited_reach", "limited_reach", "needs_proof"]

FloatArray = NDArray[np.float64]

_UNREACHABLE = _core.STATUS["unreachable"]
_NOT_FOUND = _core.STATUS["not_found"]

#: The status codes of answers with solutions: :func:`needs_proof` is False for them
#: (one target's answer is tested for this first: a set lookup, not a call).
ANSWERED = frozenset(_core.STATUS[k] for k in ("ok", "singular", "out_of_limits"))


def needs_proof(code: int, gap: float | None) -> bool:
    """True for an answer that proved nothing: "not found", or "unreachable" without a gap."""
    return code == _NOT_FOUND or (code == _UNREACHABLE and not (gap is not None and gap > 0.0))


def limited_reach(chain: Chain) -> float:
    """Bound (m) on the tool origin's distance from the base origin, within the limits."""
    from kinematica.ik.numeric import reach_bound  # asked where no candidate reached the target

    return reach_bound(chain, chain.qlim[:, 0], chain.qlim[:, 1])


def beyond_limited_reach(
    chain: Chain,
    poses: FloatArray,
    status: Any,
    gap: Any,
    tol_position: float,
    weights: tuple[float, ...] = (1.0, 1.0, 1.0, 1.0, 1.0, 1.0),
) -> tuple[NDArray[np.bool_], FloatArray]:
    """Targets left without a proof that the limited reach proves out of reach.

    Args:
        chain: The chain (joint limits respected).
        poses: ``(N, 4, 4)`` targets in the chain's base frame.
        status: ``(N,)`` the core's status codes.
        gap: ``(N,)`` the gaps the solver proved (NaN: none).
        tol_position: The position tolerance (m): a gap must exceed it.
        weights: The error components' weights (x, y, z, rx, ry, rz); a solution may
            miss by the tolerance in the weighted norm, so the proof needs the
            smallest position weight times the gap beyond it (none when a
            position component does not count).

    Returns:
        ``(rows, gaps)``: ``(N,)`` True where the answer was "not found" or an
        "unreachable" without a gap and the target lies beyond the limited reach
        by more than ``tol_position``; ``(N,)`` that distance (NaN elsewhere).
    """
    code = np.asarray(status)
    unproven = (code == _NOT_FOUND) | ((code == _UNREACHABLE) & ~(np.asarray(gap) > 0.0))
    out = np.full(code.shape, np.nan)
    w_min = min(weights[:3])
    if w_min <= 0.0 or not unproven.any():  # nothing to prove (the bound is not asked)
        return np.zeros(code.shape, dtype=bool), out
    reach = limited_reach(chain)
    if not np.isfinite(reach):
        return np.zeros(code.shape, dtype=bool), out
    d = poses[:, :3, 3] - chain.start[:3, 3]
    # the largest component first: no square of a coordinate near 1e200 overflows
    big = np.max(np.abs(d), axis=-1)
    scale = np.where(big > 0.0, big, 1.0)
    dist = big * np.linalg.norm(d / scale[:, None], axis=-1)
    g = dist - reach
    rows = unproven & (g * w_min > tol_position)
    out[rows] = g[rows]
    return rows, out
