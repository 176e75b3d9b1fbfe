"""Jerk-limited moves through waypoints: reached, limits held, shorter than stopping at each."""

from __future__ import annotations

import numpy as np
import pytest
from support.scurve_reference import random_limits, rest_to_rest_time

from kinematica.errors import DimensionError, KinematicaError
from kinematica.motion import JerkTrajectory, via_polynomials, via_trajectory
from kinematica.motion.scurve_via import POSITION_ATOL
from kinematica.motion.trajectory import LIMIT_RTOL

#: Waypoints hit at their times (rad, m).
WAYPOINT_ATOL = 1e-10


def _stop_at_each(W: np.ndarray, V: np.ndarray, A: np.ndarray, J: np.ndarray) -> float:
    """The move with a stop at every waypoint, from the hand-derived closed form."""
    return sum(
        max(rest_to_rest_time(d, *lim) for d, *lim in zip(seg, V, A, J, strict=True))
        for seg in np.diff(W, axis=0)
    )


def _check(traj: JerkTrajectory, W: np.ndarray) -> None:
    p = traj.pieces
    assert traj.waypoint_times is not None
    assert np.abs(p(traj.waypoint_times) - W).max() <= WAYPOINT_ATOL
    assert np.array_equal(p.knots, traj.waypoint_times)
    assert np.isin(traj.waypoint_times, traj.t).all()  # every waypoint is a sample
    t = np.union1d(np.arange(0.0, traj.duration, 1e-3), [traj.duration])
    for order, lim in ((1, traj.vmax), (2, traj.amax), (3, traj.jmax)):
        assert np.all(np.abs(p(t, order)) <= lim * (1.0 + LIMIT_RTOL))
    # continuity of position, velocity and acceleration at every break, waypoints included
    inner = p.breaks[1:-1]
    for order in range(3):
        assert np.allclose(p(inner, order, left=True), p(inner, order), atol=1e-9)


def test_random_moves_pass_every_waypoint_sooner_than_stopping() -> None:
    rng = np.random.default_rng(5)
    for _ in range(6):
        n, k = int(rng.choice([6, 7])), int(rng.integers(5, 11))
        V, A, J = random_limits(rng, n)
        W = np.cumsum(rng.uniform(-0.5, 1.0, (k, n)), axis=0)  # mostly onwards, some turns
        traj = via_trajectory(W, "scurve", vmax=V, amax=A, jmax=J, dt=0.02)
        assert isinstance(traj, JerkTrajectory)
        _check(traj, W)
        stop = _stop_at_each(W, V, A, J)
        assert traj.stop_duration is not None and traj.margin is not None
        assert abs(traj.stop_duration - stop) <= 1e-9 * k
        assert abs(traj.margin - (stop - traj.duration)) <= 1e-9 * k
        assert traj.margin > 0.02 * stop  # mostly onward waypoints: a real saving


def test_the_joint_that_sets_the_time_moves_through_its_waypoint() -> None:
    # joint 1 runs on and sets the time; joint 2 turns back over a short distance
    W = np.array([[0.0, 0.0], [1.0, 0.1], [2.0, 0.0]])
    traj = via_trajectory(W, "scurve", vmax=1.0, amax=2.0, jmax=10.0)
    assert traj.waypoint_qd is not None and traj.margin is not None
    assert traj.waypoint_qd[1, 0] > 0.5 and traj.margin > 0.2
    _check(traj, W)
    # where the joint that turns back sets the time of both segments, nothing is gained
    W = np.array([[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]])
    traj = via_trajectory(W, "scurve", vmax=1.0, amax=2.0, jmax=10.0)
    assert traj.margin is not None and abs(traj.margin) < 1e-12


def test_two_waypoints_are_the_state_to_state_move() -> None:
    W = np.array([[0.0, 1.0], [1.0, -1.0]])
    traj = via_trajectory(W, "scurve", vmax=1.0, amax=2.0, jmax=10.0)
    want = max(rest_to_rest_time(d, 1.0, 2.0, 10.0) for d in W[1] - W[0])
    assert abs(traj.duration - want) <= 1e-9 and traj.margin == 0.0


def test_position_limits_are_held_by_slower_waypoints() -> None:
    # joint 1 sets the time of segment 1 and arrives 1 mm below its limit; joint 2 sets
    # the time of segment 2, in which joint 1 has time to overshoot and come back: the
    # planner lets it, unless qlim is given, and then slows it at waypoint 2
    W = np.array([[0.0, 0.0], [0.999, 0.1], [1.0, 3.0]])
    lim = {"vmax": 1.0, "amax": 1.0, "jmax": 5.0}
    free = via_trajectory(W, "scurve", **lim)
    assert free.pieces.peak(0)[0] > 1.0 + 1e-3  # the unconstrained choice overshoots
    qlim = np.array([[-1.0, 1.0], [-5.0, 5.0]])
    held = via_trajectory(W, "scurve", **lim, qlim=qlim)
    _check(held, W)
    t = np.union1d(np.arange(0.0, held.duration, 1e-3), held.pieces.breaks)
    assert held.pieces(t)[:, 0].max() <= 1.0 + POSITION_ATOL
    assert held.pieces.peak(0)[0] <= 1.0 + POSITION_ATOL  # exact extremes, not samples
    assert held.waypoint_qd is not None and free.waypoint_qd is not None
    assert 0.0 < held.waypoint_qd[1, 0] < free.waypoint_qd[1, 0]
    assert free.duration < held.duration < held.stop_duration  # type: ignore[operator]


def test_position_atol_boundary() -> None:
    lim = [[-1.0, 1.0]]
    just_in = np.array([[0.0], [1.0 + 0.5 * POSITION_ATOL]])
    via_trajectory(just_in, "scurve", vmax=1, amax=1, jmax=1, qlim=lim)
    just_out = np.array([[0.0], [1.0 + 2.0 * POSITION_ATOL]])
    with pytest.raises(KinematicaError, match="waypoint 2: joint 1"):
        via_trajectory(just_out, "scurve", vmax=1, amax=1, jmax=1, qlim=lim)


def test_ends_that_must_leave_the_limits_are_refused() -> None:
    # starting 1 cm below the limit, moving up at 0.9: it cannot stop before the limit
    W = np.array([[0.99], [0.5], [0.0]])
    with pytest.raises(KinematicaError, match=r"segment 1 .* leaves qlim"):
        via_trajectory(W, "scurve", vmax=1, amax=1, jmax=1, qd0=[0.9], qlim=[[-1.0, 1.0]])


@pytest.mark.parametrize(
    ("kwargs", "error", "match"),
    [
        ({"jmax": -1.0}, KinematicaError, "jmax must be positive"),
        ({"jmax": None}, KinematicaError, "needs jmax"),
        ({"vmax": [np.nan, 1.0]}, DimensionError, "vmax holds NaN"),
        ({"amax": [1.0, 2.0, 3.0]}, DimensionError, "amax must be a number or 2 values"),
        ({"amax": "fast"}, DimensionError, "amax must be"),
        ({"qd1": [0.0, -1.5]}, KinematicaError, "qd1 of joint 2 is -1.5, beyond its vmax 1"),
        ({"times": [0, 1, 2]}, KinematicaError, "drop times"),
        ({"tacc": 0.1}, KinematicaError, "drop tacc"),
        ({"qlim": [[0.0, 1.0]]}, DimensionError, "qlim must be"),
        ({"qd0": [2.0, 0.0]}, KinematicaError, "joint 1"),
        ({"qdd0": [0.0, 0.1]}, KinematicaError, "qdd0 must be 0"),
        ({"qdd1": 0.1}, KinematicaError, "qdd1 must be 0"),
    ],
)
def test_bad_input_is_named(kwargs: dict, error: type, match: str) -> None:
    W = np.array([[0.0, 0.0], [1.0, 1.0], [2.0, 1.5]])
    args = {"vmax": 1.0, "amax": 1.0, "jmax": 1.0} | kwargs
    with pytest.raises(error, match=match):
        via_trajectory(W, "scurve", **args)


def test_equal_waypoints_and_other_methods() -> None:
    W = np.array([[0.0, 0.0], [1.0, 1.0], [1.0, 1.0]])
    with pytest.raises(KinematicaError, match="waypoints 2 and 3 are equal"):
        via_trajectory(W, "scurve", vmax=1, amax=1, jmax=1)
    with pytest.raises(KinematicaError, match="jmax apply to method='scurve'"):
        via_trajectory(W[:2], "cubic", vmax=1, jmax=1)
    with pytest.raises(KinematicaError, match=r"\.pieces"):
        via_polynomials(W[:2], "scurve")


def test_each_segment_lasts_what_ruckig_plans_for_its_states() -> None:
    """The core's segments at the chosen waypoint velocities against ruckig's planner."""
    ruckig = pytest.importorskip("ruckig")
    rng = np.random.default_rng(11)
    n, k = 6, 8
    V, A, J = random_limits(rng, n)
    W = np.cumsum(rng.uniform(-0.5, 1.0, (k, n)), axis=0)
    traj = via_trajectory(W, "scurve", vmax=V, amax=A, jmax=J, dt=0.05)
    assert traj.waypoint_qd is not None and traj.waypoint_times is not None
    otg, inp, out = ruckig.Ruckig(n), ruckig.InputParameter(n), ruckig.Trajectory(n)
    inp.max_velocity, inp.max_acceleration, inp.max_jerk = V.tolist(), A.tolist(), J.tolist()
    for i in range(k - 1):
        inp.current_position, inp.current_velocity = W[i].tolist(), traj.waypoint_qd[i].tolist()
        inp.target_position, inp.target_velocity = (
            W[i + 1].tolist(),
            traj.waypoint_qd[i + 1].tolist(),
        )
        otg.calculate(inp, out)
        assert abs(np.diff(traj.waypoint_times)[i] - out.duration) <= 1e-9
