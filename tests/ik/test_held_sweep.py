"""A joint held where the arm left is nearly a continuum: solutions along the self-motion.

The Realman RM75 (micrometre offsets from an SRS arm) and rtb-data's iiwa 14 URDF
(a 0.44 mm shoulder offset) with the elbow held: never the numeric search's single
answer; every row reaches the target by forward kinematics (an independent check),
and the configuration that made the pose is among the rows to within what the arm's
conditioning determines, or on the continuum named. The crossing logic is checked on
made-up branches at each tolerance's boundary.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

import kinematica as km
from kinematica.ik.held_sweep import (
    HUG_G,
    MAX_CROSSINGS,
    ROUNDOFF_G,
    SWEEP_JUMP,
    TOUCH_G,
    crossings,
    touches,
)

pytestmark = pytest.mark.filterwarnings("ignore::kinematica.KinematicaWarning")

DATA = Path(__file__).parent.parent / "data"
PI = math.pi
#: Rows reach their target to this (m, rad).
FK_TOL = 1e-10


def _wrapped(d: np.ndarray) -> np.ndarray:
    return np.abs(np.remainder(d + PI, 2 * PI) - PI)


def _check(robot: km.Robot, res: km.IKResult, q: np.ndarray, T: np.ndarray, near: float) -> None:
    assert not res.method.startswith("numeric"), res.message
    rows = np.concatenate([res.solutions, res.out_of_limits])
    assert len(rows)
    F = robot.fk(rows)
    assert np.linalg.norm(F[:, :3, 3] - T[:3, 3], axis=1).max() <= FK_TOL
    assert max(km.rotation_angle(f[:3, :3], T[:3, :3]) for f in F) <= FK_TOL
    if res.status == "singular":  # on the continuum named: a free joint held there gives q
        j = res.free_joints[0]
        again = robot.ik(T, fixed={j: float(q[j])}, respect_limits=False)
        assert _wrapped(again.solutions - q).max(axis=1).min() <= 1e-6
    else:
        assert res.near_singular and not res.complete
        assert "nearly a continuum" in res.message
        assert _wrapped(rows - q).max(axis=1).min() <= near


def test_the_rm75_with_its_elbow_held() -> None:
    robot = km.load(str(DATA / "makers" / "realman_rm75.urdf"))
    rng = np.random.default_rng(0)
    for _ in range(2):
        q = rng.uniform(-1.5, 1.5, 7)
        T = robot.fk(q)
        res = robot.ik(T, fixed={3: float(q[3])}, respect_limits=False)
        assert res.method == "sweep:srs-neighbour", res.message
        # σ6/σ1 ≈ 1e-7: the rows are determined to about 1e-16 / 1e-7 rad
        _check(robot, res, q, T, 1e-6)


@pytest.mark.parametrize(("elbow", "near"), [(0.0, 1e-5), (0.05, 1e-6)])
def test_rtb_data_s_iiwa_urdf_with_its_elbow_held(elbow: float, near: float) -> None:
    robot = km.load(str(DATA / "urdf" / "kuka_lbr_iiwa_14_r820.urdf"))
    rng = np.random.default_rng(1)
    q = rng.uniform(-1.5, 1.5, 7)
    q[3] = elbow
    T = robot.fk(q)
    res = robot.ik(T, fixed={3: elbow}, respect_limits=False)
    # at q4 = 0 axes 3 and 5 are parallel 0.44 mm apart: σ6/σ1 ≈ 2e-11 at the solutions,
    # which are determined to about 1e-16 / 2e-11 rad (the configuration that made the
    # pose, 2.5e-6 rad from its row, is as exact)
    _check(robot, res, q, T, near)


# ------------------------------------------------------------ the crossing logic
def _branch(g: list[float]) -> list[np.ndarray]:
    """One branch over len(g) samples: joint 1 moves by 0.1 a sample, joint 0 is value + g."""
    return [np.array([[0.3 + gi, 0.1 * i]]) for i, gi in enumerate(g)]


def _never(t: float) -> np.ndarray:
    raise AssertionError("narrowed")


def _linear(g0: float, g1: float, t0: float, t1: float) -> Callable[[float], np.ndarray]:
    def at(t: float) -> np.ndarray:
        w = (t - t0) / (t1 - t0)
        return np.array([[0.3 + g0 + w * (g1 - g0), 0.1 * w]])

    return at


def test_a_branch_held_all_along_is_one_point_of_a_continuum() -> None:
    grid = np.linspace(-PI, PI, 4, endpoint=False)
    inside = crossings(_branch([0.5 * ROUNDOFF_G] * 4), grid, 0, 0.3, _never)
    assert len(inside) == 1
    outside = crossings(_branch([2 * ROUNDOFF_G, -2 * ROUNDOFF_G, 1.0, 1.0]), grid, 0, 0.3, _never)
    assert len(outside) == 1 and outside[0][0] != 0.3 + 0.5 * ROUNDOFF_G


@pytest.mark.parametrize(("g", "narrowed"), [(0.5 * HUG_G, False), (2 * HUG_G, True)])
def test_a_branch_hugging_the_value_is_not_narrowed(g: float, narrowed: bool) -> None:
    grid = np.linspace(-PI, PI, 4, endpoint=False)
    step = grid[1] - grid[0]
    calls: list[float] = []
    line = _linear(g, -g, grid[0], grid[0] + step)

    def at(t: float) -> np.ndarray:
        calls.append(t)
        return line(t)

    seeds = crossings(_branch([g, -g, 1.0, 1.0]), grid, 0, 0.3, at)
    assert len(seeds) >= 1
    assert bool(calls) is narrowed
    if narrowed:  # the crossing of the line, at the bracket's middle
        assert any(abs(s[0] - 0.3) <= ROUNDOFF_G for s in seeds)


def test_branches_link_within_the_jump() -> None:
    grid = np.linspace(-PI, PI, 2, endpoint=False)
    for jump, linked in ((0.9 * SWEEP_JUMP, True), (1.1 * SWEEP_JUMP, False)):
        rows = [np.array([[0.3 + 1e-3, 0.0]]), np.array([[0.3 - 1e-3, jump]])]
        line = _linear(1e-3, -1e-3, grid[0], grid[1])
        assert bool(crossings(rows, grid, 0, 0.3, line)) is linked


def test_crossings_everywhere_are_not_narrowed() -> None:
    n = 2 * (MAX_CROSSINGS + 1)
    grid = np.linspace(-PI, PI, n, endpoint=False)
    seeds = crossings(_branch([1e-4 * (-1) ** i for i in range(n)]), grid, 0, 0.3, _never)
    assert len(seeds) == MAX_CROSSINGS


@pytest.mark.parametrize(("g", "touch"), [(0.5 * TOUCH_G, True), (2 * TOUCH_G, False)])
def test_a_branch_touching_the_value_is_newton_s_start(g: float, touch: bool) -> None:
    rows = _branch([3 * TOUCH_G, g, 3 * TOUCH_G])
    assert (len(touches(rows, 0, 0.3)) == 1) is touch
