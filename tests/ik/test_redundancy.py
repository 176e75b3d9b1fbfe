"""method="auto" on a 7-joint arm: every solution at a parameter, named, or the search.

Which joint is chosen depends on the closed forms the registry has (the Panda has
none for any lock until a spherical-shoulder family lands): the tests compute the
expected choice from the registry itself, then check what auto says and returns.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from support import DATA
from support.helpers import assert_same_result, assert_transform_close

import kinematica as km
from kinematica.ik import IKBatchResult, IKResult, closed_form, nearest_value
from kinematica.ik.arm_angle import ArmAngleParameter
from kinematica.ik.parameter import JointParameter, locked_chain
from kinematica.ik.redundancy import PARAMETER_SWEEP, REDUNDANT_DOF, choose, preference

TOL = 1e-10


def test_the_preference_is_last_first_then_base_to_tip() -> None:
    assert preference(7) == (6, 0, 1, 2, 3, 4, 5)
    assert preference(2) == (1, 0)


def test_an_srs_arm_holds_its_arm_angle_not_a_joint() -> None:
    # the iiwa's solutions at an arm angle keep every joint free (tests/ik/analytic/test_srs.py)
    assert isinstance(choose(km.load("iiwa14").chain), ArmAngleParameter)
    assert not isinstance(choose(km.load("panda").chain), ArmAngleParameter)


def test_auto_prefers_a_special_family_to_the_general_6r() -> None:
    # a joint before the PUMA 560: holding the last joint leaves a general 6R, holding the
    # first leaves the PUMA itself (a spherical wrist): the first is held
    puma = km.load("puma560")
    rows = [km.Revolute(d=0.3, a=0.1, alpha=np.pi / 2), *puma.links]
    robot = km.Robot.from_dh(rows, convention=puma.convention, tool=puma.tool)
    last = closed_form(locked_chain(robot.chain, 6, 0.0), "pose")
    assert last is not None and last.name == "general-6R"
    joint = choose(robot.chain)
    assert isinstance(joint, JointParameter) and joint.index == 0
    q = np.array([0.4, 0.1, -0.5, 0.3, 0.7, 0.4, -0.2])
    res = robot.ik(robot.fk(q), q0=q)
    assert res.method == "analytic:spherical-wrist" and res.parameter == ("q1", 0.4)
    np.testing.assert_allclose(res.solutions[0], q, atol=1e-9)


@pytest.mark.parametrize(
    ("name", "held"), [("realman_gen72", 0), ("kinova_gen3", 6), ("realman_rm75", 6)]
)
def test_of_two_general_6r_end_locks_auto_holds_the_one_that_answers_more(
    name: str, held: int
) -> None:
    # each end joint's lock is the general 6R: the one at whose default more poses have a
    # solution is held, measured here on other poses than the choice's own (another seed,
    # the whole held call with its search)
    robot = km.load(str(DATA / "makers" / f"{name}.urdf"))
    joint = choose(robot.chain, robot.joint_names)
    assert isinstance(joint, JointParameter) and joint.index == held
    for k in (0, 6):
        lock = locked_chain(robot.chain, k, JointParameter(k, "q", False).default(robot.chain))
        assert closed_form(lock, "pose").search_note  # type: ignore[union-attr]
    T = robot.fk(robot.random_q(100, seed=123))
    answered = {}
    for k in (0, 6):
        value = JointParameter(k, "q", False).default(robot.chain)
        res = robot.ik(T, fixed={k: value}, workers=1)
        assert isinstance(res, IKBatchResult)
        answered[k] = int((res.count > 0).sum())
    other = 6 - held
    assert answered[held] > answered[other], answered


def test_auto_says_its_parameter_and_every_solution_holds_it() -> None:
    # the Panda's axes 1-3 meet: held at q7 (its last joint, first in the preference), the
    # arm left has a spherical shoulder; q7's limits are symmetric, so it is held at 0
    robot = km.load("panda")
    joint = choose(robot.chain, robot.joint_names)
    assert isinstance(joint, JointParameter) and joint.index == 6
    q = np.array([0.2, 0.4, -0.1, -1.4, 0.3, 1.2, 0.0])  # made at q7 = 0
    T = robot.fk(q)
    res = robot.ik(T)
    assert isinstance(res, IKResult)
    assert res.parameter == ("q7", 0.0) and res.method == "analytic:spherical-shoulder"
    np.testing.assert_array_equal(res.solutions[:, 6], 0.0)
    assert_transform_close(robot.fk(res.solutions), np.broadcast_to(T, (res.count, 4, 4)), atol=TOL)
    assert min(np.abs(res.solutions - q).max(axis=1)) < 1e-9  # the configuration that made it
    assert any("q7 = 0 rad" in n and "redundancy parameter" in n for n in res.notes)
    assert "with q7 = " in res.message


def test_auto_on_the_panda_holds_q0s_value() -> None:
    robot = km.load("panda")
    k = 6  # its last joint: the arm left has a spherical shoulder
    q = np.array([0.3, 0.5, -0.2, -1.2, 0.4, 0.9, 0.2])
    T = robot.fk(q)
    res = robot.ik(T, q0=q)
    assert res.parameter == (f"q{k + 1}", q[k])
    assert res.complete and res.count >= 1
    np.testing.assert_allclose(res.solutions[0], q, atol=1e-9)  # nearest q0 first: q itself
    # a q0 beyond the joint's limits holds the nearest limit
    beyond = q.copy()
    beyond[k] = 4.0
    T = robot.fk(np.concatenate([q[:k], [2.85], q[k + 1 :]]))  # reached near that limit
    res = robot.ik(T, q0=beyond, respect_limits=False)
    assert res.parameter is not None
    assert res.parameter[1] == pytest.approx(robot.qlim[k, 1], abs=0)


def test_where_the_default_finds_nothing_the_nearest_value_with_solutions_answers() -> None:
    robot = km.load("panda")
    joint = choose(robot.chain)
    assert isinstance(joint, JointParameter)
    value = joint.default(robot.chain)
    T = robot.fk(robot.random_q(40, seed=4))
    locked = robot.ik(T, fixed={joint.index: value})
    assert isinstance(locked, IKBatchResult)
    aside = T[np.flatnonzero(locked.count == 0)[0]]
    res = robot.ik(aside)
    assert res.parameter is not None and res.method == "analytic:spherical-shoulder"
    held = res.parameter[1]
    np.testing.assert_array_equal(res.solutions[:, joint.index], held)
    assert_transform_close(
        robot.fk(res.solutions), np.broadcast_to(aside, (res.count, 4, 4)), atol=TOL
    )
    assert any("the nearest of 73 values" in n for n in res.notes)
    # it is the grid's value nearest the default with a solution: none nearer has one
    lo, hi = robot.chain.qlim[joint.index]
    grid = np.linspace(lo, hi, PARAMETER_SWEEP)
    assert held in grid
    nearer = grid[np.abs(grid - value) < abs(held - value)]
    for v in nearer:
        assert robot.ik(aside, fixed={joint.index: float(v)}).count == 0


def test_where_no_value_finds_one_the_search_over_every_joint_answers(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # two values tried (the limits): most poses have no solution there
    monkeypatch.setattr(nearest_value, "PARAMETER_SWEEP", 2)
    robot = km.load("panda")
    joint = choose(robot.chain)
    assert isinstance(joint, JointParameter)  # its last joint leaves a spherical shoulder
    value = joint.default(robot.chain)
    # poses the whole arm reaches (made by fk) and, some of them, not with the lock
    T = robot.fk(robot.random_q(40, seed=4))
    locked = robot.ik(T, fixed={joint.index: value})
    assert isinstance(locked, IKBatchResult)
    lo, hi = robot.chain.qlim[joint.index]
    at_ends = [robot.ik(T, fixed={joint.index: float(v)}).count for v in (lo, hi)]
    missed = np.flatnonzero((locked.count == 0) & (at_ends[0] == 0) & (at_ends[1] == 0))
    held = np.flatnonzero(locked.count > 0)
    assert missed.size and held.size
    aside, reached = T[missed[0]], T[held[0]]
    res = robot.ik(aside)
    assert res.status == "ok" and res.parameter is None and res.method == "numeric:lm"
    assert any(f"no solution with {joint.describe(value)}" in n for n in res.notes)
    assert_transform_close(
        robot.fk(res.solutions), np.broadcast_to(aside, (res.count, 4, 4)), atol=TOL
    )
    # a batch: each row as its single call says it
    many = robot.ik(np.stack([reached, aside, reached]))
    assert isinstance(many, IKBatchResult)
    values = np.asarray(many.parameter[1])  # type: ignore[index]
    assert values[0] == values[2] == value and math.isnan(values[1])
    for i, target in enumerate((reached, aside, reached)):
        one = robot.ik(target)
        assert many[i].parameter == one.parameter
        assert many[i].method == one.method
        assert str(many[i].status) == str(one.status)
        if one.parameter is not None:
            np.testing.assert_allclose(many[i].solutions, one.solutions, atol=1e-12)
            assert many[i].message == one.message


@pytest.mark.parametrize(("extra", "held"), [(0, True), (1, False)])
def test_only_seven_joint_arms_are_held(extra: int, held: bool) -> None:
    # an iiwa with one more joint at the tip (8 joints) is searched as before
    iiwa = km.load("iiwa14")
    rows = list(iiwa.links) + [km.Revolute(d=0.05, alpha=math.pi / 2)] * extra
    robot = km.Robot.from_dh(rows, convention="standard")
    assert robot.dof == REDUNDANT_DOF + extra
    T = robot.fk(np.r_[0.3, 0.5, -0.2, -1.2, 0.4, 0.9, 0.2, [0.1] * extra])
    res = robot.ik(T, seed=1)
    assert (res.parameter is not None) == held


def test_six_joint_arms_a_mask_and_positions_are_not_held() -> None:
    puma = km.load("puma560")
    assert puma.ik(puma.fk([0.3, -0.6, 0.2, 0.5, 0.9, -0.4])).parameter is None
    iiwa = km.load("iiwa14")
    T = iiwa.fk(np.array([0.3, 0.5, -0.2, -1.2, 0.4, 0.9, 0.2]))
    assert iiwa.ik(T, mask=[1, 1, 1, 1, 1, 0], seed=1).parameter is None
    assert iiwa.ik(T[:3, 3], seed=1).parameter is None
    assert iiwa.ik(T, method="numeric", seed=1).parameter is None


def test_a_ur5_with_a_seventh_joint_is_held_at_it_with_every_ur5_solution() -> None:
    # its last joint leaves the UR5's three parallel axes: first in the preference
    ur5 = km.load("ur5")
    rows = [*ur5.links, km.Revolute(d=0.05, a=0.03, alpha=0.4)]
    robot = km.Robot.from_dh(rows, base=ur5.base, tool=ur5.tool, convention="standard")
    q = np.array([0.3, -1.0, 1.2, -0.5, 0.8, 0.4, 0.25])
    T = robot.fk(q)
    res = robot.ik(T, q0=q, respect_limits=False)
    assert res.parameter == ("q7", 0.25)
    assert res.method.startswith("analytic:") and res.count == 8
    np.testing.assert_allclose(res.solutions[0], q, atol=1e-9)  # nearest q0 first
    assert_transform_close(robot.fk(res.solutions), np.broadcast_to(T, (8, 4, 4)), atol=TOL)


@pytest.mark.parametrize("name", ["iiwa14", "panda"])
def test_a_batch_of_any_shape_equals_single_calls(name: str) -> None:
    robot = km.load(name)
    rng = np.random.default_rng(5)
    q = rng.uniform(*robot.qlim.T, size=(3, 4, 7))
    q[0, :, 6] = 0.0  # the Panda's lock (q7 at the middle of its limits) holds these
    T = robot.fk(q)
    T[1, 1, :3, 3] += 5.0  # beyond reach
    many = robot.ik(T)
    assert isinstance(many, IKBatchResult)
    for idx in np.ndindex(3, 4):
        assert_same_result(many[idx], robot.ik(np.ascontiguousarray(T[idx])))


@pytest.mark.parametrize("name", ["panda", "iiwa14"])
def test_a_q0_holding_nan_is_refused_by_name_on_every_path(name: str) -> None:
    # the Panda's auto path holds a joint at q0's value: NaN reached the core's locked
    # arm, whose ValueError was all the user saw
    robot = km.load(name)
    T = robot.fk(np.full(7, 0.3))
    for q0 in ([np.nan] * 7, [0.0] * 6 + [np.inf]):
        for extra in ({}, {"method": "numeric"}, {"fixed": {"q2": 0.1}}):
            with pytest.raises(km.DimensionError, match="q0 holds NaN or inf") as info:
                robot.ik(T, q0=q0, **extra)  # type: ignore[arg-type]
            assert info.value.arg == "q0"
        with pytest.raises(km.DimensionError, match="q0 holds NaN or inf"):
            robot.ik(np.stack([T, T]), q0=q0)


@pytest.mark.parametrize("name", ["panda", "iiwa14"])
@pytest.mark.parametrize("held", [{}, {"fixed": {"q1": 0.1}}, {"fixed": {"q3": 0.1}}])
def test_an_empty_batch_of_a_redundant_arm_is_an_empty_result(name: str, held: dict) -> None:
    robot = km.load(name)
    one = robot.ik(robot.fk(np.full(7, 0.3)), **held)
    for shape in ((0,), (2, 0)):
        res = robot.ik(np.zeros((*shape, 4, 4)), **held)
        assert isinstance(res, IKBatchResult)
        assert res.shape == shape and res.status.shape == shape and res.count.shape == shape
        assert res.solutions.shape[: len(shape)] == shape and res.solutions.shape[-1] == 7
        assert res.method == one.method


def test_the_nearest_value_is_the_one_every_value_solved_in_full_would_give() -> None:
    # GEN72: its end joint held leaves a general 6R, whose elimination the search completes;
    # the screen tries values nearest first by the elimination alone, and must pick the value
    # that solving the target in full at every value of the grid picks
    robot = km.load(str(DATA / "makers" / "realman_gen72.urdf"))
    joint = choose(robot.chain, robot.joint_names)
    assert isinstance(joint, JointParameter) and joint.index in (0, 6)
    assert robot.ik(robot.fk(robot.random_q(1, seed=1))[0], fixed={joint.index: 0.0}).method == (
        "analytic:general-6R"
    )
    value = joint.default(robot.chain)
    lo, hi = robot.chain.qlim[joint.index]
    grid = np.linspace(lo, hi, PARAMETER_SWEEP)
    T = robot.fk(robot.random_q(12, seed=5))
    at_default = robot.ik(T, fixed={joint.index: value})
    assert isinstance(at_default, IKBatchResult)
    aside = np.flatnonzero(at_default.count == 0)[:3]
    assert aside.size == 3
    moved = 0
    for i in aside.tolist():
        counts = np.array([robot.ik(T[i], fixed={joint.index: float(v)}).count for v in grid])
        distance = np.where(counts > 0, np.abs(grid - value), np.inf)
        res = robot.ik(T[i])
        if np.isfinite(distance).any():
            assert res.parameter == (joint.name, grid[int(np.argmin(distance))])
            assert res.count == counts[int(np.argmin(distance))]
            moved += 1
        else:
            assert res.parameter is None
    assert moved  # a target held at a value other than the default


def test_the_arm_angle_sweep_is_one_round_and_gives_the_nearest_value_with_solutions(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # the iiwa's arm angle: a value costs its closed form, far less than a round, so one
    # target's sweep tries its first ArmAngleParameter.round_values values in one round,
    # leaving out the default (solved already); the value it picks is the nearest the
    # default with a solution, as arm_angle= at every value of the grid says
    robot = km.load("iiwa14")
    joint = choose(robot.chain)
    assert isinstance(joint, ArmAngleParameter) and joint.round_values > 1
    grid = np.linspace(-math.pi, math.pi, PARAMETER_SWEEP)
    T = robot.fk(robot.random_q(300, seed=0))
    at_default = robot.ik(T, arm_angle=0.0)
    assert isinstance(at_default, IKBatchResult)
    aside = np.flatnonzero(at_default.count == 0)[:3]
    assert aside.size == 3
    calls: list[np.ndarray] = []  # the values each round tries
    screen = nearest_value.has_solutions

    def counted(*args: object) -> np.ndarray:
        calls.append(np.asarray(args[3]))
        return screen(*args)  # type: ignore[arg-type]

    monkeypatch.setattr(nearest_value, "has_solutions", counted)
    for i in aside.tolist():
        counts = robot.ik(np.repeat(T[i][None], grid.size, axis=0), arm_angle=grid).count
        distance = np.where(counts > 0, np.abs(grid), np.inf)
        calls.clear()
        res = robot.ik(T[i])
        assert np.isfinite(distance).any()
        assert res.parameter == (joint.name, grid[int(np.argmin(distance))])
        assert res.count == counts[int(np.argmin(distance))]
        assert counts[grid == 0.0].sum() == 0  # the default has none: left out of the sweep
        order = [k for k in np.argsort(np.abs(grid), kind="stable").tolist() if grid[k] != 0.0]
        rank = order.index(int(np.argmin(distance)))  # the values tried before the answer's
        assert calls[0].size == min(joint.round_values, PARAMETER_SWEEP - 1)
        assert len(calls) == (1 if rank < joint.round_values else 2)
        assert not any((c == 0.0).any() for c in calls)


@pytest.mark.parametrize("name", ["panda", "realman_gen72", "iiwa14"])
def test_auto_at_the_default_value_is_the_held_calls_answer_with_its_note(name: str) -> None:
    # one pose answered at the default value takes the held joint's one core call (the
    # iiwa: its closed form at the arm angle): the answer fixed= (arm_angle=) gives there,
    # to the bit, with auto's note of why that value
    robot = km.load(str(DATA / "makers" / f"{name}.urdf") if name == "realman_gen72" else name)
    joint = choose(robot.chain, robot.joint_names)
    value = joint.default(robot.chain)
    hold = {"arm_angle": value} if isinstance(joint, ArmAngleParameter) else None
    T = robot.fk(robot.random_q(30, seed=2))
    at_default = 0
    for t in T:
        res = robot.ik(t)
        assert isinstance(res, IKResult) and res.parameter is not None
        if res.parameter[1] != value:
            continue
        at_default += 1
        held = robot.ik(t, **(hold or {"fixed": {joint.index: value}}))
        assert isinstance(held, IKResult) and "its redundancy parameter" in res.notes[-1]
        assert_same_result(dataclasses.replace(res, notes=res.notes[:-1]), held)
    assert at_default >= 5


@pytest.mark.parametrize("name", ["panda", "realman_gen72", "iiwa14"])
def test_auto_at_q0s_value_is_the_held_calls_answer_with_q0_and_its_note(name: str) -> None:
    # q0 (a float64 vector) holds the parameter at its value (a joint's, or the iiwa's arm
    # angle): the held call's answer with q0 beside it, to the bit, with the note saying
    # whence the value
    robot = km.load(str(DATA / "makers" / f"{name}.urdf") if "_" in name else name)
    joint = choose(robot.chain, robot.joint_names)
    Q = robot.random_q(20, seed=3)
    T = robot.fk(Q)
    rng = np.random.default_rng(3)
    at_q0 = 0
    for t, q in zip(T, Q, strict=True):
        q0 = np.clip(q + rng.normal(scale=0.05, size=q.size), *robot.qlim.T)
        res = robot.ik(t, q0=q0)
        assert isinstance(res, IKResult) and res.parameter is not None
        if isinstance(joint, JointParameter):
            value = float(q0[joint.index])
            held = robot.ik(t, fixed={joint.index: value}, q0=q0)
        else:
            assert isinstance(joint, ArmAngleParameter)
            value = float(robot.arm_angle(q0))
            held = robot.ik(t, arm_angle=value, q0=q0)
        assert isinstance(held, IKResult)
        if res.parameter[1] == value:
            at_q0 += 1
            assert "q0's value, within its limits" in res.notes[-1]
            assert_same_result(dataclasses.replace(res, notes=res.notes[:-1]), held)
        else:  # no solution at q0's value: the sweep's nearest value
            assert held.count == 0
    assert at_q0 >= 5
