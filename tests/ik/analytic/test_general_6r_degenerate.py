"""The general 6R solver where its method degenerates: a continuum and a fold.

A continuum is built from the geometry, independently of the solver: a configuration
where joint 6's axis lies on joint 1's line (Gauss-Newton on q2..q5 over the axes'
Plücker coordinates from the Jacobian's columns). There, turning joint 1 by t and joint
6 by -t (+t when the axes point opposite ways) holds the pose: infinitely many
solutions, q1 and q6 free. A fold is a configuration where the Jacobian's determinant
changes sign along joint 3 (bisection): two solution branches meet there. The
self-motion test's tolerances (general_6r.hpp) are each met from both sides.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from support.general6r import G, labelling
from support.ik_search import joint_distance

import kinematica as km
from kinematica.ik.analytic import general_6r as g6

pytestmark = pytest.mark.filterwarnings("ignore::kinematica.KinematicaWarning")

#: Every solution's FK reaches its target to this (m, rad).
FK_TOL = 1e-10
#: Just inside / just outside a boundary: the tolerance times (1 ∓ this).
EDGE = 1e-3

# The documented values (general_6r.hpp), which the boundary cases below are made from.
SINGULAR_RANK_TOL = 1e-7
SELF_MOTION_STEP = 1e-2
SELF_MOTION_STEPS = 8
SELF_MOTION_TOL = 1e-12
FREE_JOINT_TOL = 1e-8


def _robot(seed: int) -> km.Robot:
    arm = g6.sample_arm(np.random.default_rng(seed), False)
    return km.Robot.from_dh(arm.links, convention=arm.convention, base=arm.base, tool=arm.tool)


def _wrapped(q: np.ndarray) -> np.ndarray:
    return np.remainder(q + math.pi, 2 * math.pi) - math.pi


def _axes(robot: km.Robot, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(z, m) (6, 3): each joint axis's direction and moment o × z at q (base frame)."""
    J = robot.jacobian(q)
    z = J[3:].T
    return z, J[:3].T + np.cross(robot.fk(q)[:3, 3], z)  # z × (p - o) + p × z = o × z


def _coaxial(robot: km.Robot, rng: np.random.Generator, count: int) -> list[tuple[Any, float]]:
    """``count`` configurations (q, s) with axis 6 on axis 1's line, s = ±1 their sense."""
    found: list[tuple[Any, float]] = []
    while len(found) < count:
        q, s = rng.uniform(-math.pi, math.pi, 6), float(rng.choice([-1.0, 1.0]))

        def f(x: np.ndarray, s: float = s) -> np.ndarray:
            z, m = _axes(robot, x)
            return np.concatenate([z[5] - s * z[0], m[5] - s * m[0]])

        for _ in range(30):
            r = f(q)
            if np.abs(r).max() < 1e-14:
                break
            D = np.stack([(f(q + 1e-7 * e) - r) / 1e-7 for e in np.eye(6)[1:5]], axis=1)
            q[1:5] -= np.linalg.lstsq(D, r, rcond=None)[0]
        if np.abs(f(q)).max() < 1e-13:
            found.append((_wrapped(q), s))
    return found


def _fold(robot: km.Robot, rng: np.random.Generator) -> np.ndarray:
    """A configuration where det J changes sign along joint 3 (bisection to round-off)."""
    while True:
        q = rng.uniform(-math.pi, math.pi, 6)

        def det(t: float, q: np.ndarray = q) -> float:
            x = q.copy()
            x[2] = t
            return float(np.linalg.det(robot.jacobian(x)))

        ts = np.linspace(-math.pi, math.pi, 25)
        dets = [det(t) for t in ts]
        for i in range(24):
            if dets[i] * dets[i + 1] < 0:
                lo, hi, dlo = ts[i], ts[i + 1], dets[i]
                for _ in range(60):
                    mid = 0.5 * (lo + hi)
                    if det(mid) * dlo > 0:
                        lo = mid
                    else:
                        hi = mid
                q[2] = 0.5 * (lo + hi)
                return q


def _params(robot: km.Robot, start: int, reverse: bool) -> Any:
    """Params of one labelling (not the cached solver's: the builder's choice may change)."""
    built = labelling(robot.chain, start, reverse)
    assert built is not None
    return built[0]


def test_the_documented_values_are_the_core_s() -> None:
    assert G.SINGULAR_RANK_TOL == SINGULAR_RANK_TOL
    assert (G.SELF_MOTION_STEP, G.SELF_MOTION_STEPS) == (SELF_MOTION_STEP, SELF_MOTION_STEPS)
    assert G.SELF_MOTION_TOL == SELF_MOTION_TOL
    assert G.FREE_JOINT_TOL == FREE_JOINT_TOL
    assert G.DEGENERACY == ("regular", "fold", "continuum")


def test_a_continuum_is_singular_with_its_free_joints_named() -> None:
    # whichever path answers (the elimination's candidate or, where its pencil is
    # singular and no candidate closes, the numeric search), never a finite "ok"
    robot = _robot(0)
    found = _coaxial(robot, np.random.default_rng(0), 3)
    poses = robot.fk(np.array([q for q, _ in found]))
    batch = robot.ik(poses)
    for i, (q, s) in enumerate(found):
        res = robot.ik(poses[i])
        assert res.status == "singular", res.message
        assert res.free_joints == (0, 5)
        assert "q1, q6 free" in res.message
        assert batch[i].status == "singular" and batch[i].free_joints == (0, 5)
        assert res.count >= 1
        for sol in res.solutions:
            # a representative of this family: q2..q5 those of the configuration built
            assert np.abs(_wrapped(sol[1:5] - q[1:5])).max() <= 1e-9
            for t in (0.0, 0.7, -2.0):  # moving the free joints along it keeps the pose
                moved = sol + t * np.array([1.0, 0, 0, 0, 0, -s])
                F = robot.fk(moved)
                assert np.linalg.norm(F[:3, 3] - poses[i][:3, 3]) <= FK_TOL
                assert km.rotation_angle(F[:3, :3], poses[i][:3, :3]) <= FK_TOL


def test_the_elimination_never_says_ok_at_a_continuum() -> None:
    # The forward labelling (q'6 = q6, free): its candidates on the continuum say
    # singular with q1, q6 free; where none closes the loop, near (the search answers)
    robot = _robot(0)
    params = _params(robot, 0, False)
    verdicts = []
    for q, _ in _coaxial(robot, np.random.default_rng(0), 3):
        singular, near, free, rank, reclosure = G.degeneracy(params, robot.fk(q))
        verdicts.append(singular)
        assert singular or near
        if singular:
            assert free == 0b100001 and not near
            assert rank < 1e-15 and reclosure < 1e-14
    assert any(verdicts)


def test_the_test_at_a_continuum_names_the_joints_that_move() -> None:
    robot = _robot(0)
    params = _params(robot, 0, False)
    q, _ = _coaxial(robot, np.random.default_rng(1), 1)[0]
    verdict, rank, reclosure, moved, free = G.self_motion(params, robot.fk(q), q)
    assert G.DEGENERACY[verdict] == "continuum" and free == 0b100001
    assert rank < 1e-15 and reclosure < 1e-14
    # the step along the null direction (1, 0, 0, 0, 0, ∓1) / √2, exactly
    assert moved[[0, 5]] == pytest.approx(SELF_MOTION_STEP / math.sqrt(2), rel=1e-9)
    assert moved[1:5].max() < 1e-13
    with pytest.raises(ValueError, match="CLOSURE_TOL"):
        G.self_motion(params, robot.fk(q), q + 1e-3)


def test_a_fold_is_found_with_near_raised() -> None:
    robot = _robot(0)
    q = _fold(robot, np.random.default_rng(2))
    T = robot.fk(q)
    res = robot.ik(T)
    assert res.status == "ok" and res.near_singular and res.free_joints == ()
    # the double root found (to √ε: a fold's), every solution exact
    assert joint_distance(robot, res.solutions, q).min() <= 1e-6
    for sol in res.solutions:
        F = robot.fk(sol)
        assert np.linalg.norm(F[:3, 3] - T[:3, 3]) <= FK_TOL
        assert km.rotation_angle(F[:3, :3], T[:3, :3]) <= FK_TOL
    verdict, rank, reclosure, _, free = G.self_motion(_params(robot, 0, False), T, q)
    assert G.DEGENERACY[verdict] == "fold" and free == 0
    assert rank < SINGULAR_RANK_TOL and reclosure > 1e3 * SELF_MOTION_TOL


def _rodrigues(w: np.ndarray) -> np.ndarray:
    """The rotation matrix of the rotation vector w (rad)."""
    th = float(np.linalg.norm(w))
    K = np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]]) / th
    return np.eye(3) + math.sin(th) * K + (1 - math.cos(th)) * K @ K


def _secant(f: Any, target: float, x: float) -> float:
    """x with f(x) = target to 1e-5 relative (f about proportional to x)."""
    for _ in range(30):
        now = f(x)
        if abs(now / target - 1.0) < 1e-5:
            return x
        x *= target / now
    raise AssertionError(f"no x gives {target}")


def test_singular_rank_tol_separates_a_fold_from_a_regular_solution() -> None:
    # q moved off the fold along joint 3 by t: σ6/σ1 about proportional to t; just
    # below the tolerance the test runs (a fold), just above the solution is regular
    robot = _robot(0)
    params = _params(robot, 0, False)
    qf = _fold(robot, np.random.default_rng(2))

    def at(t: float) -> tuple[int, float]:
        q = qf.copy()
        q[2] += t
        verdict, rank, *_ = G.self_motion(params, robot.fk(q), q)
        return verdict, rank

    t = _secant(lambda t: at(t)[1], SINGULAR_RANK_TOL, 1e-7)
    below, above = at(t * (1 - 10 * EDGE)), at(t * (1 + 10 * EDGE))
    assert below[1] < SINGULAR_RANK_TOL < above[1]
    assert G.DEGENERACY[below[0]] == "fold" and G.DEGENERACY[above[0]] == "regular"


def test_self_motion_tol_bounds_how_far_a_target_may_be_from_a_continuum() -> None:
    # The target moved off the continuum by eps along the direction the Jacobian cannot
    # reach (its left null vector): the re-closure's miss is about eps; just below the
    # tolerance a continuum, just above none (a fold's verdict)
    robot = _robot(0)
    params = _params(robot, 0, False)
    q, _ = _coaxial(robot, np.random.default_rng(1), 1)[0]
    T0 = robot.fk(q)
    u = np.linalg.svd(robot.jacobian(q))[0][:, -1]

    def test(eps: float) -> tuple[int, float]:
        T = T0.copy()
        T[:3, 3] += eps * u[:3]
        T[:3, :3] = _rodrigues(eps * u[3:]) @ T0[:3, :3]
        verdict, _, reclosure, _, _ = G.self_motion(params, T, q)
        return verdict, reclosure

    eps = _secant(lambda e: test(e)[1], SELF_MOTION_TOL, SELF_MOTION_TOL)
    inside, outside = test(eps * (1 - 10 * EDGE)), test(eps * (1 + 10 * EDGE))
    assert inside[1] <= SELF_MOTION_TOL < outside[1]
    assert G.DEGENERACY[inside[0]] == "continuum" and G.DEGENERACY[outside[0]] == "fold"


def test_free_joint_tol_is_the_move_that_makes_a_joint_free() -> None:
    # the decision at its boundary, and the margins on a continuum: the joints held
    # there stay below it by orders, those that move pass it by orders
    assert G.moves(FREE_JOINT_TOL * (1 + EDGE)) and not G.moves(FREE_JOINT_TOL * (1 - EDGE))
    robot = _robot(0)
    q, _ = _coaxial(robot, np.random.default_rng(1), 1)[0]
    moved = G.self_motion(_params(robot, 0, False), robot.fk(q), q)[3]
    assert moved[1:5].max() < 1e-4 * FREE_JOINT_TOL < 1e4 * FREE_JOINT_TOL < moved[[0, 5]].min()
