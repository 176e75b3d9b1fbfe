"""The calibrated arm (calibration/export.py): exact robot, URDF, DH table; IK on it."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from support.calibration import NOISE, perturbed
from support.helpers import assert_transform_close

import kinematica as km
from kinematica import calibration
from kinematica.calibration.export import calibrated_extraction
from kinematica.calibration.model import ErrorModel


def _tilted_ur5():
    """UR5 as it is: its parallel axes 2, 3, 4 tilted by 1e-3 rad, every link off."""
    robot = km.load("ur5")
    model = ErrorModel.of(robot.chain)
    rng = np.random.default_rng(7)
    delta = np.zeros(model.size)
    for k, name in enumerate(model.names):
        if name[:-1] in ("theta", "d", "a", "alpha") and name[-1] != "6":
            delta[k] = rng.uniform(-1, 1) * (1e-3 if name[0] in "da" else 1.7e-3)
    delta[model.names.index("beta2")] = 1e-3
    delta[model.names.index("beta3")] = -1e-3
    return robot, calibrated_extraction(robot, model, delta).robot


@pytest.fixture(scope="module")
def ur5_fit():
    robot, true = _tilted_ur5()
    q = robot.random_q(60, seed=8)
    measured = calibration.simulate(true, q, NOISE, seed=9)
    return robot, true, calibration.calibrate(robot, q, measured, noise=NOISE)


def test_calibrated_robot_is_the_fitted_model(ur5_fit):
    robot, true, res = ur5_fit
    q = robot.random_q(10, seed=10)
    # the calibrated arm is the arm as it is, to what 60 noisy poses can tell
    assert_transform_close(res.robot.fk(q), true.fk(q), atol=5e-5)


def test_urdf_reproduces_the_calibrated_robot_exactly(ur5_fit, tmp_path):
    robot, _, res = ur5_fit
    path = tmp_path / "calibrated.urdf"
    path.write_text(res.urdf)
    back = km.load(path)
    q = robot.random_q(20, seed=12)
    assert np.abs(back.fk(q) - res.robot.fk(q)).max() < 1e-12


@pytest.mark.parametrize("suffix", [".yaml", ".json", ".toml"])
def test_robot_file_reproduces_the_calibrated_robot_exactly(ur5_fit, tmp_path, suffix):
    robot, _, res = ur5_fit
    path = tmp_path / f"calibrated{suffix}"
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        res.robot.save(path)
        back = km.load(path)
    q = robot.random_q(20, seed=16)
    assert np.abs(back.fk(q) - res.robot.fk(q)).max() < 1e-12
    assert [link.d for link in back.links] == [link.d for link in res.robot.links]


def test_dh_table_and_its_error(ur5_fit, tmp_path):
    robot, _, res = ur5_fit
    path = tmp_path / "calibrated.yaml"
    with warnings.catch_warnings(record=True) as caught:  # the far common normals
        warnings.simplefilter("always")
        res.dh.robot.save(path)
        back = km.load(path)
    assert caught and all("longer than 20 m" in str(w.message) for w in caught)
    q = robot.random_q(20, seed=13)
    err = np.abs(back.fk(q) - res.robot.fk(q)).max()
    # the DH table describes the calibrated arm to its reported error: round-off here,
    # though the tilted parallel axes put its common normals hundreds of metres away
    assert res.dh.fk_error < 1e-12 and err < 1e-12
    assert max(abs(link.d) for link in back.links) > 10.0


def test_ik_on_the_calibrated_ur5_gives_every_solution(ur5_fit):
    *_, res = ur5_fit
    arm = res.robot
    for q in arm.random_q(4, seed=14):
        T = arm.fk(q)
        sol = arm.ik(T)
        assert sol.status == "ok", sol.method
        for s in sol.solutions:
            assert np.abs(arm.fk(s) - T).max() < 1e-10
        assert _gaps(sol.solutions, q).min() < 1e-8, (sol.method, len(sol.solutions))


def test_ik_on_a_calibrated_puma_gives_every_solution():
    robot = km.load("puma560")
    true = perturbed(robot, 61)
    q = robot.random_q(40, seed=62)
    res = calibration.calibrate(
        robot, q, calibration.simulate(true, q, NOISE, seed=63), noise=NOISE
    )
    arm = res.robot.with_limits([None] * 6)  # every branch, not only those within the limits
    rng = np.random.default_rng(65)
    for q0 in res.robot.random_q(2, seed=64):
        T = arm.fk(q0)
        sol = arm.ik(T)
        assert sol.status == "ok" and sol.method == "analytic:general-6R"
        assert len(sol.solutions) >= 8  # the PUMA's eight branches survive the calibration
        assert np.abs(arm.fk(sol.solutions) - T).max() < 1e-10
        assert _gaps(sol.solutions, q0).min() < 1e-8
        # an independent search (numeric IK from random starts) finds nothing else
        for start in rng.uniform(-np.pi, np.pi, (12, 6)):
            found = arm.ik(T, method="numeric", q0=start)
            for s in found.solutions if found.status == "ok" else ():
                assert _gaps(sol.solutions, s).min() < 1e-6


def _gaps(solutions, q):
    return np.abs(np.angle(np.exp(1j * (solutions - q)))).max(axis=1)


def test_calibrated_robot_reproduces_the_fitted_model_exactly(ur5_fit):
    robot, _, res = ur5_fit
    model = ErrorModel.of(robot.chain)
    delta = np.array([p.correction for p in res.parameters])  # every parameter, in order
    assert [p.name for p in res.parameters] == list(model.names)
    q = robot.random_q(20, seed=15)
    assert np.abs(res.robot.fk(q) - model.fk(delta, q)).max() < 1e-12
