"""Cartesian paths: poses on the line/arc, one branch, and every event reported."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation, Slerp

import kinematica as km
from kinematica.motion import MAX_JOINT_STEP, cartesian_path

PUMA_Q = np.array([0.2, -0.5, 0.3, 0.4, 0.9, -0.1])


def shifted(T: np.ndarray, d: list[float] | np.ndarray) -> np.ndarray:
    out = T.copy()
    out[:3, 3] += d
    return out


def test_line_away_from_singularities_keeps_one_branch() -> None:
    puma = km.load("puma560")
    T0 = puma.fk(PUMA_Q)
    T1 = shifted(T0, [0.05, 0.1, -0.05])
    T1[:3, :3] = T0[:3, :3] @ km.rotx(0.3)
    path = cartesian_path(puma, T0, T1, steps=50, q0=PUMA_Q)
    assert path.ok and path.events == ()
    assert np.allclose(path.q[0], PUMA_Q)
    # every sample reaches its pose; the poses are equally spaced on the segment
    assert np.allclose(puma.fk(path.q), path.poses, atol=1e-9)
    p = path.poses[:, :3, 3]
    assert np.allclose(p, T0[:3, 3] + np.linspace(0, 1, 50)[:, None] * (T1[:3, 3] - T0[:3, 3]))
    # orientation by slerp (scipy as the reference)
    ref = Slerp([0, 1], Rotation.from_matrix([T0[:3, :3], T1[:3, :3]]))(np.linspace(0, 1, 50))
    assert np.allclose(path.poses[:, :3, :3], ref.as_matrix(), atol=1e-12)
    # the bound: each joint step equals the first-order step J⁻¹·Δx to 5 %, and
    # the largest is 0.0052 rad here (0.12 m and 0.3 rad in 49 steps)
    for k in range(49):
        twist = km.se3_error(path.poses[k], path.poses[k + 1])
        predicted = np.linalg.solve(puma.jacobian(path.q[k]), twist)
        step = path.q[k + 1] - path.q[k]
        assert np.abs(step - predicted).max() <= 0.05 * np.abs(predicted).max() + 1e-9
    assert path.max_step < 0.006


def test_line_through_the_puma_wrist_singularity_is_an_event() -> None:
    puma = km.load("puma560")
    q_sing = np.array([0.2, -0.5, 0.3, 0.4, 0.0, -0.1])
    Ts = puma.fk(q_sing)
    d = np.array([0.0, 0.1, 0.05])
    for steps in (40, 41):  # the singular pose between two samples, then on one
        path = cartesian_path(puma, shifted(Ts, -0.7 * d), shifted(Ts, 1.3 * d), steps, q0=q_sing)
        kinds = [(e.kind, e.names) for e in path.events]
        assert ("singularity", ("wrist",)) in kinds, kinds
        event = next(e for e in path.events if e.kind == "singularity")
        assert abs(event.s - 0.35) < 1e-4  # 0.7 of the way to the middle of 2.0
        assert "wrist" in event.message


def test_arc_through_via() -> None:
    puma = km.load("puma560")
    T0 = puma.fk(PUMA_Q)
    T1 = shifted(T0, [0.0, 0.1, 0.0])
    via = T0[:3, 3] + [0.03, 0.05, 0.02]
    path = cartesian_path(puma, T0, T1, steps=60, q0=PUMA_Q, via=via)
    assert path.ok
    # centre of the circle through the three points, by a linear solve (reference)
    a, b, c = T0[:3, 3], via, T1[:3, 3]
    n = np.cross(b - a, c - a)
    A = np.array([b - a, c - a, n])
    rhs = np.array([(b @ b - a @ a) / 2, (c @ c - a @ a) / 2, n @ a])
    centre = np.linalg.solve(A, rhs)
    p = path.poses[:, :3, 3]
    r = np.linalg.norm(p - centre, axis=1)
    assert np.allclose(r, np.linalg.norm(a - centre)) and np.allclose((p - a) @ n, 0.0, atol=1e-12)
    assert np.allclose(p[[0, -1]], [a, c])
    # the arc passes through via (between two samples: the nearest is within one step)
    step = np.linalg.norm(np.diff(p, axis=0), axis=1).max()
    assert np.linalg.norm(p - via, axis=1).min() <= 0.51 * step  # half an arc step
    assert np.allclose(puma.fk(path.q), path.poses, atol=1e-9)


def test_leaving_the_workspace() -> None:
    puma = km.load("puma560")
    T0 = puma.fk(PUMA_Q)
    path = cartesian_path(puma, T0, shifted(T0, [1.0, 0.0, 0.0]), steps=30, q0=PUMA_Q)
    events = [e for e in path.events if e.kind == "unreachable"]
    assert len(events) == 1 and events[0].stop == 29
    assert np.isnan(path.q[events[0].index :]).all()
    assert np.isfinite(path.q[: events[0].index]).all()


def test_joint_limit() -> None:
    puma = km.load("puma560")  # q1 within ±160°
    q = np.array([np.radians(150.0), -0.5, 0.3, 0.4, 0.9, -0.1])
    T0 = puma.fk(q)
    Tz = km.make_transform(km.rotz(np.radians(30.0)))  # turn the pose about the base z
    path = cartesian_path(puma, T0, Tz @ T0, steps=20, q0=q)
    limits = [e for e in path.events if e.kind == "joint_limit"]
    assert limits and limits[0].names == ("q1",) and "q1" in limits[0].message


def planar_2r() -> km.Robot:
    return km.Robot.from_dh(
        [km.Revolute(a=1.0), km.Revolute(a=1.0)], name="2R", convention="standard"
    )


def test_branch_change_between_far_samples_is_reported() -> None:
    arm = planar_2r()
    qa = np.array([0.0, 0.3])
    qb = np.array([-1.0, 0.3])  # same elbow branch, rotated by -1 rad
    Ta, Tb = arm.fk(qa), arm.fk(qb)
    # With two samples, the solution of Tb nearest qa is the other branch (0.92 < 1 rad away):
    path = cartesian_path(arm, Ta, Tb, steps=2, q0=qa)
    assert [e.kind for e in path.events] == ["branch_change"]
    assert np.sign(path.q[-1, 1]) != np.sign(qa[1])
    # sampled finely, the same line is followed on its branch
    fine = cartesian_path(arm, Ta, Tb, steps=60, q0=qa)
    assert fine.ok and np.allclose(fine.q[-1], qb) and fine.max_step < MAX_JOINT_STEP


def test_revolute_joints_are_unwrapped_not_jumped() -> None:
    ur5 = km.load("ur5")
    q = np.array([np.pi - 0.05, -1.0, 1.2, -0.5, 1.0, 0.3])
    T0 = ur5.fk(q)
    Tz = km.make_transform(km.rotz(0.1))
    path = cartesian_path(ur5, T0, Tz @ T0, steps=20, q0=q)
    assert path.ok
    assert path.q[-1, 0] > np.pi  # continued past π, within the ±360° limits
    assert np.abs(np.diff(path.q, axis=0)).max() < 0.05


def test_bad_input() -> None:
    puma = km.load("puma560")
    T0 = puma.fk(PUMA_Q)
    with pytest.raises(km.KinematicaError, match="steps"):
        cartesian_path(puma, T0, T0, steps=1)
    with pytest.raises(km.KinematicaError, match="via lies on the line"):
        cartesian_path(puma, T0, shifted(T0, [0.1, 0, 0]), via=T0[:3, 3] + [0.05, 0, 0])
    with pytest.raises(km.DimensionError, match="T1"):
        cartesian_path(puma, T0, np.eye(3))
    with pytest.raises(km.KinematicaError, match="non-decreasing"):
        cartesian_path(puma, T0, T0, s=[0.0, 0.5, 0.2])


COLLINEAR_TOL = 1e-9  # motion/cartesian.py


#: A case a factor 10 inside a tolerance, and one a factor 10 outside it.
FACTORS = [(0.1, True), (10.0, False)]


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_collinear_tol_rejects_a_via_on_the_line(factor: float, inside: bool) -> None:
    """COLLINEAR_TOL: three points closer than it (m) to one line define no circle.

    The ends are 0.1 m apart along x and via is halfway, lifted by ``h`` along
    y: |u × v| = 0.1 h (below 1 m², so the tolerance is not scaled). Lifted by
    less than COLLINEAR_TOL / 0.1 it is an error; by more, an arc through via.
    """
    puma = km.load("puma560")
    q = np.array([0.2, -0.5, 0.3, 0.4, 0.9, -0.1])
    T0 = puma.fk(q)
    T1 = T0.copy()
    T1[:3, 3] += [0.1, 0.0, 0.0]
    h = factor * COLLINEAR_TOL / 0.1
    via = T0[:3, 3] + [0.05, h, 0.0]
    if inside:
        with pytest.raises(km.KinematicaError, match="via lies on the line"):
            cartesian_path(puma, T0, T1, steps=4, q0=q, via=via)
    else:
        path = cartesian_path(puma, T0, T1, steps=4, q0=q, via=via)
        assert np.allclose(path.poses[-1], T1, atol=1e-9)
