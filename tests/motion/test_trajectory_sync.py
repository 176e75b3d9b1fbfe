"""Minimum-time synchronised moves: the slowest joint's own time, every joint within its limits."""

from __future__ import annotations

import math

import numpy as np
import pytest

import kinematica as km
from kinematica.motion import joint_trajectory, minimum_time

# Issue 23's example: joint 3 limits by its acceleration, joint 1 by its speed.
A = np.array([-0.0681, -0.448, 1.79, -0.5028])
B = np.array([1.5185, -0.3257, -0.5059, -0.5543])
VMAX = np.array([0.402, 0.7714, 0.6901, 0.406])
AMAX = np.array([2.3955, 2.0477, 0.5879, 1.0457])


def own_time(d: float, v: float, a: float) -> float:
    """Rest-to-rest minimum time of one joint, by hand: a triangle or a trapezoid."""
    d = abs(d)
    if d == 0.0:
        return 0.0
    if v * v / a >= d:  # accelerate to the middle, brake: d = a·(T/2)²
        return 2.0 * math.sqrt(d / a)
    return d / v + v / a  # d = v·(T - v/a)


def test_issue_example_takes_the_slowest_joints_own_time() -> None:
    t, q, qd, qdd = joint_trajectory(A, B, None, "trapezoid", vmax=VMAX, amax=AMAX, dt=1e-3)
    slowest = own_time(B[2] - A[2], VMAX[2], AMAX[2])  # 2.2959/0.6901 + 0.6901/0.5879
    assert t[-1] == pytest.approx(4.500748231882696, abs=1e-12)
    assert abs(t[-1] - slowest) <= 1e-12 * slowest
    shared = joint_trajectory(A, B, None, "trapezoid", vmax=VMAX, amax=AMAX, sync="shared")
    assert shared.t[-1] == pytest.approx(4.9362486539386135, abs=1e-12)  # today's, by name
    assert np.array_equal(q[-1], B)
    # joint 3 saturates both limits (its own minimum-time profile); all stay within theirs
    assert np.isclose(np.abs(qd[:, 2]).max(), VMAX[2], rtol=1e-12)
    assert np.abs(qdd).max(axis=0) == pytest.approx(AMAX, rel=1e-15)


def integrate(t: np.ndarray, qd: np.ndarray) -> np.ndarray:
    """Cumulative trapezoidal integral of the sampled velocities (an independent q)."""
    steps = 0.5 * (qd[1:] + qd[:-1]) * np.diff(t)[:, None]
    return np.vstack([np.zeros(qd.shape[1]), np.cumsum(steps, axis=0)])


def test_random_moves_take_the_slowest_joints_own_time() -> None:
    rng = np.random.default_rng(23)
    dt = 2e-3
    for _ in range(200):
        n = int(rng.integers(1, 8))
        a, b = rng.uniform(-2, 2, n), rng.uniform(-2, 2, n)
        if rng.random() < 0.2:  # a joint that does not move
            b[0] = a[0]
        v, acc = rng.uniform(0.1, 2.0, n), rng.uniform(0.1, 4.0, n)
        t, q, qd, qdd = joint_trajectory(a, b, None, "trapezoid", dt=dt, vmax=v, amax=acc)
        own = [own_time(d, vj, aj) for d, vj, aj in zip(b - a, v, acc, strict=True)]
        T = max(own)
        assert abs(t[-1] - T) <= 1e-12 * T
        assert np.all(np.abs(qd) <= v * (1 + 1e-12)) and np.all(np.abs(qdd) <= acc * (1 + 1e-12))
        assert np.array_equal(q[0], a) and np.array_equal(q[-1], b)
        assert np.all(qd[[0, -1]] == 0.0)
        # q is the integral of qd (trapezoidal rule: exact but at the kinks of qd)
        err = np.abs(q - a - integrate(t, qd)).max(axis=0)
        assert np.all(err <= acc * dt * dt)
        # every moving joint accelerates at its own amax (stretched, not slowed down)
        moving = b != a
        assert np.allclose(np.abs(qdd[:, moving]).max(axis=0), acc[moving], rtol=1e-15)
        # and the library's own-time function agrees with the hand formula
        assert np.allclose(minimum_time(b - a, v, acc), own, rtol=1e-14, atol=0)


def test_no_shorter_duration_fits_and_the_tolerance_is_round_off() -> None:
    T = own_time(B[2] - A[2], VMAX[2], AMAX[2])
    for inside in (T, T * (1 - 1e-13), T * 1.2):
        tr = joint_trajectory(A, B, inside, "trapezoid", vmax=VMAX, amax=AMAX)
        assert tr.t[-1] == inside and np.all(np.abs(tr.qd) <= VMAX * (1 + 1e-12))
    with pytest.raises(km.KinematicaError, match="too short for vmax and amax: joint 3"):
        joint_trajectory(A, B, T * (1 - 1e-10), "trapezoid", vmax=VMAX, amax=AMAX)


def test_a_given_duration_stretches_each_joint_at_its_own_amax() -> None:
    T = 6.0
    t, q, qd, qdd = joint_trajectory(A, B, T, "trapezoid", amax=AMAX, dt=1e-3)
    assert t[-1] == T and np.array_equal(q[-1], B)
    assert np.allclose(np.abs(qdd).max(axis=0), AMAX, rtol=1e-15)
    # cruise speed of each joint by hand: V² - a·T·V + a·|Δ| = 0, the smaller root
    d = np.abs(B - A)
    V = (AMAX * T - np.sqrt((AMAX * T) ** 2 - 4 * AMAX * d)) / 2
    assert np.allclose(np.abs(qd).max(axis=0), V, rtol=1e-12)
    # the shared profile: one line in joint space, joint accelerations proportional to |Δ|
    shared = joint_trajectory(A, B, T, "trapezoid", amax=AMAX, sync="shared", dt=1e-3)
    peak = np.abs(shared.qdd).max(axis=0)
    assert np.allclose(peak / d, peak[0] / d[0]) and np.all(peak <= AMAX * (1 + 1e-12))


@pytest.mark.parametrize("profile", ["quintic", "cubic"])
def test_polynomial_moves_are_minimum_time_for_both_rules(profile: str) -> None:
    kv, ka = {"quintic": (15 / 8, 10 / math.sqrt(3)), "cubic": (1.5, 6.0)}[profile]
    d = np.abs(B - A)
    T = float(np.max(np.maximum(kv * d / VMAX, np.sqrt(ka * d / AMAX))))  # slowest joint's own
    for sync in ("each", "shared"):
        tr = joint_trajectory(A, B, None, profile, vmax=VMAX, amax=AMAX, sync=sync)  # type: ignore[arg-type]
        assert abs(tr.t[-1] - T) <= 1e-12 * T


def test_sync_names() -> None:
    with pytest.raises(km.KinematicaError, match="sync must be 'each' or 'shared'"):
        joint_trajectory(A, B, None, "trapezoid", vmax=VMAX, amax=AMAX, sync="joint")  # type: ignore[arg-type]
    with pytest.raises(km.DimensionError, match="use via_trajectory"):
        joint_trajectory(np.stack([A, B]), B)
