"""``auto`` on a 7R arm: every row of a batch is its own single call.

A batch row answered at another held value than the one asked (the nearest value of the
sweep with a solution, :mod:`kinematica.ik.redundancy`) must say what that answer says:
its method and notes, not those of the first answer at the value asked (a numeric search
that found nothing there). The rows held elsewhere are swept in one core call
(``Prepared.sweep``) on one thread or several: the same rows either way.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from support import DATA
from support.helpers import assert_same_result, random_7r

import kinematica as km
from kinematica.ik import IKBatchResult, IKResult


def _robot(name: str) -> km.Robot:
    if name.startswith("random"):
        _, seed, off = name.split(":")
        return random_7r(int(seed), off == "off")
    return km.load(str(DATA / "makers" / f"{name}.urdf"))


def _rows_are_single_calls(robot: km.Robot, T: np.ndarray, q0: np.ndarray | None) -> int:
    """Assert each row of ``robot.ik(T, q0=q0)`` is its single call; the rows held elsewhere."""
    batches = [robot.ik(T, q0=q0, workers=w) for w in (1, 2)]  # the rows on 1 or 2 threads
    moved = 0
    for i in range(T.shape[0]):
        one = robot.ik(np.array(T[i]), q0=None if q0 is None else q0[i])
        assert isinstance(one, IKResult)
        for batch in batches:
            assert isinstance(batch, IKBatchResult)
            assert_same_result(batch[i], one)
        moved += any("the nearest of" in n for n in one.notes)
    return moved


@pytest.mark.parametrize(
    ("name", "count"),
    [
        ("kinova_gen3", 10),
        ("realman_rm75", 10),
        ("realman_gen72", 8),
        ("random:3:on", 8),
        ("random:7:off", 8),
    ],
)
def test_every_row_of_a_batch_is_its_own_single_call(name: str, count: int) -> None:
    robot = _robot(name)
    rng = np.random.default_rng(11)
    lo, hi = np.nan_to_num(robot.qlim, posinf=math.pi, neginf=-math.pi).T
    T = robot.fk(rng.uniform(lo, hi, size=(count, 7)))
    T[0, :3, 3] += 5.0  # beyond reach: the search over every joint answers
    moved = _rows_are_single_calls(robot, T, None)
    far = robot.ik(np.array(T[0]))
    assert isinstance(far, IKResult) and far.parameter is None  # the search answered it
    if name.startswith("random"):
        assert moved  # rows answered at another value than the default
        # targets read with a note (a rotation given to 4 decimals), and rows with a q0:
        # the screen, then the value found solved again (not the prepared call)
        T4 = np.round(T, 4)
        read = [robot.ik(np.array(t)).notes for t in T4]
        assert any(str(n[0]).startswith("target rotation projected") for n in read if n)
        _rows_are_single_calls(robot, T4, None)
        _rows_are_single_calls(robot, T, np.zeros((count, 7)))


def test_a_pose_held_elsewhere_is_not_solved_again_at_the_value_found(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # GEN72's last joint: the prepared call that screens a value of the sweep answers at
    # the first with a solution; the held joint is solved once (at the default value)
    from kinematica.ik.parameter import JointParameter

    robot = km.load(str(DATA / "makers" / "realman_gen72.urdf"))
    T = robot.fk(robot.random_q(12, seed=5))
    answers = [robot.ik(t) for t in T]
    moved = [i for i, a in enumerate(answers) if any("the nearest of" in n for n in a.notes)]
    assert moved
    calls: list[float] = []
    solve = JointParameter.solve

    def counted(self, chain, target, values, options):  # type: ignore[no-untyped-def]
        calls.append(float(np.asarray(values).reshape(-1)[0]))
        return solve(self, chain, target, values, options)

    monkeypatch.setattr(JointParameter, "solve", counted)
    for i in moved:
        calls.clear()
        assert_same_result(robot.ik(T[i]), answers[i])
        found = answers[i].parameter
        assert found is not None and found[1] != 0.0  # held elsewhere than the default
        assert found[1] not in calls
