"""robot.ik end to end: statuses, round trips on every built-in arm, batches.

Every solution is re-checked here with forward kinematics and the geodesic
rotation angle, independently of the solver's own bookkeeping.
"""

from __future__ import annotations

import numpy as np
import pytest

import kinematica as km
from kinematica.ik.result import IKBatchResult, IKResult

TOL = 1e-10
ANALYTIC = [
    "puma560",
    "ur5",
    "irb120",
    "kr6",
    "stanford",
    "arm6-dh",
    "scara",
    "planar-3r",
    "planar-prr",
]
POSITION_ANALYTIC = ["anthropomorphic-3r", "rrr-geometric", "planar-pr"]


def random_q(robot: km.Robot, rng: np.random.Generator, size: int) -> np.ndarray:
    lo, hi = robot.qlim.T
    lo = np.where(np.isfinite(lo), lo, -1.0)
    hi = np.where(np.isfinite(hi), hi, 1.0)
    margin = 1e-3 * (hi - lo)
    return rng.uniform(lo + margin, hi - margin, size=(size, robot.dof))


def assert_solutions_reach(robot: km.Robot, res: IKResult, target: np.ndarray) -> None:
    assert res.solutions.shape == (res.count, robot.dof)
    if target.shape == (3,):
        err = np.linalg.norm(robot.fk(res.solutions)[:, :3, 3] - target, axis=-1)
        assert np.all(err <= TOL), err
        return
    T = robot.fk(res.solutions)
    assert np.all(np.linalg.norm(T[:, :3, 3] - target[:3, 3], axis=-1) <= TOL)
    assert np.all(km.rotation_angle(T[:, :3, :3], target[:3, :3]) <= TOL)


def assert_distinct(robot: km.Robot, sols: np.ndarray) -> None:
    rev = ~robot.is_prismatic
    for i in range(len(sols)):
        for j in range(i):
            d = sols[i] - sols[j]
            d[rev] = km.wrap_angle(d[rev])
            assert np.max(np.abs(d)) > 1e-7, (sols[i], sols[j])


def contains(robot: km.Robot, sols: np.ndarray, q: np.ndarray, atol: float = 1e-7) -> bool:
    d = sols - q
    rev = ~robot.is_prismatic
    d[:, rev] = km.wrap_angle(d[:, rev])
    return bool(np.any(np.all(np.abs(d) < atol, axis=-1)))


@pytest.mark.parametrize("name", ANALYTIC)
def test_round_trip_closed_form(name: str) -> None:
    robot = km.load(name)
    rng = np.random.default_rng(7)
    for q in random_q(robot, rng, 15):
        T = robot.fk(q)
        res = robot.ik(T)
        assert isinstance(res, IKResult)
        assert res.method.startswith("analytic:"), res.method
        assert res.status in ("ok", "singular"), res.message
        assert_solutions_reach(robot, res, T)
        assert_distinct(robot, res.solutions)
        lo, hi = robot.qlim.T
        assert np.all((res.solutions >= lo - 1e-12) & (res.solutions <= hi + 1e-12))
        assert contains(robot, res.solutions, q), (name, q, res.solutions)


@pytest.mark.parametrize("name", POSITION_ANALYTIC)
def test_round_trip_position(name: str) -> None:
    robot = km.load(name)
    rng = np.random.default_rng(3)
    for q in random_q(robot, rng, 15):
        p = robot.fk(q)[:3, 3]
        res = robot.ik(p)
        assert res.method.startswith("analytic:"), res.method
        assert res.status in ("ok", "singular")
        assert_solutions_reach(robot, res, p)
        assert contains(robot, res.solutions, q)


@pytest.mark.parametrize("name", ["panda", "iiwa14", "cylindrical-4dof"])
def test_round_trip_numeric(name: str) -> None:
    robot = km.load(name)
    rng = np.random.default_rng(11)
    for q in random_q(robot, rng, 8):
        T = robot.fk(q)
        res = robot.ik(T, method="numeric", seed=1)  # auto holds a 7R's joint: test_redundancy
        assert res.method == "numeric:lm"
        assert res.status == "ok", res.message
        assert_solutions_reach(robot, res, T)


def test_puma_has_eight_solutions_and_named_branches() -> None:
    puma = km.load("puma560")
    T = puma.fk([0.3, -0.6, 0.2, 0.5, 0.9, -0.4])
    res = puma.ik(T, respect_limits=False)
    assert res.count == 8
    assert len(set(res.branches)) == 8
    assert all(b for b in res.branches)


def test_seed_counts() -> None:
    # Seed 002: two q1 times two q3 for the anthropomorphic arm.
    arm = km.load("anthropomorphic-3r")
    p = arm.fk([0.4, 0.3, 0.7])[:3, 3]
    assert arm.ik(p, respect_limits=False).count == 4
    # Seed 000: q2A = asin(y / l2), q2B = pi - asin(y / l2).
    pr = km.load("planar-pr")
    p = pr.fk([0.2, 0.6])[:3, 3]
    res = pr.ik(p, respect_limits=False)
    assert res.count == 2
    l2 = np.hypot(*(pr.fk([0.0, 0.0])[:2, 3] - pr.fk([0.0, np.pi])[:2, 3])) / 2
    q2 = sorted(km.wrap_angle(res.solutions[:, 1]))
    expected = sorted(km.wrap_angle([np.arcsin(p[1] / l2), np.pi - np.arcsin(p[1] / l2)]))
    np.testing.assert_allclose(q2, expected, atol=1e-10)


def test_unreachable_is_reported_with_distance() -> None:
    puma = km.load("puma560")
    T = puma.fk(np.zeros(6))
    T[:3, 3] = [3.0, 0.0, 0.0]
    res = puma.ik(T)
    assert res.status == "unreachable"
    assert res.count == 0 and not res.success
    assert res.gap is None or res.gap > 1.0
    with pytest.raises(km.UnreachableError):
        _ = res.q


def test_out_of_limits_is_kept_apart() -> None:
    puma = km.load("puma560")
    q = np.array([0.3, -0.6, 0.2, 0.5, 0.9, -0.4])
    T = puma.fk(q)
    tight = puma.with_limits([(v - 0.01, v + 0.01) for v in q + 0.5])
    res = tight.ik(T)
    assert res.status == "out_of_limits"
    assert res.count == 0 and res.out_of_limits.shape[0] >= 1
    assert contains(puma, res.out_of_limits, q)


def test_singular_wrist_names_free_joints() -> None:
    puma = km.load("puma560")
    T = puma.fk([0.3, -0.6, 0.2, 0.5, 0.0, -0.4])
    res = puma.ik(T, respect_limits=False)
    assert res.status == "singular", res.message
    assert {3, 5} <= set(res.free_joints)
    assert_solutions_reach(puma, res, T)


def test_batch_matches_single() -> None:
    ur5 = km.load("ur5")
    rng = np.random.default_rng(5)
    qs = random_q(ur5, rng, 6)
    Ts = ur5.fk(qs)
    many = ur5.ik(Ts)
    assert isinstance(many, IKBatchResult)
    assert many.solutions.shape[0] == 6 and many.count.shape == (6,)
    for i in range(6):
        one = ur5.ik(Ts[i])
        assert one.count == many.count[i] == many[i].count
        np.testing.assert_allclose(many.solutions[i, : one.count], one.solutions, atol=1e-12)
        assert np.all(np.isnan(many.solutions[i, one.count :]))


def test_q0_sorts_solutions() -> None:
    puma = km.load("puma560")
    q = np.array([0.3, -0.6, 0.2, 0.5, 0.9, -0.4])
    res = puma.ik(puma.fk(q), q0=q, respect_limits=False)
    np.testing.assert_allclose(res.solutions[0], q, atol=1e-9)


def test_numeric_method_and_masks() -> None:
    puma = km.load("puma560")
    T = puma.fk([0.3, -0.6, 0.2, 0.5, 0.9, -0.4])
    res = puma.ik(T, method="numeric", seed=0)
    assert res.status == "ok" and res.method == "numeric:lm"
    assert_solutions_reach(puma, res, T)
    res = puma.ik(T[:3, 3], seed=0)  # position only: the arm solutions, wrist free
    assert res.status == "singular" and res.method == "analytic:arm-position"
    assert res.free_joints == (3, 4, 5)
    assert_solutions_reach(puma, res, T[:3, 3])
    res = puma.ik(T[:3, 3], method="numeric", seed=0)  # one solution, numerically
    assert res.status == "ok" and res.method == "numeric:lm"
    assert_solutions_reach(puma, res, T[:3, 3])


def test_analytic_on_unsupported_structure_is_an_error() -> None:
    with pytest.raises(km.KinematicaError, match="numeric"):
        km.load("panda").ik(np.eye(4), method="analytic")


@pytest.mark.parametrize(
    "target",
    [np.zeros((2, 3, 5)), np.zeros(5), np.full((4, 4), np.nan), "pose", np.eye(3), np.eye(4) * 1j],
)
def test_bad_targets(target: object) -> None:
    with pytest.raises(km.KinematicaError):
        km.load("puma560").ik(target)  # type: ignore[arg-type]


def test_batch_with_bad_rows_reports_them_and_solves_the_rest() -> None:
    puma = km.load("puma560")
    rng = np.random.default_rng(2)
    Ts = puma.fk(random_q(puma, rng, 5))
    Ts[1, 0, 3] = np.nan
    Ts[3, :3, :3] *= 2.0  # scaled: not a rotation
    many = puma.ik(Ts)
    assert list(many.status[[1, 3]]) == ["invalid", "invalid"]
    assert many.count[1] == many.count[3] == 0
    assert "row 1" in many[1].message and "NaN" in many[1].message
    assert "row 3" in many[3].message and "orthonormal" in many[3].message
    for i in (1, 3):  # a malformed row has no numbers, only its message
        assert np.isnan(many.gap[i]) and np.all(np.isnan(many.nearest_error[i]))
        assert many[i].gap is None and not many.near_singular[i]
    numeric = km.load("panda").ik(np.stack([np.eye(4), np.full((4, 4), np.nan)]), seed=0)
    assert numeric.status[1] == "invalid" and np.isnan(numeric.gap[1])
    assert np.all(np.isnan(numeric.nearest_error[1]))
    for i in (0, 2, 4):
        assert many.status[i] in ("ok", "singular")
        assert_solutions_reach(puma, many[i], Ts[i])
    positions = np.array([[0.3, 0.2, 0.5], [np.inf, 0.0, 0.0]])
    res = km.load("anthropomorphic-3r").ik(positions)
    assert list(res.status) == ["ok", "invalid"]
