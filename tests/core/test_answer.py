"""The core's typed answers (cpp/python/answer.hpp): Answer, BatchAnswer, a Prepared plan.

Each is checked against a second path: the one-target answer against the batch's row
of the same target, a prepared plan's result against the general path's (the target as
a view the core does not read in place, parsed first), and every solution by FK.
"""

from __future__ import annotations

import numpy as np
import pytest

import kinematica as km
from kinematica import _core
from kinematica.ik.request import IKRequest
from kinematica.ik.result import BATCH_FIELDS, IKResult, replaced
from kinematica.ik.solvers import plan_of
from kinematica.ik.tolerance import POSITION_TOL, ROTATION_TOL, Tolerance
from kinematica.spatial import rotation_angle


def _puma() -> tuple[km.Robot, np.ndarray]:
    robot = km.load("puma560")
    return robot, np.ascontiguousarray(robot.fk(robot.random_q(6, seed=3)))


def test_one_answer_is_the_batch_row_by_name_and_read_only() -> None:
    robot, T = _puma()
    plan = plan_of(robot.chain, "pose", IKRequest.parse())
    core = robot.chain.core
    many = plan.solver.ik_batch(core, T, plan.options, None, None, 1)
    for i in range(len(T)):
        one = plan.solver.ik(core, T[i], plan.options, None, plan.labels)
        k, m = len(one.branches), len(one.out_of_limits_branches)
        assert one.solutions.shape == (k, 6) and one.residuals.shape == (k, 2)
        np.testing.assert_array_equal(one.solutions, many.q[i, :k])
        np.testing.assert_array_equal(one.out_of_limits, many.q[i, k : k + m])
        np.testing.assert_array_equal(one.residuals, many.res[i, :k])
        assert [plan.labels.index(b) for b in one.branches] == many.slot[i, :k].tolist()
        assert one.status == many.status[i] and k == many.count[i] and m == many.out_count[i]
        assert one.gap is None and np.isnan(many.gap[i])
        assert one.near_singular == many.near[i] and one.free_joints == ()
        F = robot.fk(one.solutions)  # each solution reaches the target (an independent FK)
        assert np.abs(F[:, :3, 3] - T[i][:3, 3]).max() <= 1e-10
        assert rotation_angle(F[:, :3, :3], T[i][:3, :3]).max() <= 1e-10
        with pytest.raises(ValueError, match="read-only"):
            one.solutions[0, 0] = 1.0
    for name in BATCH_FIELDS:
        with pytest.raises(ValueError, match="read-only"):
            getattr(many, name)[0] = 0


def test_a_batch_answer_made_in_python_is_checked() -> None:
    robot, T = _puma()
    plan = plan_of(robot.chain, "pose", IKRequest.parse())
    raw = plan.solver.ik_batch(robot.chain.core, T, plan.options, None, None, 1)
    status = np.array(raw.status)
    status[0] = _core.STATUS["unreachable"]
    changed = replaced(raw, status=status)
    assert changed.status[0] == _core.STATUS["unreachable"] and changed.q is raw.q
    with pytest.raises(TypeError, match="status must be of the dtype"):
        replaced(raw, status=status.astype(np.float64))
    with pytest.raises(ValueError, match="gap must be of 6 rows"):
        replaced(raw, gap=np.zeros(5))
    with pytest.raises(ValueError, match="q must be of rank 3"):
        replaced(raw, q=np.zeros((6, 4)))
    with pytest.raises(TypeError, match="near must be a numpy array"):
        replaced(raw, near=[True] * 6)


def test_a_prepared_plan_gives_the_general_paths_result() -> None:
    robot, T = _puma()
    for settings in ({}, {"respect_limits": False}, {"tol": 1e-9}):
        plan = plan_of(robot.chain, "pose", IKRequest.parse(**settings))  # type: ignore[arg-type]
        assert plan.prepared is not None
        for t in T:
            got = plan.prepared(t)
            assert type(got) is IKResult
            strided = np.asfortranarray(t)  # not read in place: parsed, then the core's ik
            assert plan.prepared(strided) is None
            want = robot.ik(strided, **settings)  # type: ignore[arg-type]
            assert isinstance(want, IKResult)
            for name in ("solutions", "residuals", "out_of_limits"):
                np.testing.assert_array_equal(getattr(got, name), getattr(want, name))
            for name in ("status", "method", "branches", "out_of_limits_branches", "free_joints",
                         "gap", "notes", "complete", "near_singular", "parameter"):  # fmt: skip
                assert getattr(got, name) == getattr(want, name), name
            assert got.message == want.message


def test_a_prepared_plan_declines_what_the_core_does_not_read_as_a_rigid_pose() -> None:
    robot, T = _puma()
    plan = plan_of(robot.chain, "pose", IKRequest.parse())
    bent = T[0].copy()
    bent[0, 0] += 1e-6  # not rigid to round-off: projected (with a note) by the parse
    nan = np.full((4, 4), np.nan)
    for wrong in (bent, T[0].astype(np.float32), T[0][:3], T[0].tolist(), nan, None):
        assert plan.prepared(wrong) is None
    assert "projected" in robot.ik(bent).message


def test_prepare_checks_what_it_is_given() -> None:
    robot, _ = _puma()
    plan = plan_of(robot.chain, "pose", IKRequest.parse())
    core, opts, labels = robot.chain.core, plan.options, plan.labels
    statuses = tuple(range(6))
    with pytest.raises(TypeError, match="result must be a class"):
        plan.solver.prepare(core, opts, 0.0, labels, 3, {}, statuses, 1)
    with pytest.raises(TypeError, match="fields must be a dict"):
        plan.solver.prepare(core, opts, 0.0, labels, IKResult, (), statuses, 1)
    with pytest.raises(TypeError, match="statuses must be a tuple"):
        plan.solver.prepare(core, opts, 0.0, labels, IKResult, {}, statuses[:3], 1)
    with pytest.raises(ValueError, match="labels must be a tuple"):
        plan.solver.prepare(core, opts, 0.0, labels[:2], IKResult, {}, statuses, 1)
    iiwa = km.load("iiwa14")
    with pytest.raises(ValueError, match="takes a chain of 6 joints"):
        plan.solver.prepare(iiwa.chain.core, opts, 0.0, labels, IKResult, {}, statuses, 1)


def test_one_tolerance_its_defaults_written_once() -> None:
    """The core's Tolerance holds the defaults; the check, the search and Python read them."""
    core = _core.Tolerance()
    assert (core.position, core.rotation) == (POSITION_TOL, ROTATION_TOL) == (1e-10, 1e-10)
    assert Tolerance() == Tolerance(POSITION_TOL, ROTATION_TOL)
    opts = _core.CheckOptions()
    assert (opts.tol.position, opts.tol.rotation) == (POSITION_TOL, ROTATION_TOL)
    given = _core.Tolerance(rotation=2e-9)
    assert (given.position, given.rotation) == (POSITION_TOL, 2e-9)
