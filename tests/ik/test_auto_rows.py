"""``auto`` on a 7R arm: every row of a batch is its own single call.

A batch row answered at another held value than the one asked (the nearest value of the
sweep with a solution, :mod:`kinematica.ik.redundancy`) must say what that answer says:
its method and notes, not those of the first answer at the value asked (a numeric search
that found nothing there).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from support import DATA
from support.helpers import assert_same_result

import kinematica as km
from kinematica.ik import IKBatchResult, IKResult


def _random_7r(seed: int, tool_off_axis: bool) -> km.Robot:
    """A generic 7R arm (standard DH drawn at random), its tool off the last axis if asked."""
    rng = np.random.default_rng(seed)
    rows = [
        km.Revolute(
            d=float(rng.uniform(-0.4, 0.4)),
            a=float(rng.uniform(-0.4, 0.4)),
            alpha=float(rng.uniform(-math.pi, math.pi)),
        )
        for _ in range(7)
    ]
    tool = np.eye(4)
    if tool_off_axis:
        tool[:3, 3] = [0.05, -0.03, 0.1]
    return km.Robot.from_dh(rows, name=f"random 7R ({seed})", convention="standard", tool=tool)


def _robot(name: str) -> km.Robot:
    if name.startswith("random"):
        _, seed, off = name.split(":")
        return _random_7r(int(seed), off == "off")
    return km.load(str(DATA / "makers" / f"{name}.urdf"))


@pytest.mark.parametrize(
    ("name", "count"),
    [
        ("kinova_gen3", 10),
        ("realman_rm75", 10),
        ("realman_gen72", 6),
        ("random:3:on", 6),
        ("random:7:off", 6),
    ],
)
def test_every_row_of_a_batch_is_its_own_single_call(name: str, count: int) -> None:
    robot = _robot(name)
    rng = np.random.default_rng(11)
    lo, hi = np.nan_to_num(robot.qlim, posinf=math.pi, neginf=-math.pi).T
    T = robot.fk(rng.uniform(lo, hi, size=(count, 7)))
    T[0, :3, 3] += 5.0  # beyond reach: the search over every joint answers
    batch = robot.ik(T)
    assert isinstance(batch, IKBatchResult)
    moved = 0
    for i in range(count):
        one = robot.ik(np.ascontiguousarray(T[i]))
        assert isinstance(one, IKResult)
        assert_same_result(batch[i], one)
        value = None if one.parameter is None else one.parameter[1]
        moved += value is not None and any("the nearest of" in n for n in one.notes)
    assert batch[0].parameter is None  # the search answered the pose beyond reach
