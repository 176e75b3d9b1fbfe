"""The core's jerk-limited segments and waypoint search (``cpp/include/kinematica/jerk.hpp``).

Every state here has zero acceleration: a segment goes from ``(p0, v0, 0)`` to
``(p1, v1, 0)``, each joint's profile time-optimal or, for a joint that is not the
slowest, of the common duration. The caller (:mod:`kinematica.motion.scurve_via`)
checks the user's input; this module only names what the core returns.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import NDArray

import kinematica._core as _core

__all__ = [
    "MAX_PHASES",
    "PIECE_RTOL",
    "SETTLE_ULPS",
    "STATE_ROW",
    "Segments",
    "StateMove",
    "ViaChoice",
    "ViaMove",
    "jerk_segments",
    "jerk_state_move",
    "jerk_via",
    "jerk_via_move",
]

FloatArray = NDArray[np.float64]

#: Most phases of constant jerk in one joint's profile of one segment.
MAX_PHASES: int = _core.JERK_MAX_PHASES
#: Pieces of a move shorter than this fraction of its duration (or of 1 s) are merged into
#: their neighbour: two joints' switches at the same time up to round-off would otherwise
#: leave a piece of 1e-17 s.
PIECE_RTOL: float = _core.JERK_PIECE_RTOL
#: End-position errors of a state-to-state move up to this many units in the last place of
#: the target are round-off of the pieces' own arithmetic, and left as they are; beyond,
#: the end is settled on the target (``jerk_pieces.hpp``).
SETTLE_ULPS: float = _core.JERK_SETTLE_ULPS
#: Values in one joint's row of a state-to-state move's phases (:func:`jerk_state_move`).
STATE_ROW: int = _core.JERK_STATE_ROW


class Segments(NamedTuple):
    """``m`` segments of ``n`` joints.

    Attributes:
        duration: ``(m,)`` each segment's duration (s).
        t: ``(m, n, MAX_PHASES)`` each joint's phase durations (s; zero past ``phases``).
        j: ``(m, n, MAX_PHASES)`` their jerks.
        phases: ``(m, n)`` how many phases each joint has.
    """

    duration: FloatArray
    t: FloatArray
    j: FloatArray
    phases: NDArray[np.int64]


class ViaChoice(NamedTuple):
    """What the waypoint search chose.

    Attributes:
        velocity: ``(k, n)`` the velocities at the waypoints.
        time: ``(k - 1,)`` each segment's duration (s).
        stop: ``(k - 1,)`` each segment's duration with a stop at every waypoint (inf
            where a segment then leaves qlim).
        evaluations: Segments the search planned.
    """

    velocity: FloatArray
    time: FloatArray
    stop: FloatArray
    evaluations: int


class ViaMove(NamedTuple):
    """The waypoint search's choice and the move it makes (:func:`jerk_via_move`).

    Attributes:
        choice: The :class:`ViaChoice`.
        breaks: ``(p + 1,)`` the exact pieces' breaks (s), every knot among them; ``None``
            (and every field below) where a segment leaves qlim with a stop at each
            waypoint, or the samples would be too many.
        coef: ``(p, 4, n)`` each piece's cubic per joint in ``t - breaks[i]`` (lowest
            power first).
        knots: ``(k,)`` the waypoints' times (s).
        peak: ``(3, n)`` each joint's largest ``|velocity|``, ``|acceleration|``,
            ``|jerk|`` on the pieces (exact: at the pieces' ends and extremes).
        samples: ``(t, q, qd, qdd, qddd)``: ``(m,)`` times (s), every knot among them,
            spacing ``<= dt``; ``(m, n)`` each; the last is the end state exactly.
    """

    choice: ViaChoice
    breaks: FloatArray | None
    coef: FloatArray | None
    knots: FloatArray | None
    peak: FloatArray | None
    samples: tuple[FloatArray, FloatArray, FloatArray, FloatArray, FloatArray] | None


class StateMove(NamedTuple):
    """The exact pieces and samples of a state-to-state move (:func:`jerk_state_move`).

    Attributes:
        breaks: ``(p + 1,)`` the pieces' breaks (s).
        coef: ``(p, 4, n)`` each piece's cubic per joint in ``t - breaks[i]`` (lowest power
            first), or ``(p, 6, n)`` quintic where a joint's end was settled on its target.
        knots: ``(2,)`` ``0`` and the duration.
        peak: ``(3, n)`` each joint's largest ``|velocity|``, ``|acceleration|``, ``|jerk|``
            (exact on the cubics; where a step settled a joint's end, its phase's with the
            step's peaks added: a bound).
        samples: ``(t, q, qd, qdd, qddd)``: ``(m,)`` times (s), spacing ``<= dt``; ``(m, n)``
            each; the last is the end state exactly.
    """

    breaks: FloatArray
    coef: FloatArray
    knots: FloatArray
    peak: FloatArray
    samples: tuple[FloatArray, FloatArray, FloatArray, FloatArray, FloatArray]


def _f(x: FloatArray) -> FloatArray:
    return np.ascontiguousarray(x, dtype=float)


def jerk_segments(
    p0: FloatArray,
    v0: FloatArray,
    p1: FloatArray,
    v1: FloatArray,
    limits: tuple[FloatArray, FloatArray, FloatArray],
) -> Segments:
    """Time-optimal synchronised segments, each ``(m, n)`` state at zero acceleration.

    Args:
        p0: ``(m, n)`` start positions.
        v0: ``(m, n)`` start velocities.
        p1: ``(m, n)`` end positions.
        v1: ``(m, n)`` end velocities.
        limits: ``(vmax, amax, jmax)``, each ``(n,)`` positive; ``|v| <= vmax``.

    Returns:
        The :class:`Segments`.
    """
    vm, am, jm = (_f(x) for x in limits)
    return Segments(*_core.jerk_segments(_f(p0), _f(v0), _f(p1), _f(v1), vm, am, jm))


def jerk_via(
    w: FloatArray,
    v_start: FloatArray,
    v_end: FloatArray,
    limits: tuple[FloatArray, FloatArray, FloatArray],
    qlim: FloatArray | None,
    qlim_atol: float,
    search: tuple[int, int, int],
) -> ViaChoice:
    """The waypoints' velocities of a short jerk-limited move through ``w`` (k, n).

    :func:`jerk_via_move`'s search alone (no pieces or samples made: ``max_samples`` 0).

    Args:
        w: ``(k, n)`` waypoints, no two in a row equal.
        v_start: ``(n,)`` the velocity at the first waypoint.
        v_end: ``(n,)`` the velocity at the last waypoint.
        limits: ``(vmax, amax, jmax)``, each ``(n,)``.
        qlim: ``(n, 2)`` position limits every segment keeps, or ``None``.
        qlim_atol: How far a segment's extreme may pass a position limit.
        search: ``(sweeps, golden_steps, joint_sweeps)`` (``jerk_via.hpp``).

    Returns:
        The :class:`ViaChoice`.
    """
    return jerk_via_move(w, v_start, v_end, limits, qlim, qlim_atol, search, 1.0, 0.0).choice


def jerk_via_move(
    w: FloatArray,
    v_start: FloatArray,
    v_end: FloatArray,
    limits: tuple[FloatArray, FloatArray, FloatArray],
    qlim: FloatArray | None,
    qlim_atol: float,
    search: tuple[int, int, int],
    dt: float,
    max_samples: float,
) -> ViaMove:
    """:func:`jerk_via`'s search, then the move's exact pieces and samples, in one call.

    Args:
        w: ``(k, n)`` waypoints, no two in a row equal.
        v_start: ``(n,)`` the velocity at the first waypoint.
        v_end: ``(n,)`` the velocity at the last waypoint.
        limits: ``(vmax, amax, jmax)``, each ``(n,)``.
        qlim: ``(n, 2)`` position limits every segment keeps, or ``None``.
        qlim_atol: How far a segment's extreme may pass a position limit.
        search: ``(sweeps, golden_steps, joint_sweeps)`` (``jerk_via.hpp``).
        dt: Largest sample spacing (s), > 0.
        max_samples: No pieces or samples are made where ``duration / dt + k`` exceeds it.

    Returns:
        The :class:`ViaMove`.
    """
    vm, am, jm = (_f(x) for x in limits)
    q = None if qlim is None else _f(qlim)
    out = _core.jerk_via_move(
        _f(w), _f(v_start), _f(v_end), vm, am, jm, q, float(qlim_atol), *search, dt, max_samples
    )
    velocity, time, stop, evaluations, exact, samples = out
    choice = ViaChoice(velocity, time, stop, int(evaluations))
    if exact is None:
        return ViaMove(choice, None, None, None, None, None)
    breaks, coef, knots, peak = exact
    return ViaMove(choice, breaks, coef, knots, peak, samples)


def jerk_state_move(
    T: float,
    rows: FloatArray,
    limits: tuple[FloatArray, FloatArray, FloatArray],
    end: tuple[FloatArray, FloatArray, FloatArray],
    dt: float,
    max_samples: float,
) -> StateMove:
    """A state-to-state move's exact pieces and samples from its joints' phases, in one call.

    Args:
        T: Duration (s), >= 0.
        rows: ``(n, STATE_ROW)`` each joint's phases as ruckig plans them
            (``jerk_pieces.hpp``: the durations of a brake's 2 phases and the profile's 7,
            their jerks, their start positions, velocities and accelerations, the target).
        limits: ``(vmax, amax, jmax)``, each ``(n,)`` positive.
        end: ``(q1, v1, a1)``, each ``(n,)``: the last sample.
        dt: Largest sample spacing (s), > 0.
        max_samples: Refused (``ValueError``) where ``T / dt + 1`` exceeds it.

    Returns:
        The :class:`StateMove`, each joint's end settled on its target position.
    """
    vm, am, jm = (_f(x) for x in limits)
    q1, v1, a1 = (_f(x) for x in end)
    exact, samples = _core.jerk_state_move(
        float(T), _f(rows), vm, am, jm, q1, v1, a1, float(dt), float(max_samples)
    )
    breaks, coef, knots, peak = exact
    return StateMove(breaks, coef, knots, peak, samples)
