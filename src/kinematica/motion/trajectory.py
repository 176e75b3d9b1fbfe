"""Joint-space trajectories: quintic, cubic and trapezoidal profiles, synchronised.

All joints start and stop together. Quintic and cubic profiles are Hermite
polynomials in normalised time ``s = t / T``, written in their basis so that
the boundary values come out exactly (the basis polynomials are exactly 0 or
1 at ``s = 0`` and ``s = 1``): position, velocity (and acceleration for the
quintic) at both ends, zero unless given.

The trapezoid is synchronised in one of two ways (``sync``):

- ``"each"`` (the default, the textbook minimum-time synchronised move): every
  joint's own minimum time under its ``vmax`` and ``amax`` is computed
  (``Δ/v + v/a``, or ``2·sqrt(Δ/a)`` for a triangle when the joint cannot
  reach ``v``), the slowest sets the duration ``T``, and every other joint is
  stretched to ``T`` by keeping its own acceleration ``±amax`` and cruising at
  the lowest speed that covers its distance in ``T``:
  ``V = 2Δ / (T + sqrt(T² − 4Δ/a))`` (a root of ``V² − a·T·V + a·Δ = 0``,
  written without cancellation), which is at most its ``vmax`` because ``T``
  is at least its own minimum time.
- ``"shared"``: every joint moves along the straight joint-space line
  ``q0 + (q1 - q0)·s(t)`` with one trapezoidal speed profile ``s(t)`` whose
  limits are those of the most limited joint, ``min(vmax/Δ)`` and
  ``min(amax/Δ)``. The path in joint space is a line, but when one joint limits
  the speed and another the acceleration the move is longer than ``"each"``.

For the quintic and cubic profiles the two rules coincide: the shape is fixed,
only ``T`` is free, and the shortest ``T`` within every joint's limits is the
slowest joint's own minimum time.
"""

from __future__ import annotations

import math
from typing import Literal

import numpy as np
from numpy.polynomial import polynomial as npoly
from numpy.typing import ArrayLike, NDArray

from kinematica.arguments import check_choice, check_number, check_size
from kinematica.errors import ArgumentError, DimensionError, KinematicaError
from kinematica.motion.samples import (
    DURATION_RTOL,
    LIMIT_RTOL,
    MAX_SAMPLES,
    JointTrajectory,
    sample_times,
)
from kinematica.spatial.checks import as_float_array

__all__ = [
    "CUBIC_BASIS",
    "DURATION_RTOL",
    "LIMIT_RTOL",
    "MAX_DURATION",
    "MAX_SAMPLES",
    "QUINTIC_BASIS",
    "JointTrajectory",
    "Profile",
    "Sync",
    "joint_trajectory",
    "minimum_time",
    "sample_times",
    "time_scaling",
]

FloatArray = NDArray[np.float64]
Profile = Literal["quintic", "cubic", "trapezoid", "scurve"]
Sync = Literal["each", "shared"]
PROFILES: tuple[Profile, ...] = ("quintic", "cubic", "trapezoid")
#: joint_trajectory's profiles: the time scalings and the jerk-limited move (motion.scurve).
MOVES: tuple[Profile, ...] = (*PROFILES, "scurve")
SYNCS: tuple[Sync, ...] = ("each", "shared")

#: Default sample spacing (s).
DEFAULT_DT = 0.01
#: Longest trajectory (s), given or derived from the limits: about 30 years.
MAX_DURATION = 1e9

# Hermite bases, coefficients in s (lowest power first). Weights: quintic
# (p0, T·v0, T²·a0, T²·a1, T·v1, p1); cubic (p0, T·v0, T·v1, p1). The splines
# through waypoints (splines.py) use them segment by segment.
QUINTIC_BASIS = np.array(
    [
        [1, 0, 0, -10, 15, -6],
        [0, 1, 0, -6, 8, -3],
        [0, 0, 0.5, -1.5, 1.5, -0.5],
        [0, 0, 0, 0.5, -1, 0.5],
        [0, 0, 0, -4, 7, -3],
        [0, 0, 0, 10, -15, 6],
    ],
    dtype=float,
)
CUBIC_BASIS = np.array([[1, 0, -3, 2], [0, 1, -2, 1], [0, 0, -1, 1], [0, 0, 3, -2]], dtype=float)
# Peak |ds/dt|·T and |d²s/dt²|·T² of the rest-to-rest profiles.
_PEAKS = {"quintic": (15.0 / 8.0, 10.0 / math.sqrt(3.0)), "cubic": (1.5, 6.0)}


def _vector(x: ArrayLike | None, n: int, name: str, positive: bool = False) -> FloatArray:
    if x is None:
        return np.zeros(n)
    a = as_float_array(x, name)
    if a.ndim == 0:
        a = np.full(n, float(a))
    if a.shape != (n,):
        raise DimensionError(f"{name} must be a number or {n} values, got shape {a.shape}")
    if not np.all(np.isfinite(a)):
        raise DimensionError(f"{name} holds NaN or inf")
    if positive and np.any(a <= 0):
        j = int(np.flatnonzero(a <= 0)[0]) + 1
        raise KinematicaError(f"{name} must be positive, got {a[j - 1]:g} for joint {j}")
    return a


def _trapezoid_params(
    duration: float | None, V: float | None, A: float | None
) -> tuple[float, float, float]:
    """``(T, V, A)`` of a rest-to-rest trapezoid on s from 0 to 1."""
    if duration is None:
        if V is None or A is None:
            raise KinematicaError("a trapezoid needs a duration, or both vmax and amax")
        if V * V / A >= 1.0:  # cruise speed not reached: triangle
            ta = math.sqrt(1.0 / A)
            return 2.0 * ta, A * ta, A
        return 1.0 / V + V / A, V, A
    T = duration
    if A is not None:
        disc = A * A * T * T - 4.0 * A
        if disc < 0.0:
            raise KinematicaError(
                f"duration {T:g} s is too short for amax: at least {2.0 / math.sqrt(A):.6g} s"
            )
        Vt = (A * T - math.sqrt(disc)) / 2.0
        if V is not None and Vt > V * (1.0 + 1e-12):
            raise KinematicaError(
                f"duration {T:g} s is too short for vmax and amax: at least "
                f"{_trapezoid_params(None, V, A)[0]:.6g} s"
            )
        return T, Vt, A
    Vt = 1.5 / T if V is None else V
    if not 1.0 / Vt <= T <= 2.0 / Vt:
        raise KinematicaError(
            f"duration {T:g} s does not fit vmax: between {1.0 / Vt:.6g} and {2.0 / Vt:.6g} s"
        )
    ta = T - 1.0 / Vt
    return T, Vt, Vt / ta


def time_scaling(
    profile: Profile, t: ArrayLike, duration: float, vmax: float | None = None
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """A rest-to-rest path parameter ``s(t)`` from 0 to 1 and its derivatives.

    Args:
        profile: ``"quintic"``, ``"cubic"`` or ``"trapezoid"``.
        t: ``(m,)`` times (s) in ``[0, duration]``.
        duration: T (s).
        vmax: Trapezoid cruise speed of ``s`` (1/s); 1.5/T by default.

    Returns:
        ``(s, ds/dt, d²s/dt²)``, each ``(m,)``.

    Raises:
        ArgumentError: Unknown profile, ``duration`` not in (0, MAX_DURATION] s,
            ``vmax`` not a positive number.
        DimensionError: ``t`` not numbers of shape ``(m,)``.
        KinematicaError: ``duration`` does not fit ``vmax`` (trapezoid).
    """
    check_choice(profile, "profile", PROFILES)
    ta = as_float_array(t, "t")
    if ta.ndim != 1:
        raise DimensionError(f"t must be times of shape (m,), got shape {ta.shape}")
    duration = check_number(
        duration, "duration", positive=True, hi=MAX_DURATION, unit="s", what="a number of seconds"
    )
    if vmax is not None:
        vmax = check_number(vmax, "vmax", positive=True, unit="1/s", what="a speed")
    if profile == "trapezoid":
        T, V, A = _trapezoid_params(duration, vmax, None)
        return _trapezoid(ta, T, V, A)
    _, _, s, sd, sdd = _hermite(profile, ta, duration, 1, None)
    return s[:, 0], sd[:, 0], sdd[:, 0]


def _trapezoid(
    t: FloatArray,
    T: float,
    V: float | FloatArray,
    A: float | FloatArray,
    D: float | FloatArray = 1.0,
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Distance covered (0 to ``D``), speed and acceleration; ``V``, ``A``, ``D`` broadcast."""
    tb = V / A  # blend time
    u = T - t
    s = np.where(
        t < tb, 0.5 * A * t * t, np.where(u < tb, D - 0.5 * A * u * u, V * t - 0.5 * V * tb)
    )
    sd = np.where(t < tb, A * t, np.where(u < tb, A * u, V))
    sdd = np.where(t < tb, A, np.where(u < tb, -A, 0.0))
    s = np.where(t >= T, D, s)
    return s, sd, sdd


def minimum_time(
    delta: ArrayLike, vmax: ArrayLike, amax: ArrayLike, profile: Profile = "trapezoid"
) -> FloatArray:
    """Each joint's own minimum time for a rest-to-rest move of ``|delta|``.

    Args:
        delta: ``(..., n)`` joint displacements (rad, m).
        vmax: Speed limits (> 0) broadcast to ``delta``; ``inf`` for none.
        amax: Acceleration limits (> 0) broadcast to ``delta``; ``inf`` for none.
        profile: ``"trapezoid"``: ``Δ/v + v/a``, or ``2·sqrt(Δ/a)`` (a
            triangle) when ``v²/a >= Δ``; ``"quintic"`` / ``"cubic"``: the
            larger of ``kv·Δ/v`` and ``sqrt(ka·Δ/a)`` with the profile's peak
            factors (15/8 and 10/√3; 3/2 and 6).

    Returns:
        ``(..., n)`` times (s); 0 for a joint that does not move.
    """
    d = np.abs(np.asarray(delta, dtype=float))
    v = np.broadcast_to(np.asarray(vmax, dtype=float), d.shape)
    a = np.broadcast_to(np.asarray(amax, dtype=float), d.shape)
    # a limit near 0 (1e-320) gives an infinite time: the callers refuse it by name
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        if profile == "trapezoid":
            triangle = v * v >= a * d
            out = np.where(triangle, 2.0 * np.sqrt(d / a), d / v + v / a)
        else:
            kv, ka = _PEAKS[profile]
            out = np.maximum(kv * d / v, np.sqrt(ka * d / a))
    res: FloatArray = np.where(d > 0, out, 0.0)
    return res


def _trapezoid_each(
    a: FloatArray,
    b: FloatArray,
    duration: float | None,
    vm: FloatArray | None,
    am: FloatArray,
    dt: float,
) -> JointTrajectory:
    """Every joint its own trapezoid at ``±amax``, all lasting the slowest joint's time."""
    delta = b - a
    D = np.abs(delta)
    v = np.full(D.size, np.inf) if vm is None else vm
    if duration is None:
        T = float(minimum_time(D, v, am).max())
        _derived_check(T, dt, vm, am)
    else:
        T = float(duration)
        own = minimum_time(D, v, am)
        slow = own > T * (1.0 + DURATION_RTOL)
        if slow.any():
            j = int(np.argmax(own))
            what = "amax" if vm is None else "vmax and amax"
            raise KinematicaError(
                f"duration {T:g} s is too short for {what}: joint {j + 1} needs at least "
                f"{own[j]:.6g} s",
                arg="duration",
            )
    # The lowest cruise speed covering D in T at acceleration a (a root of
    # V² - a·T·V + a·D = 0 without cancellation); at the slowest joint's own
    # time it is its vmax (or its triangle's peak) up to round-off, hence min().
    disc = np.maximum(T * T - 4.0 * D / am, 0.0)
    V = np.minimum(2.0 * D / (T + np.sqrt(disc)), v)
    t = sample_times(T, dt)
    s, sd, sdd = _trapezoid(t[:, None], T, V, am, D)
    sign = np.sign(delta)
    q = a + sign * s
    q[-1] = b
    return JointTrajectory(t, q, sign * sd, sign * sdd)


def _hermite(
    profile: str,
    t: FloatArray,
    T: float,
    n: int,
    bc: tuple[FloatArray, ...] | None,
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray, FloatArray]:
    """Basis values (and derivatives) at ``t``; with ``bc`` the combined joint samples."""
    basis = QUINTIC_BASIS if profile == "quintic" else CUBIC_BASIS
    s = np.clip(t / T, 0.0, 1.0)
    B: FloatArray = np.stack([npoly.polyval(s, c) for c in basis], axis=-1)
    dB: FloatArray = np.stack([npoly.polyval(s, npoly.polyder(c)) for c in basis], axis=-1)
    ddB: FloatArray = np.stack([npoly.polyval(s, npoly.polyder(c, 2)) for c in basis], axis=-1)
    dB, ddB = dB / T, ddB / (T * T)
    if bc is None:  # a unit rest-to-rest move: the last basis function alone
        return B, dB, B[:, -1:], dB[:, -1:], ddB[:, -1:]
    W: FloatArray = np.stack(bc)  # (k, n) weights
    return B, dB, B @ W, dB @ W, ddB @ W


def joint_trajectory(
    q0: ArrayLike,
    q1: ArrayLike,
    duration: float | None = None,
    profile: Profile = "quintic",
    dt: float = DEFAULT_DT,
    vmax: ArrayLike | None = None,
    amax: ArrayLike | None = None,
    *,
    qd0: ArrayLike | None = None,
    qd1: ArrayLike | None = None,
    qdd0: ArrayLike | None = None,
    qdd1: ArrayLike | None = None,
    sync: Sync = "each",
    jmax: ArrayLike | None = None,
) -> JointTrajectory:
    """A synchronised joint trajectory from ``q0`` to ``q1``.

    Args:
        q0: ``(n,)`` start joint values (rad, m).
        q1: ``(n,)`` end joint values.
        duration: T (s). If ``None``, the shortest duration that keeps every
            joint within ``vmax`` and ``amax`` (rest to rest; at least one of
            them is then needed, both for the trapezoid).
        profile: ``"quintic"`` (zero or given velocity and acceleration at
            both ends), ``"cubic"`` (velocity at both ends) or ``"trapezoid"``
            (rest to rest, constant acceleration ``±amax``, a cruise or a
            triangle when the cruise speed is not reached; ``sync``) or
            ``"scurve"`` (jerk-limited, time-optimal from any start state to
            any target state: :mod:`kinematica.motion.scurve`; needs ``vmax``,
            ``amax`` and ``jmax``, and ruckig, the extra ``trajectory``).
        dt: Largest sample spacing (s); samples are uniform, the last at T.
        vmax: Speed limit per joint (scalar or ``(n,)``; rad/s, m/s).
        amax: Acceleration limit per joint (rad/s², m/s²).
        qd0: ``(n,)`` start velocity (quintic, cubic, scurve); zero by default.
        qd1: ``(n,)`` end velocity.
        qdd0: ``(n,)`` start acceleration (quintic, scurve).
        qdd1: ``(n,)`` end acceleration (quintic, scurve).
        sync: How the trapezoid synchronises the joints (module docstring):
            ``"each"`` (default: every joint its own profile at its ``amax``,
            the slowest joint's minimum time for all) or ``"shared"`` (one
            profile on the joint-space line, limited by the most limited
            joint). The quintic and cubic give the same for both.
        jmax: Jerk limit per joint (rad/s³, m/s³) of the ``"scurve"``.

    Returns:
        :class:`JointTrajectory` ``(t, q, qd, qdd)``; for ``"scurve"`` a
        :class:`~kinematica.motion.scurve.JerkTrajectory` (its jerk ``qddd`` too),
        at least ``duration`` long if one is given.

    Raises:
        DimensionError: Shapes differ, NaN or inf.
        ArgumentError: Unknown profile or sync; ``duration`` not in (0,
            MAX_DURATION] s; ``dt`` not > 0; more than MAX_SAMPLES samples from
            the duration (given, or the one ``vmax``/``amax`` need) and ``dt``.
            Checked before any sample is made.
        KinematicaError: Limits that are not positive, or a given duration
            too short for the limits.
    """
    check_choice(profile, "profile", MOVES)
    check_choice(sync, "sync", SYNCS)
    a = as_float_array(q0, "q0")
    if a.ndim == 2:
        raise DimensionError(
            f"q0 must be one configuration (n,), got shape {a.shape}; "
            "for a (k, n) array of waypoints use via_trajectory"
        )
    if a.ndim != 1 or a.size == 0:
        raise DimensionError(f"q0 must be one configuration (n,), got shape {a.shape}")
    n = a.size
    a = _vector(a, n, "q0")
    b = _vector(q1, n, "q1")
    seconds = "a number of seconds"
    if duration is not None:
        duration = check_number(
            duration, "duration", positive=True, hi=MAX_DURATION, unit="s", what=seconds
        )
    dt = check_number(dt, "dt", positive=True, unit="s", what=seconds)
    if duration is not None:
        _times_check(duration, dt, "duration/dt")
    vm = None if vmax is None else _vector(vmax, n, "vmax", positive=True)
    am = None if amax is None else _vector(amax, n, "amax", positive=True)
    if profile == "scurve":
        if sync != "each":
            raise KinematicaError(
                "the scurve times each joint's own profile: drop sync", arg="sync"
            )
        from kinematica.motion.scurve import scurve_trajectory

        move = (qd0, qd1, qdd0, qdd1)
        return scurve_trajectory(a, b, duration, dt, vm, am, jmax, *move)
    if jmax is not None:
        raise KinematicaError("jmax limits the 'scurve' profile only", arg="jmax")
    delta = np.abs(b - a)
    moving = delta > 0
    # Limits of the path parameter s in [0, 1], set by the most limited joint.
    Vs = float(np.min(vm[moving] / delta[moving])) if vm is not None and moving.any() else None
    As = float(np.min(am[moving] / delta[moving])) if am is not None and moving.any() else None

    if profile == "trapezoid":
        if any(x is not None for x in (qd0, qd1, qdd0, qdd1)):
            raise KinematicaError("the trapezoid profile is rest to rest: drop qd0/qd1/qdd0/qdd1")
        if not moving.any():
            T = duration or 0.0
            return _still(np.zeros(1) if T == 0 else sample_times(T, dt), a, b)
        if sync == "each" and am is not None and (duration is not None or vm is not None):
            return _trapezoid_each(a, b, duration, vm, am, dt)
        T, V, A = _trapezoid_params(duration, Vs, As)
        if duration is None:
            _derived_check(T, dt, vmax, amax)
        t = sample_times(T, dt)
        s, sd, sdd = _trapezoid(t, T, V, A)
        d = b - a
        q = (1.0 - s)[:, None] * a + s[:, None] * b
        return JointTrajectory(t, q, sd[:, None] * d, sdd[:, None] * d)

    v0, v1 = _vector(qd0, n, "qd0"), _vector(qd1, n, "qd1")
    if profile == "cubic" and (qdd0 is not None or qdd1 is not None):
        raise KinematicaError("the cubic profile sets velocities only: use 'quintic' for qdd0/qdd1")
    acc0, acc1 = _vector(qdd0, n, "qdd0"), _vector(qdd1, n, "qdd1")
    if duration is None:
        if np.any(v0) or np.any(v1) or np.any(acc0) or np.any(acc1):
            raise KinematicaError("give a duration when boundary velocities are not zero")
        if Vs is None and As is None:
            raise KinematicaError("give a duration, or vmax and/or amax to derive it")
        inf = np.full(n, np.inf)
        own = minimum_time(delta, inf if vm is None else vm, inf if am is None else am, profile)
        T = float(own.max())
        if T == 0.0:
            return _still(np.zeros(1), a, b)
        _derived_check(T, dt, vmax, amax)
    else:
        T = float(duration)
    t = sample_times(T, dt)
    bc: tuple[FloatArray, ...]
    if profile == "quintic":
        bc = (a, T * v0, T * T * acc0, T * T * acc1, T * v1, b)
    else:
        bc = (a, T * v0, T * v1, b)
    _, _, q, qd, qdd = _hermite(profile, t, T, n, bc)
    q[0], q[-1] = a, b  # the basis gives them to round-off; make them exact
    if duration is not None:
        _check_limits(profile, T, bc, vm, am)
    return JointTrajectory(t, q, qd, qdd)


def _check_limits(
    profile: str,
    T: float,
    bc: tuple[FloatArray, ...],
    vm: FloatArray | None,
    am: FloatArray | None,
) -> None:
    """Raise when a given duration makes some joint exceed its limits."""
    if vm is None and am is None:
        return
    dense = np.linspace(0.0, T, 2001)
    _, _, _, qd, qdd = _hermite(profile, dense, T, bc[0].size, bc)
    for lim, val, what in ((vm, qd, "vmax"), (am, qdd, "amax")):
        if lim is None:
            continue
        peak = np.abs(val).max(axis=0)
        over = peak > lim * (1.0 + LIMIT_RTOL)
        if over.any():
            j = int(np.flatnonzero(over)[0])
            raise KinematicaError(
                f"duration {T:g} s is too short: joint {j + 1} would reach "
                f"{peak[j]:.6g} > {what} {lim[j]:g}"
            )


def _times_check(T: float, dt: float, name: str) -> None:
    """Refuse a duration ``T`` and spacing ``dt`` that give more than MAX_SAMPLES samples."""
    check_size(T / dt + 1.0, MAX_SAMPLES, name, f"samples ({T:g} s every {dt!r} s)")


def _derived_check(T: float, dt: float, vmax: object, amax: object) -> None:
    """The duration the speed/acceleration limits need, checked like a given one."""
    given = [k for k, v in (("vmax", vmax), ("amax", amax)) if v is not None]
    name = "/".join(given)
    verb = "give" if len(given) > 1 else "gives"
    if not T <= MAX_DURATION:
        raise ArgumentError(
            f"{name} {verb} a duration of {T:.3g} s; at most {MAX_DURATION:g} s are made "
            "(raise the limits)",
            arg=name,
        )
    _times_check(T, dt, name)


def _still(t: FloatArray, a: FloatArray, b: FloatArray) -> JointTrajectory:
    """A trajectory that does not move (q0 == q1)."""
    q = np.broadcast_to(a, (t.size, a.size)).copy()
    q[-1] = b
    z = np.zeros_like(q)
    return JointTrajectory(t, q, z, z.copy())
