"""Elbow 3R arms whose axes 2 and 3 are parallel only to within 5e-10 rad, at the elbow's fold.

Such an arm is solved by the closed form of the exact elbow arm beside it, each
candidate carried to this arm's solution by the check's repair (Gauss-Newton steps,
``check.hpp``). At the stretched or folded elbow the two elbow branches meet: the
arm's Jacobian loses rank there, and the exact arm beside it sees the branches
merge or vanish (the target out of its reach by up to the slack, m). Position
targets made by FK with q3 at the fold or up to 1e-4 rad off it must give the
generating configuration to what round-off allows (``found_tolerance``: 1e-13 /
σmin, or √(2e-13 / κ) at the fold), and both branches where they are apart.

Before (issue 32, item 4c): the repair's constant damping stalled 1e-6 to 2e-4 rad
from the fold's solution (within the tolerance's residual), and where the exact arm
saw one merged branch only one of the real arm's two was found.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.typing import NDArray
from support.ik_search import dls_solutions, found_tolerance, joint_distance

import kinematica as km
from kinematica.ik.structure import features

pytestmark = pytest.mark.filterwarnings("ignore::kinematica.KinematicaWarning")

FloatArray = NDArray[np.float64]
PI = math.pi
ALPHA2 = 5e-10
#: Position (m) every solution reaches (the default tolerance).
TOL = 1e-10
#: How far q3 is put off the fold (rad).
OFFSETS = (0.0, 1e-12, 1e-10, 1e-8, 1e-6, 1e-4)


#: Elbow arms with α2 = 5e-10 (DH rows, standard) and a tool off the last axis (m): two
#: anthropomorphic ones and two with a shoulder offset, on which the repair stalled.
ARMS: dict[str, tuple[list[km.Revolute], tuple[float, float, float]]] = {
    "anthropomorphic": (
        [
            km.Revolute(d=0.45, alpha=PI / 2),
            km.Revolute(d=-0.06, a=0.51, alpha=ALPHA2),
            km.Revolute(d=0.14, a=0.49, alpha=0.19),
        ],
        (0.1, 0.09, -0.01),
    ),
    "anthropomorphic, twisted wrist": (
        [
            km.Revolute(d=0.38, alpha=PI / 2),
            km.Revolute(d=0.03, a=0.46, alpha=ALPHA2),
            km.Revolute(d=-0.2, a=0.47, alpha=1.87),
        ],
        (-0.04, -0.19, -0.1),
    ),
    "offset": (
        [
            km.Revolute(d=0.41, a=0.18, alpha=-PI / 2),
            km.Revolute(d=-0.06, a=0.31, alpha=PI + ALPHA2),
            km.Revolute(d=0.03, a=0.34, alpha=0.88),
        ],
        (-0.06, -0.02, 0.19),
    ),
    "offset, long links": (
        [
            km.Revolute(d=0.45, a=0.14, alpha=-PI / 2),
            km.Revolute(d=0.08, a=0.56, alpha=PI + ALPHA2),
            km.Revolute(d=0.06, a=0.46, alpha=1.05),
        ],
        (0.09, -0.01, 0.03),
    ),
}


def arm(name: str) -> km.Robot:
    """The robot of ``ARMS[name]``."""
    rows, at = ARMS[name]
    tool = np.eye(4)
    tool[:3, 3] = at
    robot = km.Robot.from_dh(rows, tool=tool, convention="standard")
    kind = "anthropomorphic-3R" if name.startswith("anthropomorphic") else "elbow-3R"
    assert km.classify(robot).kind == kind
    assert features(robot.chain).near_degenerate
    return robot


def fold_of(robot: km.Robot, folded: bool) -> float:
    """q3 (rad) where the exact arm beside this one is stretched (or folded): links 2
    and 3 in line in the plane normal to axis 2 (axis 2 to axis 3, axis 3 to the tool)."""
    f = features(robot.chain)
    h, p = f.directions, f.points
    k = h[1] / np.linalg.norm(h[1])
    x = robot.fk(np.zeros(3))[:3, 3]
    a, b = p[2] - p[1], x - p[2]
    a, b = a - (a @ k) * k, b - (b @ k) * k  # in the plane normal to k
    psi0 = math.atan2(float(k @ np.cross(a, b)), float(a @ b))
    s3 = 1.0 if float(h[2] @ k) > 0.0 else -1.0
    return s3 * (-psi0 + (PI if folded else 0.0))


def configurations(fold: float) -> FloatArray:
    """``(k, 3)`` q with q3 at ``fold`` plus each offset (both signs), q1, q2 at random."""
    rng = np.random.default_rng(int(abs(fold) * 1000) + 7)
    rows = []
    for off in OFFSETS:
        for sign in (1.0, -1.0):
            q = rng.uniform(-PI, PI, 3)
            q[2] = fold + sign * off
            rows.append(q)
    return np.array(rows)


@pytest.mark.parametrize("name", list(ARMS))
@pytest.mark.parametrize("folded", [False, True])
def test_the_generating_configuration_is_found_at_the_fold(name: str, folded: bool) -> None:
    robot = arm(name)
    q = configurations(fold_of(robot, folded))
    p = np.ascontiguousarray(robot.fk(q)[:, :3, 3])
    many = robot.ik(p, respect_limits=False)
    for i in range(len(q)):
        one = many[i]
        assert one.status == "ok", (q[i].tolist(), one.message)
        reached = robot.fk(one.solutions)[:, :3, 3]
        assert np.linalg.norm(reached - p[i], axis=-1).max() <= TOL
        gap = float(joint_distance(robot, one.solutions, q[i]).min())
        assert gap <= found_tolerance(robot, q[i], position=True), (q[i].tolist(), gap)


def solved(robot: km.Robot, ref: FloatArray, p: FloatArray) -> FloatArray:
    """The search's answers ``ref`` (stopped at 1e-10) taken to round-off by Gauss-Newton
    steps on the position: those that get there (beside a fold some only crawl)."""
    out = []
    for x in ref:
        for _ in range(30):
            x = x + np.linalg.lstsq(robot.jacobian(x)[:3], p - robot.fk(x)[:3, 3], rcond=None)[0]
        if np.linalg.norm(robot.fk(x)[:3, 3] - p) <= 1e-14:
            out.append(x)
    return np.array(out).reshape(-1, robot.dof)


@pytest.mark.parametrize("name", ["anthropomorphic", "offset"])
def test_both_branches_beside_the_fold_are_found(name: str) -> None:
    """q3 1e-6 and 1e-4 rad off the fold: the other branch (q3 about as far on the
    other side) is a solution too. The target has four (two shoulders, two elbows),
    which a 200-start search finds (its answers, stopped at 1e-10, taken to round-off
    by Gauss-Newton steps): each is one of ours to its ``found_tolerance``."""
    robot = arm(name)
    rng = np.random.default_rng(5)
    for folded in (False, True):
        for off in (1e-6, -1e-6, 1e-4, -1e-4):
            q = rng.uniform(-PI, PI, 3)
            q[2] = fold_of(robot, folded) + off
            p = robot.fk(q)[:3, 3]
            res = robot.ik(p, respect_limits=False)
            assert res.count == 4, (q.tolist(), res.solutions.tolist())
            for x in solved(robot, dls_solutions(robot, p, rng), p):
                near = float(joint_distance(robot, res.solutions, x).min())
                assert near <= found_tolerance(robot, x, position=True), (q.tolist(), x.tolist())


def height_equation(robot: km.Robot, q: FloatArray) -> tuple[float, float, float]:
    """A, B, e of the exact arm's height equation A cos θ + B sin θ = e (θ = -q1) for the
    target fk(q) (``elbow.hpp``'s height())."""
    f = features(robot.chain)
    h1 = f.directions[0] / np.linalg.norm(f.directions[0])
    k = f.directions[1] / np.linalg.norm(f.directions[1])
    p1 = f.points[0]
    height = float(k @ (robot.fk(np.zeros(3))[:3, 3] - p1))  # the tool's height over axis 1
    v = robot.fk(q)[:3, 3] - p1
    kh, hv = float(k @ h1), float(h1 @ v)
    return float(k @ v) - kh * hv, -float(np.cross(h1, k) @ v), height - kh * hv


def merge_margin(robot: km.Robot, q: FloatArray) -> float:
    """hypot(A, B) - |e| (m): the height equation's two roots (the shoulders) merge at 0."""
    A, B, e = height_equation(robot, q)
    return math.hypot(A, B) - abs(e)


def at_merge_margin(robot: km.Robot, q: FloatArray, margin: float) -> FloatArray:
    """q with q2 moved until merge_margin is ``margin`` (m): where the equation's slope
    at the root θ = -q1, s = B cos θ - A sin θ, is √(2 hypot(A, B) margin) (margin about
    s² / (2 hypot(A, B))), by bisection across its sign change."""

    def slope(x: float) -> float:
        A, B, _ = height_equation(robot, np.array([q[0], x, q[2]]))
        return B * math.cos(q[0]) + A * math.sin(q[0])  # θ = -q1

    def f(x: float) -> float:
        A, B, _ = height_equation(robot, np.array([q[0], x, q[2]]))
        return slope(x) - math.sqrt(2.0 * math.hypot(A, B) * margin)

    grid = np.linspace(-PI, PI, 721)
    values = [f(x) for x in grid]
    i = next(i for i in range(720) if values[i] * values[i + 1] < 0.0)
    lo, hi = float(grid[i]), float(grid[i + 1])
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if (f(mid) < 0.0) == (values[i] < 0.0) else (lo, mid)
    return np.array([q[0], 0.5 * (lo + hi), q[2]])


@pytest.mark.parametrize("name", ["anthropomorphic", "offset"])
def test_both_shoulders_beside_their_merge_are_found(name: str) -> None:
    """The exact arm's height equation (q1) is known to within the slack too (about 1e-9
    m here): where its two roots merge to within it (the tool at the edge of the heights
    it reaches about axis 1), they are proposed apart, one on each side. Targets whose
    roots are 1e-13..1e-10 m from merging (hypot(A, B) - |e|, on the exact arm): the
    generating q and every solution of a 200-start search (taken to round-off) among
    ours to found_tolerance. Before, 22 of these 42 targets lost one."""
    robot = arm(name)
    rng = np.random.default_rng(9)
    for margin in (1e-13, 1e-12, 1e-11, 1e-10):
        for _ in range(6):
            try:
                q = at_merge_margin(robot, rng.uniform(-PI, PI, 3), margin)
            except StopIteration:  # q3 whose q2 does not reach the merge
                continue
            p = robot.fk(q)[:3, 3]
            res = robot.ik(p, respect_limits=False)
            for x in (q, *solved(robot, dls_solutions(robot, p, rng), p)):
                near = float(joint_distance(robot, res.solutions, x).min())
                assert near <= found_tolerance(robot, x, position=True), (q.tolist(), x.tolist())
