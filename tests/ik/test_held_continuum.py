"""A joint held where the arm left reaches every pose along a continuum.

Checked against what the geometry says by hand: with an SRS arm's q2 held at 0,
axes 1 and 3 are one line, so only q1 + q3 counts and every other joint is that of
the configuration that made the pose; with its elbow q4 held, the shoulder and
wrist centres keep their distance and the arm turns about the line through them
(every joint but q4 free). Every representative reaches the target by forward
kinematics, with the held joint exactly at its value.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import kinematica as km
from kinematica.ik.held_continuum import HELD_MATCH_TOL, holds_value

pytestmark = pytest.mark.filterwarnings("ignore::kinematica.KinematicaWarning")

#: Representatives reach their target to this (m, rad).
FK_TOL = 1e-10


def _wrapped(d: np.ndarray) -> np.ndarray:
    return np.abs(np.remainder(d + math.pi, 2 * math.pi) - math.pi)


def _reaches(robot: km.Robot, q: np.ndarray, T: np.ndarray) -> None:
    F = robot.fk(q)
    assert np.linalg.norm(F[..., :3, 3] - T[:3, 3], axis=-1).max() <= FK_TOL
    assert max(km.rotation_angle(f[:3, :3], T[:3, :3]) for f in F.reshape(-1, 4, 4)) <= FK_TOL


@pytest.mark.parametrize("name", ["iiwa14", "panda"])
def test_coaxial_joints_held_apart_give_a_continuum_of_their_sum(name: str) -> None:
    robot = km.load(name)
    rng = np.random.default_rng(5)
    for _ in range(5):
        q = rng.uniform(-1.2, 1.2, 7)
        q[1] = 0.0  # axes 1 and 3 one line
        T = robot.fk(q)
        res = robot.ik(T, fixed={1: 0.0}, respect_limits=False)
        assert res.status == "singular", res.message
        assert res.free_joints == (0, 2)
        assert res.method.startswith("analytic:")
        assert res.parameter == ("q2", 0.0)
        assert np.all(res.solutions[:, 1] == 0.0)
        _reaches(robot, res.solutions, T)
        # the configuration that made the pose, moved along the continuum, is among them
        same = (_wrapped(res.solutions[:, [3, 4, 5, 6]] - q[[3, 4, 5, 6]]).max(axis=1) <= 1e-8) & (
            _wrapped(res.solutions[:, 0] + res.solutions[:, 2] - q[0] - q[2]) <= 1e-8
        )
        assert same.any()


def test_an_srs_arm_s_elbow_held_leaves_the_arm_angle_circle() -> None:
    robot = km.load("iiwa14")
    rng = np.random.default_rng(6)
    for _ in range(5):
        q = rng.uniform(-1.2, 1.2, 7)
        T = robot.fk(q)
        res = robot.ik(T, fixed={3: float(q[3])}, respect_limits=False)
        assert res.status == "singular", res.message
        assert res.free_joints == (0, 1, 2, 4, 5, 6)
        assert len(res.solutions) >= 1 and np.all(res.solutions[:, 3] == q[3])
        _reaches(robot, res.solutions, T)
        assert "continuum" in res.message
        # the elbow held at a value the pose does not allow: no solution, never "ok"
        other = robot.ik(T, fixed={3: float(q[3]) + 0.3}, respect_limits=False)
        assert other.status != "ok" or len(other.solutions) == 0


def test_a_batch_answers_each_target_as_one_call_does() -> None:
    robot = km.load("iiwa14")
    rng = np.random.default_rng(7)
    q = rng.uniform(-1.2, 1.2, (3, 7))
    q[:, 1] = 0.0
    T = robot.fk(q)
    batch = robot.ik(T, fixed={1: 0.0}, respect_limits=False)
    for i in range(3):
        one = robot.ik(T[i], fixed={1: 0.0}, respect_limits=False)
        assert batch.status[i] == one.status == "singular"
        np.testing.assert_array_equal(batch[i].solutions, one.solutions)
        assert batch[i].free_joints == one.free_joints


def test_held_match_tol_at_its_boundary() -> None:
    v = 0.7
    assert holds_value(v + 0.5 * HELD_MATCH_TOL, v, False)
    assert not holds_value(v + 2.0 * HELD_MATCH_TOL, v, False)
    assert holds_value(v + 2 * math.pi - 0.5 * HELD_MATCH_TOL, v, False)  # modulo 2π
    assert not holds_value(v + 2 * math.pi, v, True)  # a slide: no wrap
    # the margins it sits between, measured on 60 poses of the iiwa and the Panda (q2 at 0,
    # q4 at its own value): the representatives' held joint before it is set exactly is
    # within 3.6e-14 of the value, the other branches' 0.025 rad and more away
    robot = km.load("iiwa14")
    q = np.random.default_rng(8).uniform(-1.2, 1.2, 7)
    res = robot.ik(robot.fk(q), fixed={3: float(q[3])}, respect_limits=False)
    assert res.status == "singular"
