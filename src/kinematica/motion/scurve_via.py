"""Jerk-limited moves through waypoints, without a stop at each.

Every waypoint is reached exactly; between two waypoints the move is one
jerk-limited state-to-state segment (:mod:`kinematica.motion.scurve`). What
is chosen is the velocity at each intermediate waypoint (the acceleration
there is zero), to make the whole move short:

1. A direction per waypoint from its neighbours: a joint that moves the same
   way before and after the waypoint keeps moving through it, along the chord
   ``w[i+1] - w[i-1]``; a joint that turns back (or does not move on one
   side) passes it at rest. The chord is scaled to the highest speed the
   joints' ``vmax`` allow along it: ``vhat[i]``.
2. The velocity at waypoint ``i`` is ``λ_i · vhat[i]`` with ``λ_i`` in
   ``[0, 1]``: one common ``λ`` for every waypoint is tried on a grid
   (:data:`UNIFORM_GRID`, which includes a stop at each), then each ``λ_i``
   in turn is searched (golden section, :data:`GOLDEN_STEPS` evaluations)
   on the sum of its two segments' durations, for :data:`SWEEPS` sweeps. A
   value is only accepted when it shortens the move, so the result is never
   longer than stopping at each waypoint; ``margin`` on the result says by
   how much it is shorter. Then each joint's speed at each waypoint is
   searched on its own (``[0, vmax]`` in its direction of travel; both ways for
   a joint that turns back there, which may pass its waypoint moving and turn
   beyond it) for :data:`JOINT_SWEEPS` sweeps: the joint that sets a segment's
   time wants its speed high, another may be better off slower.
3. With position limits (``qlim``) a segment whose exact extremes (ruckig's
   position extrema, which include any overshoot of a waypoint) leave them
   counts as infinitely long, so the search only keeps waypoint velocities
   whose segments stay inside: a segment that would overshoot is re-planned
   with smaller velocities at its ends, down to a stop.

The search is a heuristic over one number per waypoint, not a global
optimum over every joint's velocity: the duration it gives is an upper bound
of the best jerk-limited move through the same waypoints.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.arguments import check_size
from kinematica.errors import DimensionError, KinematicaError
from kinematica.motion.piecewise import PiecewisePolynomial
from kinematica.motion.samples import MAX_SAMPLES
from kinematica.motion.scurve import (
    JerkTrajectory,
    Segment,
    check_peaks,
    jerk_samples,
    limits_from,
    scurve_pieces,
    state_from,
)

__all__ = ["GOLDEN_STEPS", "JOINT_SWEEPS", "POSITION_ATOL", "SWEEPS", "UNIFORM_GRID", "scurve_via"]

FloatArray = NDArray[np.float64]

#: Common waypoint-speed fractions tried first (0: a stop at every waypoint).
UNIFORM_GRID = (0.0, 0.25, 0.5, 0.75, 1.0)
#: Evaluations of each waypoint's golden-section search on [0, 1] (0.618^10 ~ 0.8 %).
GOLDEN_STEPS = 10
#: Sweeps over the waypoints with one speed fraction each, then with each joint's own.
SWEEPS = 2
JOINT_SWEEPS = 2
#: How far (rad, m) a waypoint or a segment's extreme may pass a position limit:
#: round-off of a segment that ends on the limit.
POSITION_ATOL = 1e-12

_GOLD = (math.sqrt(5.0) - 1.0) / 2.0


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


def _directions(w: FloatArray, vmax: FloatArray) -> FloatArray:
    """``(k, n)`` the fastest velocity along each waypoint's chord (module docstring, 1)."""
    k, n = w.shape
    d = np.diff(w, axis=0)
    vhat = np.zeros((k, n))
    for i in range(1, k - 1):
        same = (np.sign(d[i - 1]) == np.sign(d[i])) & (d[i - 1] != 0.0)
        u = np.where(same, w[i + 1] - w[i - 1], 0.0)
        moving = u != 0.0
        if moving.any():
            vhat[i] = u * float(np.min(vmax[moving] / np.abs(u[moving])))
    return np.clip(vhat, -vmax, vmax)  # the joint that sets the scale: vmax, not one ulp over


def _golden(f: Callable[[float], float]) -> tuple[float, float]:
    """``(x, f(x))``: the best point a golden-section search of ``f`` on [0, 1] tried."""
    lo, hi = 0.0, 1.0
    x1, x2 = hi - _GOLD, lo + _GOLD
    f1, f2 = f(x1), f(x2)
    tried = [(f1, x1), (f2, x2)]
    for _ in range(GOLDEN_STEPS - 2):
        if f1 <= f2:
            hi, x2, f2 = x2, x1, f1
            x1 = hi - _GOLD * (hi - lo)
            f1 = f(x1)
            tried.append((f1, x1))
        else:
            lo, x1, f1 = x1, x2, f2
            x2 = lo + _GOLD * (hi - lo)
            f2 = f(x2)
            tried.append((f2, x2))
    f_best, x_best = min(tried)
    return x_best, f_best


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
        qdd0: ``(n,)`` start acceleration.
        qdd1: ``(n,)`` end acceleration.

    Returns:
        :class:`~kinematica.motion.scurve.JerkTrajectory` with
        ``waypoint_times``, ``waypoint_qd``, ``stop_duration`` and ``margin``.

    Raises:
        KinematicaError: A missing or non-positive limit, two equal waypoints
            in a row, a waypoint outside ``qlim``, end states outside the
            limits, or ends whose segments leave ``qlim`` even with a stop at
            every waypoint.
        MissingDependencyError: ruckig is not installed.
    """
    k, n = w.shape
    vm, am = limits_from(vmax, n, "vmax"), limits_from(amax, n, "amax")
    jm = limits_from(jmax, n, "jmax")
    lim = _qlim(qlim, w)
    same = np.all(np.diff(w, axis=0) == 0.0, axis=1)
    if same.any():
        i = int(np.flatnonzero(same)[0])
        raise KinematicaError(f"waypoints {i + 1} and {i + 2} are equal: drop one")
    V = np.zeros((k, n))
    A = np.zeros((k, n))
    V[0], V[-1] = state_from(qd0, n, "qd0"), state_from(qd1, n, "qd1")
    A[0], A[-1] = state_from(qdd0, n, "qdd0"), state_from(qdd1, n, "qdd1")
    seg = Segment(vm, am, jm)
    # the end states through ruckig's own checks (the interior ones are at rest here)
    seg.plan(w[0], V[0], A[0], w[1], V[1], A[1])
    seg.plan(w[-2], V[-2], A[-2], w[-1], V[-1], A[-1])
    vhat = _directions(w, vm)

    def time(i: int, vi: FloatArray, vj: FloatArray) -> float:
        """Duration of segment ``i`` (waypoint i to i+1), inf if it leaves qlim."""
        T = seg.plan(w[i], vi, A[i], w[i + 1], vj, A[i + 1], validate=False)
        if lim is not None:
            ext = seg.out.position_extrema
            lo = np.array([e.min for e in ext])
            hi = np.array([e.max for e in ext])
            if np.any(lo < lim[:, 0] - POSITION_ATOL) or np.any(hi > lim[:, 1] + POSITION_ATOL):
                return math.inf
        return T

    def velocities(lam: FloatArray) -> FloatArray:
        out = lam[:, None] * vhat
        out[0], out[-1] = V[0], V[-1]
        return out

    def total(lam: FloatArray) -> tuple[FloatArray, float]:
        vel = velocities(lam)
        seg_t = np.array([time(i, vel[i], vel[i + 1]) for i in range(k - 1)])
        return seg_t, float(seg_t.sum())

    stop_t, stop_duration = total(np.zeros(k))
    if not math.isfinite(stop_duration):
        i = int(np.flatnonzero(~np.isfinite(stop_t))[0])
        raise KinematicaError(
            f"segment {i + 1} (waypoints {i + 1} to {i + 2}) leaves qlim even with a stop at "
            "each waypoint: its end velocity or acceleration carries it over a limit"
        )
    lam, best = np.zeros(k), stop_duration
    for x in UNIFORM_GRID[1:]:
        trial = np.full(k, x)
        _, d = total(trial)
        if d < best:
            lam, best = trial, d
    seg_t, _ = total(lam)
    vel = velocities(lam)

    def improve(i: int, candidate: Callable[[float], FloatArray]) -> None:
        """Waypoint i's velocity: the best ``candidate(x)``, x in [0, 1], if it is shorter."""

        def around(x: float) -> float:
            vi = candidate(x)
            return time(i - 1, vel[i - 1], vi) + time(i, vi, vel[i + 1])

        x, f = _golden(around)
        if f < seg_t[i - 1] + seg_t[i]:
            vel[i] = candidate(x)
            seg_t[i - 1] = time(i - 1, vel[i - 1], vel[i])
            seg_t[i] = time(i, vel[i], vel[i + 1])

    def along(i: int) -> Callable[[float], FloatArray]:
        return lambda x: x * vhat[i]

    for _ in range(SWEEPS):  # one speed fraction per waypoint, along its chord
        for i in range(1, k - 1):
            if vhat[i].any():
                improve(i, along(i))
    steps = np.diff(w, axis=0)
    for _ in range(JOINT_SWEEPS):  # then each joint's own speed
        for i in range(1, k - 1):
            for j in range(n):
                # an onward joint in its direction; one that turns back may pass its waypoint
                # moving either way (overshooting the waypoint on one side)
                signs = [vhat[i, j]] if vhat[i, j] else [steps[i - 1, j], steps[i, j]]
                for sign in np.sign(signs):
                    if sign == 0.0:
                        continue

                    def one(
                        x: float, i: int = i, j: int = j, top: float = sign * vm[j]
                    ) -> FloatArray:
                        out = vel[i].copy()
                        out[j] = x * top
                        return out

                    improve(i, one)
    duration = float(seg_t.sum())
    check_size(duration / dt + k, MAX_SAMPLES, "dt", f"samples ({duration:g} s every {dt!r} s)")
    parts = []
    for i in range(k - 1):
        time(i, vel[i], vel[i + 1])
        parts.append(scurve_pieces(seg))
    knots = np.concatenate([[0.0], np.cumsum([p.duration for p in parts])])
    shifted = (p.breaks[1:] + t0 for p, t0 in zip(parts, knots, strict=False))
    breaks = np.concatenate([knots[:1], *shifted])
    for t0 in knots[1:]:  # every waypoint's time exactly among the breaks
        breaks[np.argmin(np.abs(breaks - t0))] = t0
    deg = max(p.coef.shape[1] for p in parts)  # cubic, or quintic where settled
    coef = [np.pad(p.coef, ((0, 0), (0, deg - p.coef.shape[1]), (0, 0))) for p in parts]
    pieces = PiecewisePolynomial(breaks, np.concatenate(coef), knots)
    check_peaks(pieces, (vm, am, jm))
    traj = jerk_samples(pieces, dt, (vm, am, jm), (w[-1], V[-1], A[-1]))
    traj.waypoint_times = knots
    traj.waypoint_qd = vel
    traj.stop_duration = stop_duration
    traj.margin = stop_duration - float(knots[-1])
    return traj
