"""Joint trajectories: boundary conditions exactly, limits respected, joints synchronised."""

from __future__ import annotations

import numpy as np
import pytest

import kinematica as km
from kinematica.errors import ArgumentError
from kinematica.motion import joint_trajectory, time_scaling
from kinematica.motion.trajectory import MAX_DURATION, MAX_SAMPLES

Q0 = np.array([0.2, -1.0, 0.5, 0.0])
Q1 = np.array([1.4, 0.3, 0.5, -2.0])


def poly_reference(T: float, bc: list[tuple[int, float, np.ndarray]], deg: int) -> np.ndarray:
    """Coefficients (n, deg+1) from the boundary conditions, by a linear solve.

    ``bc`` holds (derivative order, time, values).
    """
    rows, rhs = [], []
    for order, t, values in bc:
        row = [0.0] * (deg + 1)
        for k in range(order, deg + 1):
            row[k] = np.prod(range(k - order + 1, k + 1)) * t ** (k - order)
        rows.append(row)
        rhs.append(values)
    return np.linalg.solve(np.array(rows), np.array(rhs)).T


def evaluate(coef: np.ndarray, t: np.ndarray, order: int) -> np.ndarray:
    out = []
    for c in coef:
        p = np.polynomial.Polynomial(c).deriv(order) if order else np.polynomial.Polynomial(c)
        out.append(p(t))
    return np.array(out).T


def test_quintic_rest_to_rest_exact_ends_and_reference() -> None:
    T = 1.7
    t, q, qd, qdd = joint_trajectory(Q0, Q1, T, "quintic", dt=0.01)
    assert t[0] == 0.0 and t[-1] == T and np.all(np.diff(t) <= 0.01 + 1e-15)
    assert np.array_equal(q[0], Q0) and np.array_equal(q[-1], Q1)
    assert np.abs(qd[[0, -1]]).max() < 1e-12 and np.abs(qdd[[0, -1]]).max() < 1e-12
    z = np.zeros(4)
    coef = poly_reference(
        T, [(0, 0, Q0), (1, 0, z), (2, 0, z), (0, T, Q1), (1, T, z), (2, T, z)], 5
    )
    for order, got in enumerate((q, qd, qdd)):
        assert np.allclose(got, evaluate(coef, t, order), atol=1e-12)


def test_quintic_and_cubic_with_boundary_velocities() -> None:
    T = 2.0
    v0, v1 = np.array([0.1, 0.0, -0.2, 0.3]), np.array([0.0, 0.4, 0.0, -0.1])
    a0, a1 = np.array([0.5, 0.0, 0.0, -0.2]), np.array([0.0, -0.3, 0.1, 0.0])
    t, q, qd, qdd = joint_trajectory(Q0, Q1, T, "quintic", qd0=v0, qd1=v1, qdd0=a0, qdd1=a1)
    coef = poly_reference(
        T, [(0, 0, Q0), (1, 0, v0), (2, 0, a0), (0, T, Q1), (1, T, v1), (2, T, a1)], 5
    )
    for order, got in enumerate((q, qd, qdd)):
        assert np.allclose(got, evaluate(coef, t, order), atol=1e-12)
    assert np.allclose(qd[0], v0, atol=1e-14) and np.allclose(qd[-1], v1, atol=1e-14)
    assert np.allclose(qdd[0], a0, atol=1e-13) and np.allclose(qdd[-1], a1, atol=1e-13)

    t, q, qd, qdd = joint_trajectory(Q0, Q1, T, "cubic", qd0=v0, qd1=v1)
    coef = poly_reference(T, [(0, 0, Q0), (1, 0, v0), (0, T, Q1), (1, T, v1)], 3)
    for order, got in enumerate((q, qd, qdd)):
        assert np.allclose(got, evaluate(coef, t, order), atol=1e-12)
    assert np.array_equal(q[-1], Q1)


@pytest.mark.parametrize("profile", ["quintic", "cubic"])
def test_shortest_duration_from_limits_touches_a_limit(profile: str) -> None:
    vmax, amax = np.array([1.0, 2.0, 1.0, 1.5]), np.array([3.0, 3.0, 3.0, 3.0])
    _, _, qd, qdd = joint_trajectory(Q0, Q1, None, profile, dt=1e-4, vmax=vmax, amax=amax)
    ratio = max((np.abs(qd) / vmax).max(), (np.abs(qdd) / amax).max())
    assert 0.999 < ratio <= 1.0 + 1e-9


def test_shared_trapezoid_respects_vmax_amax_and_cruises() -> None:
    vmax, amax = 0.5, 2.0
    t, q, qd, qdd = joint_trajectory(
        Q0, Q1, None, "trapezoid", dt=1e-3, vmax=vmax, amax=amax, sync="shared"
    )
    delta = np.abs(Q1 - Q0)
    # the joint with the largest move is the limiting one: T = Δ/V + V/A (hand formula)
    assert np.isclose(t[-1], delta.max() / vmax + vmax / amax)
    assert np.abs(qd).max() <= vmax * (1 + 1e-12) and np.abs(qdd).max() <= amax * (1 + 1e-12)
    assert np.isclose(np.abs(qd).max(), vmax)  # cruise reached
    assert np.array_equal(q[0], Q0) and np.allclose(q[-1], Q1, atol=1e-15)
    # synchronised: every joint on the same straight line, s in [0, 1]
    s = (q - Q0) / np.where(Q1 != Q0, Q1 - Q0, 1.0)
    moving = Q1 != Q0
    assert np.allclose(s[:, moving], s[:, [0]])
    assert np.allclose(np.gradient(q, t, axis=0), qd, atol=2 * amax * 1e-3)


def test_trapezoid_triangle_when_vmax_is_not_reached() -> None:
    vmax, amax = 10.0, 2.0
    t, _, qd, _ = joint_trajectory(Q0, Q1, None, "trapezoid", dt=1e-4, vmax=vmax, amax=amax)
    d = np.abs(Q1 - Q0).max()
    assert np.isclose(t[-1], 2 * np.sqrt(d / amax))  # hand formula of the triangle
    assert np.isclose(np.abs(qd).max(), np.sqrt(amax * d), rtol=1e-3)  # peak below vmax
    assert np.abs(qd).max() < vmax


def test_trapezoid_with_a_duration() -> None:
    t, _, _, qdd = joint_trajectory(Q0, Q1, 3.0, "trapezoid", amax=2.0)
    assert t[-1] == 3.0 and np.abs(qdd).max() <= 2.0 * (1 + 1e-12)
    with pytest.raises(km.KinematicaError, match="too short for amax"):
        joint_trajectory(Q0, Q1, 0.5, "trapezoid", amax=2.0)


def test_time_scaling_is_zero_to_one() -> None:
    t = np.linspace(0, 2.0, 201)
    for profile in ("quintic", "cubic", "trapezoid"):
        s, sd, _ = time_scaling(profile, t, 2.0)  # type: ignore[arg-type]
        assert s[0] == 0.0 and s[-1] == 1.0 and np.all(np.diff(s) >= 0) and sd[0] == 0.0


def test_still_trajectory() -> None:
    _, q, qd, _ = joint_trajectory(Q0, Q0, 1.0, "trapezoid")
    assert np.all(q == Q0) and np.all(qd == 0)


def test_bad_input() -> None:
    with pytest.raises(km.KinematicaError, match="profile"):
        joint_trajectory(Q0, Q1, 1.0, "linear")  # type: ignore[arg-type]
    with pytest.raises(km.DimensionError, match="q1"):
        joint_trajectory(Q0, Q1[:3], 1.0)
    with pytest.raises(km.KinematicaError, match="duration"):
        joint_trajectory(Q0, Q1, -1.0)
    with pytest.raises(km.KinematicaError, match="give a duration"):
        joint_trajectory(Q0, Q1)
    with pytest.raises(km.KinematicaError, match="joint 4 would reach"):
        joint_trajectory(Q0, Q1, 1.0, vmax=[100, 100, 100, 1.0])
    with pytest.raises(km.KinematicaError, match="vmax must be positive"):
        joint_trajectory(Q0, Q1, 1.0, vmax=[1, 1, 0, 1])


def test_a_duration_and_dt_that_give_too_many_samples_are_refused() -> None:
    qa, qb = [0.0, 0.0], [1.0, 1.0]
    dt = 2.0**-10  # exact in binary: duration / dt is exact too
    at_limit = (MAX_SAMPLES - 1) * dt
    inside = joint_trajectory(qa, qb, at_limit, "trapezoid", dt=dt)  # the cheapest profile
    assert inside.t.size == MAX_SAMPLES  # just inside
    with pytest.raises(
        ArgumentError, match=r"^duration/dt gives 1e\+06 samples .* 1,000,000"
    ) as info:
        joint_trajectory(qa, qb, at_limit + dt, dt=dt)  # just outside
    assert info.value.arg == "duration/dt"
    with pytest.raises(ArgumentError, match=r"^duration/dt gives inf samples \(2 s every 1e-320"):
        joint_trajectory(qa, qb, 2.0, dt=1e-320)
    with pytest.raises(
        ArgumentError,
        match=r"^duration must be a number of seconds greater than 0 and at most 1e\+09 s, "
        r"got 1e\+308",
    ):
        joint_trajectory(qa, qb, 1e308)
    with pytest.raises(
        ArgumentError, match=r"^dt must be a number of seconds greater than 0 s?, got -1"
    ):
        joint_trajectory(qa, qb, 1.0, dt=-1)


def test_limits_that_need_too_long_a_duration_are_refused() -> None:
    qa, qb = [0.0, 0.0], [1.0, 1.0]
    with pytest.raises(
        ArgumentError, match=r"^vmax gives a duration of .* s; at most 1e\+09 s"
    ) as info:
        joint_trajectory(qa, qb, vmax=1e-320)
    assert info.value.arg == "vmax"
    with pytest.raises(ArgumentError, match=r"^vmax/amax give a duration"):
        joint_trajectory(qa, qb, None, "trapezoid", vmax=1e-320, amax=1e-320)
    # A slow joint whose duration is fine but whose samples are too many at this dt.
    with pytest.raises(ArgumentError, match=r"^amax gives .* samples"):
        joint_trajectory(qa, qb, amax=1e-9, dt=1e-3)


def test_the_longest_duration() -> None:
    qa, qb = [0.0], [1.0]
    assert joint_trajectory(qa, qb, MAX_DURATION, dt=MAX_DURATION / 10).t[-1] == MAX_DURATION
    with pytest.raises(
        ArgumentError, match=r"^duration must be .* at most 1e\+09 s, got 1010000000\.0"
    ):
        joint_trajectory(qa, qb, MAX_DURATION * 1.01, dt=MAX_DURATION / 10)
