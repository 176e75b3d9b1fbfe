"""The core's jerk-limited segments at zero acceleration (``jerk.hpp``) against ruckig.

ruckig 0.19 (its community edition, the ``trajectory`` extra) solves the general
state-to-state problem; with zero accelerations at both ends it is the same problem
as ours, so the synchronised durations must agree. Our profiles are checked on their
own: the end state reached by integrating the phases, the limits at every phase's
extremes, and the phases summing to the duration. ``benchmarks/scurve.py`` repeats
this on 10,000 cases.
"""

from __future__ import annotations

import numpy as np
import pytest
from support.scurve_reference import random_limits, rest_to_rest_time

from kinematica.core.jerk import MAX_PHASES, jerk_segments, jerk_via

ruckig = pytest.importorskip("ruckig")

#: Agreement with ruckig's duration (s): the issue's bound.
DURATION_ATOL = 1e-6
#: The end state integrated from the phases.
END_ATOL = 1e-10
#: Limits at the phases' exact extremes, relative.
LIMIT_RTOL = 1e-9


def _ruckig(p0, v0, p1, v1, V, A, J) -> float:  # type: ignore[no-untyped-def]
    n = p0.size
    otg, inp, out = ruckig.Ruckig(n), ruckig.InputParameter(n), ruckig.Trajectory(n)
    inp.current_position, inp.current_velocity = p0.tolist(), v0.tolist()
    inp.current_acceleration = [0.0] * n
    inp.target_position, inp.target_velocity = p1.tolist(), v1.tolist()
    inp.target_acceleration = [0.0] * n
    inp.max_velocity, inp.max_acceleration, inp.max_jerk = V.tolist(), A.tolist(), J.tolist()
    assert otg.calculate(inp, out) == ruckig.Result.Working
    return float(out.duration)


def _walk(
    p: float, v: float, t: np.ndarray, j: np.ndarray
) -> tuple[float, float, float, float, float]:
    """End p, v, a of the phases from (p, v, 0) and the largest |v| and |a| on the way."""
    a, vmax, amax = 0.0, abs(v), 0.0
    for h, jk in zip(t, j, strict=True):
        if jk != 0.0 and 0.0 < -a / jk < h:  # the speed's extreme inside the phase
            tau = -a / jk
            vmax = max(vmax, abs(v + a * tau + jk * tau * tau / 2.0))
        p, v, a = p + h * (v + h * (a / 2.0 + h * jk / 6.0)), v + h * (a + h * jk / 2.0), a + h * jk
        vmax, amax = max(vmax, abs(v)), max(amax, abs(a))
    return p, v, a, vmax, amax


def _velocities(rng: np.random.Generator, V: np.ndarray) -> np.ndarray:
    """At rest, at a limit, or anywhere between, each joint."""
    n = V.size
    kind = rng.integers(0, 4, n)
    return np.select(
        [kind == 0, kind == 1, kind == 2], [np.zeros(n), V, -V], rng.uniform(-1, 1, n) * V
    )


def _check(p0, v0, p1, v1, V, A, J) -> float:  # type: ignore[no-untyped-def]
    seg = jerk_segments(p0[None], v0[None], p1[None], v1[None], (V, A, J))
    T = float(seg.duration[0])
    for i in range(p0.size):
        k = int(seg.phases[0, i])
        assert 0 < k <= MAX_PHASES
        t, j = seg.t[0, i, :k], seg.j[0, i, :k]
        assert np.all(t >= 0.0) and abs(t.sum() - T) <= 1e-12 * max(T, 1.0)
        p, v, a, vm, am = _walk(p0[i], v0[i], t, j)
        assert abs(p - p1[i]) <= END_ATOL and abs(v - v1[i]) <= END_ATOL and abs(a) <= END_ATOL
        assert vm <= V[i] * (1 + LIMIT_RTOL) and am <= A[i] * (1 + LIMIT_RTOL)
        assert np.all(np.abs(j) <= J[i] * (1 + LIMIT_RTOL))
    return T


def test_random_segments_match_ruckig() -> None:
    rng = np.random.default_rng(36)
    for c in range(400):
        n = 1 if c % 3 == 0 else int(rng.integers(2, 8))
        V, A, J = random_limits(rng, n)
        p0 = rng.uniform(-2.0, 2.0, n)
        scale = (2.0, 0.05, 1e-4)[c % 3]  # long moves, short ones, tiny ones
        p1 = p0 + rng.uniform(-scale, scale, n)
        v0, v1 = _velocities(rng, V), _velocities(rng, V)
        T = _check(p0, v0, p1, v1, V, A, J)
        assert abs(T - _ruckig(p0, v0, p1, v1, V, A, J)) <= DURATION_ATOL, c


def test_rest_to_rest_is_the_hand_derived_closed_form() -> None:
    rng = np.random.default_rng(7)
    for _ in range(100):
        V, A, J = random_limits(rng, 1)
        d = float(rng.uniform(-3.0, 3.0))
        z = np.zeros(1)
        T = _check(z, z, np.array([d]), z, V, A, J)
        assert abs(T - rest_to_rest_time(d, V[0], A[0], J[0])) <= 1e-9


def test_a_joint_that_cannot_take_the_slowest_joint_s_time_waits_past_it() -> None:
    # joint 2 moves at full speed and must cover 1 mm: it can take 1 ms, or long enough to
    # turn back, nothing between; joint 1 needs about 1 s, inside that gap
    V, A, J = np.array([1.0, 1.0]), np.array([1.0, 1.0]), np.array([10.0, 10.0])
    p0, p1 = np.zeros(2), np.array([0.5, 1e-3])
    v = np.array([0.0, 1.0])
    alone = jerk_segments(
        p0[None, :1], v[None, :1], p1[None, :1], v[None, :1], (V[:1], A[:1], J[:1])
    )
    T = _check(p0, v, p1, v, V, A, J)
    assert 1.5 * float(alone.duration[0]) < T  # joint 1's own time was blocked
    assert abs(T - _ruckig(p0, v, p1, v, V, A, J)) <= DURATION_ATOL


def test_the_start_state_itself_takes_no_time() -> None:
    x, v = np.array([0.3, -0.2]), np.array([0.5, -0.1])
    lim = (np.ones(2), np.ones(2), np.ones(2))
    assert jerk_segments(x[None], v[None], x[None], v[None], lim).duration[0] == 0.0


def test_the_core_refuses_what_it_cannot_plan() -> None:
    z, one = np.zeros((1, 2)), np.ones(2)
    with pytest.raises(ValueError, match="within vmax"):
        jerk_segments(z, z + 2.0, z, z, (one, one, one))
    with pytest.raises(ValueError, match="finite and positive"):
        jerk_segments(z, z, z, z, (one, one, -one))
    with pytest.raises(ValueError, match="finite"):
        jerk_segments(z + np.nan, z, z, z, (one, one, one))
    with pytest.raises(ValueError, match="two equal waypoints"):
        jerk_via(np.zeros((2, 2)), one * 0, one * 0, (one, one, one), None, 0.0, (1, 8, 0))
