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
does not do is ours: the validation, the exact pieces and samples (the
profiles ruckig returns are turned into one
:class:`~kinematica.motion.piecewise.PiecewisePolynomial` of cubic pieces,
sampled exactly, jerk included), the limit checks on the result, waypoints
with position limits (:mod:`kinematica.motion.scurve_via`) and the pictures.
"""

from __future__ import annotations

import math
import re
from typing import Any

import numpy as np
from numpy.polynomial import polynomial as npoly
from numpy.typing import ArrayLike, NDArray

from kinematica.arguments import check_size
from kinematica.errors import DimensionError, KinematicaError, MissingDependencyError
from kinematica.motion.piecewise import PiecewisePolynomial
from kinematica.motion.samples import DURATION_RTOL, LIMIT_RTOL, MAX_SAMPLES, JointTrajectory

__all__ = [
    "PIECE_RTOL",
    "SETTLE_ULPS",
    "JerkTrajectory",
    "Segment",
    "limits_from",
    "phase_pieces",
    "require_ruckig",
    "scurve_pieces",
    "scurve_trajectory",
    "state_from",
]

FloatArray = NDArray[np.float64]

#: Pieces of the result shorter than this fraction of the duration are merged into
#: their neighbour: two joints' phase boundaries that ruckig puts at the same time up to
#: round-off would otherwise leave a piece of 1e-17 s.
PIECE_RTOL = 1e-13


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


def _phases(seg: Segment) -> tuple[FloatArray, ...]:
    """``(n, 9)`` durations, jerks and start states ``p, v, a`` of the joints' phases.

    The brake's two phases, then the profile's seven; last ``(n,)`` the targets.
    """
    profs = seg.out.profiles[0]
    t = np.array([[*pr.brake.t, *pr.t] for pr in profs], dtype=float)
    j = np.array([[*pr.brake.j, *pr.j] for pr in profs], dtype=float)
    p = np.array([[*pr.brake.p, *pr.p[:7]] for pr in profs], dtype=float)
    v = np.array([[*pr.brake.v, *pr.v[:7]] for pr in profs], dtype=float)
    a = np.array([[*pr.brake.a, *pr.a[:7]] for pr in profs], dtype=float)
    pf = np.array([pr.pf for pr in profs], dtype=float)
    return t, j, p, v, a, pf


def scurve_pieces(seg: Segment) -> PiecewisePolynomial:
    """The last planned segment as cubic pieces from ``t = 0`` (knots: its two ends).

    ruckig's phases (a brake first, if any, then seven) through :func:`phase_pieces`.
    """
    return phase_pieces(float(seg.out.duration), _phases(seg), seg.limits)


def phase_pieces(
    T: float, phases: tuple[FloatArray, ...], limits: tuple[FloatArray, ...]
) -> PiecewisePolynomial:
    """Joints' phases of constant jerk as cubic pieces from ``t = 0`` to ``T`` (knots: 0, T).

    Args:
        T: Duration (s).
        phases: ``(t, j, p, v, a, pf)``: ``(n, P)`` each joint's phase durations and
            jerks and its position, velocity and acceleration at each phase's start,
            and ``(n,)`` its target position.
        limits: ``(vmax, amax, jmax)``, each ``(n,)`` (for :func:`_settle`).

    Each joint's phases are cut at the union of every joint's switch times; each
    piece holds ``p, v, a/2, j/6`` of its joint at the piece's start, evaluated from
    the phase that contains it. Then each joint's end is settled on its target
    (:func:`_settle`).
    """
    t, j, p, v, a, pf = phases
    n = t.shape[0]
    used = t > 0.0
    t0 = np.concatenate([np.zeros((n, 1)), np.cumsum(t, axis=1)[:, :-1]], axis=1)
    cuts = np.unique(np.concatenate([t0[used], [0.0, T]]))
    cuts = cuts[(cuts >= 0.0) & (cuts <= T)]
    keep = np.concatenate([[True], np.diff(cuts) > PIECE_RTOL * max(T, 1.0)])
    breaks = cuts[keep]
    breaks[-1] = T
    if breaks.size < 2:  # a move of zero duration: one empty piece holding the state
        breaks = np.array([0.0, 0.0])
    tb = breaks[:-1]
    # the phase holding each piece's midpoint: a switch merged into a piece's start
    # (PIECE_RTOL) may lie a hair after it, and its phase is the one the piece follows
    mid = 0.5 * (tb + breaks[1:])
    began = used[:, :, None] & (t0[:, :, None] <= mid[None, None, :])  # (n, P, pieces)
    k = t.shape[1] - 1 - np.argmax(began[:, ::-1, :], axis=1)  # the last phase begun
    tau = tb[None, :] - np.take_along_axis(t0, k, axis=1)
    pk, vk, ak, jk = (np.take_along_axis(x, k, axis=1) for x in (p, v, a, j))
    coef = np.stack(
        [
            pk + tau * (vk + tau * (ak / 2.0 + tau * jk / 6.0)),
            vk + tau * (ak + tau * jk / 2.0),
            (ak + tau * jk) / 2.0,
            jk / 6.0,
        ],
        axis=1,
    ).T  # (n, 4, pieces) -> (pieces, 4, n)
    still = ~used.any(axis=1)  # a joint with no phase: at rest at its target
    coef[:, :, still] = 0.0
    coef[:, 0, still] = pf[still]
    coef = _settle(limits, breaks, coef, (t0, t, v, a, j, pf), used)
    return PiecewisePolynomial(breaks, coef, np.array([0.0, T]))


#: End-position errors up to this many units in the last place of the target are
#: round-off of the pieces' own arithmetic, and left as they are.
SETTLE_ULPS = 16
#: Peaks of the smoothstep ``10s³ - 15s⁴ + 6s⁵`` on [0, 1]: its first, second and third
#: derivatives (15/8, 10/√3, 60).
_STEP_PEAKS = (15.0 / 8.0, 10.0 / np.sqrt(3.0), 60.0)
#: The smoothstep's derivatives 0..5, each a polynomial in s (lowest power first).
_STEP = [
    np.array([0.0, 0.0, 0.0, 10.0, -15.0, 6.0]),
    np.array([0.0, 0.0, 30.0, -60.0, 30.0]),
    np.array([0.0, 60.0, -180.0, 120.0]),
    np.array([60.0, -360.0, 360.0]),
    np.array([-360.0, 720.0]),
    np.array([720.0]),
]


def _step_taylor(s0: FloatArray, scale: float) -> FloatArray:
    """``(m, 6)`` coefficients in ``u`` of the smoothstep at ``s0 + scale·u``."""
    out = np.empty((s0.size, 6))
    for k, c in enumerate(_STEP):
        out[:, k] = npoly.polyval(s0, c) * scale**k / math.factorial(k)
    return out


def _settle(
    limits: tuple[FloatArray, ...],
    breaks: FloatArray,
    coef: FloatArray,
    phases: tuple[FloatArray, ...],
    used: NDArray[np.bool_],
) -> FloatArray:
    """Land each joint exactly on its target position (round-off instead of ruckig's 1e-8).

    ruckig accepts a profile whose end position is within 1e-8 of the target
    (measured here: up to 7.7e-9 for a joint re-timed to a long, slow cruise).
    The error ``e`` is taken out inside one zero-jerk phase of that joint by
    adding ``-e`` times the smoothstep ``10s³ - 15s⁴ + 6s⁵`` of the phase's
    normalised time (zero velocity, acceleration and jerk change at both of
    its ends) and ``-e`` after it: the longest such phase whose velocity,
    acceleration and jerk stay within the limits with the step's peaks added
    (:data:`_STEP_PEAKS` over the phase's duration). A joint without one keeps
    ruckig's end. Pieces become quintic where a step is added.
    """
    t0s, durs, vs, accs, jerks, pf = phases
    tb = breaks[:-1]
    mid = 0.5 * (tb + breaks[1:])
    vmax, amax, jmax = limits
    h = breaks[-1] - tb[-1]
    last = coef[-1]  # (4, n)
    e_all = last[0] + h * (last[1] + h * (last[2] + h * last[3])) - pf
    off = (np.abs(e_all) > SETTLE_ULPS * np.spacing(np.abs(pf))) & used.any(axis=1)
    out = coef
    for d in np.flatnonzero(off):
        e = float(e_all[d])
        t0, dur, v, a, j = (x[d, used[d]] for x in (t0s, durs, vs, accs, jerks))
        for k in np.argsort(-dur):
            tau = dur[k]
            v_end = v[k] + a[k] * tau
            room = (
                max(abs(v[k]), abs(v_end)) + _STEP_PEAKS[0] * abs(e) / tau <= vmax[d],
                abs(a[k]) + _STEP_PEAKS[1] * abs(e) / tau**2 <= amax[d],
                _STEP_PEAKS[2] * abs(e) / tau**3 <= jmax[d],
            )
            if j[k] != 0.0 or not all(room):
                continue
            if out.shape[1] == 4:
                out = np.concatenate([coef, np.zeros((coef.shape[0], 2, coef.shape[2]))], axis=1)
            inside = (mid >= t0[k]) & (mid <= t0[k] + tau)
            out[inside, :, d] -= e * _step_taylor((tb[inside] - t0[k]) / tau, 1.0 / tau)
            out[mid > t0[k] + tau, 0, d] -= e
            break
    return out


def check_peaks(pieces: PiecewisePolynomial, limits: tuple[FloatArray, ...]) -> None:
    """Raise when the exact peaks of speed, acceleration or jerk exceed a limit.

    ruckig holds the limits by construction; this check makes a broken
    promise (a new ruckig version, a start state just outside a limit) an
    error instead of a trajectory that a drive refuses.
    """
    for order, (lim, name) in enumerate(zip(limits, ("vmax", "amax", "jmax"), strict=True), 1):
        peak = pieces.peak(order)
        over = peak > lim * (1.0 + LIMIT_RTOL)
        if over.any():
            j = int(np.flatnonzero(over)[0])
            raise KinematicaError(f"joint {j + 1} would reach {peak[j]:.9g} > {name} {lim[j]:g}")


def jerk_samples(
    pieces: PiecewisePolynomial,
    dt: float,
    limits: tuple[FloatArray, FloatArray, FloatArray],
    end: tuple[FloatArray, FloatArray, FloatArray],
) -> JerkTrajectory:
    """Sample ``pieces`` (every knot a sample) with the jerk; the last sample is ``end``."""
    if pieces.duration == 0.0:
        t = np.zeros(1)
        q, qd, qdd = (pieces(t, order) for order in range(3))
    else:
        t, q, qd, qdd = pieces.sample(dt)
    qddd = pieces(t, 3)
    # the end state: exact by construction to round-off (tests hold it to 1e-10)
    q[-1], qd[-1], qdd[-1] = end
    qddd[-1] = pieces(t[-1:], 3, left=True)[0]
    traj = JerkTrajectory(t, q, qd, qdd)
    traj.qddd = qddd
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
    pieces = scurve_pieces(seg)
    check_peaks(pieces, limits)
    return jerk_samples(pieces, dt, limits, (b, v1, acc1))
