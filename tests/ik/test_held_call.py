"""``robot.ik(T, fixed={k: v})`` of one pose, a new v each call: one core call, the same answer.

The first joint, or the last with the tool point on its axis, moves the pose of the arm
locked at 0 (:mod:`kinematica.ik.moved`); one pose is moved, solved, checked and widened
in the core (``Prepared.at``). Its answer is held here against the batch path, which moves
the poses and widens the answers in numpy, and against our FK.
"""

from __future__ import annotations

import numpy as np
import pytest

import kinematica as km
from kinematica.ik import IKResult
from kinematica.ik.fixed import joint_parameter
from kinematica.ik.held_call import held_one
from kinematica.ik.request import HeldCall, IKRequest
from kinematica.ik.solvers import plan_of
from kinematica.spatial import rotation_angle

#: Our FK puts every solution this close to the target (m and rad).
TOL = 1e-10


def _poses(robot: km.Robot, k: int, value: float, n: int = 4) -> np.ndarray:
    """``(n, 4, 4)`` poses of random configurations with joint k at ``value``."""
    Q = robot.random_q(n, seed=5)
    Q[:, k] = value
    return np.ascontiguousarray(robot.fk(Q))


@pytest.mark.parametrize(("name", "k"), [("panda", 6), ("iiwa14", 0), ("iiwa14", 6)])
def test_a_held_end_joint_is_one_core_call_with_the_batch_paths_answer(name: str, k: int) -> None:
    robot = km.load(name)
    v = 0.3
    T = _poses(robot, k, v)
    call = IKRequest.parse(fixed={k: v})
    assert type(call) is HeldCall and call.full().fixed == {k: v}
    many = robot.ik(T, fixed={k: v})
    for i, t in enumerate(T):
        lean = held_one(robot.chain, t, call, robot.joint_names)
        assert type(lean) is IKResult  # the core's one call answered
        one = robot.ik(t, fixed={k: v})
        row = many[i]
        for field in ("status", "count", "method", "branches", "out_of_limits_branches",
                      "free_joints", "notes", "parameter", "complete"):  # fmt: skip
            assert getattr(one, field) == getattr(row, field) == getattr(lean, field), field
        assert one.parameter == (f"q{k + 1}", v) and one.count >= 1
        np.testing.assert_allclose(one.solutions, row.solutions, atol=1e-12)
        np.testing.assert_array_equal(one.solutions[:, k], v)
        F = robot.fk(one.solutions)
        assert np.abs(F[:, :3, 3] - t[:3, 3]).max() <= TOL
        R = np.broadcast_to(t[:3, :3], F[:, :3, :3].shape)
        assert rotation_angle(F[:, :3, :3], R).max() <= TOL


def test_a_singular_answer_names_its_free_joints_in_the_whole_arm() -> None:
    # q6 = 0 lines up axes 5 and 7; the first joint held: the locked arm's 3 and 5 are q5, q7
    robot = km.load("iiwa14")
    T = robot.fk(np.array([0.3, 0.5, -0.2, -1.2, 0.4, 0.0, 0.2]))
    lean = held_one(robot.chain, T, IKRequest.parse(fixed={0: 0.3}), robot.joint_names)  # type: ignore[arg-type]
    assert lean is not None and lean.status == "singular" and lean.free_joints == (4, 6)


def test_an_answer_the_core_does_not_give_finally_is_completed_as_the_batch_completes_it() -> None:
    robot = km.load("panda")
    T = _poses(robot, 6, 0.3, 1)[0]
    names = robot.joint_names
    bent = T.copy()
    bent[0, 0] += 1e-6  # not rigid to round-off: the general path projects it, with a note
    assert held_one(robot.chain, bent, IKRequest.parse(fixed={6: 0.3}), names) is None  # type: ignore[arg-type]
    assert "projected" in robot.ik(bent, fixed={6: 0.3}).message
    far = T.copy()
    far[:3, 3] += 5.0  # out of reach: the limited reach's proof completes the core's answer
    lean = held_one(robot.chain, far, IKRequest.parse(fixed={6: 0.3}), names)  # type: ignore[arg-type]
    row = robot.ik(far[None], fixed={6: 0.3})[0]
    assert lean is not None and lean.status == row.status == "unreachable"
    assert lean.parameter == row.parameter == ("q7", 0.3)
    assert lean.gap == pytest.approx(row.gap, rel=1e-12) and lean.gap > 4.0
    # the Panda's first joint held: the general 6R, whose answers the core leaves to complete
    Q = robot.random_q(3, seed=2)
    Q[:, 0] = 0.3
    P = np.ascontiguousarray(robot.fk(Q))
    many = robot.ik(P, fixed={0: 0.3})
    for i, t in enumerate(P):
        one = held_one(robot.chain, t, IKRequest.parse(fixed={0: 0.3}), names)  # type: ignore[arg-type]
        assert one is not None and one.method == many[i].method == "analytic:general-6R"
        assert one.status == many[i].status and one.count == many[i].count >= 1
        assert one.notes == many[i].notes and one.branches == many[i].branches
        np.testing.assert_allclose(one.solutions, many[i].solutions, atol=1e-9)
        np.testing.assert_array_equal(one.solutions[:, 0], 0.3)


def test_a_value_is_checked_as_before_and_a_number_passes_as_it_is() -> None:
    robot = km.load("panda")
    T = _poses(robot, 6, 0.3, 1)[0]
    assert robot.ik(T, fixed={6: 0.3}).parameter == ("q7", 0.3)
    assert robot.ik(T, fixed={"q7": np.float64(0.3)}).parameter == ("q7", 0.3)
    for bad, match in ((True, "must be a number"), (float("nan"), "must be finite"),
                       (3.5, "outside its limits")):  # fmt: skip
        with pytest.raises(km.KinematicaError, match=match):
            robot.ik(T, fixed={6: bad})
    beyond = robot.ik(T, fixed={6: 3.5}, respect_limits=False)
    assert beyond.parameter == ("q7", 3.5)
    assert np.all(np.concatenate([beyond.solutions, beyond.out_of_limits])[:, 6] == 3.5)


def test_a_prepared_call_holds_a_joint_only_when_made_to() -> None:
    robot = km.load("puma560")
    plan = plan_of(robot.chain, "pose", IKRequest.parse())  # type: ignore[arg-type]
    T = robot.fk(np.full(6, 0.3))
    with pytest.raises(ValueError, match="holds no joint"):
        plan.prepared.at(T, 0.3)
    with pytest.raises(ValueError, match="A must"):
        plan.prepared.held(6, np.zeros((2, 4, 4)), True, False, "q7")
    with pytest.raises(ValueError, match="joint out of range"):
        plan.prepared.held(-1, np.zeros((3, 4, 4)), True, False, "q7")
    # held at joint 6 of a 7-joint arm with no move (A0 = I): the pose as it is, widened
    A = np.zeros((3, 4, 4))
    A[0] = np.eye(4)
    held = plan.prepared.held(6, A, True, False, "q7")
    got, alone = held.at(T, 0.7), robot.ik(T)
    assert got.parameter == ("q7", 0.7) and got.count == alone.count
    np.testing.assert_array_equal(got.solutions[:, :6], alone.solutions)
    np.testing.assert_array_equal(got.solutions[:, 6], 0.7)


def _sweep(held, T, start, grid, skip=None, bounds=None, workers=1):  # type: ignore[no-untyped-def]
    """``Prepared.sweep`` of poses T (N, 4, 4) with the default tolerance, limits kept."""
    N = len(T)
    skip = np.full(N, np.nan) if skip is None else skip
    return held.sweep(T, np.asarray(start, float), grid, skip, bounds, 1e-10, 1e-10, True, 1e-9,
                      workers)  # fmt: skip


def test_sweep_tries_the_held_values_nearest_first_as_at_answers_each() -> None:
    """``Prepared.sweep``: each pose's first value with a solution in its order, at()'s answer."""
    from kinematica.ik.moved import end_arm, move_parts
    from kinematica.ik.reach_bounds import may_reach, reach_bounds
    from kinematica.ik.tolerance import Tolerance

    robot = km.load("puma560")
    plan = plan_of(robot.chain, "pose", IKRequest.parse())  # type: ignore[arg-type]
    T = robot.fk(np.full(6, 0.3))[None]
    far = T.copy()
    far[0, :3, 3] *= 10.0  # out of reach at every value (the move A0 = I does not move it)
    with pytest.raises(ValueError, match="holds no joint"):
        _sweep(plan.prepared, T, [0.0], np.array([0.3]))
    A = np.zeros((3, 4, 4))
    A[0] = np.eye(4)
    held = plan.prepared.held(6, A, True, False, "q7")
    index, answers = _sweep(held, far, [0.0], np.array([0.1, 0.2]))
    assert index.tolist() == [-1] and answers == [None]
    assert _sweep(held, T, [0.0], np.empty(0))[0].tolist() == [-1]
    bent = T.copy()
    bent[0, :3, :3] *= 1.01  # not a rigid pose: left to the general path
    assert _sweep(held, bent, [0.0], np.array([0.1]))[0].tolist() == [-2]
    with pytest.raises(TypeError):  # bounds are the core's ReachBounds, or None
        _sweep(held, T, [0.0], np.array([0.1]), bounds=np.zeros(5))
    with pytest.raises(ValueError, match="start"):
        _sweep(held, T, [0.0, 1.0], np.array([0.1]))
    # a held turn about z: the panda's last joint moves the pose; each pose's first value
    # with a solution within the limits, nearest its start first, is the one at() finds
    # first in that order, with at()'s answer; the values the bounds prove out of reach are
    # left out (none with a solution), and so is the value skipped
    panda = km.load("panda")
    parameter = joint_parameter(panda.chain, 6, None)
    ready = parameter.lean(panda.chain, IKRequest.parse())  # type: ignore[arg-type]
    bounds = reach_bounds(end_arm(panda.chain, 6), True)
    assert bounds is not None
    rng = np.random.default_rng(3)
    poses = _poses(panda, 6, 0.4, 12)
    grid = np.linspace(-2.9, 2.9, 9)
    start = rng.uniform(-2.9, 2.9, len(poses))
    skip = np.where(np.arange(len(poses)) % 3 == 0, grid[4], np.nan)
    kept = may_reach(bounds, poses, Tolerance(), grid, move_parts(panda.chain, 6))
    index, answers = _sweep(ready, poses, start, grid, skip, bounds)
    again, _ = _sweep(ready, poses, start, grid, skip, bounds, workers=2)
    plain, _ = _sweep(ready, poses, start, grid, skip)  # no bounds: the same values
    np.testing.assert_array_equal(index, again)
    np.testing.assert_array_equal(index, plain)
    moved_on = 0
    for i, pose in enumerate(poses):
        order = np.argsort(np.abs(grid - start[i]), kind="stable")
        ats = {int(j): ready.at(pose, float(grid[j])) for j in order if grid[j] != skip[i]}
        has = [j for j in ats if ats[j].solutions.shape[0]]
        assert all(kept[i, j] for j in has)
        if not has:
            assert index[i] == -1 and answers[i] is None
            continue
        assert index[i] == has[0]
        moved_on += has[0] != order[0]
        np.testing.assert_array_equal(answers[i].solutions, ats[has[0]].solutions)
        assert answers[i].parameter == ats[has[0]].parameter == ("q7", float(grid[has[0]]))
    assert moved_on  # some pose had no solution at its first values


def test_options_holding_one_joint_take_the_keywords_path() -> None:
    """``options=IKOptions(fixed={k: v})`` is read as ``fixed={k: v}``: one core call."""
    robot = km.load("panda")
    T = _poses(robot, 6, 0.3, 1)[0]
    opts = km.ik.IKOptions(fixed={6: 0.3}, tol=1e-9)
    assert type(IKRequest.parse(options=opts)) is HeldCall
    with_q0 = km.ik.IKOptions(fixed={6: 0.3}, q0=np.zeros(7))  # q0 rides beside (a vector)
    assert type(IKRequest.parse(options=with_q0)) is HeldCall
    listed = km.ik.IKOptions(fixed={6: 0.3}, q0=[0.0] * 7)  # anything else: the general path
    assert type(IKRequest.parse(options=listed)) is IKRequest
    got, want = robot.ik(T, options=opts), robot.ik(T, fixed={6: 0.3}, tol=1e-9)
    assert got.parameter == want.parameter == ("q7", 0.3)
    assert got.method == want.method and got.notes == want.notes
    np.testing.assert_array_equal(got.solutions, want.solutions)
    with pytest.raises(km.KinematicaError, match="outside its limits"):
        robot.ik(T, options=km.ik.IKOptions(fixed={6: 3.5}))
