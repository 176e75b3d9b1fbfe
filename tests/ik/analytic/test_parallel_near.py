"""UR-type arms whose axes 2 and 3 are parallel only to within 5e-10 rad, near the aligned wrist.

Such an arm is near-degenerate: the family's closed form solves the exact arm
beside it and the check's repair carries each candidate to this arm's solution.
Near the family's singular sets that is not enough: with the wrist β rad from
aligned, this arm's solutions lie up to about 5e-10 / β from the exact arm's,
beyond the repair's reach once β is below about 1e-5, and at β = 0 the exact arm's
continuum is broken into isolated solutions anywhere along it. The general 6R's
candidates, which know this arm, join the family's (``solvers/near_6r.hpp``) where
the family's candidates lie within WATCH_FACTOR √(slack / size) of its singular sets
(or it calls the target near or singular).

Before (issue 32, item 4b): "ok" with 4 of 7 solutions and the generating
configuration missing, at most poses with β below 1e-5.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from numpy.typing import NDArray
from support.ik_pose_audit import check_complete
from support.ik_search import dls_solutions, found_tolerance, joint_distance
from support.parallel_arms import UR5_ROWS, assert_reaches, random_arm

from kinematica import _core, _core_testing
from kinematica.dh import Revolute
from kinematica.ik import closed_form
from kinematica.ik.analytic.parallel import LABELS
from kinematica.ik.structure import features
from kinematica.robot import Robot

pytestmark = pytest.mark.filterwarnings("ignore::kinematica.KinematicaWarning")

FloatArray = NDArray[np.float64]
PI = math.pi
ALPHA2 = 5e-10
WATCH_FACTOR = 100.0  # solvers/near_6r.hpp
#: How far the wrist is put from aligned (rad). Closer, this arm's σmin falls to about
#: 1e-11 (at 1e-9 rad), where configurations a radian apart meet the 1e-10 tolerances: a
#: continuum within them (test_at_the_aligned_wrist_...).
BETAS = (1e-8, 1e-7, 1e-6, 1e-5, 1e-4, 1e-3)


def tilted(robot: Robot) -> Robot:
    """``robot`` with α2 moved by 5e-10 (axes 2 and 3 parallel within tolerance only)."""
    links = list(robot.links)
    links[1] = dataclasses.replace(links[1], alpha=links[1].alpha + ALPHA2)
    return Robot.from_dh(links, convention=robot.convention, base=robot.base, tool=robot.tool)


def arms() -> list[Robot]:
    """The UR5, and a random arm of the family with axes 5 and 6 meeting and apart, each
    tilted (standard tables: α2 is the twist of axes 2 and 3)."""
    rng = np.random.default_rng(4)
    out = [tilted(Robot.from_dh(UR5_ROWS, convention="standard"))]
    out += [tilted(random_arm(rng, mode, square=True)) for mode in ("meet", "apart")]
    for robot in out:
        assert features(robot.chain).near_degenerate
    return out


def aligned_q5(robot: Robot) -> float:
    """The q5 at which axis 6 is parallel to axes 2-4: k·R5 h6 = D1 cos q5 + E1 sin q5
    + F1 reaches ±1 (its extremum, for these arms' ±90° twists)."""
    P = _core_testing.parallel.values(robot.chain.core)
    assert P is not None
    q5 = math.atan2(P["E1"], P["D1"])
    return q5 if abs(math.hypot(P["D1"], P["E1"]) + P["F1"] - 1.0) < 1e-9 else q5 + PI


def near_aligned(robot: Robot, rng: np.random.Generator, beta: float, n: int) -> FloatArray:
    q = rng.uniform(-PI, PI, (n, 6))
    q[:, 4] = aligned_q5(robot) + rng.choice([-1.0, 1.0], n) * beta
    return q


def test_a_near_degenerate_arm_gets_the_general_6r_candidates_too() -> None:
    robot = arms()[0]
    closed = closed_form(robot.chain, "pose")
    assert closed is not None and closed.name == "three-parallel-6R"
    assert isinstance(closed.params, _core.general6r.NearParallelParams)
    assert closed.labels[: len(LABELS)] == LABELS
    assert len(closed.labels) == closed.params.slots == 8 + _core_testing.general6r.SLOTS
    # an exact arm keeps the family's closed form alone
    exact = closed_form(Robot.from_dh(UR5_ROWS, convention="standard").chain, "pose")
    assert exact is not None and isinstance(exact.params, _core.parallel.ParallelParams)


@pytest.mark.parametrize("index", [0, 1, 2])
def test_near_the_aligned_wrist_the_generating_configuration_is_found(index: int) -> None:
    """q5 1e-8 to 1e-3 rad from aligned: every pose is answered by the closed form
    (ok, or singular where the wrist is within the continuum's tolerance), and an
    "ok" holds the generating q to what round-off allows there (found_tolerance)."""
    robot = arms()[index]
    rng = np.random.default_rng(index)
    for beta in BETAS:
        q = near_aligned(robot, rng, beta, 10)
        T = robot.fk(q)
        many = robot.ik(T, respect_limits=False)
        assert not many.methods  # no target left to the numeric search
        for i in range(len(q)):
            one = many[i]
            assert one.status in ("ok", "singular"), one.message
            assert_reaches(robot, one, T[i])
            if one.status == "ok":
                gap = float(joint_distance(robot, one.solutions, q[i]).min())
                assert gap <= found_tolerance(robot, q[i]), (beta, q[i].tolist(), gap)


@pytest.mark.parametrize("index", [0, 1, 2])
def test_near_the_aligned_wrist_no_solution_of_a_search_is_missed(index: int) -> None:
    """Every solution a 200-start search finds is one of ours, to what the conditioning
    at it allows (the pose audit's check c: 1e-6 + 2e-10 / σmin), and we give at least
    as many as it finds, at q5 1e-7 to 1e-3 rad from aligned."""
    robot = arms()[index]
    size = features(robot.chain).size
    rng = np.random.default_rng(10 + index)
    for beta in BETAS[1:]:
        q = near_aligned(robot, rng, beta, 1)[0]
        T = robot.fk(q)
        res = robot.ik(T, respect_limits=False)
        ref = dls_solutions(robot, T, rng)
        missed, _ = check_complete(robot, res.solutions, ref, size)
        assert not missed, (beta, q.tolist(), [m[0].tolist() for m in missed])
        assert res.count >= len(ref), (beta, q.tolist(), res.count, len(ref))


def test_at_the_aligned_wrist_the_answer_is_a_continuum_within_tolerance() -> None:
    """q5 exactly aligned (on the exact arm's continuum; this arm's Jacobian has σmin
    about 1e-11 there): no target is "unreachable" or left to the search; each answer is
    "singular" with q6 free (within the tolerances, a continuum), or "ok" and near."""
    robot = arms()[0]
    rng = np.random.default_rng(3)
    q = near_aligned(robot, rng, 0.0, 200)
    T = robot.fk(q)
    many = robot.ik(T, respect_limits=False)
    assert not many.methods
    assert set(many.status.tolist()) <= {"ok", "singular"}
    singular = many.status == "singular"
    assert many.free[singular][:, 5].all()
    assert many.near_singular[~singular].all()
    for i in range(0, 200, 17):
        assert_reaches(robot, many[i], T[i])


@pytest.mark.parametrize("a5", [0.0, 0.05])
def test_batch_equals_single(a5: float) -> None:
    rows = [*UR5_ROWS[:4], Revolute(d=0.09465, a=a5, alpha=-PI / 2), UR5_ROWS[5]]
    robot = tilted(Robot.from_dh(rows, convention="standard"))
    rng = np.random.default_rng(8)
    q = near_aligned(robot, rng, 1e-6, 20)
    T = robot.fk(q)
    many = robot.ik(T, respect_limits=False)
    for i in range(len(q)):
        one = robot.ik(T[i], respect_limits=False)
        b = many[i]
        assert (one.status, one.method, one.message, one.branches) == (
            b.status, b.method, b.message, b.branches,
        )  # fmt: skip
        np.testing.assert_array_equal(one.solutions, b.solutions)


@pytest.mark.parametrize(("factor", "runs"), [(0.5, True), (2.0, False)])
def test_watch_factor_runs_the_general_6r_within_its_margin(factor: float, runs: bool) -> None:
    """WATCH_FACTOR: the general 6R's candidates (slots 8 on) are computed where the
    family's candidates lie within watch = WATCH_FACTOR √(slack / size) of its singular
    sets, here the wrist factor · watch from aligned (the elbow and the pairs far from
    their folds), and not beyond; either way q is found."""
    robot = arms()[0]
    f = features(robot.chain)
    closed = closed_form(robot.chain, "pose")
    assert closed is not None
    P = closed.params
    assert _core_testing.general6r.WATCH_FACTOR == WATCH_FACTOR
    watch = _core_testing.general6r.watch(P)
    assert watch == pytest.approx(WATCH_FACTOR * math.sqrt(f.slack / f.size), rel=1e-15)
    q = np.array([0.4, -1.1, 1.3, -0.7, aligned_q5(robot) + factor * watch, 0.9])
    T = robot.fk(q)
    raw = np.asarray(P.candidates(robot.chain.core, T)[0])
    assert np.isfinite(raw[:8, 0]).sum() == 8  # the family's: every branch
    assert bool(np.isfinite(raw[8:, 0]).any()) is runs
    res = robot.ik(T, respect_limits=False)
    assert res.status == "ok"
    assert float(joint_distance(robot, res.solutions, q).min()) <= found_tolerance(robot, q)
