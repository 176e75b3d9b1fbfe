"""Joint trajectories through waypoints: splines and linear segments with blends.

:func:`via_trajectory` samples, :func:`via_polynomials` returns the pieces
(for exact values at any time and the left and right limits at a knot).

Four methods:

- ``"cubic"``: the C2 cubic spline (continuous acceleration) through every
  waypoint (:mod:`kinematica.motion.splines`), clamped (end velocities given,
  zero by default) or natural (zero end accelerations);
- ``"quintic"``: the C4 quintic spline (continuous acceleration, jerk and
  snap; the least-jerk interpolant), clamped (end velocities and
  accelerations given, zero by default) or natural (zero end jerk and snap);
- ``"mstraj"``: the Robotics Toolbox's ``mstraj``, sample for sample
  (:mod:`kinematica.motion.mstraj`, with where it differs on purpose): lines
  between the waypoints joined by quintic blends of ``tacc``, every time
  rounded up to whole steps of ``dt``; the via points are cut, start and end
  reached exactly;
- ``"scurve"``: jerk-limited segments from waypoint to waypoint, the
  velocities at the waypoints chosen to shorten the move instead of stopping
  at each (the acceleration zero there), position limits held
  (:mod:`kinematica.motion.scurve_via`, in the compiled core; needs ``vmax``,
  ``amax``, ``jmax``).

With ``qd=`` (and ``qdd=``) the cubic and quintic pieces take the velocities
(and accelerations) given at every waypoint instead of solving for them, as
MATLAB's ``cubicpolytraj`` / ``quinticpolytraj`` do (whose default is zero at
every waypoint: a stop at each).

Times: given (``times``), or derived from the per-joint limits. For the
splines, segment ``i`` first gets its slowest joint's rest-to-rest minimum
time (as :func:`~kinematica.motion.trajectory.minimum_time`), then every time
is scaled by one factor so that the spline's peak speed and acceleration
(computed exactly, piece by piece) just reach the tightest ``vmax`` or
``amax``: a spline with rest or natural ends scales exactly with its times.
For ``"mstraj"``, ``vmax`` is the Toolbox's ``qdmax`` (per joint, or per
segment and joint, ``(k-1, n)``): each segment lasts its slowest joint's time.

Porting the Toolbox's ``mstraj(viapoints, dt, tacc, qdmax=, tsegment=, q0=,
qd0=, qdf=)``: ``W`` is ``viapoints`` with ``q0`` as its first row (as the
Toolbox reads ``viapoints`` without ``q0``), ``vmax=qdmax``, ``times=[0,
*cumsum(tsegment)]`` (waypoint times, as for the other methods), ``qd1=qdf``
(the end velocity's name for every method); ``dt`` and ``tacc`` as they are.
``verbose`` has no counterpart: the library prints nothing; the pieces
(:func:`via_polynomials` with the same ``dt``) hold every blend and line, each
starting and ending on a break.
"""

from __future__ import annotations

import math
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.arguments import check_number, check_size
from kinematica.errors import DimensionError, KinematicaError
from kinematica.motion.mstraj import mstraj_pieces
from kinematica.motion.piecewise import PiecewisePolynomial
from kinematica.motion.splines import Ends, hermite_pieces, spline_derivatives
from kinematica.motion.trajectory import (
    DEFAULT_DT,
    LIMIT_RTOL,
    MAX_SAMPLES,
    JointTrajectory,
    minimum_time,
)

__all__ = ["Method", "via_polynomials", "via_trajectory"]

FloatArray = NDArray[np.float64]
Method = Literal["cubic", "quintic", "mstraj", "scurve"]


def _array(x: ArrayLike | None, shape: tuple[int, ...], name: str) -> FloatArray:
    """``x`` (a number, or an array broadcastable to ``shape``) as floats, checked."""
    try:
        a = np.asarray(0.0 if x is None else x, dtype=float)
        out = np.broadcast_to(a, shape).astype(float)
    except (TypeError, ValueError):
        raise DimensionError(
            f"{name} must be a number or numbers of shape {shape}", arg=name
        ) from None
    if not np.all(np.isfinite(out)):
        raise DimensionError(f"{name} holds NaN or inf", arg=name)
    return out


def _limit(x: ArrayLike | None, shape: tuple[int, ...], name: str) -> FloatArray | None:
    if x is None:
        return None
    out = _array(x, shape, name)
    if np.any(out <= 0):
        j = int(np.flatnonzero(out.reshape(-1, shape[-1]) <= 0)[0]) % shape[-1]
        raise KinematicaError(f"{name} must be positive (joint {j + 1})", arg=name)
    return out


def _waypoints(waypoints: ArrayLike) -> FloatArray:
    try:
        w = np.asarray(waypoints, dtype=float)
    except (TypeError, ValueError):
        msg = "waypoints must be a (k, n) array of numbers"
        raise DimensionError(msg, arg="waypoints") from None
    if w.ndim != 2 or w.shape[0] < 2 or w.shape[1] == 0:
        raise DimensionError(
            f"waypoints must be (k, n) with k >= 2 configurations, got shape {w.shape}",
            arg="waypoints",
        )
    if not np.all(np.isfinite(w)):
        raise DimensionError("waypoints hold NaN or inf", arg="waypoints")
    return w


def _times(times: ArrayLike, k: int) -> FloatArray:
    t = _array(times, np.shape(times), "times")
    if t.shape != (k,) or not np.all(np.isfinite(t)):
        raise DimensionError(f"times must be {k} finite values (one per waypoint)", arg="times")
    if t[0] != 0.0 or np.any(np.diff(t) <= 0):
        raise KinematicaError("times must start at 0 and increase strictly", arg="times")
    return t


def via_polynomials(
    waypoints: ArrayLike,
    method: Method = "cubic",
    times: ArrayLike | None = None,
    vmax: ArrayLike | None = None,
    amax: ArrayLike | None = None,
    *,
    tacc: ArrayLike | None = None,
    ends: Ends = "clamped",
    qd0: ArrayLike | None = None,
    qd1: ArrayLike | None = None,
    qdd0: ArrayLike | None = None,
    qdd1: ArrayLike | None = None,
    qd: ArrayLike | None = None,
    qdd: ArrayLike | None = None,
    dt: float | None = None,
) -> PiecewisePolynomial:
    """The pieces of the trajectory through ``waypoints`` (arguments of :func:`via_trajectory`).

    For ``"scurve"`` the pieces are ``via_trajectory(...).pieces``. ``dt`` is
    ``"mstraj"``'s step (default ``DEFAULT_DT``): its pieces start and end on
    whole steps (their ``breaks``, also their ``knots``); the splines take none.
    """
    if method == "scurve":
        raise KinematicaError(
            "the scurve's pieces come with its samples: via_trajectory(..., 'scurve').pieces",
            arg="method",
        )
    if method not in ("cubic", "quintic", "mstraj"):
        raise KinematicaError(
            f"method must be 'cubic', 'quintic' or 'mstraj', got {method!r}", arg="method"
        )
    if ends not in ("clamped", "natural"):
        raise KinematicaError(f"ends must be 'clamped' or 'natural', got {ends!r}", arg="ends")
    w = _waypoints(waypoints)
    k, n = w.shape
    t = None if times is None else _times(times, k)
    am = _limit(amax, (n,), "amax")
    ends_given = {"qd0": qd0, "qd1": qd1, "qdd0": qdd0, "qdd1": qdd1, "qd": qd, "qdd": qdd}
    if method == "mstraj":
        named = [x for x in ("qdd0", "qdd1", "qd", "qdd") if ends_given[x] is not None]
        if named or ends != "clamped":
            raise KinematicaError(
                f"mstraj takes a start and an end velocity (qd0, qd1) only: drop "
                f"{', '.join(named) or 'ends'}"
            )
        step = DEFAULT_DT if dt is None else dt
        step = check_number(step, "dt", positive=True, unit="s", what="a number of seconds")
        ends_v = (_array(qd0, (n,), "qd0"), _array(qd1, (n,), "qd1"))
        return _mstraj(w, t, vmax, am, tacc, step, ends_v)
    if tacc is not None:
        raise KinematicaError("tacc is the blend time of method='mstraj'", arg="tacc")
    if dt is not None:
        raise KinematicaError("dt is the step of method='mstraj'; splines sample any dt", arg="dt")
    spline: Literal["cubic", "quintic"] = "cubic" if method == "cubic" else "quintic"
    return _spline(w, spline, t, _limit(vmax, (n,), "vmax"), am, ends, ends_given)


def _mstraj(
    w: FloatArray,
    t: FloatArray | None,
    vmax: ArrayLike | None,
    am: FloatArray | None,
    tacc: ArrayLike | None,
    dt: float,
    ends: tuple[FloatArray, FloatArray],
) -> PiecewisePolynomial:
    """Method ``"mstraj"``: the Toolbox's, timed by ``vmax`` or by ``times`` (one of them)."""
    k, n = w.shape
    if tacc is None:
        raise KinematicaError("tacc must be the blend time of mstraj (s; 0 for none)", arg="tacc")
    ta = _array(tacc, (k - 1,), "tacc")
    if np.any(ta < 0):
        raise KinematicaError(f"tacc must be >= 0 (s), got {tacc!r}", arg="tacc")
    if (t is None) == (vmax is None):
        raise KinematicaError(
            "mstraj takes times or vmax (the Toolbox's tsegment or qdmax), one of them",
            arg="times",
        )
    vm = _limit(vmax, (k - 1, n), "vmax")
    pieces = mstraj_pieces(w, dt, ta, vmax=vm, times=t, qd0=ends[0], qd1=ends[1])
    _check(pieces, None, am)
    return pieces


def _spline(
    w: FloatArray,
    method: Literal["cubic", "quintic"],
    t: FloatArray | None,
    vm: FloatArray | None,
    am: FloatArray | None,
    ends: Ends,
    bc: dict[str, ArrayLike | None],
) -> PiecewisePolynomial:
    """Methods ``"cubic"`` and ``"quintic"``: the spline, or given derivatives at every waypoint."""
    k, n = w.shape
    m = 2 if method == "cubic" else 3
    if method == "cubic" and any(bc[x] is not None for x in ("qdd0", "qdd1", "qdd")):
        raise KinematicaError("the cubic sets velocities only: use 'quintic' for accelerations")
    if bc["qdd"] is not None and bc["qd"] is None:
        raise KinematicaError("qdd at the waypoints needs qd too", arg="qdd")
    start = np.stack([_array(bc["qd0"], (n,), "qd0"), _array(bc["qdd0"], (n,), "qdd0")])
    end = np.stack([_array(bc["qd1"], (n,), "qd1"), _array(bc["qdd1"], (n,), "qdd1")])
    start, end = start[: m - 1], end[: m - 1]
    given: FloatArray | None = None
    if bc["qd"] is not None:
        if any(bc[x] is not None for x in ("qd0", "qd1", "qdd0", "qdd1")) or ends != "clamped":
            raise KinematicaError("qd (and qdd) give every waypoint's derivatives: drop qd0..qdd1")
        given = np.stack([_array(bc["qd"], (k, n), "qd"), _array(bc["qdd"], (k, n), "qdd")], 1)
        given = given[:, : m - 1]

    def build(tt: FloatArray) -> PiecewisePolynomial:
        d = given if given is not None else spline_derivatives(tt, w, m, ends, start, end)
        return hermite_pieces(tt, w, d)

    if t is None:
        if vm is None and am is None:
            raise KinematicaError(
                "times must be given, or vmax and/or amax to derive them", arg="times"
            )
        if np.any(start) or np.any(end) or (given is not None and np.any(given)):
            raise KinematicaError("give times when velocities or accelerations are not zero")
        inf = np.full(n, np.inf)
        vl, al = (inf if vm is None else vm), (inf if am is None else am)
        # Each segment its slowest joint's rest-to-rest time, then one factor for all so
        # that the spline's exact peaks just reach the tightest limit (a spline with rest
        # or natural ends scales with its times: speeds by 1/c, accelerations by 1/c²).
        seg = minimum_time(np.diff(w, axis=0), vl, al, method).max(axis=1)
        if np.any(seg <= 0):
            i = int(np.flatnonzero(seg <= 0)[0])
            raise KinematicaError(
                f"waypoints {i + 1} and {i + 2} are equal: give times to dwell there"
            )
        t0 = np.concatenate([[0.0], np.cumsum(seg)])
        trial = build(t0)
        scale = max(float((trial.peak(1) / vl).max()), math.sqrt(float((trial.peak(2) / al).max())))
        t = t0 * scale
    pieces = build(t)
    _check(pieces, vm, am)
    return pieces


def _check(
    pieces: PiecewisePolynomial,
    vm: FloatArray | None,
    am: FloatArray | None,
) -> None:
    """Raise when the trajectory exceeds a limit (beyond round-off)."""
    for lim, order, name in ((vm, 1, "vmax"), (am, 2, "amax")):
        if lim is None:
            continue
        peak = pieces.peak(order)
        over = peak > lim * (1.0 + LIMIT_RTOL)
        if over.any():
            j = int(np.flatnonzero(over)[0])
            raise KinematicaError(
                f"joint {j + 1} would reach {peak[j]:.6g} > {name} {lim[j]:g}: "
                "lengthen the times" + (" or tacc" if name == "amax" else "")
            )


def via_trajectory(
    waypoints: ArrayLike,
    method: Method = "cubic",
    times: ArrayLike | None = None,
    dt: float = DEFAULT_DT,
    vmax: ArrayLike | None = None,
    amax: ArrayLike | None = None,
    *,
    tacc: ArrayLike | None = None,
    ends: Ends = "clamped",
    qd0: ArrayLike | None = None,
    qd1: ArrayLike | None = None,
    qdd0: ArrayLike | None = None,
    qdd1: ArrayLike | None = None,
    qd: ArrayLike | None = None,
    qdd: ArrayLike | None = None,
    jmax: ArrayLike | None = None,
    qlim: ArrayLike | None = None,
) -> JointTrajectory:
    """A joint trajectory through ``waypoints`` (module docstring for the methods).

    Args:
        waypoints: ``(k, n)`` configurations (rad, m), k >= 2: start, vias, end.
        method: ``"cubic"``, ``"quintic"`` (splines through every waypoint),
            ``"mstraj"`` (lines with parabolic blends; vias cut) or
            ``"scurve"`` (jerk-limited, through every waypoint without
            stopping; times from the limits).
        times: ``(k,)`` times of the waypoints (s), from 0, increasing; for
            ``"mstraj"`` the times its lines pass them (the Toolbox's
            ``tsegment`` are their differences). Derived from the limits if
            ``None``.
        dt: Largest sample spacing (s); samples are uniform between knots and
            every knot time is a sample. For ``"mstraj"`` the step: samples
            every ``dt`` exactly, times rounded up to whole steps.
        vmax: Speed limits (rad/s, m/s): a number or ``(n,)``; for
            ``"mstraj"`` (the Toolbox's ``qdmax``; not with ``times``) also
            ``(k - 1, n)``, one row per segment: the lines' speeds.
        amax: Acceleration limits (rad/s², m/s²): a number or ``(n,)``.
        tacc: Blend time of ``"mstraj"`` (s, >= 0): a number, or ``(k - 1,)``
            one per segment (the blend at its start).
        ends: Spline ends: ``"clamped"`` (``qd0``, ``qd1``, ``qdd0``,
            ``qdd1``, zero by default) or ``"natural"``.
        qd0: ``(n,)`` start velocity of a clamped spline or of ``"mstraj"``.
        qd1: ``(n,)`` end velocity (the Toolbox's ``qdf`` for ``"mstraj"``).
        qdd0: ``(n,)`` start acceleration (quintic).
        qdd1: ``(n,)`` end acceleration (quintic).
        qd: ``(k, n)`` velocity at every waypoint (MATLAB's ``cubicpolytraj`` /
            ``quinticpolytraj``): no spline, C1 pieces.
        qdd: ``(k, n)`` acceleration at every waypoint (quintic with ``qd``;
            zero by default, as MATLAB's).
        jmax: Jerk limits of ``"scurve"`` (rad/s³, m/s³): a number or ``(n,)``.
        qlim: ``(n, 2)`` position limits ``"scurve"`` holds (e.g. ``robot.qlim``).

    Returns:
        :class:`JointTrajectory` ``(t, q, qd, qdd)``; ``q`` is every waypoint
        at its time (splines, scurve; exactly) and ends at the last one
        exactly. For ``"mstraj"`` the Toolbox's samples with the start added
        at ``t = 0`` (the Toolbox leaves it out and stamps its first sample,
        one step later, 0): ``t = j·dt``. For ``"scurve"`` a
        :class:`~kinematica.motion.scurve.JerkTrajectory`: its jerk, the
        waypoint times and velocities, and ``margin``, how much shorter it is
        than stopping at every waypoint.

    Raises:
        DimensionError: Shapes, NaN or inf.
        ArgumentError: ``dt`` not a positive number, or more than MAX_SAMPLES
            samples from the duration and ``dt`` (checked before sampling).
        KinematicaError: Unknown method or ends, times not increasing from 0,
            arguments that do not apply to the method, or given times that make
            a joint exceed ``vmax``/``amax`` (the message names the joint).
    """
    dt = check_number(dt, "dt", positive=True, unit="s", what="a number of seconds")
    if method == "scurve":
        extra = {"times": times, "tacc": tacc, "qd": qd, "qdd": qdd}
        named = [x for x, v in extra.items() if v is not None]
        if named or ends != "clamped":
            what = ", ".join(named) or "ends"
            raise KinematicaError(f"the scurve times itself from vmax, amax and jmax: drop {what}")
        from kinematica.motion.scurve_via import scurve_via

        ends_given = {"qd0": qd0, "qd1": qd1, "qdd0": qdd0, "qdd1": qdd1}
        return scurve_via(_waypoints(waypoints), dt, vmax, amax, jmax, qlim=qlim, **ends_given)
    if jmax is not None or qlim is not None:
        given = " and ".join(x for x, v in (("jmax", jmax), ("qlim", qlim)) if v is not None)
        raise KinematicaError(f"{given} apply to method='scurve' only")
    pieces = via_polynomials(
        waypoints,
        method,
        times,
        vmax,
        amax,
        tacc=tacc,
        ends=ends,
        qd0=qd0,
        qd1=qd1,
        qdd0=qdd0,
        qdd1=qdd1,
        qd=qd,
        qdd=qdd,
        dt=dt if method == "mstraj" else None,
    )
    if method == "mstraj":  # the Toolbox's grid: every sample ends a step, and is its left limit
        steps = round(pieces.duration / dt)
        check_size(steps + 1, MAX_SAMPLES, "dt", f"samples ({pieces.duration:g} s every {dt!r} s)")
        t = np.arange(steps + 1, dtype=float) * dt
        out = JointTrajectory(t, pieces(t, left=True), pieces(t, 1, True), pieces(t, 2, True))
        out.q[-1] = np.asarray(waypoints, dtype=float)[-1]
        return out
    # every knot is a sample too: at most one more per piece than duration / dt
    count = pieces.duration / dt + pieces.knots.size
    check_size(count, MAX_SAMPLES, "dt", f"samples ({pieces.duration:g} s every {dt!r} s)")
    traj = pieces.sample(dt)
    traj.q[-1] = np.asarray(waypoints, dtype=float)[-1]
    return traj
