"""Jerk-limited (S-curve) moves from any state to any state, synchronised across joints.

Each joint's jerk is bounded by ``jmax`` (its acceleration by ``amax``, its
speed by ``vmax``); the time-optimal profile of one joint has up to seven
phases of constant jerk (``+j, 0, -j, 0, -j, 0, +j`` or ``+j, 0, -j, 0, +j, 0,
-j``, the zero-jerk phases at an acceleration or speed limit). The slowest
joint sets the duration and every other joint is re-timed to end with it.
From a start state that is not at rest the set of durations a joint can take
is not always an interval (a joint that must brake and turn back cannot take
some durations), so the common duration is the shortest one that every joint
can take, not only the largest of their own minimum times.

The engine is ruckig's community edition (Berscheid & Kröger, "Jerk-limited
Real-time Trajectory Generation with Arbitrary Target States", RSS 2021; MIT
licence; the optional extra ``trajectory``). An own solver was weighed and
left out: matching ruckig's durations to 1e-6 s from arbitrary states needs
its whole case analysis (a dozen profile families per direction, each with its
own polynomial roots, plus the blocked intervals of the synchronisation), and
a half-correct copy would be worse than the well-tested original. What ruckig
does not do is ours: the validation, the exact pieces and samples (the phases
ruckig returns are turned into one
:class:`~kinematica.motion.piecewise.PiecewisePolynomial` of cubic pieces, each
joint's end settled on its target, and sampled exactly, jerk included, by one
call of the compiled core: ``cpp/include/kinematica/jerk_pieces.hpp``), the
limit checks on the result, waypoints with position limits
(:mod:`kinematica.motion.scurve_via`) and the pictures.
"""

from __future__ import annotations

import re
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.arguments import check_size
from kinematica.core.jerk import PIECE_RTOL, SETTLE_ULPS, STATE_ROW, StateMove, jerk_state_move
from kinematica.errors import DimensionError, KinematicaError, MissingDependencyError
from kinematica.motion.piecewise import PiecewisePolynomial
from kinematica.motion.samples import DURATION_RTOL, LIMIT_RTOL, MAX_SAMPLES, JointTrajectory

__all__ = [
    "PIECE_RTOL",
    "SETTLE_ULPS",
    "JerkTrajectory",
    "Segment",
    "check_peak",
    "limits_from",
    "require_ruckig",
    "scurve_move",
    "scurve_pieces",
    "scurve_trajectory",
    "state_from",
    "wrap",
]

FloatArray = NDArray[np.float64]


class JerkTrajectory(JointTrajectory):
    """A :class:`JointTrajectory` with its jerk (unpacks as ``t, q, qd, qdd`` all the same).

    Attributes:
        qddd: ``(m, n)`` joint jerk at the samples (rad/s³, m/s³): piecewise
            constant, the right-hand value at a switch.
        pieces: The exact trajectory: cubic pieces in time, one per interval
            between phase switches of any joint (``pieces(t, 3)`` is the jerk;
            quintic where a joint's end was settled, :func:`scurve_pieces`).
        vmax, amax, jmax: ``(n,)`` the limits it was planned with.
        waypoint_times: ``(k,)`` times (s) of the waypoints, through waypoints
            only (``None`` for a state-to-state move).
        waypoint_qd: ``(k, n)`` the velocities chosen at the waypoints.
        stop_duration: Duration (s) of the same waypoints with a stop at each.
        margin: ``stop_duration - duration`` (s): what not stopping saves.
    """

    qddd: FloatArray
    pieces: PiecewisePolynomial
    vmax: FloatArray
    amax: FloatArray
    jmax: FloatArray
    waypoint_times: FloatArray | None
    waypoint_qd: FloatArray | None
    stop_duration: float | None
    margin: float | None

    @property
    def duration(self) -> float:
        """The last sample's time (s)."""
        return float(self.t[-1])


def require_ruckig() -> Any:
    """The ``ruckig`` module (imported when a jerk-limited move is asked for).

    Raises:
        MissingDependencyError: ruckig is not installed.
    """
    try:
        import ruckig
    except ImportError as exc:
        raise MissingDependencyError(
            "jerk-limited (scurve) moves need ruckig: pip install 'kinematica[trajectory]'"
        ) from exc
    return ruckig


def limits_from(x: ArrayLike | None, n: int, name: str) -> FloatArray:
    """``(n,)`` a positive finite limit per joint from a number or ``(n,)``.

    Raises:
        KinematicaError: ``x`` missing or not positive (the joint named).
        DimensionError: Wrong shape, NaN or inf.
    """
    if x is None:
        raise KinematicaError(f"a jerk-limited move needs {name}", arg=name)
    try:
        a = np.broadcast_to(np.asarray(x, dtype=float), (n,)).copy()
    except (TypeError, ValueError):
        raise DimensionError(f"{name} must be a number or {n} values", arg=name) from None
    if not np.all(np.isfinite(a)):
        raise DimensionError(f"{name} holds NaN or inf", arg=name)
    if np.any(a <= 0):
        j = int(np.flatnonzero(a <= 0)[0])
        raise KinematicaError(f"{name} must be positive, got {a[j]:g} for joint {j + 1}", arg=name)
    return a


def state_from(x: ArrayLike | None, n: int, name: str) -> FloatArray:
    """``(n,)`` a start or target value per joint (a number or ``(n,)``), zero if ``None``.

    Raises:
        DimensionError: Wrong shape, NaN or inf.
    """
    if x is None:
        return np.zeros(n)
    try:
        a = np.asarray(x, dtype=float)
    except (TypeError, ValueError):
        raise DimensionError(f"{name} must be {n} numbers", arg=name) from None
    if a.ndim == 0:
        a = np.full(n, float(a))
    if a.shape != (n,):
        raise DimensionError(
            f"{name} must be a number or {n} values, got shape {a.shape}", arg=name
        )
    if not np.all(np.isfinite(a)):
        raise DimensionError(f"{name} holds NaN or inf", arg=name)
    return a


class Segment:
    """One reusable ruckig planner for ``n`` joints under fixed limits.

    A planner is made once per move (or per waypoint sequence) and called
    for each state-to-state segment, so ruckig's objects are not rebuilt.

    Args:
        vmax, amax, jmax: ``(n,)`` positive limits.
    """

    def __init__(self, vmax: FloatArray, amax: FloatArray, jmax: FloatArray) -> None:
        rk = require_ruckig()
        n = vmax.size
        self._rk = rk
        self.n = n
        self.otg = rk.Ruckig(n)
        self.inp = rk.InputParameter(n)
        self.out = rk.Trajectory(n)
        self.limits = (vmax, amax, jmax)
        self.inp.max_velocity = vmax.tolist()
        self.inp.max_acceleration = amax.tolist()
        self.inp.max_jerk = jmax.tolist()

    def plan(
        self,
        p0: FloatArray,
        v0: FloatArray,
        a0: FloatArray,
        p1: FloatArray,
        v1: FloatArray,
        a1: FloatArray,
        minimum: float | None = None,
        validate: bool = True,
    ) -> float:
        """Plan one segment; its duration (s). The profiles stay in ``self.out``.

        Raises:
            KinematicaError: A state ruckig cannot start from or reach within the
                limits (its reason, with the joint numbered from 1).
        """
        inp = self.inp
        inp.current_position = p0.tolist()
        inp.current_velocity = v0.tolist()
        inp.current_acceleration = a0.tolist()
        inp.target_position = p1.tolist()
        inp.target_velocity = v1.tolist()
        inp.target_acceleration = a1.tolist()
        if minimum is not None:
            inp.minimum_duration = minimum
        try:
            if validate:
                self.otg.validate_input(inp, True, True)
            result = self.otg.calculate(inp, self.out)
        except self._rk.RuckigError as exc:
            raise KinematicaError(_reason(str(exc))) from None
        if result != self._rk.Result.Working:
            raise KinematicaError(f"no jerk-limited move found between these states ({result})")
        return float(self.out.duration)


def _reason(message: str) -> str:
    """The message of ruckig, its DoF numbered from 0 turned into our joints from 1."""
    text = message.strip().removeprefix("[ruckig]").strip()
    return re.sub(r"DoF (\d+)", lambda m: f"joint {int(m.group(1)) + 1}", text)


def _rows(seg: Segment) -> FloatArray:
    """``(n, STATE_ROW)`` the joints' phases of the last planned segment, as ruckig gives them.

    Each row (``jerk_pieces.hpp``): the brake's 2 phase durations and the profile's 7, their
    jerks, their start positions (the profile's 8 states), velocities and accelerations,
    and the target position.
    """
    flat: list[float] = []
    for pr in seg.out.profiles[0]:
        br = pr.brake
        flat += (*br.t, *pr.t, *br.j, *pr.j, *br.p, *pr.p, *br.v, *pr.v, *br.a, *pr.a, pr.pf)
    return np.array(flat).reshape(seg.n, STATE_ROW)


def scurve_move(
    seg: Segment, dt: float, end: tuple[FloatArray, FloatArray, FloatArray]
) -> StateMove:
    """The last planned segment's exact pieces (knots: its two ends) and samples every ``dt``.

    Built in the core from ruckig's phases (:func:`~kinematica.core.jerk.jerk_state_move`):
    each joint's phases are cut at the union of every joint's switch times, each piece a
    cubic per joint, and each joint's end is settled on its target (``jerk_pieces.hpp``).
    ``end``: the last sample ``(q1, v1, a1)``.
    """
    T = float(seg.out.duration)
    return jerk_state_move(T, _rows(seg), seg.limits, end, dt, MAX_SAMPLES)


def scurve_pieces(seg: Segment) -> PiecewisePolynomial:
    """The last planned segment as pieces from ``t = 0`` (:func:`scurve_move`'s)."""
    rows = _rows(seg)
    z = np.zeros(seg.n)
    move = scurve_move(seg, max(float(seg.out.duration), 1.0), (rows[:, -1], z, z))
    return PiecewisePolynomial(move.breaks, move.coef, move.knots)


def check_peak(peak: FloatArray, limits: tuple[FloatArray, ...]) -> None:
    """Raise when a peak ``(3, n)`` of speed, acceleration or jerk exceeds its limit.

    The profiles hold the limits by construction; this check makes a broken promise (a
    new ruckig version, a start state just outside a limit) an error instead of a
    trajectory that a drive refuses.
    """
    lim = np.stack(limits)
    over = peak > lim * (1.0 + LIMIT_RTOL)
    if over.any():
        order, j = (int(x[0]) for x in np.nonzero(over))
        name = ("vmax", "amax", "jmax")[order]
        raise KinematicaError(
            f"joint {j + 1} would reach {peak[order, j]:.9g} > {name} {lim[order, j]:g}"
        )


def wrap(
    samples: tuple[FloatArray, ...],
    pieces: PiecewisePolynomial,
    limits: tuple[FloatArray, FloatArray, FloatArray],
) -> JerkTrajectory:
    """The :class:`JerkTrajectory` of the core's samples ``(t, q, qd, qdd, qddd)`` and pieces."""
    traj = JerkTrajectory(*samples[:4])
    traj.qddd = samples[4]
    traj.pieces = pieces
    traj.vmax, traj.amax, traj.jmax = limits
    traj.waypoint_times = traj.waypoint_qd = None
    traj.stop_duration = traj.margin = None
    return traj


def scurve_trajectory(
    q0: ArrayLike,
    q1: ArrayLike,
    duration: float | None,
    dt: float,
    vmax: ArrayLike | None,
    amax: ArrayLike | None,
    jmax: ArrayLike | None,
    qd0: ArrayLike | None = None,
    qd1: ArrayLike | None = None,
    qdd0: ArrayLike | None = None,
    qdd1: ArrayLike | None = None,
) -> JerkTrajectory:
    """A jerk-limited move from ``(q0, qd0, qdd0)`` to ``(q1, qd1, qdd1)``.

    Called by :func:`~kinematica.motion.trajectory.joint_trajectory` with
    ``profile="scurve"`` (its arguments, already checked for shape).

    Args:
        q0: ``(n,)`` start joint values (rad, m).
        q1: ``(n,)`` target joint values.
        duration: At least this long (s), if given; the shortest otherwise.
        dt: Largest sample spacing (s).
        vmax: Speed limit per joint (a number or ``(n,)``; rad/s, m/s).
        amax: Acceleration limit per joint (rad/s², m/s²).
        jmax: Jerk limit per joint (rad/s³, m/s³); all three limits are needed.
        qd0: ``(n,)`` start velocity (zero by default).
        qd1: ``(n,)`` target velocity.
        qdd0: ``(n,)`` start acceleration.
        qdd1: ``(n,)`` target acceleration.

    Returns:
        :class:`JerkTrajectory`: time-optimal for the slowest joint, every
        joint ending together.

    Raises:
        KinematicaError: A missing or non-positive limit; a start state from
            which a limit will inevitably be broken, or a target outside them
            (ruckig's reason, joint named); a given duration too short.
        MissingDependencyError: ruckig is not installed.
    """
    a, b = np.asarray(q0, dtype=float), np.asarray(q1, dtype=float)
    n = a.size
    limits = (
        limits_from(vmax, n, "vmax"),
        limits_from(amax, n, "amax"),
        limits_from(jmax, n, "jmax"),
    )
    v0, v1 = state_from(qd0, n, "qd0"), state_from(qd1, n, "qd1")
    acc0, acc1 = state_from(qdd0, n, "qdd0"), state_from(qdd1, n, "qdd1")
    seg = Segment(*limits)
    T = seg.plan(a, v0, acc0, b, v1, acc1)
    check_size(T / dt + 1.0, MAX_SAMPLES, "dt", f"samples ({T:g} s every {dt!r} s)")
    if duration is not None:
        if duration < T * (1.0 - DURATION_RTOL):
            raise KinematicaError(
                f"duration {duration:g} s is too short for vmax, amax and jmax: at least {T:.9g} s",
                arg="duration",
            )
        seg.plan(a, v0, acc0, b, v1, acc1, minimum=duration, validate=False)
    move = scurve_move(seg, dt, (b, v1, acc1))
    check_peak(move.peak, limits)
    return wrap(move.samples, PiecewisePolynomial(move.breaks, move.coef, move.knots), limits)
