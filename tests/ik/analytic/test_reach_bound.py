"""The gap of a position target out of reach: a proven lower bound, as tight as the wrist allows.

Issue 35 item 11. The arm-position solver bounds the distance of a target to the
reachable tool origins from the shell of a point C on axis 4 (the wrist centre of a
spherical wrist) less a bound on |tool origin - C| (``km::decoupled::wrist_chain``); before, from
the shell of the tool origin at joints 4..n = 0 less twice a sum of link lengths.
Checked here against an independent measure of the distance (a bounded numeric
minimisation of |FK(q) - target| within the limits, from the best of dense samples),
on five arms and hundreds of targets: never above it, never below the old bound.
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest
from scipy.optimize import least_squares

import kinematica as km
from kinematica import _core_testing
from kinematica.ik.analytic import arm_position
from kinematica.ik.structure import features

#: The numeric minimum is the norm of a residual FK(q) - target: never below the true
#: distance but by round-off; a gap above it by more than this is a false claim.
ROUNDOFF = 1e-12
#: How close the minimisation comes to the true distance at a stretched (singular) arm,
#: where |FK(q) - target| is flat in q (2.1000004 m found for 2.1 m).
SAMPLING_ACCURACY = 1e-5

ARMS = ["arm6-dh", "puma560", "kr6", "ur5", "planar-3r"]


def _numeric_distance(robot: km.Robot, targets: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """``(N,)`` min over q within the limits of |FK(q) - target| (m), numerically."""
    Q = _configurations(robot, rng, 3000)
    lo, hi = np.asarray(robot.qlim, float).T
    P = np.asarray(robot.fk(Q))[:, :3, 3]
    out = np.empty(len(targets))
    for i, t in enumerate(targets):
        d = np.linalg.norm(P - t, axis=1)
        best = math.inf
        for start in Q[np.argsort(d)[:1]]:
            fit = least_squares(
                lambda q, t=t: np.asarray(robot.fk(q))[:3, 3] - t,
                start,
                bounds=(lo, hi),
                xtol=1e-12,
                ftol=1e-14,
                gtol=1e-14,
            )
            best = min(best, float(np.linalg.norm(fit.fun)))
        out[i] = best
    return out


def _old_gap(robot: km.Robot, target: np.ndarray) -> float:
    """The bound before: the tool origin's shell (joints 4..n at 0) less reach_after_joint3."""
    chain = robot.chain
    form = arm_position.build(chain, features(chain), "position")
    assert form is not None
    params = form.params
    arm = SimpleNamespace(**_core_testing.decoupled.arm_point_values(params.arm))
    d = target - np.asarray(arm.p1)
    r, zeta = float(np.linalg.norm(d)), float(d @ np.asarray(arm.h1))
    shell = max(0.0, r - arm.r_hi, arm.r_lo - r, zeta - arm.z_hi, arm.z_lo - zeta)
    return max(0.0, shell - _core_testing.decoupled.reach_after_joint3(chain.core))


def _targets(robot: km.Robot, rng: np.random.Generator, n: int) -> np.ndarray:
    """``(n, 3)`` targets 1.02 to 2.5 times the farthest sampled tool origin from the base."""
    P = np.asarray(robot.fk(_configurations(robot, rng, 2000)))[:, :3, 3]
    far = float(np.max(np.linalg.norm(P, axis=1)))
    u = rng.normal(size=(n, 3))
    u /= np.linalg.norm(u, axis=1, keepdims=True)
    return u * far * rng.uniform(1.02, 2.5, (n, 1))


def _configurations(robot: km.Robot, rng: np.random.Generator, n: int) -> np.ndarray:
    """``(n, dof)`` uniform within the limits (a joint without limits: one turn)."""
    lo, hi = np.asarray(robot.qlim, float).T
    lo = np.where(np.isfinite(lo), lo, -math.pi)
    hi = np.where(np.isfinite(hi), hi, math.pi)
    return rng.uniform(lo, hi, (n, robot.dof))


def test_seed_arm_point_gap_is_the_exact_distance() -> None:
    """(3, 0, 0.5) on the seed arm: 2.1 m, by hand.

    Axes 1 and 2 meet at the shoulder (0, 0, l1) = (0, 0, 0.5); the wrist centre lies
    within l2 + l3 = 0.8 of it, the tool origin l4 = 0.1 from the wrist centre: every
    reachable point is within 0.9 of the shoulder, and the arm stretched along +x
    (no limits) reaches (0.9, 0, 0.5). The target is 3 m from the shoulder:
    3 - 0.9 = 2.1 m exactly. The bound before was 1.9 (the shell of the tool origin,
    0.9, less twice l4).
    """
    robot = km.load("arm6-dh")
    target = np.array([3.0, 0.0, 0.5])
    res = robot.ik(target)
    assert res.status == km.ik.IKStatus.UNREACHABLE
    assert res.gap == pytest.approx(2.1, abs=1e-12)
    assert _old_gap(robot, target) == pytest.approx(1.9, abs=1e-12)
    rng = np.random.default_rng(11)
    assert _numeric_distance(robot, target[None], rng)[0] == pytest.approx(
        2.1, abs=SAMPLING_ACCURACY
    )


@pytest.mark.parametrize("name", ARMS)
def test_gap_is_proven_and_no_looser_than_before(name: str) -> None:
    rng = np.random.default_rng(35 + len(name))
    robot = km.load(name)
    targets = _targets(robot, rng, 50)
    truth = _numeric_distance(robot, targets, rng)
    gaps = np.array([robot.ik(t).gap for t in targets], dtype=float)
    assert np.all(np.isfinite(gaps)) and np.all(gaps > 0.0)
    assert np.all(gaps <= truth + ROUNDOFF), np.max(gaps - truth)
    if name != "planar-3r":
        old = np.array([_old_gap(robot, t) for t in targets])
        assert np.all(gaps >= old - 1e-12)


def test_seed_arm_gaps_are_exact() -> None:
    """Every target beyond the seed arm's reach: |target - shoulder| - 0.9 (see above)."""
    robot = km.load("arm6-dh")
    rng = np.random.default_rng(3)
    targets = _targets(robot, rng, 40)
    shoulder = np.array([0.0, 0.0, 0.5])
    expected = np.linalg.norm(targets - shoulder, axis=1) - 0.9
    gaps = np.array([robot.ik(t).gap for t in targets], dtype=float)
    np.testing.assert_allclose(gaps, expected, rtol=0.0, atol=1e-12)


# PARALLEL_SIN2's documented value, a literal (a test reading the constant would move with it).
PARALLEL_SIN2 = 1e-12


def test_parallel_sin2_value() -> None:
    assert _core_testing.decoupled.PARALLEL_SIN2 == PARALLEL_SIN2


@pytest.mark.parametrize(("factor", "parallel"), [(0.1, True), (10.0, False)])
def test_parallel_sin2_boundary(factor: float, parallel: bool) -> None:
    """Two lines at sine² a factor off PARALLEL_SIN2: the point of the first chosen.

    Line 1 is the z axis; line 2 passes through (1, 0, 0) at angle ε to it in a plane
    x = 1: their common perpendicular is the x axis, its foot on line 1 the origin.
    Treated as parallel, the point of line 1 nearest x = (0, 0, 5) is x itself.
    """
    eps = math.sqrt(factor * PARALLEL_SIN2)
    foot = _core_testing.decoupled.nearest_foot(
        np.zeros(3),
        np.array([0.0, 0.0, 1.0]),
        np.array([1.0, 0.0, 0.0]),
        np.array([0.0, math.sin(eps), math.cos(eps)]),
        np.array([0.0, 0.0, 5.0]),
    )
    expected = [0.0, 0.0, 5.0] if parallel else [0.0, 0.0, 0.0]
    np.testing.assert_allclose(foot, expected, atol=1e-9)
