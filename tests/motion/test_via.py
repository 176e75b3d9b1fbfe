"""Joint trajectories through waypoints: splines against hand-derived cases (see test_mstraj)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.interpolate import CubicSpline

import kinematica as km
from kinematica.motion import joint_trajectory, via_polynomials, via_trajectory
from kinematica.motion.trajectory import LIMIT_RTOL

W = np.array(
    [[0.0, 0.5, -1.0], [0.8, 0.2, -0.4], [0.3, 1.4, 0.1], [1.2, 0.9, 0.6], [1.0, 0.0, 0.2]]
)
TIMES = np.array([0.0, 1.0, 2.5, 3.1, 4.5])


def jumps(pieces: km.motion.PiecewisePolynomial, order: int) -> np.ndarray:
    """Right minus left limit of the order-th derivative at every interior knot."""
    inner = pieces.breaks[1:-1]
    return pieces(inner, order) - pieces(inner, order, left=True)


def test_cubic_through_three_points_by_hand() -> None:
    # y = 0, 1, 3 at t = 0, 1, 2, rest at both ends. C2 at t = 1 with h = 1:
    # v0 + 4 v1 + v2 = 3 (y2 - y0)  ->  v1 = 9/4. First segment a2 = 3(y1 - y0) - v1 = 3/4,
    # a3 = -2(y1 - y0) + v1 = 1/4: q(0.5) = 3/16 + 1/32 = 7/32, q''(1) = 2 a2 + 6 a3 = 3.
    p = via_polynomials([[0.0], [1.0], [3.0]], "cubic", times=[0, 1, 2])
    assert p(0.5)[0, 0] == pytest.approx(7 / 32, abs=1e-15)
    assert p(1.0, 1)[0, 0] == pytest.approx(9 / 4, abs=1e-14)
    assert p(1.0, 2)[0, 0] == pytest.approx(3.0, abs=1e-13)
    assert p(1.0, 2, left=True)[0, 0] == pytest.approx(3.0, abs=1e-13)


@pytest.mark.parametrize("ends", ["clamped", "natural"])
def test_cubic_spline_equals_scipy(ends: str) -> None:
    v0, v1 = np.array([0.3, 0.0, -0.2]), np.array([0.0, 0.5, 0.1])
    kw = {"qd0": v0, "qd1": v1} if ends == "clamped" else {}
    p = via_polynomials(W, "cubic", TIMES, ends=ends, **kw)  # type: ignore[arg-type]
    bc = ((1, v0), (1, v1)) if ends == "clamped" else "natural"
    ref = CubicSpline(TIMES, W, bc_type=bc)
    t = np.linspace(0, TIMES[-1], 301)
    for order in range(3):
        assert np.allclose(p(t, order), ref(t, order), atol=1e-12, rtol=0)


def power_basis_spline(t: np.ndarray, y: np.ndarray, deg: int, ends: np.ndarray) -> list:
    """The C^(deg-1) spline through (t, y), clamped derivatives 1..(deg-1)/2 at both ends.

    A second method: every coefficient of every segment (in local time) unknown,
    one dense linear system of interpolation, continuity and end conditions.
    """
    k = t.size
    p, c = k - 1, deg + 1
    rows, rhs = [], []

    def deriv_row(seg: int, tau: float, order: int) -> np.ndarray:
        r = np.zeros(p * c)
        for j in range(order, c):
            r[seg * c + j] = np.prod(np.arange(j - order + 1, j + 1)) * tau ** (j - order)
        return r

    for i in range(p):
        h = t[i + 1] - t[i]
        rows += [deriv_row(i, 0.0, 0), deriv_row(i, h, 0)]
        rhs += [y[i], y[i + 1]]
        if i + 1 < p:
            for order in range(1, deg):
                rows.append(deriv_row(i, h, order) - deriv_row(i + 1, 0.0, order))
                rhs.append(0.0)
    m = (deg - 1) // 2
    for order in range(1, m + 1):
        rows += [deriv_row(0, 0.0, order), deriv_row(p - 1, t[-1] - t[-2], order)]
        rhs += [ends[0][order - 1], ends[1][order - 1]]
    coef = np.linalg.solve(np.array(rows), np.array(rhs)).reshape(p, c)
    return [np.polynomial.Polynomial(cc) for cc in coef]


def test_quintic_spline_is_c4_and_equals_a_second_method() -> None:
    y = W[:, 1]
    ends = np.array([[0.2, -0.1], [0.0, 0.3]])  # (qd0, qdd0), (qd1, qdd1)
    p = via_polynomials(y[:, None], "quintic", TIMES, qd0=0.2, qdd0=-0.1, qd1=0.0, qdd1=0.3)
    ref = power_basis_spline(TIMES, y, 5, ends)
    for i, poly in enumerate(ref):
        tau = np.linspace(0, TIMES[i + 1] - TIMES[i], 50)
        for order in range(5):
            got = p(TIMES[i] + tau, order)[:, 0]
            assert np.allclose(got, poly.deriv(order)(tau), atol=1e-10, rtol=0)
    # continuous to the 4th derivative, and the 5th really jumps (it is a spline)
    for order in range(5):
        assert np.abs(jumps(p, order)).max() < 1e-9
    assert np.abs(jumps(p, 5)).max() > 1e-3


@pytest.mark.parametrize(("method", "order"), [("cubic", 2), ("quintic", 4)])
def test_splines_hit_every_waypoint_and_are_continuous(method: str, order: int) -> None:
    traj = via_trajectory(W, method, TIMES, dt=0.01)  # type: ignore[arg-type]
    at = np.searchsorted(traj.t, TIMES)
    assert np.array_equal(traj.t[at], TIMES)
    assert np.array_equal(traj.q[at], W)  # exactly: each knot starts a piece
    p = via_polynomials(W, method, TIMES)  # type: ignore[arg-type]
    assert np.abs(p(TIMES) - W).max() <= 1e-12  # the last one through the last piece
    for r in range(order + 1):
        assert np.abs(jumps(p, r)).max() < 1e-10 * max(1.0, np.abs(p.peak(r)).max())
    assert np.abs(jumps(p, order + 1)).max() > 1e-3
    # rest at both ends (clamped by default)
    assert np.abs(traj.qd[[0, -1]]).max() < 1e-12 and np.all(traj.t[1:] > traj.t[:-1])
    assert np.diff(traj.t).max() <= 0.01 + 1e-15


@pytest.mark.parametrize("method", ["cubic", "quintic"])
def test_times_from_limits_reach_one_limit_and_respect_all(method: str) -> None:
    vmax, amax = np.array([1.0, 0.6, 2.0]), np.array([2.0, 3.0, 0.8])
    traj = via_trajectory(W, method, vmax=vmax, amax=amax, dt=2e-4)  # type: ignore[arg-type]
    ratio = max((np.abs(traj.qd) / vmax).max(), (np.abs(traj.qdd) / amax).max())
    assert 1 - 1e-6 < ratio <= 1 + 1e-12
    p = via_polynomials(W, method, vmax=vmax, amax=amax)  # type: ignore[arg-type]
    exact = max((p.peak(1) / vmax).max(), (p.peak(2) / amax).max())
    assert abs(exact - 1) <= 1e-12
    assert np.array_equal(traj.q[-1], W[-1])


def test_given_times_are_checked_against_the_limits_to_round_off() -> None:
    vmax = 1.0
    p = via_polynomials(W, "cubic", vmax=vmax)  # its peak speed is vmax
    for factor, ok in ((1 + 0.1 * LIMIT_RTOL, True), (1 + 10 * LIMIT_RTOL, False)):
        times = p.knots / factor  # speeds up by the factor
        if ok:
            via_trajectory(W, "cubic", times, vmax=vmax)
        else:
            with pytest.raises(km.KinematicaError, match=r"would reach .* > vmax 1"):
                via_trajectory(W, "cubic", times, vmax=vmax)


def test_two_point_quintic_is_the_textbook_quintic() -> None:
    q0, q1, T = np.array([0.2, -1.0]), np.array([1.4, 0.3]), 2.0
    traj = via_trajectory([q0, q1], "quintic", [0.0, T], dt=0.01)
    s = traj.t / T
    textbook = q0 + (q1 - q0) * (10 * s**3 - 15 * s**4 + 6 * s**5)[:, None]
    assert np.allclose(traj.q, textbook, atol=1e-14)
    ref = joint_trajectory(q0, q1, T, "quintic", dt=0.01)
    for a, b in zip(traj, ref, strict=True):
        assert np.allclose(a, b, atol=1e-13)
    # MATLAB's quinticpolytraj default (zero velocity and acceleration at every waypoint)
    z = np.zeros((2, 2))
    same = via_trajectory([q0, q1], "quintic", [0.0, T], dt=0.01, qd=z, qdd=z)
    assert np.allclose(same.q, textbook, atol=1e-14)


def test_matlab_style_given_velocities_stop_or_pass_at_each_waypoint() -> None:
    y = W[:3, :1]
    t = np.array([0.0, 1.0, 3.0])
    stops = via_polynomials(y, "quintic", t, qd=np.zeros((3, 1)))
    # each segment is the rest-to-rest textbook quintic
    s = np.linspace(0, 1, 11)
    blend = 10 * s**3 - 15 * s**4 + 6 * s**5
    assert np.allclose(stops(1.0 + 2.0 * s)[:, 0], y[1] + (y[2] - y[1]) * blend, atol=1e-14)
    assert np.abs(stops(t, 1)).max() < 1e-14
    v = np.array([[0.0], [0.4], [-0.2]])
    cub = via_polynomials(y, "cubic", t, qd=v)
    assert np.allclose(cub(t, 1), v, atol=1e-14) and np.allclose(cub(t), y, atol=1e-15)


def test_bad_input() -> None:
    with pytest.raises(km.KinematicaError, match="method must be"):
        via_trajectory(W, "linear", TIMES)  # type: ignore[arg-type]
    with pytest.raises(km.DimensionError, match="k >= 2"):
        via_trajectory(W[:1], "cubic", [0.0])
    with pytest.raises(km.DimensionError, match="waypoints must be"):
        via_trajectory("abc", "cubic")
    with pytest.raises(km.KinematicaError, match="times must start at 0 and increase"):
        via_trajectory(W, "cubic", TIMES[::-1])
    with pytest.raises(km.DimensionError, match="times must be 5"):
        via_trajectory(W, "cubic", TIMES[:3])
    with pytest.raises(km.KinematicaError, match="times must be given, or vmax"):
        via_trajectory(W, "cubic")
    with pytest.raises(km.KinematicaError, match="tacc"):
        via_trajectory(W, "mstraj", TIMES)
    with pytest.raises(km.KinematicaError, match="waypoints 1 and 2 are equal"):
        via_trajectory([W[0], W[0], W[1]], "cubic", vmax=1.0)
    with pytest.raises(km.KinematicaError, match="vmax must be positive"):
        via_trajectory(W, "cubic", vmax=[1.0, 0.0, 1.0])
    with pytest.raises(km.KinematicaError, match="cubic sets velocities only"):
        via_trajectory(W, "cubic", TIMES, qdd0=[1, 1, 1])
    with pytest.raises(km.KinematicaError, match="mstraj takes a start and an end velocity"):
        via_trajectory(W, "mstraj", TIMES, tacc=0.1, qdd=np.zeros((5, 3)))


def test_random_splines_hit_and_join_whatever_the_spacing() -> None:
    rng = np.random.default_rng(7)
    for _ in range(40):
        k = int(rng.integers(2, 12))
        t = np.concatenate([[0.0], np.cumsum(np.exp(rng.uniform(-2, 2, k - 1)))])  # 1:50 spacing
        y = rng.normal(size=(k, 2))
        for method, order in (("cubic", 2), ("quintic", 4)):
            for ends in ("clamped", "natural"):
                p = via_polynomials(y, method, t, ends=ends)  # type: ignore[arg-type]
                assert np.abs(p(t) - y).max() <= 1e-12
                for r in range(order + 1):
                    scale = max(1.0, p.peak(r).max())
                    tol = 1e-12 if r <= 2 else 1e-6  # jerk, snap: h⁻³, h⁻⁴ round-off
                    assert np.abs(jumps(p, r)).max(initial=0.0) <= tol * scale


def test_a_natural_quintic_through_two_waypoints_is_the_line() -> None:
    """Every quadratic through two points has no jerk: the least-jerk interpolant is not
    unique there, and the line (of least acceleration, the natural cubic's) is taken, at
    spacings whose singular system once gave NaN or an arbitrary quadratic."""
    y = np.array([[0.88287423, -1.52937171], [0.00350815, -0.64995619]])
    for T in (4.54834549, 0.137, 1.0, 7.3):
        t = np.array([0.0, T])
        p = via_polynomials(y, "quintic", t, ends="natural")
        line = via_polynomials(y, "cubic", t, ends="natural")
        s = np.linspace(0.0, T, 9)
        assert np.all(np.isfinite(p(s)))
        assert np.abs(p(s) - line(s)).max() <= 1e-12
        assert np.abs(p(s) - (y[0] + np.outer(s / T, y[1] - y[0]))).max() <= 1e-12


def test_a_sampling_too_fine_for_its_duration_is_refused_before_any_sample() -> None:
    from kinematica.motion.trajectory import MAX_SAMPLES

    W = np.array([[0.0], [1.0]])
    times = [0.0, 1.0]
    # duration / dt + knots: one sample under MAX_SAMPLES is made, one over is refused
    ok = km.via_trajectory(W, "cubic", times=times, dt=1.0 / (MAX_SAMPLES - 3))
    assert ok.t.size <= MAX_SAMPLES
    with pytest.raises(km.ArgumentError, match="dt"):
        km.via_trajectory(W, "cubic", times=times, dt=1.0 / (MAX_SAMPLES - 1))
    with pytest.raises(km.ArgumentError, match="dt"):
        km.via_trajectory(W, "cubic", times=[0.0, 1e9], dt=1e-320)
