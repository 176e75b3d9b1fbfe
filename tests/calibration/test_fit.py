"""calibrate (calibration/fit.py): recovery on synthetic data, robust loss, bad data."""

from __future__ import annotations

import math

import numpy as np
import pytest
from support.calibration import NOISE, perturbed
from support.helpers import assert_transform_close

import kinematica as km
from kinematica import calibration
from kinematica.errors import ArgumentError, DimensionError


def _case(name="puma560", m=60, seed=11, kind="pose"):
    robot = km.load(name)
    if kind == "position":  # a target off the last axis (on it, joint 6 cannot move it)
        robot = robot.with_tool(km.transl(0.05, 0.03, 0.1))
    true = perturbed(robot, seed)
    q = robot.random_q(m, seed=seed + 1)
    measured = calibration.simulate(true, q, NOISE, kind=kind, seed=seed + 2)
    return robot, true, q, measured


@pytest.fixture(scope="module")
def puma_fit():
    robot, true, q, measured = _case()
    res = calibration.calibrate(robot, q, measured, "pose", noise=NOISE)
    # the truth in the fitted parameters: the same fit on exact measurements of the arm
    exact = calibration.calibrate(robot, q, true.fk(q), "pose", noise=NOISE)
    return robot, true, q, res, exact


def test_exact_measurements_are_fitted_exactly(puma_fit):
    robot, true, _, _, exact = puma_fit
    # the identified parameters describe the arm as it is: nothing is left unexplained
    assert exact.rms()[0] < 1e-10 and exact.rms()[1] < 1e-10
    q2 = robot.random_q(20, seed=99)  # configurations the fit never saw
    assert_transform_close(exact.robot.fk(q2), true.fk(q2), atol=1e-10)


def test_every_identified_parameter_within_three_standard_errors(puma_fit):
    *_, res, exact = puma_fit
    assert res.fitted == exact.fitted
    for p in res.parameters:
        if p.fitted:
            truth = exact.value(p.name).calibrated
            assert abs(p.calibrated - truth) < 3 * p.std_error, p


def test_rms_after_is_the_noise_level(puma_fit):
    *_, res, _ = puma_fit
    # RMS of the distance |Δp| for noise σ per coordinate: σ√3; of the rotation angle: σ√3
    position, orientation = res.rms()
    assert position == pytest.approx(math.sqrt(3) * NOISE[0], rel=0.10)
    assert orientation == pytest.approx(math.sqrt(3) * NOISE[1], rel=0.10)
    assert res.rms(after=False)[0] > 50 * position
    assert res.sigma == pytest.approx(1.0, rel=0.15)  # the noise given was the noise


def test_robust_loss_with_gross_outliers():
    robot, _, q, measured = _case(m=80, seed=21)
    rng = np.random.default_rng(3)
    bad = rng.choice(len(q), size=4, replace=False)  # 5 %
    direction = rng.normal(size=(len(bad), 3))
    measured[bad, :3, 3] += 5e-3 * direction / np.linalg.norm(direction, axis=1)[:, None]
    res = calibration.calibrate(robot, q, measured, "pose", noise=NOISE, loss="soft_l1")
    good = np.setdiff1d(np.arange(len(q)), bad)
    rms = math.sqrt(np.mean(res.after[good, 0] ** 2))
    assert rms == pytest.approx(math.sqrt(3) * NOISE[0], rel=0.20)
    assert res.after[bad, 0].min() > 4e-3  # the outliers stay outside
    assert sorted(res.outliers) == sorted(bad)
    assert res.rms(inliers=True)[0] == pytest.approx(rms)
    plain = calibration.calibrate(robot, q, measured, "pose", noise=NOISE)
    assert math.sqrt(np.mean(plain.after[good, 0] ** 2)) > 5 * rms


@pytest.mark.parametrize("factor, outlier", [(0.6, False), (1.6, True)])
def test_outlier_limit_either_side(factor, outlier):
    robot, _, q, measured = _case(m=60, seed=71)
    measured = measured.copy()
    measured[7, 0, 3] += factor * calibration.OUTLIER_LIMIT * NOISE[0]
    res = calibration.calibrate(robot, q, measured, "pose", noise=NOISE, loss="huber")
    assert (7 in res.outliers) == outlier
    assert len(res.outliers) == int(outlier)


def test_position_measurements():
    robot, _, q, measured = _case(m=60, seed=31, kind="position")
    res = calibration.calibrate(robot, q, measured, "position", noise=NOISE)
    assert res.rank == 4 * 6 + 3
    assert res.rms()[0] == pytest.approx(math.sqrt(3) * NOISE[0], rel=0.15)
    assert all(np.isnan(res.after[:, 1]))
    rotations = {f.name for f in res.undetermined if not f.partners}
    assert {"tool_rx", "tool_ry", "tool_rz"} <= rotations


def test_params_subset_fits_only_those():
    robot, _, q, measured = _case(m=30, seed=41)
    res = calibration.calibrate(robot, q, measured, "pose", params=["a2", "d3", "a3", "d4"])
    assert set(res.fitted) == {"a2", "d3", "a3", "d4"}
    assert {p.name for p in res.parameters} == {"a2", "d3", "a3", "d4"}


# ------------------------------------------------------------------------ bad data
def test_wrong_shapes_are_named():
    robot, _, q, measured = _case(m=10, seed=51)
    with pytest.raises(DimensionError, match=r"q must have shape \(m, 6\)"):
        calibration.calibrate(robot, q[:, :5], measured)
    with pytest.raises(DimensionError, match=r"measured must have shape \(10, 4, 4\)"):
        calibration.calibrate(robot, q, measured[:, :3, 3])
    with pytest.raises(DimensionError, match=r"measured must have shape \(10, 3\)"):
        calibration.calibrate(robot, q, measured, "position")
    with pytest.raises(DimensionError, match="NaN"):
        calibration.calibrate(robot, np.where(np.eye(10, 6) > 0, np.nan, q), measured)


def test_readings_outside_the_limits():
    robot, _, q, measured = _case(m=10, seed=52)
    q = q.copy()
    q[4, 2] = robot.qlim[2, 1] + 0.1
    with pytest.raises(ArgumentError, match="row 4, joint 3"):
        calibration.calibrate(robot, q, measured)


def test_too_few_measurements_says_how_many():
    robot, _, q, measured = _case(m=5, seed=53)
    with pytest.raises(ArgumentError, match=r"30 parameters .* at least 6 poses; got 5"):
        calibration.calibrate(robot, q, measured)
    calibration.calibrate(robot, *_case(m=6, seed=53)[2:])  # six are enough
    robot, _, q, measured = _case(m=5, seed=53, kind="position")
    with pytest.raises(ArgumentError, match=r"27 parameters .* at least 10 positions; got 5"):
        calibration.calibrate(robot, q, measured, "position")


def test_rotation_tolerance_either_side():
    robot, _, q, measured = _case(m=10, seed=54)
    tol = calibration.ROTATION_TOL
    for scale, ok in ((0.5, True), (2.0, False)):
        m = measured.copy()
        m[3, :3, :3] *= 1.0 + scale * tol / 2  # RᵀR - I = (1 + e)² - 1 ≈ scale * tol
        if ok:
            calibration.calibrate(robot, q, m)
        else:
            with pytest.raises(DimensionError, match="measured pose 3 is not a rigid"):
                calibration.calibrate(robot, q, m)


def test_unknown_names():
    robot, _, q, measured = _case(m=10, seed=55)
    with pytest.raises(ArgumentError, match="did you mean 'theta2'"):
        calibration.calibrate(robot, q, measured, params=["theta_2"])
    with pytest.raises(ArgumentError, match="loss must be"):
        calibration.calibrate(robot, q, measured, loss="l1")
    with pytest.raises(ArgumentError, match="kind must be"):
        calibration.calibrate(robot, q, measured, "frame")
    with pytest.raises(ArgumentError, match="noise must be"):
        calibration.calibrate(robot, q, measured, noise=(0.0, 1e-5))


@pytest.mark.parametrize(
    "source, kind",
    [
        ("stanford", "pose"),  # a prismatic joint
        ("puma560-modified", "pose"),  # Craig's convention
        ("ur10_robot.urdf", "pose"),  # a URDF's own transforms
        ("kinova_j2s6s200.urdf", "position"),  # a URDF with 60-degree wrist links
    ],
)
def test_any_chain_kinematica_reads_is_calibrated(source, kind):
    from support.urdf import URDF_DIR

    if source.endswith(".urdf"):
        tip = "tool0" if "ur10" in source else "j2s6s200_end_effector"
        robot = km.load(URDF_DIR / source, tip=tip)
    elif source.endswith("-modified"):
        robot = km.load(source.removesuffix("-modified")).to_convention("modified")
    else:
        robot = km.load(source)
    if kind == "position":
        robot = robot.with_tool(robot.tool @ km.transl(0.05, 0.03, 0.1))
    true = perturbed(robot, 81) if robot.transforms is None else _moved(robot)
    q = robot.random_q(50, seed=82)
    T = true.fk(q)
    measured = T if kind == "pose" else T[:, :3, 3]
    res = calibration.calibrate(robot, q, measured, kind, noise=NOISE)
    r, p = robot.joint_types.count("R"), robot.joint_types.count("P")
    assert res.rank == 4 * r + 2 * p + (6 if kind == "pose" else 3)
    assert res.rms()[0] < 1e-9  # exact measurements: the calibrated arm is the arm
    q2 = robot.random_q(10, seed=83)
    gap = (
        res.robot.fk(q2)[:, :3, 3] - true.fk(q2)[:, :3, 3]
    )  # (the tool's rotation: unseen by points)
    assert np.abs(gap).max() < 1e-9
    if kind == "pose":
        assert_transform_close(res.robot.fk(q2), true.fk(q2), atol=1e-9)


def _moved(robot):
    """A robot read from a URDF, as it is: its chain moved by the error model itself."""
    from kinematica.calibration.export import calibrated_extraction
    from kinematica.calibration.model import ErrorModel

    model = ErrorModel.of(robot.chain)
    delta = np.random.default_rng(84).uniform(-1e-3, 1e-3, model.size)
    return calibrated_extraction(robot, model, delta).robot
