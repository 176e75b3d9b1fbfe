"""Time-optimal timing of a path under joint velocity, acceleration and tool-speed limits.

Given a geometric path ``q(s)``, ``s`` in [0, 1] (:mod:`kinematica.motion.optimal_path`
says which path a set of waypoints, a trajectory or a Cartesian path gives),
:func:`time_optimal` finds the fastest ``s(t)`` from rest to rest (or given path
speeds) such that every joint's ``q̇ = q'ṡ`` and ``q̈ = q's̈ + q''ṡ²`` stay within
their limits and the tool's linear and angular speeds within theirs. The core runs
TOPP-RA (Pham & Pham, T-RO 2018) on a grid: backward controllable sets, then a
forward greedy pass, ``s̈`` constant within each grid interval.

**The limits hold everywhere, not only at grid points.** Within an interval with
constant ``s̈`` the squared speed ``ṡ²`` is linear in ``s``, so each joint's
``q'(s)²ṡ²`` and ``q̈`` are polynomials on the interval whose coefficients are linear
in the interval's two end speeds; the core asks every *Bernstein coefficient* of them
to lie within the limits, which bounds the polynomial on the whole interval (its
convex-hull property) — proven, not sampled; it costs ``O(h²)`` of the limit in the
grid spacing ``h``. The tool-speed limits are not polynomial in ``s`` (they go
through the Jacobian): each interval's squared tool speed per unit ``ṡ²`` is sampled
at :data:`CAP_SUBSAMPLES` + 1 points and bounded by the largest sample plus the
largest second difference, 8x the bound on a smooth function's excess between samples
``δ²·|w''|/8``: sound for a tool speed whose curvature in ``s`` does not change by a
factor of 8 within a fifth of a grid interval; the tests resample densely to check.

**Honest when it cannot.** When a limit holds the path at rest over some stretch (a
zero velocity limit on a joint that moves there, a tool speed through a singular
configuration), the result's status is ``"infeasible"``, with the ``s`` where the
path stops and the limit that stops it, and the trajectory is the fastest one that
arrives there at rest; no limit is broken anywhere.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.arguments import check_count, check_number, check_size
from kinematica.core.topp import MAX_DEGREE, time_optimal_grid
from kinematica.errors import ArgumentError, DimensionError, KinematicaError
from kinematica.motion.cartesian_types import CartesianPath
from kinematica.motion.optimal_path import (
    grid_for,
    spline_path,
    taylor_coefficients,
    trajectory_path,
    waypoint_path,
)
from kinematica.motion.piecewise import PiecewisePolynomial
from kinematica.motion.trajectory import (
    DEFAULT_DT,
    MAX_DURATION,
    MAX_SAMPLES,
    JointTrajectory,
    sample_times,
)
from kinematica.spatial.checks import as_float_array

if TYPE_CHECKING:
    from kinematica.robot import Robot

__all__ = [
    "BLOCKING_EVENTS",
    "CAP_SUBSAMPLES",
    "DEFAULT_GRID",
    "MAX_INTERVALS",
    "MAX_PATH_SPEED",
    "SLOW_FRACTION",
    "Slowdown",
    "TimeOptimal",
    "time_optimal",
]

FloatArray = NDArray[np.float64]

#: Grid intervals over s in [0, 1] by default (every knot is on the grid too).
DEFAULT_GRID = 1000
#: Most grid intervals of one timing (knots included): the core keeps ~1.5 kB a stage.
MAX_INTERVALS = 50_000
#: Largest path speed ṡ (1/s): bounds a stretch no limit constrains (the path covered in 1 µs).
MAX_PATH_SPEED = 1e6
#: Sub-intervals per grid interval where the tool speeds are sampled.
CAP_SUBSAMPLES = 4
#: A local minimum of ṡ below this fraction of its peak is reported as a slowdown.
SLOW_FRACTION = 0.5
#: Cartesian-path events past which no timing can follow the path.
BLOCKING_EVENTS = ("singularity", "unreachable", "joint_limit", "branch_change")


@dataclass(frozen=True)
class Slowdown:
    """Where the timing slows down to a local minimum of the path speed.

    Attributes:
        s: Path parameter of the minimum.
        sd: ``ṡ`` there (1/s).
        limit: The limit that binds there (``"velocity of joint 5"``, ``"tool speed"``...).
    """

    s: float
    sd: float
    limit: str


@dataclass(frozen=True)
class TimeOptimal:
    """A time-optimal timing and its phase plane.

    Attributes:
        status: ``"ok"`` or ``"infeasible"`` (the path cannot be followed to its end).
        trajectory: ``(t, q, qd, qdd)`` sampled every ``dt`` (or closer), from the
            start to the end, or to ``s_stop`` at rest when infeasible.
        s_samples: ``(m,)`` the path parameter at each of the trajectory's samples.
        duration: Its last time (s).
        s_stop: Where the timing stops short of the end (None when ``"ok"``).
        limit: The limit that stops it (``"velocity of joint 3"``, ``"tool speed"``,
            ``"singularity (wrist)"``, ``"start speed"``...; None when ``"ok"``).
        message: One sentence for people.
        path: The geometric path ``q(s)`` (pieces in ``s``, not in time).
        s: ``(N + 1,)`` grid.
        sd: ``(N + 1,)`` path speed ``ṡ`` (1/s) of the timing (NaN past ``s_stop``).
        sd_max: ``(N + 1,)`` the limit curve: the largest ``ṡ`` each grid interval's own
            limits allow (the maximum-velocity curve, with acceleration limits too).
        controllable: ``(N + 1, 2)`` the controllable sets in ``ṡ``: from where the end
            (at its speed) can be reached within the limits (NaN where empty).
        reachable: ``(N + 1, 2)`` the sets in ``ṡ`` reachable from the start within them.
        slowdowns: Interior minima of ``ṡ`` below :data:`SLOW_FRACTION` of its peak.
        vel: ``(n, 2)`` joint velocity limits ``(lo, hi)`` used (``±inf``: none).
        acc: ``(n, 2)`` joint acceleration limits used.
    """

    status: str
    trajectory: JointTrajectory
    s_samples: FloatArray
    duration: float
    s_stop: float | None
    limit: str | None
    message: str
    path: PiecewisePolynomial
    s: FloatArray
    sd: FloatArray
    sd_max: FloatArray
    controllable: FloatArray
    reachable: FloatArray
    slowdowns: tuple[Slowdown, ...]
    vel: FloatArray
    acc: FloatArray

    @property
    def ok(self) -> bool:
        """True when the whole path is timed."""
        return self.status == "ok"


def _limits(x: ArrayLike | None, n: int, name: str) -> FloatArray:
    """``(n, 2)`` limits ``(lo, hi)``: none, a number or ``(n,)`` (symmetric) or ``(n, 2)``."""
    if x is None:
        return np.tile([-np.inf, np.inf], (n, 1))
    a = as_float_array(x, name)
    if a.ndim == 0:
        a = np.full(n, float(a))
    if a.shape == (n,):
        if np.any(np.isnan(a)) or np.any(a < 0):
            raise ArgumentError(f"{name} must hold limits >= 0, got {a.tolist()}", arg=name)
        return np.stack([-a, a], axis=1)
    if a.shape != (n, 2):
        raise DimensionError(
            f"{name} must be a number, {n} values or ({n}, 2) pairs (lo, hi), got shape {a.shape}"
        )
    if np.any(np.isnan(a)) or np.any(a[:, 0] > 0) or np.any(a[:, 1] < 0):
        raise ArgumentError(f"{name} pairs (lo, hi) must have lo <= 0 <= hi", arg=name)
    return a


def _geometry(
    path: ArrayLike | JointTrajectory | CartesianPath, robot: Robot | None
) -> tuple[PiecewisePolynomial, tuple[float, str] | None]:
    """The path ``q(s)``, and for a Cartesian path met by a blocking event, where and why."""
    if isinstance(path, JointTrajectory):
        return trajectory_path(path), None
    if isinstance(path, CartesianPath):
        stop = next((e for e in path.events if e.kind in BLOCKING_EVENTS), None)
        last = path.s.size if stop is None else stop.index  # samples before the event
        good = np.isfinite(path.q[:last]).all(axis=1)
        last = int(np.argmin(good)) if not good.all() else last
        s, q = path.s[:last], path.q[:last]
        keep = np.concatenate([[True], np.diff(s) > 0])  # repeated s: one sample
        s, q = s[keep], q[keep]
        if s.size < 2:
            raise KinematicaError(
                "the Cartesian path cannot be followed from its start: "
                + (stop.message if stop is not None else "no configuration")
            )
        why = None
        if stop is not None:
            names = f" ({', '.join(stop.names)})" if stop.names else ""
            why = (float(stop.s), f"{stop.kind}{names}")
        return spline_path(s, q), why
    W = as_float_array(path, "path")
    if W.ndim != 2 or W.shape[0] < 2 or W.shape[1] < 1:
        raise DimensionError(
            "path must be (k, n) waypoints with k >= 2, a JointTrajectory or a CartesianPath, "
            f"got shape {W.shape}"
        )
    if not np.all(np.isfinite(W)):
        raise DimensionError("path holds NaN or inf")
    return waypoint_path(W), None


def _tool_caps(
    robot: Robot, pp: PiecewisePolynomial, s: FloatArray, speeds: tuple[float | None, float | None]
) -> tuple[FloatArray, FloatArray]:
    """``(cap (N,), which (N,))``: the largest ``ṡ²`` the tool speeds allow per interval.

    ``which`` is 0 where the linear speed binds, 1 where the angular one does.
    """
    k = CAP_SUBSAMPLES
    h = np.diff(s)
    sub = (s[:-1, None] + h[:, None] * np.linspace(0.0, 1.0, k + 1)[None, :]).ravel()
    sub = np.minimum(sub, s[-1])
    q, dq = pp(sub), pp(sub, 1)
    J = robot.jacobian(q)  # (M, 6, n), base frame
    v = np.einsum("mij,mj->mi", J, dq).reshape(h.size, k + 1, 6)
    caps = []
    for rows, V in ((slice(0, 3), speeds[0]), (slice(3, 6), speeds[1])):
        if V is None:
            caps.append(np.full(h.size, np.inf))
            continue
        w = np.sum(v[:, :, rows] ** 2, axis=2)  # squared speed per unit ṡ²
        flat = w.ravel()
        d2 = np.abs(np.diff(flat, 2)) if flat.size > 2 else np.zeros(1)
        d2 = np.concatenate([[d2[0]], d2, [d2[-1]]]).reshape(h.size, k + 1)
        bound = w.max(axis=1) + d2.max(axis=1)
        with np.errstate(divide="ignore"):
            caps.append(np.where(bound > 0, V * V / bound, np.inf))
    cap = np.minimum(caps[0], caps[1])
    return cap, (caps[1] < caps[0]).astype(int)


def _limit_name(kind: str, joint: int, which: int) -> str:
    if kind in ("velocity", "acceleration"):
        return f"{kind} of joint {joint + 1}"
    if kind == "cap":
        return "tool angular speed" if which else "tool speed"
    return "the limits"


def _binding(
    i: int, x: FloatArray, s: FloatArray, coef: FloatArray, lim: tuple[FloatArray, ...]
) -> tuple[str, int, float]:
    """``(kind, joint, ratio)``: the limit nearest to binding at grid point ``i``."""
    vel, acc, cap = lim
    j = min(i, s.size - 2)
    d1, d2 = coef[j, 1], 2.0 * coef[j, 2] if coef.shape[1] > 2 else np.zeros_like(coef[j, 1])
    u = (x[j + 1] - x[j]) / (2.0 * (s[j + 1] - s[j]))
    qd = d1 * np.sqrt(x[i])
    qdd = d1 * u + d2 * x[i]
    with np.errstate(divide="ignore", invalid="ignore"):
        rv = np.nan_to_num(np.where(qd >= 0, qd / vel[:, 1], qd / vel[:, 0]), nan=0.0)
        ra = np.nan_to_num(np.where(qdd >= 0, qdd / acc[:, 1], qdd / acc[:, 0]), nan=0.0)
        rc = float(x[i] / cap[j]) if np.isfinite(cap[j]) else 0.0
    best = max(
        ("velocity", int(np.argmax(rv)), float(np.max(rv))),
        ("acceleration", int(np.argmax(ra)), float(np.max(ra))),
        ("cap", -1, rc),
        key=lambda r: r[2],
    )
    return best


def time_optimal(
    path: ArrayLike | JointTrajectory | CartesianPath,
    vmax: ArrayLike | None = None,
    amax: ArrayLike | None = None,
    robot: Robot | None = None,
    *,
    tcp_speed: float | None = None,
    tcp_angular_speed: float | None = None,
    dt: float = DEFAULT_DT,
    grid: int = DEFAULT_GRID,
    sd_start: float = 0.0,
    sd_end: float = 0.0,
) -> TimeOptimal:
    """The fastest timing of a path within joint and tool limits (module docstring).

    Args:
        path: ``(k, n)`` waypoints (the natural cubic spline through them at
            chord-length ``s``), a :class:`JointTrajectory` (its path, ``s = t/T``)
            or a :class:`CartesianPath` (the spline through its configurations; the
            path stops before its first blocking event).
        vmax: Joint velocity limits (rad/s, m/s): a number or ``(n,)`` (symmetric,
            >= 0), or ``(n, 2)`` pairs ``(lo, hi)`` with ``lo <= 0 <= hi``; None: none.
        amax: Joint acceleration limits (rad/s², m/s²), likewise.
        robot: The robot, needed for the tool speeds.
        tcp_speed: Largest linear speed of the tool point (m/s, base frame).
        tcp_angular_speed: Largest angular speed of the tool (rad/s).
        dt: Largest sample spacing of the trajectory (s).
        grid: Grid intervals over ``s`` in [0, 1] (every knot is on it too).
        sd_start: Path speed ``ṡ`` at the start (1/s, ``s`` in [0, 1]).
        sd_end: Path speed at the end.

    Returns:
        The :class:`TimeOptimal` result, its trajectory within every limit.

    Raises:
        DimensionError: A path or limits of the wrong shape, NaN or inf.
        ArgumentError: Negative limits, ``dt``/``grid``/speeds out of range, no limit
            at all, a tool speed without a robot, or more than MAX_SAMPLES samples.
    """
    pp, blocked = _geometry(path, robot)
    n = pp.coef.shape[2]
    if robot is not None and n != robot.dof:
        raise DimensionError(f"the path has {n} joints, the robot {robot.dof}")
    vel, acc = _limits(vmax, n, "vmax"), _limits(amax, n, "amax")
    dt = check_number(dt, "dt", positive=True, unit="s", what="a number of seconds")
    grid = check_count(grid, "grid", lo=1, hi=MAX_INTERVALS)
    speeds = (
        None if tcp_speed is None else check_number(tcp_speed, "tcp_speed", positive=True),
        None
        if tcp_angular_speed is None
        else check_number(tcp_angular_speed, "tcp_angular_speed", positive=True),
    )
    if robot is None and speeds != (None, None):
        raise ArgumentError("tool speeds need the robot: give robot=", arg="robot")
    if vmax is None and amax is None and speeds == (None, None):
        raise ArgumentError("give at least one limit: vmax, amax or a tool speed", arg="vmax")
    ends = [
        check_number(v, name, lo=0.0, hi=MAX_PATH_SPEED, unit="1/s", what="a path speed")
        for v, name in ((sd_start, "sd_start"), (sd_end, "sd_end"))
    ]
    if pp.coef.shape[1] - 1 > MAX_DEGREE:  # pragma: no cover - the paths built here are quintic
        raise KinematicaError(f"path pieces of degree above {MAX_DEGREE}")
    s, piece = grid_for(pp.knots, grid)
    check_size(s.size - 1, MAX_INTERVALS, "grid", "grid intervals (one at least between knots)")
    coef = taylor_coefficients(pp, s, piece)
    cap, which = np.full(s.size - 1, np.inf), np.zeros(s.size - 1, dtype=int)
    if robot is not None and speeds != (None, None):
        cap, which = _tool_caps(robot, pp, s, speeds)
    x_end = 0.0 if blocked is not None else ends[1] ** 2
    g = time_optimal_grid(
        s,
        coef,
        (vel[:, 0], vel[:, 1]),
        (acc[:, 0], acc[:, 1]),
        cap,
        ends[0] ** 2,
        x_end,
        MAX_PATH_SPEED**2,
    )
    last, s_stop, limit = s.size - 1, None, None
    if g.status == "stuck":
        last, s_stop = g.stage, float(s[g.stage])
        limit = _limit_name(g.kind, g.joint, int(which[min(g.stage, which.size - 1)]))
    elif g.status == "start_outside":
        last, s_stop, limit = 0, float(s[0]), "start speed"
    elif g.status == "empty":
        last, s_stop, limit = 0, float(s[0]), "end speed"
    elif blocked is not None:
        s_stop, limit = blocked
    traj, s_samples = _sample(pp, s[: last + 1], g.x[: last + 1], dt)
    status = "ok" if s_stop is None else "infeasible"
    message = (
        f"time-optimal: {traj.t[-1]:.6g} s"
        if s_stop is None
        else f"the path cannot be followed past s = {s_stop:.6g} ({limit}); "
        f"timed to there, {traj.t[-1]:.6g} s"
    )
    sd = np.sqrt(g.x)
    slow = _slowdowns(s, sd, g.x, coef, (vel, acc, cap), which)
    return TimeOptimal(
        status=status,
        trajectory=traj,
        s_samples=s_samples,
        duration=float(traj.t[-1]),
        s_stop=s_stop,
        limit=limit,
        message=message,
        path=pp,
        s=s,
        sd=sd,
        sd_max=np.sqrt(g.mvc),
        controllable=np.sqrt(np.stack([g.k_lo, g.k_hi], axis=1)),
        reachable=np.sqrt(np.stack([g.r_lo, g.r_hi], axis=1)),
        slowdowns=slow,
        vel=vel,
        acc=acc,
    )


def _slowdowns(
    s: FloatArray,
    sd: FloatArray,
    x: FloatArray,
    coef: FloatArray,
    lim: tuple[FloatArray, ...],
    which: NDArray[np.int_],
) -> tuple[Slowdown, ...]:
    """Interior local minima of ``ṡ`` below SLOW_FRACTION of its peak, with their limits."""
    ok = np.isfinite(sd)
    if ok.sum() < 3:
        return ()
    peak = float(np.max(sd[ok]))
    out: list[Slowdown] = []
    prev = -2
    for i in range(1, int(ok.sum()) - 1):
        low = sd[i] < SLOW_FRACTION * peak and sd[i] <= sd[i - 1] and sd[i] <= sd[i + 1]
        if not low:
            continue
        if i - prev > 1:  # one report per run of minima
            kind, joint, _ = _binding(i, x, s, coef, lim)
            name = _limit_name(kind, joint, int(which[min(i, which.size - 1)]))
            out.append(Slowdown(float(s[i]), float(sd[i]), name))
        prev = i
    return tuple(out)


def _sample(
    pp: PiecewisePolynomial, s: FloatArray, x: FloatArray, dt: float
) -> tuple[JointTrajectory, FloatArray]:
    """The timing ``ṡ² = x`` on the grid ``s`` (``s̈`` constant between) and its samples' s."""
    if s.size < 2:
        q0 = pp(s[:1])
        z = np.zeros_like(q0)
        return JointTrajectory(np.zeros(1), q0, z, z.copy()), s[:1].copy()
    h = np.diff(s)
    r = np.sqrt(x)
    with np.errstate(divide="ignore"):
        step = 2.0 * h / (r[:-1] + r[1:])
    tg = np.concatenate([[0.0], np.cumsum(step)])
    T = float(tg[-1])
    if not T <= MAX_DURATION:
        raise ArgumentError(
            f"the limits give a duration of {T:.3g} s; at most {MAX_DURATION:g} s are made "
            "(raise the limits)",
            arg="vmax",
        )
    check_size(T / dt + 1.0, MAX_SAMPLES, "dt", f"samples ({T:g} s every {dt!r} s)")
    t = sample_times(T, dt)
    i = np.clip(np.searchsorted(tg, t, side="right") - 1, 0, h.size - 1)
    tau = t - tg[i]
    u = (x[i + 1] - x[i]) / (2.0 * h[i])
    sdot = np.maximum(r[i] + u * tau, 0.0)
    ss = np.clip(s[i] + r[i] * tau + 0.5 * u * tau * tau, s[i], s[i + 1])
    d1, d2 = pp(ss, 1), pp(ss, 2)
    q = pp(ss)
    q[0], q[-1] = pp(s[:1])[0], pp(s[-1:], left=True)[0]
    qd = d1 * sdot[:, None]
    qdd = d1 * u[:, None] + d2 * (sdot * sdot)[:, None]
    ss[-1] = s[-1]
    return JointTrajectory(t, q, qd, qdd), ss
