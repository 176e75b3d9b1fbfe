"""Independent checks of jerk-limited moves: a closed form, random states, first principles.

The rest-to-rest minimum time of one joint under ``|v| <= V, |a| <= A, |j| <= J``
is derived here by hand (not from ruckig): the optimal profile is symmetric, an
acceleration half from rest to the peak speed ``u`` and back to zero
acceleration, an optional cruise at ``u = V``, and the mirror image. Reaching
speed ``u`` from rest takes

* ``u / A + A / J`` and covers ``u/2 · (u/A + A/J)`` when ``u >= A²/J`` (the
  acceleration reaches ``A`` and holds it),
* ``2·sqrt(u/J)`` and covers ``u·sqrt(u/J)`` otherwise (a triangle in ``a``);

the distance of the acceleration half grows with ``u``, so the peak speed is
``V`` when ``2·s(V) <= D`` (then a cruise of ``(D - 2 s(V)) / V``) and else the
root of ``2·s(u) = D`` in the branch that applies:
``u = A/2·(-A/J + sqrt(A²/J² + 4D/A))`` or ``u = (D·sqrt(J)/2)^(2/3)``.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]


def _rise(u: float, A: float, J: float) -> tuple[float, float]:
    """Time and distance from rest to speed ``u`` at zero acceleration."""
    t = u / A + A / J if u >= A * A / J else 2.0 * math.sqrt(u / J)
    return t, 0.5 * u * t


def rest_to_rest_time(D: float, V: float, A: float, J: float) -> float:
    """Minimum time (s) of one joint moving ``|D|`` from rest to rest (module docstring)."""
    D = abs(D)
    if D == 0.0:
        return 0.0
    tV, sV = _rise(V, A, J)
    if 2.0 * sV <= D:
        return 2.0 * tV + (D - 2.0 * sV) / V
    u = A / 2.0 * (-A / J + math.sqrt(A * A / (J * J) + 4.0 * D / A))
    if u < A * A / J:
        u = (D * math.sqrt(J) / 2.0) ** (2.0 / 3.0)
    t, s = _rise(u, A, J)
    assert abs(2.0 * s - D) <= 1e-9 * D, (s, D)
    return 2.0 * t


def random_limits(rng: np.random.Generator, n: int) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Limits spread over two decades each, so every regime of the profile occurs."""
    V = 10.0 ** rng.uniform(-1.0, 1.0, n)
    A = 10.0 ** rng.uniform(-1.0, 1.0, n)
    J = 10.0 ** rng.uniform(-0.5, 1.5, n)
    return V, A, J


def random_state(
    rng: np.random.Generator, V: FloatArray, A: FloatArray, J: FloatArray, target: bool = False
) -> tuple[FloatArray, FloatArray]:
    """A velocity and acceleration from which no limit must be broken.

    A start needs ``|v| <= V`` and ``|v + c| <= V`` with ``c = a·|a|/(2J)``
    (the speed where the acceleration can first be brought to zero); a target,
    reached from inside the limits, the same with ``-c``. So ``|c| <= 2V``:
    ``a`` is drawn within that, then ``v`` uniformly in its interval.
    """
    a = rng.uniform(-1.0, 1.0, V.shape) * np.minimum(A, np.sqrt(4.0 * J * V))
    c = a * np.abs(a) / (2.0 * J) * (-1.0 if target else 1.0)
    lo, hi = np.maximum(-V, -V - c), np.minimum(V, V - c)
    return lo + rng.uniform(0.0, 1.0, V.shape) * (hi - lo), a


def integrate_jerk(
    t: FloatArray, jerk: FloatArray, start: tuple[FloatArray, FloatArray, FloatArray]
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Acceleration, velocity, position from the jerk samples by the trapezoid rule.

    From first principles: nothing but the start state and the jerk at ``t``.
    The jerk is piecewise constant, so each switch between two samples costs
    at most ``2·J·h`` of acceleration; the caller's tolerance says so.
    """
    h = np.diff(t)[:, None]
    a = start[2] + np.concatenate(
        [np.zeros((1, jerk.shape[1])), np.cumsum(h * (jerk[1:] + jerk[:-1]) / 2, axis=0)]
    )
    v = start[1] + np.concatenate(
        [np.zeros((1, a.shape[1])), np.cumsum(h * (a[1:] + a[:-1]) / 2, axis=0)]
    )
    q = start[0] + np.concatenate(
        [np.zeros((1, v.shape[1])), np.cumsum(h * (v[1:] + v[:-1]) / 2, axis=0)]
    )
    return q, v, a


def retimed_durations(
    q0: FloatArray,
    v0: FloatArray,
    a0: FloatArray,
    q1: FloatArray,
    v1: FloatArray,
    a1: FloatArray,
    limits: tuple[FloatArray, FloatArray, FloatArray],
    at_least: float,
) -> FloatArray:
    """``(n,)`` each joint alone, planned to last at least ``at_least`` s (ruckig, one DoF).

    A joint that can take exactly ``at_least`` returns it; one that cannot (its own
    minimum is longer, or ``at_least`` falls in a gap of the durations it can take)
    returns the next duration it can. So the synchronised duration ``T`` of all
    joints is the smallest ``T`` every joint returns unchanged: each returns ``T``
    at ``T``, and some joint returns more than ``T - δ`` at ``T - δ``. This checks
    ruckig's synchronisation one joint at a time, through its fixed-duration path.
    """
    import ruckig

    out = np.empty(q0.size)
    for d in range(q0.size):
        otg, inp, traj = ruckig.Ruckig(1), ruckig.InputParameter(1), ruckig.Trajectory(1)
        inp.current_position, inp.current_velocity = [q0[d]], [v0[d]]
        inp.current_acceleration = [a0[d]]
        inp.target_position, inp.target_velocity = [q1[d]], [v1[d]]
        inp.target_acceleration = [a1[d]]
        inp.max_velocity, inp.max_acceleration = [limits[0][d]], [limits[1][d]]
        inp.max_jerk = [limits[2][d]]
        inp.minimum_duration = at_least
        otg.calculate(inp, traj)
        out[d] = traj.duration
    return out
