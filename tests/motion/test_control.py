"""Resolved-rate control: reaching, damping near singularities, limits, the null space."""

from __future__ import annotations

import math

import numpy as np
import pytest

import kinematica as km
from kinematica.motion import read_csv, resolved_rate, write_csv
from kinematica.motion.control import MARGIN_RATE, damping_factor


def planar_2r() -> km.Robot:
    return km.Robot.from_dh([km.Revolute(a=0.5), km.Revolute(a=0.5)], convention="standard")


def test_reaches_a_reachable_pose_to_1e_9() -> None:
    puma = km.load("puma560")
    q0 = np.radians([10, -20, 30, 15, 40, 5])
    goal = q0 + np.radians([25, 15, -20, 30, -25, 40])
    target = puma.fk(goal)
    run = resolved_rate(puma, q0, target=target, dt=0.01, gain=20.0)
    assert run.reached is True
    T = puma.fk(run.q[-1])
    assert np.linalg.norm(T[:3, 3] - target[:3, 3]) <= 1e-9
    assert km.rotation_angle(T[:3, :3], target[:3, :3]) <= 1e-9
    assert run.error[-1, 0] <= 1e-10 and run.error[-1, 1] <= 1e-10
    # samples: q[k+1] = q[k] + qd[k]·dt, and the run stops with qd = 0
    assert np.allclose(np.diff(run.q, axis=0), run.qd[:-1] * 0.01, atol=1e-15)
    assert np.all(run.qd[-1] == 0.0)
    assert np.allclose(run.t, 0.01 * np.arange(run.t.size))


def test_position_only_control_of_a_3r_arm() -> None:
    arm = km.load("anthropomorphic-3r")
    target = km.transl(0.3, 0.2, 0.6)
    run = resolved_rate(arm, [0.1, 0.3, 0.5], target=target, axes="trans", gain=20.0)
    assert run.reached
    assert np.linalg.norm(arm.fk(run.q[-1])[:3, 3] - target[:3, 3]) <= 1e-9
    assert np.all(run.error[:, 1] == 0.0)  # no rotation rows controlled


def test_not_reached_within_the_steps() -> None:
    puma = km.load("puma560")
    q0 = np.radians([10, -20, 10, 15, 40, 5])
    run = resolved_rate(puma, q0, target=puma.fk(q0 + 0.3), steps=5)
    assert run.reached is False and run.t.size == 6
    assert run.error[-1, 0] > 1e-3


def test_twist_following_moves_the_tool_at_the_twist() -> None:
    arm = planar_2r()
    v = np.array([0.05, 0.1])
    run = resolved_rate(arm, [0.3, 1.2], twist=v, axes=[0, 1], dt=1e-3, steps=200, damping=None)
    assert run.reached is None
    p = arm.fk(run.q)[:, :2, 3]
    # Euler steps: J q̇ = v exactly at each sample, the chord differs by O(dt)
    assert np.allclose(np.diff(p, axis=0) / 1e-3, v, atol=2e-4)
    assert np.allclose(
        arm.jacobian(run.q[:-1])[:, :2] @ run.qd[:-1, :, None], v[:, None], atol=1e-12
    )


def test_moving_target_is_tracked_with_the_lag_of_a_p_controller() -> None:
    """A Cartesian PPP arm (J = I): the error of P control on a ramp settles at v/gain."""
    ppp = km.Robot.from_dh(
        [
            km.Prismatic(alpha=-math.pi / 2),
            km.Prismatic(theta=-math.pi / 2, alpha=-math.pi / 2),
            km.Prismatic(),
        ],
        convention="standard",
    )
    v, gain = np.array([0.02, -0.01, 0.03]), 4.0
    T0 = ppp.fk([0.1, 0.1, 0.1])

    def target(t: float) -> np.ndarray:
        T = T0.copy()
        T[:3, 3] += v * t
        return T

    run = resolved_rate(ppp, [0.1, 0.1, 0.1], target=target, axes="trans", gain=gain, steps=600)
    assert run.reached is False
    assert abs(run.error[-1, 0] - np.linalg.norm(v) / gain) < 1e-9


# ------------------------------------------------------------ damping
def test_damping_laws_by_hand() -> None:
    assert damping_factor(None, 0.0, 0.0, 0.1, 0.2) == 0.0
    assert damping_factor(0.03, 1.0, 1.0, 0.1, 0.2) == 0.03
    # λ² = λmax² (1 − (x/x0)²) below the threshold, 0 above
    assert math.isclose(
        damping_factor("manipulability", 0.05, 9.0, 0.1, 0.2), 0.2 * math.sqrt(0.75)
    )
    assert damping_factor("manipulability", 0.1, 0.0, 0.1, 0.2) == 0.0
    assert math.isclose(damping_factor("min_singular", 9.0, 0.0, 0.1, 0.2), 0.2)
    assert math.isclose(damping_factor("min_singular", 9.0, 0.08, 0.1, 0.2), 0.2 * 0.6)


def test_dls_bounds_the_rates_and_the_floor_keeps_manipulability() -> None:
    """Pull a planar 2R arm's tip outward past its reach (w = 0.25·|sin q2|, 0 stretched).

    The pseudo-inverse's rates blow up as q2 nears 0; damped least squares bounds
    them by |v|/(2λ) but still creeps toward the singular set; asked for a floor,
    w stays at or above it."""
    arm = planar_2r()
    v = np.array([0.2, 0.0])
    common = {"twist": v, "axes": [0, 1], "dt": 0.01, "steps": 150, "respect_limits": False}
    plain = resolved_rate(arm, [0.0, 0.6], damping=None, **common)
    dls = resolved_rate(arm, [0.0, 0.6], damping=0.05, **common)
    floor = resolved_rate(arm, [0.0, 0.6], damping=0.05, min_manipulability=0.05, **common)
    adaptive = resolved_rate(
        arm,
        [0.0, 0.6],
        damping="manipulability",
        threshold=0.08,
        lambda_max=0.05,
        min_manipulability=0.05,
        **common,
    )
    assert np.abs(plain.qd).max() > 50.0 and plain.manipulability.min() < 2e-3
    assert np.linalg.norm(dls.qd, axis=1).max() <= np.linalg.norm(v) / (2 * 0.05) + 1e-12
    assert dls.manipulability.min() < 1e-4  # damping alone creeps on
    for run in (floor, adaptive):
        assert run.manipulability.min() >= 0.05 * (1 - 1e-9)
        assert run.manipulability.min() < 0.0501  # it did get there
    # the adaptive law is exact (no damping) far from the singularity
    assert adaptive.damping[0] == 0.0 and adaptive.damping.max() > 0.0


def test_floor_margin_rate_boundary() -> None:
    """One step from w = 2·w_min toward the singular set: it may use MARGIN_RATE of the
    margin (to first order), so w stays above w_min + (1 − MARGIN_RATE)·margin − O(dt²)."""
    arm = planar_2r()
    q2 = math.asin(0.1 / 0.25)  # w = 0.1
    run = resolved_rate(
        arm,
        [0.0, q2],
        twist=[5.0, 0.0],
        axes=[0, 1],
        dt=0.01,
        steps=1,
        damping=None,
        min_manipulability=0.05,
        respect_limits=False,
    )
    w1 = run.manipulability[1]
    assert 0.05 + (1 - MARGIN_RATE) * 0.05 - 1e-3 < w1 < 0.05 + (1 - MARGIN_RATE) * 0.05 + 1e-3


# ------------------------------------------------------------ limits
def test_speed_limits_scale_the_whole_rate() -> None:
    puma = km.load("puma560")
    q0 = np.radians([10, -20, 10, 15, 40, 5])
    target = puma.fk(q0 + 0.4)
    qd_max = np.full(6, 0.5)
    free = resolved_rate(puma, q0, target=target, steps=1)
    capped = resolved_rate(puma, q0, target=target, steps=1, qd_max=qd_max)
    assert np.abs(free.qd[0]).max() > 0.5
    assert np.abs(capped.qd[0]).max() == pytest.approx(0.5, rel=1e-12)
    # same direction
    assert np.allclose(
        capped.qd[0] / np.linalg.norm(capped.qd[0]),
        free.qd[0] / np.linalg.norm(free.qd[0]),
        atol=1e-12,
    )


# Found by a search over random moves (the plain pseudo-inverse takes joint 2 0.13 rad
# below its limit -1.7628 on the way); both configurations within the limits.
PANDA_Q0 = np.array([-1.871, -1.428, 0.498, -2.739, -2.204, 1.587, -0.255])
PANDA_GOAL = np.array([-1.476, -1.713, 0.94, -2.853, -1.781, 1.169, -0.797])


def test_null_space_keeps_the_panda_within_its_limits() -> None:
    panda = km.load("panda")
    lo, hi = panda.qlim[:, 0], panda.qlim[:, 1]
    assert np.all((lo < PANDA_GOAL) & (hi > PANDA_GOAL))
    target = panda.fk(PANDA_GOAL)
    common = {"target": target, "gain": 5.0, "steps": 1000, "damping": None}
    plain = resolved_rate(panda, PANDA_Q0, respect_limits=False, **common)
    avoided = resolved_rate(
        panda, PANDA_Q0, respect_limits=False, nullspace="limits", nullspace_gain=200.0, **common
    )
    beyond = np.maximum(plain.q - hi, lo - plain.q).max(axis=0)
    assert plain.reached and beyond[1] > 0.1  # the plain pseudo-inverse leaves the limits
    assert np.all((avoided.q >= lo + 0.05) & (avoided.q <= hi - 0.05))
    assert avoided.reached
    assert np.linalg.norm(panda.fk(avoided.q[-1])[:3, 3] - target[:3, 3]) <= 1e-9
    # clipping at the limits keeps the plain run inside, at the cost of the task
    clipped = resolved_rate(panda, PANDA_Q0, **common)
    assert np.all((clipped.q >= lo) & (clipped.q <= hi))
    assert np.isclose(clipped.q[:, 1].min(), lo[1], atol=1e-12)


def test_manipulability_objective_raises_the_panda_manipulability() -> None:
    panda = km.load("panda")
    q0 = np.array([0.3, -0.3, 0.5, -2.2, 0.2, 2.0, 0.8])
    hold = np.zeros(6)  # hold the pose: only the null space moves
    common = {"twist": hold, "steps": 200, "damping": None}
    run = resolved_rate(panda, q0, nullspace="manipulability", nullspace_gain=20.0, **common)
    assert run.manipulability[-1] > 1.08 * run.manipulability[0]
    assert np.all(np.diff(run.manipulability) > -1e-9)  # it climbs
    # the tool pose did not move (null-space motion only, to first order per step)
    assert np.linalg.norm(panda.fk(run.q[-1])[:3, 3] - panda.fk(q0)[:3, 3]) < 1e-3


# ------------------------------------------------------------ output and errors
def test_trajectory_exports_like_the_others(tmp_path) -> None:  # type: ignore[no-untyped-def]
    puma = km.load("puma560")
    q0 = np.radians([10, -20, 30, 15, 40, 5])
    run = resolved_rate(puma, q0, target=puma.fk(q0 + 0.1), steps=50)
    t, q, qd, qdd = run.trajectory
    assert qd.shape == q.shape == qdd.shape and t.shape == (q.shape[0],)
    path = write_csv(tmp_path / "run.csv", t, q)
    t2, q2 = read_csv(path)
    assert np.array_equal(t2, t) and np.array_equal(q2, q)


def test_bad_arguments() -> None:
    puma = km.load("puma560")
    q0, T = np.zeros(6), puma.fk(np.zeros(6))
    with pytest.raises(km.KinematicaError, match="exactly one of target and twist"):
        resolved_rate(puma, q0)
    with pytest.raises(km.KinematicaError, match="exactly one"):
        resolved_rate(puma, q0, target=T, twist=np.zeros(6))
    with pytest.raises(km.KinematicaError, match="dt must be a positive number"):
        resolved_rate(puma, q0, target=T, dt=0.0)
    with pytest.raises(km.KinematicaError, match="steps or duration"):
        resolved_rate(puma, q0, target=T, steps=3, duration=1.0)
    with pytest.raises(km.KinematicaError, match="damping must be"):
        resolved_rate(puma, q0, target=T, damping="heavy")  # type: ignore[arg-type]
    with pytest.raises(km.KinematicaError, match="nullspace must be"):
        resolved_rate(puma, q0, target=T, nullspace="comfort")  # type: ignore[arg-type]
    with pytest.raises(km.DimensionError, match="twist must be 3 finite"):
        resolved_rate(puma, q0, twist=np.zeros(6), axes="trans")
    with pytest.raises(km.KinematicaError, match="qd_max"):
        resolved_rate(puma, q0, target=T, qd_max=-1.0)
    with pytest.raises(km.DimensionError, match="6 joint values"):
        resolved_rate(puma, np.zeros(5), target=T)


def test_a_run_longer_than_max_steps_is_refused_before_it_starts() -> None:
    from kinematica.motion.control import MAX_STEPS

    puma = km.load("puma560")
    q0 = np.zeros(6)
    T = puma.fk(q0 + 0.1)
    with pytest.raises(km.ArgumentError, match="steps must be a whole number from 1"):
        km.resolved_rate(puma, q0, target=T, steps=MAX_STEPS + 1)
    with pytest.raises(km.ArgumentError, match="duration/dt"):
        km.resolved_rate(puma, q0, target=T, dt=0.01, duration=0.01 * (MAX_STEPS + 1.5))
    with pytest.raises(km.ArgumentError, match="duration/dt"):
        km.resolved_rate(puma, q0, target=T, dt=0.01, duration=1e308)
    run = km.resolved_rate(puma, q0, target=T, dt=0.01, duration=0.01 * (MAX_STEPS - 0.5))
    assert run.reached  # stops when reached: the bound is on what may be asked


def test_a_step_clipped_at_a_limit_lands_on_it_exactly() -> None:
    # Issue 35, item 6: q + ((hi - q) / dt) * dt rounded 1-2 ulp past the PUMA's joint 3
    # limit (45°) and warned that 0.785398 rad was outside [.., 0.785398].
    import warnings

    puma = km.load("puma560")
    with warnings.catch_warnings():
        warnings.simplefilter("error", km.KinematicaWarning)
        run = resolved_rate(puma, np.zeros(6), target=km.from_pose([5, 0, 0, 0, 0, 0]), steps=50)
    lo, hi = puma.qlim[:, 0], puma.qlim[:, 1]
    assert np.all(run.q >= lo) and np.all(run.q <= hi)
    assert np.any(run.q == hi) or np.any(run.q == lo)  # it did reach a limit, exactly
