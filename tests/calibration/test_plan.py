"""next_poses and simulate (calibration/plan.py)."""

from __future__ import annotations

import numpy as np
import pytest
from support.calibration import NOISE

import kinematica as km
from kinematica import calibration
from kinematica.calibration.model import ErrorModel
from kinematica.calibration.plan import RIDGE
from kinematica.calibration.residuals import Measurements, jacobian
from kinematica.errors import ArgumentError


def _logdet(robot, q):
    model = ErrorModel.of(robot.chain)
    cols = calibration.identifiable(robot).chosen
    T = robot.fk(q)
    _, J = jacobian(model, np.zeros(model.size), Measurements(q, T, "pose", (1.0, 1.0)), cols)
    return np.linalg.slogdet(J.T @ J)[1]


def test_next_poses_beat_random_ones():
    robot = km.load("puma560")
    done = robot.random_q(6, seed=1)
    planned = calibration.next_poses(robot, done, 6, candidates=300, seed=2)
    assert planned.shape == (6, 6)
    lo, hi = robot.qlim[:, 0], robot.qlim[:, 1]
    assert np.all((planned >= lo) & (planned <= hi))
    ours = _logdet(robot, np.vstack([done, planned]))
    rng = np.random.default_rng(3)
    for _ in range(5):  # any 6 random configurations do worse
        other = robot.random_q(6, seed=int(rng.integers(1 << 30)))
        assert ours > _logdet(robot, np.vstack([done, other]))


def test_next_poses_from_nothing_is_identifiable():
    # the ridge lets the first picks be scored; what they give determines every parameter
    robot = km.load("ur5")
    planned = calibration.next_poses(robot, None, 6, candidates=200, seed=4)
    assert len({tuple(q) for q in planned}) == 6
    assert np.isfinite(_logdet(robot, planned))
    assert RIDGE < 1e-6


def test_simulate_is_fk_plus_the_noise():
    robot = km.load("puma560")
    q = robot.random_q(2000, seed=5)
    T = calibration.simulate(robot, q, NOISE, seed=6)
    exact = robot.fk(q)
    dp = T[:, :3, 3] - exact[:, :3, 3]
    assert np.std(dp) == pytest.approx(NOISE[0], rel=0.05)
    turn = km.rotvec_from_matrix(T[:, :3, :3] @ np.swapaxes(exact[:, :3, :3], 1, 2))
    assert np.std(turn) == pytest.approx(NOISE[1], rel=0.05)
    points = calibration.simulate(robot, q[:3], NOISE, kind="position", seed=6)
    assert points.shape == (3, 3)
    with pytest.raises(ArgumentError, match="noise must be"):
        calibration.simulate(robot, q, (-1.0, 0.0))
