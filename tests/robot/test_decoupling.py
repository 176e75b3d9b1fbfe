"""Seed 002's kinematic decoupling, step by step: robot.wrist_center and robot.decouple.

References, each independent of the solvers:

* Seed 002 ("Fundamentos de Robótica: Cinemática Inversa", J. C. Grieco and
  G. Fernández, Universidad Simón Bolívar; /work/shared/seeds/002_b8512dbb810468a2.txt):
  the wrist centre ``p_m = p - d6·R·z`` (its "p_muñeca = p_extremo - d6 r_i3" rows),
  ``R36 = (R03)ᵀ·R06``, and for the anthropomorphic arm of its table (θ1 = q1, d1 = L1,
  α1 = 90°; a2, a3 along x) ``q1 = atan2(py, px)`` (two), ``cos q3 = ((py/s1)² +
  (pz - d1)² - a2² - a3²) / (2 a2 a3)`` (two), ``sin q2 = ((pz - d1)(a2 + a3 c3) -
  (py/s1) a3 s3) / ((a2 + a3 c3)² + a3² s3²)`` (one each), written out below.
* Issue 35, item 4: on the seed arm (arm6-dh: l1 = 0.5, l2 = l3 = 0.4, d6 = l4 = 0.1),
  q1..q3 = (-150, -10, -30)° is the arm solution the decoupling must give, where
  ``robot.ik(p_m)`` (the tool origin at p_m) gives (-150, 9.88, -62.1)°.
* The DH product written from the slides (support.helpers), for R03 and frame origins.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import kinematica as km
from kinematica.errors import KinematicaError
from kinematica.robot.decoupling import ARM_MATCH_TOL, group_by_arm

#: The seed arm's lengths (arm6-dh, seed 000's table with DESIGN's lengths): d1, a2, a3, d6.
L1, L2, L3, D6 = 0.5, 0.4, 0.4, 0.1
#: Issue 35, item 4: the arm solution of the seed arm's example (degrees)...
SEED_ARM_Q123 = (-150.0, -10.0, -30.0)
#: ... and what robot.ik(p_m) answers instead (the tool origin, not the wrist centre, at p_m).
TOOL_AT_PM_Q123 = (-150.0, 9.88, -62.1)


def seed002_arm(p: np.ndarray, d1: float, a2: float, a3: float) -> list[tuple[float, float, float]]:
    """Seed 002's algebraic solution of the anthropomorphic arm, formula by formula (rad)."""
    px, py, pz = p
    out = []
    for q1 in (math.atan2(py, px), math.atan2(py, px) + math.pi):  # "dos soluciones para q1"
        s1, c1 = math.sin(q1), math.cos(q1)
        r = py / s1 if abs(s1) > abs(c1) else px / c1  # p_y/s_1 (p_x/c_1 where s_1 is ~0)
        c3 = (r**2 + (pz - d1) ** 2 - a2**2 - a3**2) / (2 * a2 * a3)
        for q3 in (math.acos(c3), -math.acos(c3)):  # "dos soluciones para q3"
            s3 = math.sin(q3)
            s2 = ((pz - d1) * (a2 + a3 * c3) - r * a3 * s3) / ((a2 + a3 * c3) ** 2 + a3**2 * s3**2)
            c2 = (r + a3 * s3 * s2) / (a2 + a3 * c3)  # the seed's c2 from its first equation
            out.append((q1, math.atan2(s2, c2), q3))
    return out


def _same(a: np.ndarray, b: np.ndarray, tol: float = 1e-9) -> bool:
    return bool(np.max(np.abs(km.wrap_angle(np.asarray(a) - np.asarray(b)))) <= tol)


@pytest.fixture(scope="module")
def seed_arm() -> km.Robot:
    return km.load("arm6-dh")


def test_wrist_center_is_the_seeds_p_minus_d6_R_z(seed_arm: km.Robot) -> None:
    q = np.radians([*SEED_ARM_Q123, 20.0, 40.0, 60.0])
    T = seed_arm.fk(q)
    expected = T[:3, 3] - D6 * T[:3, :3] @ np.array([0.0, 0.0, 1.0])
    assert np.allclose(seed_arm.wrist_center(T), expected, atol=1e-15)
    # the same point by FK: where axes 4-6 meet, the origin of DH frame 4 (and 5)
    frames = seed_arm.fk(q, all_frames=True)
    assert np.allclose(seed_arm.wrist_center(T), frames[4, :3, 3], atol=1e-14)
    batch = seed_arm.fk(np.stack([q, q + 0.1, q - 0.2]).reshape(3, 1, 6))
    assert seed_arm.wrist_center(batch).shape == (3, 1, 3)


def test_wrist_center_carries_the_tool(seed_arm: km.Robot) -> None:
    tool = km.from_pose([0.0, 0.02, 0.05, 0, 0, 0])
    arm = seed_arm.with_tool(tool)
    q = np.radians([10.0, 20.0, -30.0, 40.0, 50.0, 60.0])
    assert np.allclose(
        arm.wrist_center(arm.fk(q)), seed_arm.wrist_center(seed_arm.fk(q)), atol=1e-14
    )


def test_seed_arm_decoupling_gives_the_issue_arm_solution(seed_arm: km.Robot) -> None:
    q = np.radians([*SEED_ARM_Q123, 20.0, 40.0, 60.0])
    T = seed_arm.fk(q)
    steps = seed_arm.decouple(T)
    arms = np.array([a.q for a in steps.arms])
    assert any(_same(a, np.radians(SEED_ARM_Q123)) for a in arms)
    # the tool origin at p_m is another question, with another answer (the issue's numbers)
    tool_at = seed_arm.ik(steps.wrist_center, respect_limits=False).solutions[:, :3]
    assert not any(_same(a, np.radians(SEED_ARM_Q123), 1e-3) for a in tool_at)
    assert any(np.allclose(np.degrees(a), TOOL_AT_PM_Q123, atol=0.01) for a in tool_at)


def test_seed_arm_arm_solutions_are_seed_002_formulas(seed_arm: km.Robot) -> None:
    rng = np.random.default_rng(2)
    for _ in range(5):
        q = rng.uniform(-1.2, 1.2, 6)
        steps = seed_arm.decouple(seed_arm.fk(q))
        assert steps.arm_status == "ok" and len(steps.arms) == 4
        # seed 000's table writes θ2 = q2 + 90° and θ3 = q3 - 90° (its forearm along z3):
        # the seed 002 arm's angles are q2 + 90° and q3
        shift = np.array([0, math.pi / 2, 0])
        ours = sorted(tuple(np.round(km.wrap_angle(a.q + shift), 9)) for a in steps.arms)
        seed = sorted(
            tuple(np.round(km.wrap_angle(s), 9))
            for s in seed002_arm(steps.wrist_center, L1, L2, L3)
        )
        assert np.allclose(ours, seed, atol=1e-8)


@pytest.mark.parametrize("name", ["arm6-dh", "puma560", "stanford", "kr6"])
def test_every_step_checks_by_forward_kinematics(name: str) -> None:
    robot = km.load(name)
    free = robot.with_limits([None] * 6)
    for q in robot.random_q(4, seed=7):
        T = free.fk(q)
        steps = robot.decouple(T)
        R06 = T[:3, :3] @ robot.tool[:3, :3].T
        assert np.allclose(steps.R06, R06, atol=1e-15)
        total = 0
        for a in steps.arms:
            q_arm = np.concatenate([a.q, np.zeros(3)])
            frames = free.fk(q_arm, all_frames=True)
            assert np.allclose(frames[4, :3, 3], steps.wrist_center, atol=1e-10)  # p_m placed
            assert np.allclose(a.R03, frames[3, :3, :3], atol=1e-14)
            assert np.allclose(a.R36, a.R03.T @ R06, atol=1e-14)
            for w in a.wrist:
                full = free.fk(np.concatenate([a.q, w]), all_frames=True)
                # frame 6 without the tool (the last frame of fk carries it)
                wrist_rotation = full[3, :3, :3].T @ full[6, :3, :3] @ robot.tool[:3, :3].T
                assert np.allclose(wrist_rotation, a.R36, atol=1e-10)  # the wrist makes R36
                assert np.allclose(full[-1], T, atol=1e-10)
            total += len(a.wrist)
        # every solution of the whole arm, each under its own arm solution, once
        assert total == steps.solutions.shape[0] == robot.ik(T, respect_limits=False).count
        arms = np.array([a.q for a in steps.arms])
        assert len({tuple(np.round(a, 6)) for a in arms}) == len(arms)


def test_puma_recovers_the_readme_configuration() -> None:
    puma = km.load("puma560")
    q = np.radians([10, -30, 20, 40, 50, -10])  # the README's PUMA example
    steps = puma.decouple(puma.fk(q))
    assert np.allclose(steps.offset, 0.0, atol=1e-15)  # its tool origin is the wrist centre
    assert np.allclose(steps.wrist_center, puma.fk(q)[:3, 3], atol=1e-15)
    hits = [a for a in steps.arms if _same(a.q, q[:3])]
    assert len(hits) == 1 and any(_same(w, q[3:]) for w in hits[0].wrist)
    # within_limits says what robot.ik keeps among its solutions
    kept = sum(int(a.within_limits.sum()) for a in steps.arms)
    assert kept == puma.ik(puma.fk(q)).count == 2


def test_no_spherical_wrist_and_wrong_sizes_are_errors() -> None:
    with pytest.raises(KinematicaError, match="no spherical wrist"):
        km.load("ur5").wrist_center(np.eye(4))
    with pytest.raises(KinematicaError, match="6 joints"):
        km.load("anthropomorphic-3r").decouple(np.eye(4))


def test_arm_match_tolerance_boundary(seed_arm: km.Robot) -> None:
    arm = np.array([0.1, 0.2, 0.3])
    inside = np.array([[0.1 + 0.9 * ARM_MATCH_TOL, 0.2, 0.3, 0, 0, 0]])
    outside = np.array([[0.1 + 1.1 * ARM_MATCH_TOL, 0.2, 0.3, 0, 0, 0]])
    assert group_by_arm(seed_arm, [arm], inside) == ([[0]], [])
    assert group_by_arm(seed_arm, [arm], outside) == ([[]], [0])
