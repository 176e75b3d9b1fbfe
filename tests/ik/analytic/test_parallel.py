"""Closed-form IK of UR-type arms (axes 2-3-4 parallel): all solutions, exact.

Independent references: EAIK's solution sets for the UR5
(``data/reference/ik_reference.json``), forward kinematics of every solution,
the product-of-exponentials identity the solver is built on, the branch
definitions checked on the arm's own frames, and the numeric solver started
from 200 random configurations (completeness).
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from numpy.typing import NDArray
from support import DATA
from support.helpers import assert_transform_close
from support.parallel_arms import (
    MODES,
    PI,
    UR5,
    UR5_A5,
    UR5_P56,
    UR5_ROWS,
    assert_honest_batch,
    assert_reaches,
    joint_gap,
    random_arm,
)

import kinematica as km
from kinematica import _core
from kinematica.dh import Prismatic, Revolute
from kinematica.ik.analytic.parallel import DEGENERATE, GENERAL_LABELS, LABELS, SPEC
from kinematica.ik.result import IKBatchResult
from kinematica.ik.structure import features
from kinematica.robot import Robot, classify

FloatArray = NDArray[np.float64]
REFERENCE = DATA / "reference" / "ik_reference.json"


def solve_all(robot: Robot, T: FloatArray) -> IKBatchResult:
    """Every solution of poses ``T (N, 4, 4)``, limits ignored."""
    many = robot.ik(T, respect_limits=False)
    assert isinstance(many, IKBatchResult)
    assert many.method == "analytic:three-parallel-6R"
    return many


def exp_twist(h: FloatArray, p: FloatArray, q: float) -> FloatArray:
    """Rotation by ``q`` about the line ``(h, p)``, 4x4 (Rodrigues, written here)."""
    K = np.array([[0, -h[2], h[1]], [h[2], 0, -h[0]], [-h[1], h[0], 0]])
    R = np.eye(3) + math.sin(q) * K + (1 - math.cos(q)) * K @ K
    E = np.eye(4)
    E[:3, :3] = R
    E[:3, 3] = p - R @ p
    return E


# ----------------------------------------------------------- the model it uses
@pytest.mark.parametrize("mode", MODES)
def test_product_of_exponentials_is_the_forward_kinematics(mode: str) -> None:
    rng = np.random.default_rng(1)
    for modified in (False, True):
        robot = random_arm(rng, mode, modified)
        h, p = robot.joint_axes()
        M = robot.fk(np.zeros(6))
        for q in rng.uniform(-PI, PI, (10, 6)):
            T = np.linalg.multi_dot([*(exp_twist(h[i], p[i], q[i]) for i in range(6)), M])
            assert_transform_close(T, robot.fk(q), atol=1e-12)


def test_builder_modes() -> None:
    """Axes 5 and 6 meeting, parallel or apart: the solver's mode and the labels."""
    for robot, mode, labels in ((UR5, 0, LABELS), (UR5_P56, 1, GENERAL_LABELS)):
        chain = robot.chain
        params = _core.parallel.build(chain.core)
        assert params is not None and params.mode == mode
        built = SPEC.build(chain, features(chain), "pose")
        assert built is not None and built.labels == labels
    params = _core.parallel.build(UR5_A5.chain.core)
    assert params is not None and params.mode == 2
    assert SPEC.build(UR5.chain, features(UR5.chain), "position") is None


# ---------------------------------------------------------------------- UR5
def test_ur5_round_trip() -> None:
    rng = np.random.default_rng(10)
    q = rng.uniform(-PI, PI, (2000, 6))
    many = solve_all(UR5, UR5.fk(q))
    assert set(many.status.tolist()) == {"ok"}
    assert all(joint_gap(many.solutions[i, : many.count[i]], q[i]) < 1e-9 for i in range(2000))
    assert set(many.count.tolist()) <= {2, 4, 6, 8} and (many.count == 8).mean() > 0.6
    reached = UR5.fk(np.nan_to_num(many.solutions))
    real = ~np.isnan(many.solutions[..., 0])
    want = np.broadcast_to(UR5.fk(q)[:, None], reached.shape)
    assert_transform_close(reached[real], want[real], atol=1e-12)


def test_ur5_matches_eaik_reference_solution_sets() -> None:
    arms = {a["name"]: a for a in json.loads(REFERENCE.read_text())["arms"]}
    ref = arms["ur5"]
    robot = Robot.from_dh(
        [Revolute(d=j["d"], a=j["a"], alpha=j["alpha"], offset=j["theta"]) for j in ref["joints"]],
        convention="standard",
    )
    assert_transform_close(robot.fk(np.zeros(6)), UR5.fk(np.zeros(6)), atol=0)
    T = np.array([s["T"] for s in ref["samples"]])
    many = solve_all(robot, T)
    for i, sample in enumerate(ref["samples"]):
        ours = many.solutions[i, : many.count[i]]
        theirs = np.array(sample["solutions"]).reshape(-1, 6)
        assert len(ours) == len(theirs), f"sample {i}"
        for s in theirs:  # same set modulo 2π
            assert joint_gap(ours, s) < 1e-9, f"sample {i}: missed {s}"
        assert joint_gap(ours, np.array(sample["q_generating"])) < 1e-9


def test_ur5_labels_mean_what_they_say() -> None:
    """Each branch label, checked on the arm's own frames at its solutions."""
    rng = np.random.default_rng(11)
    many = solve_all(UR5, UR5.fk(rng.uniform(-PI, PI, (300, 6))))
    for label in LABELS:
        q = many.solutions[many.branches == label]
        assert len(q) > 50, label
        h, p = UR5.joint_axes(q)
        frames = UR5.fk(q, all_frames=True)
        h1, k1, h5, h6 = h[:, 0], h[:, 1], h[:, 4], h[:, 5]
        c = frames[:, 5, :3, 3]  # UR5 DH frame 5 sits where axes 5 and 6 meet
        sigma = np.einsum("ij,ij->i", c - p[:, 0], np.cross(h1, k1))
        assert ((sigma >= -1e-12) if "right" in label else (sigma <= 1e-12)).all(), label
        wrist = np.einsum("ij,ij->i", np.cross(k1, h6), h5)
        assert ((wrist >= -1e-12) if "no-flip" in label else (wrist <= 1e-12)).all(), label
        sin5 = np.sin(q[:, 4])  # for the UR5's table, "no-flip" is sin q5 >= 0
        assert ((sin5 >= -1e-12) if "no-flip" in label else (sin5 <= 1e-12)).all(), label
        s, e, w = p[:, 1], p[:, 2], p[:, 3]  # points on axes 2, 3, 4

        def across(x: FloatArray, k1: FloatArray = k1) -> FloatArray:
            return x - np.einsum("ij,ij->i", x, k1)[:, None] * k1

        n = np.cross(k1, across(w - s))
        up = np.einsum("ij,ij->i", across(e - s), n) * np.einsum("ij,ij->i", h1, n)
        assert ((up >= -1e-12) if "up" in label else (up <= 1e-12)).all(), label


def test_general_labels_order_roots_by_q1() -> None:
    rng = np.random.default_rng(12)
    for robot in (UR5_A5, UR5_P56):
        many = solve_all(robot, robot.fk(rng.uniform(-PI, PI, (100, 6))))
        assert set(many.branches[many.count > 0].ravel().tolist()) <= {*GENERAL_LABELS, ""}
        for i in range(100):
            roots = {}
            for b, q in zip(many.branches[i], many.solutions[i], strict=True):
                if b:
                    roots.setdefault(b.split(",")[0], q[0])
            q1 = [roots[k] for k in sorted(roots)]
            assert q1 == sorted(q1)


# --------------------------------------------------------------- random arms
@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("modified", [False, True])
def test_random_arms_round_trip(mode: str, modified: bool) -> None:
    rng = np.random.default_rng(20 + 2 * MODES.index(mode) + modified)
    for trial in range(6):
        robot = random_arm(rng, mode, modified, square=trial % 2 == 1, equal=trial == 2)
        q = rng.uniform(-PI, PI, (150, 6))
        many = solve_all(robot, robot.fk(q))
        assert_honest_batch(robot, q, many)
        assert set(many.count.tolist()) <= {1, 2, 3, 4, 5, 6, 7, 8}


def numeric_solutions(robot: Robot, T: FloatArray, rng: np.random.Generator) -> FloatArray:
    """The distinct solutions the numeric solver reaches from 200 random starts."""
    starts = rng.uniform(-PI, PI, (200, 6))
    res = robot.ik(np.broadcast_to(T, (200, 4, 4)), method="numeric", q0=starts, seed=0)
    assert isinstance(res, IKBatchResult)
    found = res.solutions[res.count > 0, 0]
    distinct: list[FloatArray] = []
    for s in found:
        if joint_gap(np.array(distinct).reshape(-1, 6), s) > 1e-6:
            distinct.append(s)
    return np.array(distinct)


@pytest.mark.parametrize("mode", MODES)
def test_complete_against_multistart_search(mode: str) -> None:
    rng = np.random.default_rng(30 + MODES.index(mode))
    named = {"meet": UR5, "apart": UR5_A5, "parallel": UR5_P56}[mode]
    for robot in (named, random_arm(rng, mode, True)):
        for q in rng.uniform(-PI, PI, (2, 6)):
            T = robot.fk(q)
            res = robot.ik(T, respect_limits=False)
            theirs = numeric_solutions(robot, T, rng)
            assert len(theirs) >= 1
            for s in theirs:
                assert joint_gap(res.solutions, s) < 1e-6, f"missed {s}"


# ------------------------------------------------------------------ routing
def test_classification_and_declined_arms() -> None:
    for robot in (UR5, UR5_A5, UR5_P56):
        s = classify(robot)
        assert (s.kind, s.summary) == (
            "three-parallel-6R",
            "6R, three parallel axes (2-3-4), UR type",
        )
    rows = UR5_ROWS
    # axes 5 and 6 on one line: q5 and q6 only add up (a continuum: kinematica.ik.coaxial)
    same_line = Robot.from_dh(
        [*rows[:4], Revolute(d=0.09465), Revolute(d=0.0823)], convention="standard"
    )
    # a link of the triangle of length zero: axes 2 and 3 on one line
    no_link = Robot.from_dh([rows[0], Revolute(), *rows[2:]], convention="standard")
    # axis 1 parallel to axes 2-4: four parallel axes (axes 1 and 2 on one line, a = 0)
    four = Robot.from_dh([Revolute(d=0.1), *rows[1:]], convention="standard")
    q = np.array([0.3, -1.0, 1.2, 0.3, 0.8, 0.2])
    for robot, pair in ((same_line, (4, 5)), (no_link, (1, 2)), (four, (0, 1))):
        res = robot.ik(robot.fk(q), seed=0)
        assert (res.method, res.status, res.free_joints) == (
            "analytic:coaxial-pair",
            "singular",
            pair,
        )
    # the core's builder declines them itself, and any chain not of the family
    wrist_along = Robot.from_dh([*rows[:3], Revolute(d=0.10915), *rows[4:]], convention="standard")
    puma = km.load("puma560")
    for robot in (same_line, no_link, four, wrist_along, puma):
        assert _core.parallel.build(robot.chain.core) is None
    assert _core.parallel.build(UR5.chain.core) is not None
    assert classify(puma).kind != "three-parallel-6R"
    assert (
        classify(Robot.from_dh([Revolute(), Prismatic()], convention="standard")).kind
        != "three-parallel-6R"
    )


# ------------------------------------------------------------- the spec's sample arms
@pytest.mark.parametrize("degenerate", [False, True])
def test_sample_arms_are_of_the_family_and_solved(degenerate: bool) -> None:
    """SPEC.sample_arm gives arms SPEC handles and builds (each edge geometry drawn
    at least once), whose FK targets are solved: every solution reaches the target
    and the configuration that made it is found.

    The generic arms are held to assert_honest_batch. Edge geometries the solver
    takes as exact (axes 5 and 6 1e-10 m apart taken as meeting, parallel within
    1e-10 rad, twists of axes 2-4 within 1e-9 rad) put the solutions of its model
    about that far (over σ_min) from the arm's: the check polishes them onto the
    target, and the generating q is found to 1e-6.
    """
    rng = np.random.default_rng(50 + degenerate)
    notes = set()
    for _ in range(60):
        sample = SPEC.sample_arm(rng, degenerate)
        notes.add(sample.note)
        robot = Robot.from_dh(
            sample.links, convention=sample.convention, base=sample.base, tool=sample.tool
        )
        f = features(robot.chain)
        assert SPEC.handles(f), sample
        assert SPEC.build(robot.chain, f, "pose") is not None, sample
        q = rng.uniform(-PI, PI, (5, 6))
        many = solve_all(robot, robot.fk(q))
        if not degenerate:
            assert_honest_batch(robot, q, many)
            continue
        assert set(many.status.tolist()) <= {"ok", "singular"}, sample
        for i in range(5):
            assert_reaches(robot, many[i], robot.fk(q[i]))
            if many.status[i] == "ok":
                assert joint_gap(many[i].solutions, q[i]) < 1e-6, (sample, q[i].tolist())
    assert notes == (set(DEGENERATE) if degenerate else {""})
