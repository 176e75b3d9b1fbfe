"""Targets pasted from printed numbers: rotations copied with a few decimals.

Reference: the bound by hand. A rotation whose entries are each off by at most
5e-5 (4 decimals) has max |RᵀR − I| <= 2·√3·5e-5 + 3·(5e-5)² ≈ 1.73e-4.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import kinematica as km
from kinematica.ik import PROJECTION_TOL
from kinematica.spatial.checks import shown_above


def test_every_four_decimal_copy_is_within_the_projection_tolerance():
    assert 2 * math.sqrt(3) * 5e-5 + 3 * 5e-5**2 < PROJECTION_TOL < 2 * math.sqrt(3) * 5e-4


@pytest.mark.parametrize("name", ["ur5", "panda", "puma560"])
def test_a_rotation_copied_with_4_decimals_is_accepted_with_a_note(name):
    robot = km.load(name)
    rng = np.random.default_rng(5)
    worst = 0.0
    for q in robot.random_q(40, seed=rng):
        T = np.round(robot.fk(q), 4)
        R = T[:3, :3]
        worst = max(worst, float(np.abs(R.T @ R - np.eye(3)).max()))
        res = robot.ik(T, tol=1e-3)  # the copied position is off by up to 5e-5 m too
        assert any("projected onto SO(3)" in n for n in res.notes), res.message
    assert worst > 1e-4  # copies the old 1e-4 refused were among them


def test_a_refusal_never_reads_as_within_its_limit():
    T = km.load("ur5").fk(np.zeros(6))
    T[:3, :3] = T[:3, :3] @ np.diag([1.0 + 1.02 * PROJECTION_TOL / 2, 1.0, 1.0])
    with pytest.raises(km.DimensionError) as info:
        km.load("ur5").ik(T)
    message = str(info.value)
    shown = float(message.split("= ")[1].split(",")[0])
    assert shown > PROJECTION_TOL, message


@pytest.mark.parametrize(
    ("value", "limit", "text"),
    [(1.04e-4, 1e-4, "1.04e-04"), (2.5e-4, 2e-4, "2.5e-04"), (2.0000001e-4, 2e-4, "2.0000001e-04")],
)
def test_shown_above_uses_the_digits_that_show_the_excess(value, limit, text):
    assert shown_above(value, limit) == text


# ------------------------------------------------ item 2: over-determined targets
from kinematica.ik.printed import (  # noqa: E402
    PRINTED_DIGITS_MAX,
    PRINTED_DIGITS_MIN,
    printed_precision,
    rounding_miss,
    significant_digits,
)

ARMS = [("anthropomorphic-3r", [30.0, 40.0, -30.0]), ("planar-pr", [0.2, 30.0])]


def printed(T: np.ndarray, digits: int) -> np.ndarray:
    """T as ``kinematica fk --precision digits`` prints it (%g), read back."""
    return np.array([float(f"{v:.{digits}g}") for v in T.ravel()]).reshape(4, 4)


def config(robot: km.Robot, q: list[float]) -> np.ndarray:
    return np.where(robot.is_prismatic, q, np.radians(q))


@pytest.mark.parametrize(("name", "q"), ARMS)
def test_a_pose_printed_with_5_digits_is_answered_with_the_precision_said(name, q):
    robot = km.load(name)
    target = printed(robot.fk(config(robot, q)), 5)
    res = robot.ik(target)
    assert res.status == "ok", res.message
    assert any("5 significant digits" in n for n in res.notes), res.notes
    # independent check: the answer is at least as close as the configuration that made
    # the numbers (position error and rotation angle against the projected target)
    made = robot.fk(config(robot, q))
    R = target[:3, :3]
    U, _, Vt = np.linalg.svd(R)
    R = U @ Vt
    angle = np.arccos(np.clip((np.trace(made[:3, :3].T @ R) - 1) / 2, -1, 1))
    by_made = np.hypot(np.linalg.norm(made[:3, 3] - target[:3, 3]), angle)
    assert np.hypot(*res.residuals[0]) <= by_made * (1 + 1e-6)
    assert np.allclose(res.solutions[0], config(robot, q), atol=1e-3)


@pytest.mark.parametrize(("name", "q"), ARMS)
def test_the_closest_reported_is_the_answer_given(name, q):
    robot = km.load(name)
    target = printed(robot.fk(config(robot, q)), 5)
    given = robot.ik(target)
    loose = robot.ik(target, tol=1e-4)  # the issue's --tol 1e-4: the same, closest, answer
    np.testing.assert_allclose(loose.residuals, given.residuals, rtol=1e-12)
    exact = robot.ik(target, precision=(0.0, 0.0))  # the numbers taken as exact
    assert exact.status == "not_found"
    np.testing.assert_allclose(exact.nearest_error, given.residuals[0], rtol=1e-9)
    assert f"closest off by {given.residuals[0, 0]:.3g} m" in exact.message


def test_a_pose_off_the_arms_set_beyond_its_digits_is_not_answered():
    robot = km.load("anthropomorphic-3r")
    T = robot.fk(np.radians([30.0, 40.0, -30.0]))
    T[:3, :3] = T[:3, :3] @ km.rotx(2e-3)  # an orientation the arm cannot take
    res = robot.ik(printed(T, 5))
    assert res.status in ("not_found", "unreachable")
    assert not res.success


def test_six_joint_arms_are_not_over_determined():
    puma = km.load("puma560")
    target = printed(puma.fk(np.array([0.2, -0.5, 0.3, 0.4, 0.8, -0.1])), 5)
    res = puma.ik(target)
    assert res.status == "ok" and not any("significant digits" in n for n in res.notes)


@pytest.mark.parametrize(
    ("value", "digits"), [(0.85287, 5), (-0.086824, 5), (0.5, 1), (1e-05, 1), (0.0, 0), (1.0, 1)]
)
def test_significant_digits(value, digits):
    assert significant_digits(value) == digits


def test_rounding_miss_by_hand():
    # √3 ε for a position box of half-width ε; 3ε/√2 for rotation entries off by ε
    assert rounding_miss((1e-6, 0.0)) == pytest.approx(math.sqrt(3) * 1e-6, rel=1e-12)
    assert rounding_miss((0.0, 1e-6)) == pytest.approx(3 / math.sqrt(2) * 1e-6, rel=1e-12)


@pytest.mark.parametrize(("factor", "answered"), [(1.01, True), (0.99, False)])
def test_a_miss_is_answered_up_to_the_rounding_miss(factor, answered):
    # The closest configuration misses this 5-digit target by `miss`; a precision
    # whose rounding can move a pose by just more (less) than that accepts (refuses) it.
    robot = km.load("anthropomorphic-3r")
    target = printed(robot.fk(np.radians([30.0, 40.0, -30.0])), 5)
    miss = float(np.hypot(*robot.ik(target).residuals[0]))
    eps = factor * miss / math.sqrt(7.5)  # rounding_miss((eps, eps)) = √7.5 · eps
    res = robot.ik(target, precision=(eps, eps))
    assert res.success is answered


def test_a_rounding_past_the_reach_is_answered():
    # Folded to q3 = -0.038°: printed with 4 digits the target lies 4e-5 m past the
    # reach, less than rounding to 4 digits can move a pose.
    robot = km.load("anthropomorphic-3r")
    target = printed(robot.fk(np.radians([-21.464, 163.653, -0.038])), 4)
    strict = robot.ik(target, precision=(0.0, 0.0))
    assert strict.status == "unreachable" and strict.gap is not None
    res = robot.ik(target)
    assert res.status == "ok" and res.count == 1
    assert any("past the reach" in n for n in res.notes)


@pytest.mark.parametrize(("text", "assumed"), [("0.123", True), ("0.12", False)])
def test_printed_digits_min_is_3(text, assumed):
    # 0.5, 1e200: numbers typed, taken as exact; three digits or more: printed
    T = np.eye(4)
    T[0, 3] = float(text)
    assert PRINTED_DIGITS_MIN == 3
    assert (printed_precision(T) is not None) is assumed


def test_printed_digits_max_is_12():
    T = np.eye(4)
    T[0, 3] = 0.123456789012  # 12 digits: printed
    assert printed_precision(T) == pytest.approx((5e-13, 5e-12), rel=1e-12)
    T[0, 3] = 0.1234567890123  # 13 digits: computed
    assert PRINTED_DIGITS_MAX == 12 and printed_precision(T) is None


def test_a_batch_answers_printed_targets_as_one_target_each():
    robot = km.load("anthropomorphic-3r")
    q = robot.random_q(12, seed=np.random.default_rng(8))
    targets = np.stack([printed(T, 5) for T in robot.fk(q)])
    targets[3, 0, 3] += 1.0  # one far off the arm's poses
    many = robot.ik(targets)
    for i in range(len(targets)):
        one = robot.ik(targets[i])
        assert many.status[i] == one.status
        np.testing.assert_allclose(many[i].solutions, one.solutions, rtol=0, atol=0)
        np.testing.assert_allclose(many[i].residuals, one.residuals, rtol=0, atol=0)
        assert many[i].notes == one.notes
    assert (many.status == "ok").sum() == 11
