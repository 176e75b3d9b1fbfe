"""Named singularities on puma560, ur5, arm6-dh and anthropomorphic-3r.

Configurations are built singular by independent means: hand formulas, or the
roots of det J(q) found by scipy's brentq along one joint; random samples are
regular. Each named tolerance is pinned on both sides of its boundary.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from scipy.optimize import brentq
from support.helpers import PROPERTY, RobotSpec, random_q, robot_specs, seeds

import kinematica as km
from kinematica.motion import ELBOW_TOL, RANK_TOL, SHOULDER_TOL, WRIST_TOL, jacobian_rank

L2, L3 = 0.4, 0.3  # anthropomorphic-3r (seed 002)
BASE = np.array([0.3, -0.7, 0.9, 0.5, 0.8, -0.4])


def det_roots(robot: km.Robot, joint: int, base: np.ndarray) -> list[np.ndarray]:
    """Configurations where det J = 0 along joint ``joint`` (0-based), from ``base``."""

    def det(x: float) -> float:
        q = base.copy()
        q[joint] = x
        return float(np.linalg.det(robot.jacobian(q)))

    grid = np.linspace(-3.3, 3.3, 661)
    vals = [det(x) for x in grid]
    roots = []
    for a, b, fa, fb in zip(grid[:-1], grid[1:], vals[:-1], vals[1:], strict=True):
        if fa * fb < 0:
            q = base.copy()
            q[joint] = brentq(det, a, b, xtol=1e-15, rtol=1e-15)
            roots.append(q)
    return roots


def lost_ok(robot: km.Robot, q: np.ndarray, position_rows: bool = False) -> None:
    J = robot.jacobian(q)
    for s in robot.singularities(q, detail=True):
        assert np.isclose(np.linalg.norm(s.direction), 1.0)
        if position_rows:
            assert np.allclose(s.direction[3:], 0.0)
            assert np.abs(s.direction[:3] @ J[:3]).max() < 1e-9
        else:
            assert np.abs(s.direction @ J).max() < 1e-9


@pytest.mark.parametrize("name", ["puma560", "ur5", "arm6-dh"])
def test_6r_wrist_shoulder_elbow_at_roots_of_det_j(name: str) -> None:
    robot = km.load(name)
    # q5 moves only the wrist; q2 moves the wrist centre off the shoulder plane only.
    wrist = det_roots(robot, 4, BASE)
    shoulder = det_roots(robot, 1, BASE)
    elbow_or_shoulder = det_roots(robot, 2, BASE)
    assert len(wrist) >= 2 and shoulder and len(elbow_or_shoulder) >= 2
    for q in wrist:
        assert robot.singularities(q) == ["wrist"], q
        lost_ok(robot, q)
    for q in shoulder:
        assert robot.singularities(q) == ["shoulder"], q
        lost_ok(robot, q)
    names = [robot.singularities(q) for q in elbow_or_shoulder]
    assert all(n in (["elbow"], ["shoulder"]) for n in names), names
    assert ["elbow"] in names


def test_puma_elbow_is_the_extreme_reach_of_the_wrist_centre() -> None:
    puma = km.load("puma560")

    def reach_rate(q3: float) -> float:  # d|c - o2|/dq3 by central differences
        def reach(x: float) -> float:
            q = BASE.copy()
            q[2] = x
            F = puma.fk(q, all_frames=True)
            return float(np.linalg.norm(F[4, :3, 3] - F[1, :3, 3]))  # wrist centre, axis 2

        return (reach(q3 + 1e-6) - reach(q3 - 1e-6)) / 2e-6

    for a, b in [(-2.0, -1.0), (1.0, 2.0)]:
        q = BASE.copy()
        q[2] = brentq(reach_rate, a, b, xtol=1e-14)
        assert "elbow" in puma.singularities(q)


def test_ur5_named_by_its_joint_values() -> None:
    ur5 = km.load("ur5")
    for q3 in (0.0, np.pi, -np.pi):
        q = BASE.copy()
        q[2] = q3
        assert ur5.singularities(q) == ["elbow"]
        lost_ok(ur5, q)
    for q5 in (0.0, np.pi):
        q = BASE.copy()
        q[4] = q5
        assert ur5.singularities(q) == ["wrist"]
        h, _ = ur5.joint_axes(q)
        assert np.linalg.norm(np.cross(h[5], h[1])) < 1e-12  # axis 6 parallel to axis 2


def test_puma_wrist_and_elbow_together() -> None:
    puma = km.load("puma560")
    q = BASE.copy()
    q[2] = np.arctan2(0.0203, 0.4318) - np.pi / 2  # a3 and d4 in line with a2: stretched
    q[4] = 0.0
    assert sorted(puma.singularities(q)) == ["elbow", "wrist"]
    lost_ok(puma, q)


def anthropomorphic_shoulder(q2: float, dist: float = 0.0) -> np.ndarray:
    """q with the tool at ``dist`` from axis 1: L2 cos q2 + L3 cos(q2 + q3) = dist."""
    return np.array([0.3, q2, np.arccos((dist - L2 * np.cos(q2)) / L3) - q2])


def test_anthropomorphic_by_hand() -> None:
    arm = km.load("anthropomorphic-3r")
    for q3 in (0.0, np.pi):
        q = np.array([0.3, 0.5, q3])
        assert arm.singularities(q) == ["elbow"]
        lost_ok(arm, q, position_rows=True)
        # lost direction: radial, along the arm from the shoulder (hand formula)
        s = arm.singularities(q, detail=True)[0]
        radial = np.array([np.cos(0.3) * np.cos(0.5), np.sin(0.3) * np.cos(0.5), np.sin(0.5)])
        assert np.isclose(abs(s.direction[:3] @ radial), 1.0)
    q = anthropomorphic_shoulder(1.2)
    assert np.allclose(arm.fk(q)[:2, 3], 0.0, atol=1e-12)  # on axis 1
    assert arm.singularities(q) == ["shoulder"]
    s = arm.singularities(q, detail=True)[0]
    assert np.isclose(abs(s.direction[:3] @ [np.sin(0.3), -np.cos(0.3), 0.0]), 1.0)  # along z2


@pytest.mark.parametrize("name", ["puma560", "ur5", "arm6-dh", "anthropomorphic-3r", "planar-3r"])
def test_random_samples_are_regular(name: str) -> None:
    robot = km.load(name)
    q = robot.random_q(300, seed=11)
    assert all(s == [] for s in robot.singularities(q))


def test_wrist_tolerance_boundary() -> None:
    puma = km.load("puma560")  # sine of the angle between axes 4 and 6 = |sin q5|
    q = BASE.copy()
    q[4] = 0.5 * WRIST_TOL
    assert puma.singularities(q) == ["wrist"]
    q[4] = 2.0 * WRIST_TOL
    assert puma.singularities(q) == []


def test_elbow_tolerance_boundary() -> None:
    arm = km.load("anthropomorphic-3r")

    def q_with_rate(rate: float) -> np.ndarray:
        # r(q3)² = L2² + L3² + 2 L2 L3 cos q3, |dr/dq3| = L2 L3 sin q3 / r (hand formula)
        q3 = rate * (L2 + L3) / (L2 * L3)  # first-order solution near q3 = 0
        for _ in range(5):
            r = np.sqrt(L2**2 + L3**2 + 2 * L2 * L3 * np.cos(q3))
            q3 = np.arcsin(rate * r / (L2 * L3))
        return np.array([0.3, 0.5, q3])

    assert arm.singularities(q_with_rate(0.5 * ELBOW_TOL)) == ["elbow"]
    assert arm.singularities(q_with_rate(2.0 * ELBOW_TOL)) == []


def test_shoulder_tolerance_boundary() -> None:
    arm = km.load("anthropomorphic-3r")
    assert arm.singularities(anthropomorphic_shoulder(1.2, 0.5 * SHOULDER_TOL)) == ["shoulder"]
    assert arm.singularities(anthropomorphic_shoulder(1.2, 2.0 * SHOULDER_TOL)) == []


def polar_arm() -> km.Robot:
    """R then P along the radius: the Jacobian's singular values are 1 and the extension."""
    return km.Robot.from_dh(
        [km.Revolute(alpha=-np.pi / 2), km.Prismatic(qlim=(0.0, 1.0))],
        name="polar",
        convention="standard",
    )


def test_rank_tolerance_boundary_on_an_unnamed_structure() -> None:
    arm = polar_arm()
    assert arm.singularities([0.2, 0.5 * RANK_TOL]) == ["rank"]
    assert arm.singularities([0.2, 2.0 * RANK_TOL]) == []
    s = arm.singularities([0.2, 0.0], detail=True)
    assert [x.name for x in s] == ["rank"]
    # lost: the tangential direction z0 x z1, with z1 = (-sin q1, cos q1, 0) the radial one
    assert np.isclose(abs(s[0].direction[:3] @ [-np.cos(0.2), -np.sin(0.2), 0.0]), 1.0)


@pytest.mark.parametrize("batch", [(), (1,), (3, 2)])
def test_batch_shapes(batch: tuple[int, ...]) -> None:
    puma = km.load("puma560")
    q = np.broadcast_to(BASE, (*batch, 6)).copy()
    if batch:
        q[(0,) * len(batch) + (4,)] = 0.0
    out = puma.singularities(q)
    if not batch:
        assert out == []
        return
    arr = np.array(out, dtype=object) if len(batch) == 1 else out
    assert len(arr) == batch[0]
    first = out[0] if len(batch) == 1 else out[0][0]
    assert first == ["wrist"]
    if len(batch) == 2:
        assert all(len(row) == batch[1] for row in out)
        assert out[2][1] == []


def test_bad_input() -> None:
    with pytest.raises(km.DimensionError, match="6 joint values"):
        km.load("puma560").singularities([0.0, 1.0])


@PROPERTY
@given(spec=robot_specs(max_dof=7), seed=seeds)
def test_random_robots_lost_directions_are_lost(spec: RobotSpec, seed: int) -> None:
    """On any robot, each reported direction u has uᵀ J ≈ 0 on the judged rows, and a
    configuration with no report has full generic rank."""
    robot = spec.build()
    q = random_q(spec, np.random.default_rng(seed))
    rank, generic = jacobian_rank(robot, q)
    found = robot.singularities(q, detail=True)
    J = robot.jacobian(q)
    smax = np.linalg.svd(J, compute_uv=False)[0]
    for s in found:
        assert s.name in ("wrist", "elbow", "shoulder", "rank")
        assert np.isclose(np.linalg.norm(s.direction), 1.0)
        assert np.abs(s.direction @ J).max() <= 1e-5 * max(1.0, smax)
    if not found:
        assert rank == generic
    if rank < generic:
        assert len(found) >= generic - rank
