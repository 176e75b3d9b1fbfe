"""Time-optimal timing: closed forms, every limit between grid points, toppra, honesty."""

from __future__ import annotations

import numpy as np
import pytest

import kinematica as km
from kinematica.errors import ArgumentError, DimensionError, KinematicaError
from kinematica.motion import JointTrajectory, joint_trajectory, time_optimal
from kinematica.motion.optimal import MAX_INTERVALS, MAX_PATH_SPEED, SLOW_FRACTION, TimeOptimal

#: Relative excess over a limit accepted on a 1 ms resampling (round-off only).
HOLD_RTOL = 1e-9
#: Largest excess of our duration over toppra's on the same path and limits.
TOPPRA_RTOL = 0.005
#: Resampling step of the checks (s).
DENSE_DT = 1e-3


def excess(values: np.ndarray, lim: np.ndarray) -> float:
    """Largest relative excess of ``values`` (m, n) over limits ``(n, 2)`` (lo, hi); <= 0 inside."""
    with np.errstate(divide="ignore", invalid="ignore"):
        hi = np.where(values > 0, values / lim[:, 1] - 1.0, -1.0)
        lo = np.where(values < 0, values / lim[:, 0] - 1.0, -1.0)
    hi = np.where(np.isinf(lim[:, 1]), -1.0, np.nan_to_num(hi, nan=-1.0, posinf=np.inf))
    lo = np.where(np.isinf(lim[:, 0]), -1.0, np.nan_to_num(lo, nan=-1.0, posinf=np.inf))
    return float(max(hi.max(), lo.max()))


def held(res: TimeOptimal) -> tuple[float, float]:
    """The largest relative excess over the velocity and acceleration limits."""
    tr = res.trajectory
    return excess(tr.qd, res.vel), excess(tr.qdd, res.acc)


def random_case(rng: np.random.Generator, n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    k = int(rng.integers(5, 21))
    W = np.cumsum(rng.uniform(-0.8, 0.8, (k, n)), axis=0)
    vel = np.stack([-rng.uniform(0.3, 3.0, n), rng.uniform(0.3, 3.0, n)], axis=1)
    acc = np.stack([-rng.uniform(1.0, 10.0, n), rng.uniform(1.0, 10.0, n)], axis=1)
    return W, vel, acc


# ------------------------------------------------------------------ closed forms
@pytest.mark.parametrize(
    ("v", "a", "T"),
    [(1.0, 1.0, 2.0), (0.5, 1.0, 1.0 / 0.5 + 0.5 / 1.0), (2.0, 4.0, 2.0 * np.sqrt(1.0 / 4.0))],
)
def test_a_straight_line_is_the_textbook_trapezoid(v: float, a: float, T: float) -> None:
    # one joint from 0 to 1: T = D/v + v/a, or 2·sqrt(D/a) when v²/a >= D (a triangle)
    res = time_optimal([[0.0], [1.0]], v, a, dt=DENSE_DT)
    assert res.ok and res.status == "ok"
    assert res.duration == pytest.approx(T, rel=1e-9)
    assert res.slowdowns == ()  # ṡ rises then falls: no interior minimum to report
    ref = joint_trajectory([0.0], [1.0], None, "trapezoid", DENSE_DT, v, a)
    assert ref.t[-1] == pytest.approx(T, rel=1e-12)
    assert (
        np.abs(np.interp(ref.t, res.trajectory.t, res.trajectory.q[:, 0]) - ref.q[:, 0]).max()
        < 1e-6
    )


def test_a_spline_path_passes_its_waypoints_at_chord_length_s() -> None:
    W = np.array([[0.0, 0.0], [3.0, 4.0], [3.0, 10.0]])  # chords 5 and 6
    res = time_optimal(W, 1.0, 2.0)
    assert np.allclose(res.path.knots, [0.0, 5.0 / 11.0, 1.0])
    assert np.allclose(res.path(res.path.knots), W, atol=1e-12)
    assert np.allclose(res.trajectory.q[[0, -1]], W[[0, -1]], atol=1e-12)


# ------------------------------------------------- every limit, between grid points
@pytest.mark.parametrize("n", [6, 7])
def test_random_paths_hold_every_limit_on_a_dense_resampling(n: int) -> None:
    rng = np.random.default_rng(n)
    for _ in range(4):
        W, vel, acc = random_case(rng, n)
        res = time_optimal(W, vel, acc, dt=DENSE_DT, grid=300)
        assert res.ok
        ev, ea = held(res)
        assert ev <= HOLD_RTOL and ea <= HOLD_RTOL, (ev, ea)
        # some limit is reached (the timing is not slack): within 1 % somewhere
        assert max(ev, ea) > -0.01
        # qd and qdd are the derivatives of q (central differences, an independent check)
        tr = res.trajectory
        fd = np.gradient(tr.q, tr.t, axis=0)[1:-1]
        assert np.abs(fd - tr.qd[1:-1]).max() <= 2e-3 * np.abs(tr.qd).max()


def test_the_phase_plane_is_consistent() -> None:
    rng = np.random.default_rng(3)
    W, vel, acc = random_case(rng, 6)
    res = time_optimal(W, vel, acc, grid=200)
    k = res.controllable
    assert res.sd.shape == res.sd_max.shape == res.s.shape and k.shape == (res.s.size, 2)
    assert np.all(res.sd <= k[:, 1] * (1 + 1e-9) + 1e-12)
    assert np.all(res.sd >= k[:, 0] * (1 - 1e-9) - 1e-12)
    assert np.all(res.sd <= res.sd_max * (1 + 1e-9) + 1e-12)
    r = res.reachable
    assert np.all(res.sd <= r[:, 1] * (1 + 1e-9) + 1e-12)
    assert res.sd[0] == 0.0 and res.sd[-1] == 0.0
    # the time of the grid profile: Σ 2h / (ṡ_i + ṡ_i+1)
    h = np.diff(res.s)
    assert res.duration == pytest.approx(np.sum(2 * h / (res.sd[:-1] + res.sd[1:])), rel=1e-12)


def test_end_speeds_are_met() -> None:
    W = np.array([[0.0, 0.0], [1.0, 0.5], [2.0, 0.0]])
    res = time_optimal(W, 2.0, 4.0, sd_start=0.1, sd_end=0.2, dt=DENSE_DT)
    assert res.ok and res.sd[0] == pytest.approx(0.1) and res.sd[-1] == pytest.approx(0.2)
    d1 = res.path(np.array([0.0, 1.0]), 1)
    assert np.allclose(res.trajectory.qd[0], 0.1 * d1[0]) and np.allclose(
        res.trajectory.qd[-1], 0.2 * d1[1]
    )
    too_fast = time_optimal(W, 2.0, 4.0, sd_start=100.0)
    assert too_fast.status == "infeasible" and too_fast.limit == "start speed"


def test_a_joint_trajectory_is_retimed_along_its_own_path() -> None:
    slow = joint_trajectory([0.0, 0.0, 0.0], [1.0, -0.5, 0.2], 5.0, "quintic", 0.01)
    res = time_optimal(slow, 1.0, 2.0, dt=DENSE_DT)
    assert res.ok and res.duration < 5.0
    ev, ea = held(res)
    assert ev <= HOLD_RTOL and ea <= HOLD_RTOL
    # the same straight joint-space path: every sample on the line q0 + s·Δ
    q = res.trajectory.q
    lam = q[:, 0] / 1.0
    assert np.allclose(q, lam[:, None] * np.array([1.0, -0.5, 0.2]), atol=1e-9)


# ------------------------------------------------------------------ toppra
def toppra_time(W: np.ndarray, vel: np.ndarray, acc: np.ndarray, grid: np.ndarray | None) -> tuple:
    toppra = pytest.importorskip("toppra")  # the test extra installs it
    import toppra.algorithm as algo
    import toppra.constraint as constraint

    chord = np.linalg.norm(np.diff(W, axis=0), axis=1)
    knots = np.concatenate([[0.0], np.cumsum(chord)]) / chord.sum()
    knots[-1] = 1.0
    path = toppra.SplineInterpolator(knots, W, bc_type="natural")
    cons = [constraint.JointVelocityConstraint(vel), constraint.JointAccelerationConstraint(acc)]
    inst = algo.TOPPRA(cons, path, gridpoints=grid, parametrizer="ParametrizeConstAccel")
    return inst.compute_trajectory(0.0, 0.0), path


@pytest.mark.parametrize("n", [6, 7])
def test_duration_within_half_a_percent_of_toppra_which_breaks_limits_between_points(
    n: int,
) -> None:
    rng = np.random.default_rng(10 + n)
    worst_theirs = 0.0
    for _ in range(3):
        W, vel, acc = random_case(rng, n)
        vel = np.stack([-vel[:, 1], vel[:, 1]], axis=1)  # toppra's velocity limits: symmetric here
        ours = time_optimal(W, vel, acc, dt=DENSE_DT, grid=1000)
        theirs, _ = toppra_time(W, vel, acc, np.linspace(0.0, 1.0, 1001))
        assert ours.ok and theirs is not None
        assert ours.duration <= theirs.duration * (1.0 + TOPPRA_RTOL), (
            ours.duration,
            theirs.duration,
        )
        t = np.arange(0.0, theirs.duration, DENSE_DT)
        worst_theirs = max(
            worst_theirs, *(excess(theirs(t, k), lim) for k, lim in ((1, vel), (2, acc)))
        )
    # theirs breaks a limit between grid points by far more than our tolerance (just outside)
    assert worst_theirs > 1e3 * HOLD_RTOL


#: A feasible path with limits spread over six decades (one of 200 random cases with
#: limits log-uniform over 0-8 decades and path lengths over 5; toppra 0.6.10 fails on it
#: with its default grid and with 1,001 and 5,001 points: "FailUncontrollable").
WIDE_W = np.array(
    [
        [9.063, -37.108, 11.377, -34.259, -50.598, 35.818],
        [50.807, 8.052, 16.831, -67.969, -8.337, 32.505],
        [77.016, 50.179, 54.414, -107.676, -36.584, 34.120],
        [76.910, 78.968, 60.194, -78.228, -26.801, 54.801],
        [28.251, 110.200, 88.178, -112.718, 22.140, 23.376],
        [39.505, 132.883, 113.871, -139.365, 39.593, 11.788],
        [29.596, 93.563, 75.816, -116.940, 44.730, -35.341],
        [-20.280, 137.710, 38.512, -146.754, 72.525, -26.194],
        [-10.127, 131.293, 83.087, -166.392, 46.782, -31.579],
        [-35.883, 137.920, 80.979, -185.708, 28.841, -1.021],
        [-76.897, 167.406, 30.488, -184.459, 58.828, -46.445],
        [-55.414, 160.847, 31.383, -137.545, 26.028, -0.184],
        [-81.361, 164.103, 75.700, -112.884, 6.540, 0.729],
        [-114.531, 150.050, 33.732, -90.702, 36.114, 22.717],
        [-101.096, 194.845, 49.825, -61.069, 31.284, 60.977],
        [-62.857, 242.780, 57.131, -95.378, 30.875, 19.779],
        [-97.518, 212.551, 22.499, -86.152, 78.973, 56.971],
    ]
)
WIDE_V = np.array([0.00676, 0.0397, 0.153, 17.5, 0.72, 2.65])
WIDE_A = np.array([0.0319, 3.29e-05, 3.47, 0.000465, 0.096, 1.76e-05])


def test_a_wide_spread_of_limits_where_toppra_fails_is_timed() -> None:
    vel, acc = np.stack([-WIDE_V, WIDE_V], axis=1), np.stack([-WIDE_A, WIDE_A], axis=1)
    theirs, _ = toppra_time(WIDE_W, vel, acc, None)
    assert theirs is None  # toppra: FailUncontrollable
    ours = time_optimal(WIDE_W, vel, acc, dt=1.0)
    assert ours.ok and 7.1e4 < ours.duration < 7.2e4
    ev, ea = held(ours)
    assert ev <= HOLD_RTOL and ea <= HOLD_RTOL
    assert max(ev, ea) > -1e-6  # and a limit is reached: not timed slowly to be safe


# ------------------------------------------------------------- honest failures
def two_moves() -> JointTrajectory:
    """Joint 1 moves in the first second, joint 2 in the next (each rest to rest)."""
    a = joint_trajectory([0.0, 0.0], [1.0, 0.0], 1.0, "quintic", 0.05)
    b = joint_trajectory([1.0, 0.0], [1.0, 1.0], 1.0, "quintic", 0.05)
    return JointTrajectory(
        np.concatenate([a.t, 1.0 + b.t[1:]]),
        np.concatenate([a.q, b.q[1:]]),
        np.concatenate([a.qd, b.qd[1:]]),
        np.concatenate([a.qdd, b.qdd[1:]]),
    )


def test_a_zero_velocity_limit_on_a_joint_that_moves_later_stops_the_path_there() -> None:
    res = time_optimal(two_moves(), [1.0, 0.0], 2.0, dt=DENSE_DT)
    assert res.status == "infeasible" and not res.ok
    assert res.limit == "velocity of joint 2"
    assert res.s_stop == pytest.approx(0.5, abs=1e-3)
    assert "s = 0.5" in res.message and "velocity of joint 2" in res.message
    tr = res.trajectory  # the fastest timing to there, at rest there, within every limit
    assert np.allclose(tr.q[-1], [1.0, 0.0], atol=1e-6) and np.allclose(tr.qd[-1], 0.0)
    ev, ea = held(res)
    assert ev <= HOLD_RTOL and ea <= HOLD_RTOL
    # a zero limit on a joint that does not move is no limit at all
    assert time_optimal([[0.0, 0.0], [1.0, 0.0]], [1.0, 0.0], 2.0).ok


def test_a_zero_acceleration_limit_stops_the_path_at_its_start() -> None:
    res = time_optimal([[0.0, 0.0], [1.0, 1.0]], 1.0, [1.0, 0.0])
    assert res.status == "infeasible" and res.s_stop == 0.0
    assert res.limit == "acceleration of joint 2" and res.duration == 0.0


def test_a_line_through_the_puma_wrist_singularity_stops_before_it() -> None:
    puma = km.load("puma560")
    q_sing = np.array([0.2, -0.5, 0.3, 0.4, 0.0, -0.1])
    Ts = puma.fk(q_sing)
    d = np.array([0.0, 0.1, 0.05])
    T0, T1 = Ts.copy(), Ts.copy()
    T0[:3, 3] -= 0.7 * d
    T1[:3, 3] += 1.3 * d
    path = km.cartesian_path(puma, T0, T1, 40, q0=q_sing, vmax=2.0, amax=5.0, tcp_speed=0.25)
    assert path.t is not None and path.qd is not None and path.qdd is not None
    stop = [e for e in path.events if e.kind == "stopped"]
    assert len(stop) == 1 and "wrist" in stop[0].names[0] and abs(stop[0].s - 0.35) < 1e-3
    assert not path.ok and path.s[-1] < 0.35
    assert np.allclose(path.qd[-1], 0.0)
    J = puma.jacobian(path.q)
    speed = np.linalg.norm(np.einsum("mij,mj->mi", J[:, :3], path.qd), axis=1)
    assert speed.max() <= 0.25 * (1 + HOLD_RTOL)
    assert np.abs(path.qd).max() <= 2.0 * (1 + HOLD_RTOL)


def test_a_cartesian_line_slows_near_the_wrist_singularity_and_says_so() -> None:
    puma = km.load("puma560")
    q_near = np.array([0.2, -0.5, 0.3, 0.4, 0.02, -0.1])  # q5 = 0.02 rad from the wrist singularity
    Ts = puma.fk(q_near)
    d = np.array([0.0, 0.1, 0.05])
    T0, T1 = Ts.copy(), Ts.copy()
    T0[:3, 3] -= 0.5 * d
    T1[:3, 3] += 0.5 * d
    free = km.cartesian_path(puma, T0, T1, 400, q0=q_near)
    timed = km.cartesian_path(
        puma, T0, T1, 400, q0=q_near, vmax=1.5, amax=20.0, tcp_speed=0.5, dt=DENSE_DT
    )
    assert timed.t is not None and timed.qd is not None
    slowed = [e for e in timed.events if e.kind == "slowed"]
    nearest = free.s[np.argmin(np.abs(np.sin(free.q[:, 4])))]  # closest to q5 = 0 on the line
    assert slowed and "joint" in slowed[0].names[0] and abs(slowed[0].s - nearest) < 0.02
    # the tool slows below half its top speed there; within every limit everywhere
    J = puma.jacobian(timed.q)
    speed = np.linalg.norm(np.einsum("mij,mj->mi", J[:, :3], timed.qd), axis=1)
    assert speed.max() <= 0.5 * (1 + HOLD_RTOL)
    assert np.abs(timed.qd).max() <= 1.5 * (1 + HOLD_RTOL)
    mid = np.argmin(np.abs(timed.s - nearest))
    assert speed[mid] < SLOW_FRACTION * speed.max()
    # the joint path is the one followed without timing (the spline through its samples)
    assert np.allclose(puma.fk(timed.q)[:, :3, 3], timed.poses[:, :3, 3], atol=1e-4)
    assert np.allclose(timed.q[0], free.q[0]) and np.allclose(timed.q[-1], free.q[-1], atol=1e-9)


def test_a_tool_speed_alone_bounds_a_cartesian_line_at_that_speed() -> None:
    puma = km.load("puma560")
    q = np.array([0.2, -0.5, 0.3, 0.4, 0.9, -0.1])
    T0 = puma.fk(q)
    T1 = T0.copy()
    T1[:3, 3] += [0.1, 0.05, 0.0]
    L = float(np.linalg.norm([0.1, 0.05]))
    res = time_optimal(
        km.cartesian_path(puma, T0, T1, 60, q0=q), robot=puma, tcp_speed=0.2, amax=50.0
    )
    J = puma.jacobian(res.trajectory.q)
    speed = np.linalg.norm(np.einsum("mij,mj->mi", J[:, :3], res.trajectory.qd), axis=1)
    assert speed.max() <= 0.2 * (1 + HOLD_RTOL) and speed.max() > 0.2 * 0.99
    assert res.duration > L / 0.2  # at most 0.2 m/s over L metres, accelerating first


@pytest.mark.parametrize(
    ("name", "q"),
    [("puma560", [0.2, -0.5, 0.3, 0.4, 0.9, -0.1]), ("ur5", [0.3, -1.2, 1.4, -1.0, -1.5, 0.2])],
)
def test_cartesian_lines_of_built_in_arms_hold_joint_and_tool_limits(
    name: str, q: list[float]
) -> None:
    robot = km.load(name)
    T0 = robot.fk(q)
    T1 = T0 @ km.make_transform(km.rotz(0.4), [0.05, -0.08, 0.06])
    path = km.cartesian_path(
        robot, T0, T1, 80, q0=q, vmax=1.0, amax=4.0, tcp_speed=0.3, tcp_angular_speed=1.0
    )
    assert path.t is not None and path.qd is not None and path.qdd is not None
    assert path.ok, path.events
    assert np.abs(path.qd).max() <= 1.0 * (1 + HOLD_RTOL)
    assert np.abs(path.qdd).max() <= 4.0 * (1 + HOLD_RTOL)
    J = robot.jacobian(path.q)
    tw = np.einsum("mij,mj->mi", J, path.qd)
    lin, ang = np.linalg.norm(tw[:, :3], axis=1), np.linalg.norm(tw[:, 3:], axis=1)
    assert lin.max() <= 0.3 * (1 + HOLD_RTOL) and ang.max() <= 1.0 * (1 + HOLD_RTOL)
    # some limit is reached
    top = max(lin.max() / 0.3, ang.max(), np.abs(path.qd).max(), np.abs(path.qdd).max() / 4.0)
    assert top > 0.99
    # the tool follows the line: FK of the timed joints against the poses asked for
    assert np.abs(robot.fk(path.q)[:, :3, 3] - path.poses[:, :3, 3]).max() < 1e-4


def test_a_via_path_is_timed_too() -> None:
    puma = km.load("puma560")
    q = np.array([0.2, -0.5, 0.3, 0.4, 0.9, -0.1])
    T0 = puma.fk(q)
    poses = np.stack([T0, T0.copy(), T0.copy()])
    poses[1, :3, 3] += [0.08, 0.0, 0.0]
    poses[2, :3, 3] += [0.08, 0.08, 0.0]
    path = km.cartesian_via_path(puma, poses, blend=0.02, steps=120, q0=q, tcp_speed=0.2)
    untimed = km.cartesian_via_path(puma, poses, blend=0.02, steps=120, q0=q)
    assert path.t is not None and untimed.t is None and path.ok
    assert np.allclose(path.q[[0, -1]], untimed.q[[0, -1]], atol=1e-9)
    speed = np.linalg.norm(np.einsum("mij,mj->mi", puma.jacobian(path.q)[:, :3], path.qd), axis=1)
    assert speed.max() <= 0.2 * (1 + HOLD_RTOL)


def test_the_largest_path_speed_is_a_bound_not_an_error() -> None:
    W = [[0.0, 0.0], [1.0, 1.0]]
    res = time_optimal(W, 1.0, 1.0, sd_start=MAX_PATH_SPEED)  # accepted: too fast to start
    assert res.status == "infeasible" and res.limit == "start speed"


# ------------------------------------------------------------------ bad input
def test_bad_input_is_named() -> None:
    W = [[0.0, 0.0], [1.0, 1.0]]
    with pytest.raises(ArgumentError, match="vmax"):
        time_optimal(W, -1.0, 1.0)
    with pytest.raises(DimensionError, match="vmax"):
        time_optimal(W, [1.0, 1.0, 1.0], 1.0)
    with pytest.raises(ArgumentError, match="lo <= 0 <= hi"):
        time_optimal(W, [[0.5, 1.0], [-1.0, 1.0]], 1.0)
    with pytest.raises(ArgumentError, match="at least one limit"):
        time_optimal(W)
    with pytest.raises(ArgumentError, match="robot"):
        time_optimal(W, 1.0, tcp_speed=0.1)
    with pytest.raises(KinematicaError, match="waypoints 1 and 2 are equal"):
        time_optimal([[0.0], [0.0], [1.0]], 1.0, 1.0)
    with pytest.raises(DimensionError, match="NaN"):
        time_optimal([[0.0], [np.nan]], 1.0, 1.0)
    with pytest.raises(ArgumentError, match="sd_start"):
        time_optimal(W, 1.0, 1.0, sd_start=2 * MAX_PATH_SPEED)
    with pytest.raises(ArgumentError, match="grid"):
        time_optimal(W, 1.0, 1.0, grid=0)
    with pytest.raises(ArgumentError, match="grid"):
        time_optimal(W, 1.0, 1.0, grid=MAX_INTERVALS + 1)
    assert time_optimal(W, 1.0, 1.0, grid=MAX_INTERVALS).ok  # the largest grid is taken
    with pytest.raises(DimensionError, match="robot 6"):
        time_optimal(W, 1.0, 1.0, km.load("puma560"), tcp_speed=0.1)


def test_the_figure_is_drawn(tmp_path) -> None:  # type: ignore[no-untyped-def]
    from kinematica.motion.plot import plot_time_optimal

    res = time_optimal(two_moves(), [1.0, 0.0], 2.0)
    out = plot_time_optimal(res, tmp_path / "topp.png", title="two moves")
    assert out.stat().st_size > 10_000
