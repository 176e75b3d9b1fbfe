"""Jerk-limited moves through waypoints, without a stop at each.

Every waypoint is reached exactly; between two waypoints the move is one
jerk-limited segment, time-optimal for its slowest joint and synchronised across
the joints. The acceleration at every waypoint, the two ends included, is zero:
then each segment is a move between two states of velocity only, whose
time-optimal profile, the durations each joint can take and a profile of any of
them have closed forms (one scalar root at most), so the whole move is made in the
compiled core in one call (``cpp/include/kinematica/jerk.hpp``, ``jerk_via.hpp``,
``jerk_pieces.hpp``): the search, at a fraction of a µs a segment planned, then the
exact pieces (each segment's joints' profiles cut at their switches into cubics) and
the samples. The price: the
velocity a waypoint is passed at is searched, its acceleration is not (a move
that passes a waypoint still accelerating could be shorter). A start or end
acceleration is refused here: :func:`~kinematica.motion.trajectory.joint_trajectory`
plans a move from any state.

What is chosen is the velocity at each intermediate waypoint, to make the whole
move short:

1. A direction per waypoint from its neighbours: a joint that moves the same way
   before and after the waypoint keeps moving through it, along the chord
   ``w[i+1] - w[i-1]``; a joint that turns back (or does not move on one side)
   passes it at rest. The chord is scaled to the highest speed the joints'
   ``vmax`` allow along it: ``vhat[i]``.
2. The velocity at waypoint ``i`` is ``λ_i · vhat[i]`` with ``λ_i`` in ``[0, 1]``:
   one common ``λ`` for every waypoint is tried on a grid (a stop at each
   included), then each ``λ_i`` in turn is searched (golden section,
   :data:`GOLDEN_STEPS` evaluations) on the sum of its two segments' durations,
   for :data:`SWEEPS` sweeps; then each joint's own speed at each waypoint, for
   :data:`JOINT_SWEEPS` sweeps. A value is only accepted when it shortens the
   move, so the result is never longer than stopping at each waypoint; ``margin``
   on the result says by how much it is shorter. A joint's own speed is searched
   only where the joint binds one of the waypoint's two segments (the slowest
   joint alone, or one whose blocked durations moved the segment's), since no
   other joint's speed can shorten them, and it is timed against the other
   joints' duration without planning them again; that duration bounds the search
   from below, so it is skipped where the bound is no shorter than the two
   segments today and ends once a candidate reaches it; a candidate keeps the
   durations of the joints it does not change. A golden-section point whose lower
   bound (its segments' slowest joints timed so far) already passes the point the
   section keeps is dropped there, which changes nothing the section does. About
   30-45 segments are timed in full for each segment of the move (a joint timed
   against the others counts as one; ``docs/performance.md`` has the times).
3. With position limits (``qlim``) a segment whose exact extremes (which include
   any overshoot of a waypoint) leave them counts as infinitely long, so the
   search only keeps waypoint velocities whose segments stay inside.

The search is a heuristic, not a global optimum over every joint's velocity: the
duration it gives is an upper bound of the best jerk-limited move through the
same waypoints with zero acceleration at each.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.arguments import check_size
from kinematica.core.jerk import jerk_via_move
from kinematica.errors import DimensionError, KinematicaError
from kinematica.motion.piecewise import PiecewisePolynomial
from kinematica.motion.samples import MAX_SAMPLES
from kinematica.motion.scurve import JerkTrajectory, check_peak, limits_from, state_from, wrap

__all__ = ["GOLDEN_STEPS", "JOINT_SWEEPS", "POSITION_ATOL", "SWEEPS", "scurve_via"]

FloatArray = NDArray[np.float64]

#: Evaluations of each waypoint's golden-section search on [0, 1] (0.618^8 ~ 2 %).
GOLDEN_STEPS = 8
#: Sweeps over the waypoints with one speed fraction each, then with each joint's own.
SWEEPS = 1
JOINT_SWEEPS = 1
#: How far (rad, m) a waypoint or a segment's extreme may pass a position limit:
#: round-off of a segment that ends on the limit.
POSITION_ATOL = 1e-12


def _qlim(qlim: ArrayLike | None, w: FloatArray) -> FloatArray | None:
    """``(n, 2)`` position limits, checked, with every waypoint inside them."""
    if qlim is None:
        return None
    n = w.shape[1]
    try:
        lim = np.asarray(qlim, dtype=float)
    except (TypeError, ValueError):
        raise DimensionError(f"qlim must be ({n}, 2) numbers: low, high", arg="qlim") from None
    if lim.shape != (n, 2) or np.any(np.isnan(lim)) or np.any(lim[:, 0] > lim[:, 1]):
        raise DimensionError(
            f"qlim must be ({n}, 2): a low and a high limit per joint, low <= high", arg="qlim"
        )
    out = (w < lim[:, 0] - POSITION_ATOL) | (w > lim[:, 1] + POSITION_ATOL)
    if out.any():
        i, j = (int(x[0]) for x in np.nonzero(out))
        raise KinematicaError(
            f"waypoint {i + 1}: joint {j + 1} at {w[i, j]:.9g} is outside its limits "
            f"[{lim[j, 0]:g}, {lim[j, 1]:g}]",
            arg="qlim",
        )
    return lim


def scurve_via(
    w: FloatArray,
    dt: float,
    vmax: ArrayLike | None,
    amax: ArrayLike | None,
    jmax: ArrayLike | None,
    *,
    qlim: ArrayLike | None = None,
    qd0: ArrayLike | None = None,
    qd1: ArrayLike | None = None,
    qdd0: ArrayLike | None = None,
    qdd1: ArrayLike | None = None,
) -> JerkTrajectory:
    """A jerk-limited move through every waypoint (module docstring).

    Called by :func:`~kinematica.motion.via.via_trajectory` with
    ``method="scurve"``.

    Args:
        w: ``(k, n)`` waypoints (rad, m), checked; no two in a row equal.
        dt: Largest sample spacing (s); every waypoint's time is a sample.
        vmax: Speed limit per joint (a number or ``(n,)``; rad/s, m/s).
        amax: Acceleration limit per joint (rad/s², m/s²).
        jmax: Jerk limit per joint (rad/s³, m/s³).
        qlim: ``(n, 2)`` position limits (low, high) every sample keeps; none if ``None``.
        qd0: ``(n,)`` start velocity (zero by default).
        qd1: ``(n,)`` end velocity.
        qdd0: ``(n,)`` start acceleration: zero (the acceleration at every waypoint is).
        qdd1: ``(n,)`` end acceleration: zero.

    Returns:
        :class:`~kinematica.motion.scurve.JerkTrajectory` with
        ``waypoint_times``, ``waypoint_qd``, ``stop_duration`` and ``margin``.

    Raises:
        KinematicaError: A missing or non-positive limit, two equal waypoints
            in a row, a waypoint outside ``qlim``, end states outside the
            limits, a start or end acceleration that is not zero, or ends whose
            segments leave ``qlim`` even with a stop at every waypoint.
    """
    k, n = w.shape
    limits = _limits((vmax, amax, jmax), n)
    lim = _qlim(qlim, w)
    v_start, v_end = state_from(qd0, n, "qd0"), state_from(qd1, n, "qd1")
    for name, x in (("qdd0", qdd0), ("qdd1", qdd1)):
        if x is not None and np.any(state_from(x, n, name) != 0.0):
            raise KinematicaError(
                f"through waypoints the acceleration is zero at every waypoint, the ends "
                f"included: {name} must be 0; joint_trajectory(..., profile='scurve') "
                "moves from or to an accelerating state",
                arg=name,
            )
    search = (SWEEPS, GOLDEN_STEPS, JOINT_SWEEPS)
    lims = (limits[0], limits[1], limits[2])
    try:  # the core checks the limits, the end velocities and the waypoints
        move = jerk_via_move(w, v_start, v_end, lims, lim, POSITION_ATOL, search, dt, MAX_SAMPLES)
    except ValueError:
        _refused(w, limits, v_start, v_end)
        raise
    choice = move.choice
    if not np.all(np.isfinite(choice.stop)):
        i = int(np.flatnonzero(~np.isfinite(choice.stop))[0])
        raise KinematicaError(
            f"segment {i + 1} (waypoints {i + 1} to {i + 2}) leaves qlim even with a stop at "
            "each waypoint: its end velocity carries it over a limit"
        )
    duration = float(choice.time.sum())
    check_size(duration / dt + k, MAX_SAMPLES, "dt", f"samples ({duration:g} s every {dt!r} s)")
    assert move.samples is not None and move.peak is not None and move.knots is not None
    check_peak(move.peak, lims)
    pieces = PiecewisePolynomial(move.breaks, move.coef, move.knots)  # type: ignore[arg-type]
    traj = wrap(move.samples, pieces, lims)
    traj.waypoint_times = move.knots
    traj.waypoint_qd = choice.velocity
    traj.stop_duration = float(choice.stop.sum())
    traj.margin = traj.stop_duration - float(move.knots[-1])
    return traj


def _limits(given: tuple[ArrayLike | None, ...], n: int) -> FloatArray:
    """``(3, n)`` vmax, amax, jmax as numbers (a number or ``(n,)`` each).

    The core checks their values, and :func:`_refused` names a bad one.

    Raises:
        KinematicaError: A limit missing.
        DimensionError: A limit of the wrong shape or not numbers.
    """
    out = np.empty((3, n))
    for row, (x, name) in enumerate(zip(given, ("vmax", "amax", "jmax"), strict=True)):
        if x is None:
            limits_from(x, n, name)  # raises: the limit is needed
        try:
            out[row] = x
        except (TypeError, ValueError):
            limits_from(x, n, name)  # raises with the shape
            raise
    return out


def _refused(w: FloatArray, limits: FloatArray, v_start: FloatArray, v_end: FloatArray) -> None:
    """Name the input the core refused (it says only which argument).

    Raises:
        KinematicaError: A limit not positive (the joint named), two equal waypoints in
            a row, an end velocity beyond vmax.
        DimensionError: A limit NaN or inf.
    """
    n = w.shape[1]
    for row, name in enumerate(("vmax", "amax", "jmax")):
        limits_from(limits[row], n, name)
    same = np.all(np.diff(w, axis=0) == 0.0, axis=1)
    if same.any():
        i = int(np.flatnonzero(same)[0])
        raise KinematicaError(f"waypoints {i + 1} and {i + 2} are equal: drop one")
    for name, x in (("qd0", v_start), ("qd1", v_end)):
        over = np.abs(x) > limits[0]
        if over.any():
            j = int(np.flatnonzero(over)[0])
            raise KinematicaError(
                f"{name} of joint {j + 1} is {x[j]:g}, beyond its vmax {limits[0, j]:g}", arg=name
            )
