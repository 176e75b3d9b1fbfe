"""Jerk-limited state-to-state moves: optimal against a closed form, limits, first principles."""

from __future__ import annotations

import sys
from types import SimpleNamespace

import numpy as np
import pytest
import ruckig
from support.scurve_reference import (
    integrate_jerk,
    random_limits,
    random_state,
    rest_to_rest_time,
    retimed_durations,
)

from kinematica.core.jerk import STATE_ROW, jerk_state_move
from kinematica.errors import ArgumentError, DimensionError, KinematicaError
from kinematica.motion import JointTrajectory, joint_trajectory, time_scaling
from kinematica.motion.piecewise import PiecewisePolynomial
from kinematica.motion.plot import MissingDependencyError
from kinematica.motion.scurve import PIECE_RTOL, JerkTrajectory, Segment, scurve_move, scurve_pieces
from kinematica.motion.trajectory import LIMIT_RTOL

#: Durations against the hand-derived rest-to-rest minimum time (s).
DURATION_ATOL = 1e-9
#: End state against the target (the issue's bound).
END_ATOL = 1e-10
#: The resampling of the limit checks (s).
RESAMPLE = 1e-3
#: How much shorter a synchronised duration is shown infeasible (s; the issue's bound).
SHORTER = 1e-6
#: Durations of one joint re-timed on its own against the synchronised one (s).
SYNC_ATOL = 1e-9


def _resample(traj: JerkTrajectory) -> np.ndarray:
    T = traj.duration
    return np.union1d(np.arange(0.0, T, RESAMPLE), [T])


def _check_limits(traj: JerkTrajectory) -> None:
    """Every limit held on a 1 ms resampling (and at the samples), to LIMIT_RTOL."""
    t = _resample(traj)
    for order, lim in ((1, traj.vmax), (2, traj.amax), (3, traj.jmax)):
        assert np.all(np.abs(traj.pieces(t, order)) <= lim * (1.0 + LIMIT_RTOL))
    for got, lim in ((traj.qd, traj.vmax), (traj.qdd, traj.amax), (traj.qddd, traj.jmax)):
        assert np.all(np.abs(got) <= lim * (1.0 + LIMIT_RTOL))


def _check_first_principles(traj: JerkTrajectory, start: tuple[np.ndarray, ...]) -> None:
    """Integrating the jerk from the start state gives the samples' a, v, q."""
    t = np.union1d(np.linspace(0.0, traj.duration, 20001), traj.pieces.breaks)
    jerk = traj.pieces(t, 3)
    q, v, a = integrate_jerk(t, jerk, start)
    h = np.diff(t).max()
    switches = traj.pieces.breaks.size
    J = traj.jmax
    tol_a = 2.0 * J * h * switches
    assert np.all(np.abs(a - traj.pieces(t, 2)) <= tol_a + 1e-12)
    tol_v = tol_a * traj.duration + 1e-12
    assert np.all(np.abs(v - traj.pieces(t, 1)) <= tol_v)
    assert np.all(np.abs(q - traj.pieces(t, 0)) <= tol_v * traj.duration + 1e-12)


def _saturates(traj: JerkTrajectory, joint: int) -> bool:
    """Whether every phase of ``joint`` saturates a limit (time-optimal structure).

    Pontryagin's principle for the triple integrator under box limits: the jerk
    is ±jmax except on arcs where the acceleration is at ±amax or the speed at
    ±vmax (with zero acceleration).
    """
    p = traj.pieces
    tol = 1e-7
    J, A, V = traj.jmax[joint], traj.amax[joint], traj.vmax[joint]
    for i in range(p.coef.shape[0]):
        if p.breaks[i + 1] - p.breaks[i] <= 1e-9 * max(traj.duration, 1.0):
            continue
        j = 6.0 * p.coef[i, 3, joint]
        a = 2.0 * p.coef[i, 2, joint]
        v = p.coef[i, 1, joint]
        if abs(abs(j) - J) <= tol * J:
            continue
        if abs(j) <= tol * J and (
            abs(abs(a) - A) <= tol * A or (abs(a) <= tol * A and abs(abs(v) - V) <= tol * V)
        ):
            continue
        return False
    return True


def test_rest_to_rest_single_joint_equals_the_closed_form() -> None:
    rng = np.random.default_rng(1)
    for _ in range(150):
        V, A, J = random_limits(rng, 1)
        D = 10.0 ** rng.uniform(-3, 1.5) * rng.choice([-1.0, 1.0])
        traj = joint_trajectory([0.0], [D], profile="scurve", vmax=V, amax=A, jmax=J)
        expected = rest_to_rest_time(D, float(V[0]), float(A[0]), float(J[0]))
        assert abs(traj.duration - expected) <= DURATION_ATOL
        assert traj.q[-1, 0] == D
        _check_limits(traj)
        assert _saturates(traj, 0)


def test_each_regime_of_the_closed_form_is_met() -> None:
    # V=1, A=1, J=1: A²/J = 1. Cruise (D large), peak speed above and below A²/J.
    cases = {10.0: 12.0, 2.0 * 1.0: None, 0.1: None}
    for D in cases:
        traj = joint_trajectory([0.0], [D], profile="scurve", vmax=1.0, amax=1.0, jmax=1.0)
        assert abs(traj.duration - rest_to_rest_time(D, 1.0, 1.0, 1.0)) <= DURATION_ATOL
    # by hand: D = 10 cruises (s(V) = 1 each way, 8 m at 1 m/s): 2·2 + 8 = 12 s
    assert abs(rest_to_rest_time(10.0, 1.0, 1.0, 1.0) - 12.0) < 1e-15
    # D = 0.1: a triangle in a, u = (0.05)^(2/3), T = 4·sqrt(u)
    assert abs(rest_to_rest_time(0.1, 1.0, 1.0, 1.0) - 4.0 * 0.05 ** (1.0 / 3.0)) < 1e-12


def test_rest_to_rest_joints_synchronised_on_the_slowest() -> None:
    rng = np.random.default_rng(2)
    for _ in range(60):
        n = int(rng.integers(2, 8))
        V, A, J = random_limits(rng, n)
        q0, q1 = rng.uniform(-2, 2, n), rng.uniform(-2, 2, n)
        traj = joint_trajectory(q0, q1, profile="scurve", vmax=V, amax=A, jmax=J)
        own = [rest_to_rest_time(d, v, a, j) for d, v, a, j in zip(q1 - q0, V, A, J, strict=True)]
        assert abs(traj.duration - max(own)) <= DURATION_ATOL
        assert np.abs(traj.pieces(traj.duration)[0] - q1).max() <= END_ATOL
        assert _saturates(traj, int(np.argmax(own)))
        _check_limits(traj)


def test_any_state_to_any_state() -> None:
    rng = np.random.default_rng(3)
    for case in range(80):
        n = 1 if case % 3 == 0 else int(rng.integers(2, 8))
        V, A, J = random_limits(rng, n)
        q0, q1 = rng.uniform(-2, 2, n), rng.uniform(-2, 2, n)
        v0, a0 = random_state(rng, V, A, J)
        v1, a1 = random_state(rng, V, A, J, target=True)
        traj = joint_trajectory(
            q0, q1, profile="scurve", vmax=V, amax=A, jmax=J, qd0=v0, qdd0=a0, qd1=v1, qdd1=a1
        )
        p, T = traj.pieces, traj.duration
        for order, want in enumerate((q0, v0, a0)):
            assert np.abs(p(0.0, order)[0] - want).max() <= END_ATOL
        for order, want in enumerate((q1, v1, a1)):
            assert np.abs(p(T, order, left=True)[0] - want).max() <= END_ATOL
        _check_limits(traj)
        _check_first_principles(traj, (q0, v0, a0))
        # the duration is the slowest joint's own optimum, or later (a joint that
        # cannot take some durations): either way some joint's profile is extremal
        assert any(_saturates(traj, j) for j in range(n)), case
        # every joint can take T, and some joint cannot take T - 1e-6 (one at a time)
        lim = (V, A, J)
        at_T = retimed_durations(q0, v0, a0, q1, v1, a1, lim, T)
        assert np.abs(at_T - T).max() <= SYNC_ATOL
        shorter = retimed_durations(q0, v0, a0, q1, v1, a1, lim, T - SHORTER)
        assert np.any(shorter > T - SHORTER + SYNC_ATOL), case


def test_pieces_agree_with_ruckigs_own_evaluation() -> None:
    # the conversion of ruckig's phases into pieces, against ruckig's at_time
    rng = np.random.default_rng(4)
    n = 7
    V, A, J = random_limits(rng, n)
    q0, q1 = rng.uniform(-2, 2, n), rng.uniform(-2, 2, n)
    v0, a0 = random_state(rng, V, A, J)
    traj = joint_trajectory(q0, q1, profile="scurve", vmax=V, amax=A, jmax=J, qd0=v0, qdd0=a0)
    otg, inp, out = ruckig.Ruckig(n), ruckig.InputParameter(n), ruckig.Trajectory(n)
    inp.current_position, inp.current_velocity, inp.current_acceleration = q0, v0, a0
    inp.target_position = q1
    inp.max_velocity, inp.max_acceleration, inp.max_jerk = V, A, J
    otg.calculate(inp, out)
    for t in rng.uniform(0.0, traj.duration, 50):
        want = out.at_time(t)
        for order in range(3):
            assert np.allclose(traj.pieces(t, order)[0], want[order], rtol=0, atol=1e-11)


def test_the_end_is_settled_where_ruckig_stops_at_1e_9() -> None:
    # joint 2 is re-timed to a 17 s cruise at 1/5 of its vmax; ruckig's own profile ends
    # 8.7e-10 from its target position (its precision is 1e-8): ours within round-off
    V, A, J = (
        [0.21408505168916647, 0.14811895771890776],
        [0.8933303831395544, 3.8665166524679115],
        [1.1645216903630877, 5.357365487550325],
    )
    q0, q1 = [-1.8492218013449508, 1.523811133573088], [1.5936465609481227, 1.7119241986036142]
    v0, a0 = (
        [-0.10090283135460065, -0.09101208521469142],
        [-0.28728207575289233, -0.34532513792828323],
    )
    v1, a1 = (
        [0.09797185061656716, 0.015374228266414047],
        [-0.46351153817476387, 0.24054743291442995],
    )
    n = 2
    otg, inp, out = ruckig.Ruckig(n), ruckig.InputParameter(n), ruckig.Trajectory(n)
    inp.current_position, inp.current_velocity, inp.current_acceleration = q0, v0, a0
    inp.target_position, inp.target_velocity, inp.target_acceleration = q1, v1, a1
    inp.max_velocity, inp.max_acceleration, inp.max_jerk = V, A, J
    otg.calculate(inp, out)
    assert abs(out.at_time(out.duration)[0][1] - q1[1]) > 5 * END_ATOL
    traj = joint_trajectory(
        q0, q1, profile="scurve", vmax=V, amax=A, jmax=J, qd0=v0, qdd0=a0, qd1=v1, qdd1=a1
    )
    assert traj.pieces.coef.shape[1] == 6  # a quintic step in the cruise
    for order, want in enumerate((q1, v1, a1)):
        assert np.abs(traj.pieces(traj.duration, order, left=True)[0] - want).max() <= END_ATOL
    _check_limits(traj)
    _check_first_principles(traj, (np.array(q0), np.array(v0), np.array(a0)))


def test_samples_are_the_pieces_and_unpack_as_four() -> None:
    traj = joint_trajectory(
        [0.0, 1.0], [1.0, -1.0], profile="scurve", dt=0.05, vmax=1, amax=2, jmax=5
    )
    t, q, _, _ = traj
    assert isinstance(traj, JointTrajectory) and len(traj) == 4
    assert t[0] == 0.0 and np.all(np.diff(t) <= 0.05 + 1e-15)
    assert np.allclose(q, traj.pieces(t), atol=1e-12)
    assert np.allclose(traj.qddd[:-1], traj.pieces(t[:-1], 3), atol=1e-12)
    assert traj.qddd.shape == q.shape and traj.margin is None


def test_a_longer_duration_is_kept_and_a_shorter_one_refused() -> None:
    shortest = joint_trajectory([0.0], [1.0], profile="scurve", vmax=1, amax=1, jmax=1).duration
    slow = joint_trajectory([0.0], [1.0], 2.0 * shortest, "scurve", vmax=1, amax=1, jmax=1)
    assert abs(slow.duration - 2.0 * shortest) < 1e-12
    _check_limits(slow)
    with pytest.raises(KinematicaError, match="too short"):
        joint_trajectory([0.0], [1.0], 0.99 * shortest, "scurve", vmax=1, amax=1, jmax=1)


def test_no_move_is_one_sample() -> None:
    traj = joint_trajectory([0.5, 0.5], [0.5, 0.5], profile="scurve", vmax=1, amax=1, jmax=1)
    assert traj.duration == 0.0 and traj.q.shape == (1, 2)


def _cruise(T: float, switch: float, v: float, miss: float = 0.0) -> SimpleNamespace:
    """A fake ruckig profile: a cruise at ``v`` cut in two phases at ``switch``, its
    target ``miss`` beyond where the cruise ends."""
    t = [switch, T - switch, 0, 0, 0, 0, 0]
    p = [0.0, v * switch] + [v * T] * 6
    brake = SimpleNamespace(t=[0, 0], j=[0, 0], p=[0, 0], v=[0, 0], a=[0, 0])
    return SimpleNamespace(
        brake=brake, t=t, j=[0.0] * 7, p=p, v=[v] * 8, a=[0.0] * 8, pf=v * T + miss
    )


def _fake(T: float, *profiles: SimpleNamespace) -> SimpleNamespace:
    two = np.full(len(profiles), 2.0)
    out = SimpleNamespace(duration=T, profiles=[list(profiles)])
    return SimpleNamespace(out=out, n=len(profiles), limits=(two, two, two))


def test_settle_ulps_boundary() -> None:
    # an end 8 units in the last place off is round-off (kept, cubic pieces); 32 are
    # settled (a quintic step in the cruise), and the end lands on the target
    ulp = float(np.spacing(2.0))
    kept = scurve_pieces(_fake(2.0, _cruise(2.0, 1.0, 1.0, 8 * ulp)))  # type: ignore[arg-type]
    assert kept.coef.shape[1] == 4
    moved = scurve_pieces(_fake(2.0, _cruise(2.0, 1.0, 1.0, 32 * ulp)))  # type: ignore[arg-type]
    assert moved.coef.shape[1] == 6
    assert abs(moved(2.0, left=True)[0, 0] - (2.0 + 32 * ulp)) <= 2 * ulp
    assert abs(moved(2.0, 1, left=True)[0, 0] - 1.0) <= 1e-15
    # a cruise at vmax has no room for the step: ruckig's end is kept, no limit broken
    at_vmax = scurve_pieces(_fake(2.0, _cruise(2.0, 1.0, 2.0, 1e-9)))  # type: ignore[arg-type]
    assert at_vmax.coef.shape[1] == 4 and at_vmax.peak(1)[0] == 2.0


def test_piece_rtol_boundary() -> None:
    # two joints switching 0.5 and 2 PIECE_RTOL apart: merged into one cut, or kept apart
    T = 2.0
    for gap, pieces in ((0.5, 2), (2.0, 3)):
        seg = _fake(T, _cruise(T, 1.0, 1.0), _cruise(T, 1.0 + gap * PIECE_RTOL * T, 0.5))
        pp = scurve_pieces(seg)  # type: ignore[arg-type]
        assert pp.coef.shape[0] == pieces
        assert np.abs(pp(T, left=True)[0] - [2.0, 1.0]).max() <= END_ATOL


@pytest.mark.parametrize(
    ("kwargs", "error", "match"),
    [
        ({"jmax": 0.0}, KinematicaError, "jmax must be positive, got 0 for joint 1"),
        ({"jmax": [1.0, -1.0]}, KinematicaError, "joint 2"),
        ({"jmax": None}, KinematicaError, "needs jmax"),
        ({"jmax": [1.0, 2.0, 3.0]}, DimensionError, "jmax"),
        ({"qd0": [0.5, 1.5]}, KinematicaError, "joint 2"),
        ({"qdd0": [0.9, 0.0], "qd0": [0.9, 0.0]}, KinematicaError, "joint 1 will inevitably"),
        ({"qd1": [0.0, 1.2]}, KinematicaError, "joint 2"),
        ({"qdd0": [1.0, 2.0, 3.0]}, DimensionError, "qdd0"),
        ({"qd1": [np.nan, 0.0]}, DimensionError, "NaN"),
        ({"sync": "shared"}, KinematicaError, "drop sync"),
    ],
)
def test_bad_input_is_named(kwargs: dict, error: type, match: str) -> None:
    args = {"vmax": 1.0, "amax": 1.0, "jmax": 1.0} | kwargs
    with pytest.raises(error, match=match):
        joint_trajectory([0.0, 0.0], [1.0, 1.0], profile="scurve", **args)


def test_jmax_belongs_to_the_scurve() -> None:
    with pytest.raises(KinematicaError, match="jmax limits the 'scurve'"):
        joint_trajectory([0.0], [1.0], profile="trapezoid", vmax=1, amax=1, jmax=1)
    with pytest.raises(ArgumentError, match="profile"):
        time_scaling("scurve", [0.0], 1.0)  # type: ignore[arg-type]


def test_without_ruckig_the_error_names_the_extra(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "ruckig", None)  # import ruckig raises ImportError
    with pytest.raises(MissingDependencyError, match=r"kinematica\[trajectory\]"):
        joint_trajectory([0.0], [1.0], profile="scurve", vmax=1, amax=1, jmax=1)


def test_the_cores_peaks_bound_the_exact_ones_within_the_limits() -> None:
    # jerk_state_move's peaks: exact on cubic pieces, a bound where a step settled an end;
    # against the pieces' own exact peaks (roots of the next derivative, piecewise.py)
    rng = np.random.default_rng(5)
    settled = 0
    for _ in range(40):
        n = int(rng.integers(1, 8))
        V, A, J = random_limits(rng, n)
        q0, q1 = rng.uniform(-2, 2, n), rng.uniform(-2, 2, n)
        v0, a0 = random_state(rng, V, A, J)
        seg = Segment(V, A, J)
        T = seg.plan(q0, v0, a0, q1, np.zeros(n), np.zeros(n))
        seg.plan(q0, v0, a0, q1, np.zeros(n), np.zeros(n), minimum=1.5 * T, validate=False)
        move = scurve_move(seg, 0.01, (q1, np.zeros(n), np.zeros(n)))
        pp = PiecewisePolynomial(move.breaks, move.coef, move.knots)
        exact = np.stack([pp.peak(order) for order in (1, 2, 3)])
        settled += move.coef.shape[1] == 6
        assert np.all(move.peak >= exact * (1.0 - 1e-14))
        assert np.all(move.peak <= np.stack([V, A, J]) * (1.0 + LIMIT_RTOL))
        if move.coef.shape[1] == 4:
            assert np.allclose(move.peak, exact, rtol=1e-14, atol=0.0)
    assert settled > 0  # some ends were settled (re-timed joints end up to 1e-8 off)


def test_the_core_refuses_bad_phase_data() -> None:
    one, z = np.ones(1), np.zeros(1)
    rows = np.zeros((1, STATE_ROW))
    lim = (one, one, one)
    with pytest.raises(ValueError, match="rows"):
        jerk_state_move(0.0, np.zeros((1, STATE_ROW - 1)), lim, (z, z, z), 0.1, 10.0)
    bad = rows.copy()
    bad[0, 3] = -1.0  # a negative phase duration
    with pytest.raises(ValueError, match="rows"):
        jerk_state_move(0.0, bad, lim, (z, z, z), 0.1, 10.0)
    with pytest.raises(ValueError, match="dt"):
        jerk_state_move(0.0, rows, lim, (z, z, z), 0.0, 10.0)
    with pytest.raises(ValueError, match="max_samples"):
        jerk_state_move(100.0, rows, lim, (z, z, z), 0.1, 10.0)
    still = jerk_state_move(0.0, rows, lim, (z, z, z), 0.1, 10.0)
    assert still.samples[0].shape == (1,) and still.coef.shape == (1, 4, 1)
