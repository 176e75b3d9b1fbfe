"""Closed-form IK of spherical-wrist arms (6R with general first three axes, RRP).

Independent references: EAIK's solution sets for the PUMA 560 and a general
spherical-wrist arm (``data/reference/ik_reference.json``), the Stanford arm's
forward kinematics from the Robotics Toolbox (``fk_reference.json``), forward
kinematics of every candidate, the product-of-exponentials identity the solver
is built on, and a multi-start damped-least-squares search (completeness).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from helpers import assert_transform_close, transform_from
from numpy.typing import NDArray
from test_ik_small import dls_solutions, joint_distance

from kinematica.dh import Prismatic, Revolute
from kinematica.errors import DimensionError
from kinematica.ik.analytic import pieper, pieper_single
from kinematica.ik.analytic.poe import Screws
from kinematica.ik.analytic.wrist import (
    SphericalWristSolver,
    make_rrp_wrist_solver,
    make_spherical_wrist_solver,
)
from kinematica.robot import Robot, classify

FloatArray = NDArray[np.float64]
PI = math.pi
EXACT = 1e-12
DATA = Path(__file__).parent / "data" / "reference"


def robot_from_rows(arm: dict, name: str) -> Robot:
    rows = [
        Revolute(d=j["d"], a=j["a"], alpha=j["alpha"], offset=j["theta"])
        if j["type"] == "R"
        else Prismatic(theta=j["theta"], a=j["a"], alpha=j["alpha"], offset=j["d"])
        for j in arm["joints"]
    ]
    return Robot.from_dh(rows, convention=arm["convention"], tool=arm.get("tool"), name=name)


def reference_arm(file: str, name: str) -> dict:
    arms = json.loads((DATA / file).read_text())["arms"]
    return next(a for a in arms if a["name"] == name)


PUMA = robot_from_rows(reference_arm("ik_reference.json", "puma560"), "puma560")
STANFORD = robot_from_rows(reference_arm("fk_reference.json", "stanford"), "stanford")


def solver_of(robot: Robot) -> SphericalWristSolver:
    solver = make_spherical_wrist_solver(robot) or make_rrp_wrist_solver(robot)
    assert solver is not None
    return solver


def solve_checked(robot: Robot, T: FloatArray) -> FloatArray:
    """Candidates ``(N, 8, 6)``; every real one reproduces its pose exactly."""
    cand = solver_of(robot).solve(T)
    q = cand.q
    assert q.shape == (len(T), 8, 6) and len(cand.labels) == 8
    nan = np.isnan(q)
    assert (nan.any(axis=2) == nan.all(axis=2)).all(), "a branch is partly NaN"
    real = ~nan.any(axis=2)
    reached = robot.fk(np.where(real[..., None], q, 0.0))
    assert_transform_close(reached[real], np.broadcast_to(T[:, None], reached.shape)[real], EXACT)
    assert np.isnan(cand.gap[real.any(axis=1)]).all()
    return q


def random_q(robot: Robot, rng: np.random.Generator, n: int) -> FloatArray:
    q = rng.uniform(-PI, PI, (n, robot.dof))
    return np.where(robot.is_prismatic, rng.uniform(-0.5, 0.8, (n, robot.dof)), q)


def assert_found(robot: Robot, q: FloatArray, expected: FloatArray, tol: float = 1e-9) -> None:
    """Every row of ``expected (N, n)`` is among the candidates ``q (N, m, n)``."""
    d = joint_distance(robot, q, expected[:, None, :])
    assert (np.nan_to_num(d, nan=np.inf).min(axis=1) < tol).all(), d.min(axis=1).max()


def distinct(robot: Robot, q: FloatArray, tol: float = 1e-7) -> list[FloatArray]:
    out: list[FloatArray] = []
    for qi in q[~np.isnan(q).any(axis=1)]:
        if all(joint_distance(robot, qi, o) > tol for o in out):
            out.append(qi)
    return out


# ------------------------------------------------------------ random arms
def twist(rng: np.random.Generator) -> float:
    """A twist well away from 0 and π."""
    return float(rng.uniform(0.3, PI - 0.3) * rng.choice([-1.0, 1.0]))


def sign(rng: np.random.Generator) -> float:
    return float(rng.choice([-1.0, 1.0]))


def random_wrist_arm(rng: np.random.Generator, shoulder: str, joint3: str) -> Robot:
    """A random spherical-wrist arm.

    Args:
        rng: Random numbers.
        shoulder: ``"meet"`` (axes 1, 2 meet), ``"parallel"`` or ``"general"`` (skew).
        joint3: ``"R23"`` (revolute, axis 3 ∥ axis 2), ``"R"`` (revolute,
            general) or ``"P"`` (slide).
    """
    u = rng.uniform
    a1 = 0.0 if shoulder == "meet" else u(0.1, 0.4) * sign(rng)
    alpha1 = float(rng.choice([0.0, PI])) if shoulder == "parallel" else twist(rng)
    alpha2 = float(rng.choice([0.0, PI])) if joint3 == "R23" else twist(rng)
    if joint3 == "P" and shoulder == "parallel":
        alpha2 = u(0.3, 1.2) * sign(rng)  # the slide must have a part along axes 1, 2
    rows: list[Revolute | Prismatic] = [
        Revolute(d=u(0.1, 0.5), a=a1, alpha=alpha1, offset=u(-PI, PI)),
        Revolute(d=u(-0.2, 0.2), a=u(0.2, 0.5) * sign(rng), alpha=alpha2, offset=u(-PI, PI)),
    ]
    if joint3 == "P":
        rows.append(Prismatic(theta=u(-PI, PI), a=u(-0.1, 0.1), alpha=twist(rng), offset=0.3))
    else:
        rows.append(Revolute(d=u(-0.2, 0.2), a=u(-0.2, 0.2), alpha=twist(rng), offset=u(-PI, PI)))
    rows += [  # a spherical wrist: a4 = a5 = d5 = 0, any twists
        Revolute(d=u(0.2, 0.5) * sign(rng), alpha=twist(rng), offset=u(-PI, PI)),
        Revolute(alpha=twist(rng), offset=u(-PI, PI)),
        Revolute(d=u(0.0, 0.2), a=u(-0.1, 0.1), alpha=u(-PI, PI), offset=u(-PI, PI)),
    ]
    base = transform_from(rng.normal(size=4), rng.uniform(-0.5, 0.5, 3))
    tool = transform_from(rng.normal(size=4), rng.uniform(-0.2, 0.2, 3))
    robot = Robot.from_dh(rows, base=base, tool=tool, name=f"{shoulder}-{joint3}")
    if rng.random() < 0.5:
        robot = robot.to_convention("modified")
    return robot


GEOMETRIES = [
    ("meet", "R23"),
    ("meet", "R"),
    ("meet", "P"),
    ("parallel", "R"),
    ("parallel", "P"),
    ("general", "R23"),
    ("general", "R"),
    ("general", "P"),
]


# ------------------------------------------------------------------ tests
@pytest.mark.parametrize(("shoulder", "joint3"), GEOMETRIES)
def test_product_of_exponentials_is_the_dh_forward_kinematics(shoulder: str, joint3: str) -> None:
    rng = np.random.default_rng(10)
    for _ in range(3):
        robot = random_wrist_arm(rng, shoulder, joint3)
        q = random_q(robot, rng, 50)
        assert_transform_close(Screws.from_robot(robot).fk(q), robot.fk(q), 1e-12)


def test_puma_has_eight_exact_solutions_and_finds_the_original() -> None:
    rng = np.random.default_rng(11)
    q0 = random_q(PUMA, rng, 300)
    q = solve_checked(PUMA, PUMA.fk(q0))
    assert not np.isnan(q).any()  # generic poses: all eight branches real
    assert_found(PUMA, q, q0)
    assert all(len(distinct(PUMA, qi)) == 8 for qi in q[:20])


@pytest.mark.parametrize("name", ["puma560", "general-spherical-wrist"])
def test_solution_sets_equal_eaik(name: str) -> None:
    arm = reference_arm("ik_reference.json", name)
    robot = robot_from_rows(arm, name)
    T = np.array([s["T"] for s in arm["samples"]])
    q = solve_checked(robot, T)
    counts = []
    for qi, sample in zip(q, arm["samples"], strict=True):
        theirs = np.array(sample["solutions"])
        ours = np.array(distinct(robot, qi))
        counts.append(len(ours))
        assert len(ours) == len(theirs), sample["q_generating"]
        d = joint_distance(robot, ours[:, None, :], theirs[None, :, :])
        assert (d.min(axis=0) < 1e-9).all() and (d.min(axis=1) < 1e-9).all()
    if name == "general-spherical-wrist":
        assert set(counts) == {4, 8}  # the quartic has 2 or 4 real roots there


@pytest.mark.parametrize(("shoulder", "joint3"), GEOMETRIES)
def test_random_arms_round_trip(shoulder: str, joint3: str) -> None:
    rng = np.random.default_rng(12)
    for _ in range(4):
        robot = random_wrist_arm(rng, shoulder, joint3)
        solver = solver_of(robot)
        assert solver.position.kind == shoulder
        assert solver.position.parallel23 == (joint3 == "R23")
        assert solver.name == ("rrp-spherical-wrist" if joint3 == "P" else "spherical-wrist")
        q0 = random_q(robot, rng, 80)
        q = solve_checked(robot, robot.fk(q0))
        assert_found(robot, q, q0)


def test_stanford_arm() -> None:
    arm = reference_arm("fk_reference.json", "stanford")
    q_ref = np.array([s["q"] for s in arm["samples"]])
    T_ref = np.array([s["T"] for s in arm["samples"]])
    assert_transform_close(STANFORD.fk(q_ref), T_ref, 1e-9)  # the model is the RTB's arm
    assert classify(STANFORD).kind == "rrp-spherical-wrist"
    assert make_spherical_wrist_solver(STANFORD) is None
    solver = make_rrp_wrist_solver(STANFORD)
    assert solver is not None and solver.position.kind == "meet"
    assert solver.labels[:2] == (
        "shoulder right, slide out, wrist no-flip",
        "shoulder right, slide out, wrist flip",
    )
    q = solve_checked(STANFORD, T_ref)
    assert_found(STANFORD, q, q_ref, 1e-8)
    # the slide takes both signs: the "in" branches reach through the shoulder
    slide = q[:, :, 2]
    assert (slide[:, [0, 1, 4, 5]] > slide[:, [2, 3, 6, 7]]).all()
    rng = np.random.default_rng(13)
    q0 = random_q(STANFORD, rng, 200)
    assert_found(STANFORD, solve_checked(STANFORD, STANFORD.fk(q0)), q0)


@pytest.mark.parametrize(
    ("shoulder", "joint3"), [("general", "R"), ("general", "P"), ("meet", "R"), ("parallel", "R")]
)
def test_complete_against_multistart_search(shoulder: str, joint3: str) -> None:
    rng = np.random.default_rng(14)
    robot = random_wrist_arm(rng, shoulder, joint3)
    targets = robot.fk(random_q(robot, rng, 2))
    q = solve_checked(robot, targets)
    for T, qi in zip(targets, q, strict=True):
        numeric = dls_solutions(robot, T, rng)
        assert len(numeric) >= 1
        ours = np.array(distinct(robot, qi))
        d = joint_distance(robot, numeric[:, None, :], ours[None, :, :])
        assert (d.min(axis=1) < 1e-6).all(), "the search found a solution we miss"


def test_nearly_parallel_shoulder_axes_stay_exact() -> None:
    """Axes 1 and 2 at 0.7° (skew): the elimination divides by sin α, and near
    double roots of F lose digits that the final Newton step of the full
    position equation restores (a regression case found by a random search)."""
    rows = [
        Revolute(d=-0.39964551701430384, a=-0.23494747622759055, alpha=-0.0122188743799172),
        Revolute(d=-0.11579349535390293, alpha=-PI / 2, offset=-0.917807287996447),
        Revolute(d=-0.22004128595761935, a=-0.20509321793326424, offset=1.3617449446662127),
        Revolute(d=0.4087406157764789, alpha=0.44392020442861435, offset=-0.5425571608907469),
        Revolute(alpha=2.8464679704414912, offset=-PI / 2),
        Revolute(d=0.15652726621762514, alpha=-0.3451884803825527, offset=-1.5476061685567883),
    ]
    robot = Robot.from_dh(rows, name="nearly parallel shoulder")
    q0 = np.array([[-2.63290526, -1.25548875, -2.16983424, 2.16527726, 2.13149496, 0.27287491]])
    assert solver_of(robot).position.kind == "general"
    assert_found(robot, solve_checked(robot, robot.fk(q0)), q0)
    rng = np.random.default_rng(23)
    q0 = random_q(robot, rng, 300)
    assert_found(robot, solve_checked(robot, robot.fk(q0)), q0)
    # one pose at a time: the same Newton step of the position (the batched one)
    assert_one_pose_equals_batch(robot, robot.fk(q0[:30]))


def centre_jacobian_det(robot: Robot, c_tool: FloatArray, q: FloatArray) -> FloatArray:
    """det of d(wrist centre)/d(q1, q2, q3), from the robot's own Jacobian."""
    T, J = robot.fk(q), robot.jacobian(q)
    r = T[..., :3, :3] @ c_tool  # wrist centre relative to the tool origin
    return np.linalg.det(J[..., :3, :3] + np.cross(J[..., 3:, :3], r[..., :, None], axis=-2))


def fold_configurations(robot: Robot, rng: np.random.Generator, n: int = 30) -> FloatArray:
    """Configurations where two position branches merge (det of the centre's Jacobian 0)."""
    c_tool = solver_of(robot).c_tool
    joint3 = "P" if robot.is_prismatic[2] else "R"
    q = np.repeat(random_q(robot, rng, n), 2, axis=0)
    span = 1.5 if joint3 == "P" else PI
    grid = np.linspace(-span, span, 361)
    scan = np.repeat(q[:, None, :], len(grid), axis=1)
    scan[:, :, 2] = grid
    det = centre_jacobian_det(robot, c_tool, scan)
    brackets = []  # a sign change of det along q3, two per configuration if there are
    for i, row in enumerate(det):
        flips = np.nonzero(np.sign(row[:-1]) != np.sign(row[1:]))[0]
        if len(flips) > i % 2:
            brackets.append((i, flips[i % 2]))
    assert len(brackets) >= 2 * n // 3
    rows, k = np.array(brackets).T
    q, lo, hi = q[rows], grid[k], grid[k + 1]
    for _ in range(55):  # bisection on det = 0 in q3, all rows at once
        q[:, 2] = lo
        s_lo = np.sign(centre_jacobian_det(robot, c_tool, q))
        q[:, 2] = mid = (lo + hi) / 2
        same = np.sign(centre_jacobian_det(robot, c_tool, q)) == s_lo
        lo, hi = np.where(same, mid, lo), np.where(same, hi, mid)
    assert np.abs(centre_jacobian_det(robot, c_tool, q)).max() < 1e-9
    return q


@pytest.mark.parametrize(
    ("shoulder", "joint3"), [("meet", "R23"), ("general", "R"), ("general", "P")]
)
def test_targets_on_the_workspace_fold(shoulder: str, joint3: str) -> None:
    """Targets where two position branches merge (a double root): still exact."""
    rng = np.random.default_rng(21)
    robot = random_wrist_arm(rng, shoulder, joint3)
    q = fold_configurations(robot, rng)
    cand = solve_checked(robot, robot.fk(q))  # every candidate exact
    # the original is found, to within what a double root allows: along the
    # fold the pose moves only to second order, so exact solutions (1e-12)
    # can differ from it by ~sqrt(1e-12 / curvature)
    assert_found(robot, cand, q, 1e-4)


def test_singular_wrist_returns_a_representative() -> None:
    rng = np.random.default_rng(15)
    q0 = random_q(PUMA, rng, 20)
    q0[:10, 4] = 0.0  # axes 4 and 6 aligned
    q0[10:, 4] = PI  # ... or opposite
    T = PUMA.fk(q0)
    cand = solver_of(PUMA).solve(T)
    q = solve_checked(PUMA, T)
    assert cand.singular.all()
    assert (cand.free == [False, False, False, True, False, True]).all()
    # in the original's position branch (same q1..q3) the wrist is singular: the
    # representative has q4 = 0 and the "flip" slot (the same family) is NaN
    branch = np.abs(np.angle(np.exp(1j * (q[..., :3] - q0[:, None, :3])))).max(axis=2) < 1e-9
    assert branch.any(axis=1).all()
    rep, flip = q[:, 0::2][branch[:, 0::2]], q[:, 1::2][branch[:, 0::2]]
    assert (rep[:, 3] == 0.0).all() and np.isnan(flip).all()
    # ... and it keeps q4 + q6 (q5 = 0) or q4 - q6 (q5 = π) of the original
    k = np.nonzero(branch[:, 0::2])[0]
    plus = np.abs(q0[k, 4]) < 1
    want = np.where(plus, q0[k, 3] + q0[k, 5], q0[k, 3] - q0[k, 5])
    got = np.where(plus, rep[:, 3] + rep[:, 5], rep[:, 3] - rep[:, 5])
    assert (np.abs(np.angle(np.exp(1j * (got - want)))) < 1e-9).all()
    # the other position branches point the forearm elsewhere: two regular solutions
    other = ~branch[:, 0::2]
    assert not np.isnan(q[:, 1::2][other]).any()


def test_regular_poses_are_not_singular() -> None:
    rng = np.random.default_rng(16)
    cand = solver_of(PUMA).solve(PUMA.fk(random_q(PUMA, rng, 50)))
    assert not cand.singular.any() and not cand.free.any()


def test_shoulder_singularity_frees_q1() -> None:
    rows = [
        Revolute(d=0.5, alpha=PI / 2),
        Revolute(a=0.4),
        Revolute(alpha=PI / 2),
        Revolute(d=0.35, alpha=-PI / 2),
        Revolute(alpha=PI / 2),
        Revolute(d=0.1),
    ]
    robot = Robot.from_dh(rows, name="no shoulder offset")
    q0 = np.array([[0.3, PI / 2, PI / 2, 0.2, 0.4, 0.5]])  # wrist centre on axis 1
    T = robot.fk(q0)
    centre = T[0, :3, 3] - 0.1 * T[0, :3, 2]
    assert np.hypot(centre[0], centre[1]) < 1e-12
    cand = solver_of(robot).solve(T)
    solve_checked(robot, T)
    assert cand.singular[0] and cand.free[0, 0] and not cand.free[0, 3]


def test_unreachable_target_has_no_branch_and_a_gap() -> None:
    rng = np.random.default_rng(17)
    T = PUMA.fk(random_q(PUMA, rng, 5))
    T[:, :3, 3] += np.array([4.0, -3.0, 2.0])
    cand = solver_of(PUMA).solve(T)
    assert np.isnan(cand.q).all()
    # a lower bound of the distance of the wrist centre to those reachable
    samples = PUMA.fk(random_q(PUMA, rng, 20000))
    reach = samples[:, :3, 3]  # PUMA: no tool, the flange origin is the wrist centre
    centre = T[:, :3, 3]
    nearest = np.linalg.norm(centre[:, None] - reach[None], axis=-1).min(axis=1)
    assert (cand.gap > 0).all()
    assert (cand.gap <= nearest).all() and (cand.gap > 0.99 * nearest).all()
    robot = random_wrist_arm(rng, "general", "R")
    far = robot.fk(random_q(robot, rng, 3))
    far[:, :3, 3] += 10.0
    cand = solver_of(robot).solve(far)
    assert np.isnan(cand.q).all() and (cand.gap > 0).all()


def test_orientation_the_wrist_cannot_make() -> None:
    rows = [
        Revolute(d=0.4, alpha=PI / 2),
        Revolute(a=0.4),
        Revolute(alpha=PI / 2),
        Revolute(d=0.4, alpha=0.3),  # a wrist with small twists: a cone of directions
        Revolute(alpha=0.3),
        Revolute(d=0.1),
    ]
    robot = Robot.from_dh(rows, name="narrow wrist")
    rng = np.random.default_rng(18)
    T = robot.fk(np.array([0.2, 0.5, 1.0, 0.3, 0.2, 0.1]))
    flipped = T.copy()  # same wrist centre, tool axis reversed
    centre = T[:3, 3] - 0.1 * T[:3, 2]
    flipped[:3, :3] = T[:3, :3] @ np.diag([1.0, -1.0, -1.0])
    flipped[:3, 3] = centre + 0.1 * flipped[:3, 2]
    cand = solver_of(robot).solve(flipped[None])
    assert np.isnan(cand.q).all() and cand.gap[0] == 0.0  # position fine, rotation not
    assert len(dls_solutions(robot, flipped, rng)) == 0


def test_puma_labels_mean_what_they_say() -> None:
    solver = solver_of(PUMA)
    assert solver.labels == tuple(
        f"shoulder {s}, elbow {e}, wrist {w}"
        for s in ("right", "left")
        for e in ("up", "down")
        for w in ("no-flip", "flip")
    )
    rng = np.random.default_rng(19)
    q = solve_checked(PUMA, PUMA.fk(random_q(PUMA, rng, 100)))
    flat = q.reshape(-1, 6)
    h, p = PUMA.joint_axes(flat)
    T = PUMA.fk(flat)
    h1, h2, h3 = h[:, 0], h[:, 1], h[:, 2]
    o = p[:, 0] + (np.sum((p[:, 1] - p[:, 0]) * h1, axis=1))[:, None] * h1  # shoulder
    wrist = T[:, :3, 3]
    elbow = p[:, 2] + np.sum((o - p[:, 2]) * h3, axis=1)[:, None] * h3
    # shoulder right (Lee): q2 > 0 moves the wrist up, along axis 1
    right = np.sum(np.cross(h2, wrist - o) * h1, axis=1) > 0
    # elbow up: the elbow is on the side of the shoulder-wrist line axis 1 points to
    normal = np.cross(h2, wrist - o)
    normal *= np.sign(np.sum(normal * h1, axis=1))[:, None]
    up = np.sum(normal * (elbow - o), axis=1) > 0
    no_flip = np.sin(flat[:, 4]) > 0  # Corke's PUMA: wrist bent as q5 > 0
    slot = np.tile(np.arange(8), len(q))
    assert (right == (slot < 4)).all()
    assert (up == (slot % 4 < 2)).all()
    assert (no_flip == (slot % 2 == 0)).all()


@pytest.mark.parametrize(("shoulder", "joint3"), GEOMETRIES)
def test_no_flip_is_the_wrist_bend_of_the_home_pose(shoulder: str, joint3: str) -> None:
    rng = np.random.default_rng(24)
    for _ in range(3):
        robot = random_wrist_arm(rng, shoulder, joint3)
        q0 = np.zeros((1, 6))
        q0[0, 3:] = rng.uniform(-0.05, 0.05, 3)  # near home: the wrist bent as at q = 0
        q = solve_checked(robot, robot.fk(q0))[0]
        slot = np.nanargmin(joint_distance(robot, q, q0[0]))
        assert joint_distance(robot, q[slot], q0[0]) < 1e-9
        assert "no-flip" in solver_of(robot).labels[slot] and slot % 2 == 0


def test_factories_refuse_other_arms() -> None:
    ur5 = robot_from_rows(reference_arm("ik_reference.json", "ur5"), "ur5")
    assert make_spherical_wrist_solver(ur5) is None
    assert make_rrp_wrist_solver(PUMA) is None
    assert make_spherical_wrist_solver(STANFORD) is None
    # axes 1 and 2 coincide (twist 0, no offset): the wrist centre has 2 DOF only
    rows = [Revolute(d=0.3), Revolute(a=0.4), Revolute(alpha=PI / 2)]
    rows += [Revolute(d=0.3, alpha=-PI / 2), Revolute(alpha=PI / 2), Revolute(d=0.1)]
    flat = Robot.from_dh(rows)
    assert classify(flat).kind == "spherical-wrist-6R"
    assert make_spherical_wrist_solver(flat) is None
    assert make_spherical_wrist_solver(Robot.from_dh(rows[:5])) is None


def assert_one_pose_equals_batch(robot: Robot, T: FloatArray, tol: float = 1e-9) -> float:
    """Each pose alone (the Python-float path) gives the batch's candidates; max residual.

    Both are exact (residual <= EXACT); ``tol`` bounds their joint distance,
    which round-off sets (ill-conditioned joints, or double roots: see below).
    """
    solver = solver_of(robot)
    assert solver.single is not None
    batch = solver.solve(T)
    worst = 0.0
    for i in range(len(T)):
        one = solver.solve(T[i : i + 1])
        assert np.array_equal(np.isnan(one.q), np.isnan(batch.q[i : i + 1])), i
        d = joint_distance(robot, np.nan_to_num(one.q[0]), np.nan_to_num(batch.q[i]))
        assert d.max() < tol
        assert one.singular[0] == batch.singular[i] and (one.free[0] == batch.free[i]).all()
        np.testing.assert_array_equal(one.gap, batch.gap[i : i + 1])
        assert one.labels == batch.labels
        real = ~np.isnan(one.q[0, :, 0])
        reached = robot.fk(one.q[0, real])
        assert_transform_close(reached, np.broadcast_to(T[i], reached.shape), EXACT)
        worst = max(worst, float(np.abs(reached - T[i]).max(initial=0.0)))
    return worst


@pytest.mark.parametrize(("shoulder", "joint3"), [*GEOMETRIES, ("puma", "")])
def test_one_pose_path_equals_the_batch(shoulder: str, joint3: str) -> None:
    """A single pose runs on Python floats (every geometry): same answers."""
    rng = np.random.default_rng(22)
    robot = PUMA if shoulder == "puma" else random_wrist_arm(rng, shoulder, joint3)
    q0 = random_q(robot, rng, 40)
    q0[:8, 4] = 0.0  # the PUMA's wrist singularity (a regular pose on the others)
    T = robot.fk(q0)
    T[-4:, :3, 3] += 5.0  # out of reach
    assert_one_pose_equals_batch(robot, T)


@pytest.mark.parametrize("joint3", ["R", "P"])
def test_one_pose_quartic_on_random_general_arms(joint3: str) -> None:
    """Pieper's quartic on floats: many skew-shoulder arms (both DH conventions,
    random base and tool), generic poses and poses on the workspace fold."""
    rng = np.random.default_rng(25)
    conventions = set()
    for _ in range(8):
        robot = random_wrist_arm(rng, "general", joint3)
        conventions.add(robot.convention)
        assert solver_of(robot).position.kind == "general"
        assert_one_pose_equals_batch(robot, robot.fk(random_q(robot, rng, 12)))
    assert conventions == {"standard", "modified"}
    # on the fold the roots are double: the quartic's closed form (one pose) and
    # the companion matrix (a small batch) split them differently by ~sqrt(ulp),
    # and every candidate within ~sqrt(1e-12 / curvature) is exact (as above)
    robot = random_wrist_arm(rng, "general", joint3)
    assert_one_pose_equals_batch(robot, robot.fk(fold_configurations(robot, rng, 12)), 1e-5)


def test_one_pose_quartic_on_the_eaik_reference() -> None:
    name = "general-spherical-wrist"
    arm = reference_arm("ik_reference.json", name)
    robot = robot_from_rows(arm, name)
    T = np.array([s["T"] for s in arm["samples"]])
    assert assert_one_pose_equals_batch(robot, T) <= EXACT
    solver = solver_of(robot)
    for Ti, sample in zip(T, arm["samples"], strict=True):
        ours = np.array(distinct(robot, solver.solve(Ti[None]).q[0]))
        theirs = np.array(sample["solutions"])
        assert len(ours) == len(theirs)
        d = joint_distance(robot, ours[:, None, :], theirs[None, :, :])
        assert (d.min(axis=0) < 1e-9).all() and (d.min(axis=1) < 1e-9).all()


def test_one_pose_self_motion_of_the_shoulder() -> None:
    """F ≡ 0 (every q3 reaches the target): same representatives and free flags."""
    robot = random_wrist_arm(np.random.default_rng(26), "general", "R")
    solver = solver_of(robot)
    assert solver.single is not None
    F = [0.0] * 5
    q, selfmotion = pieper_single.revolute_roots(F)
    qb, sb = pieper.revolute_roots(np.zeros((1, 5)))
    assert selfmotion and sb[0] and np.array_equal(q, qb[0])


def test_shapes_and_bad_input() -> None:
    solver = solver_of(PUMA)
    empty = solver.solve(np.zeros((0, 4, 4)))
    assert empty.q.shape == (0, 8, 6) and empty.free.shape == (0, 6)
    one = solver.solve(PUMA.fk(np.zeros((1, 6))))
    assert one.q.shape == (1, 8, 6) and one.gap.shape == (1,)
    with pytest.raises(DimensionError, match=r"\(N, 4, 4\)"):
        solver.solve(np.eye(4))


def test_one_pose_quartic_roots(monkeypatch: pytest.MonkeyPatch) -> None:
    """Ferrari on floats: the roots of quartics with known roots, close or spread
    over eight orders (those fail the backward-error check: companion matrix)."""
    rng = np.random.default_rng(27)
    fallbacks = []
    companion = pieper_single._companion_roots
    monkeypatch.setattr(
        pieper_single, "_companion_roots", lambda k: fallbacks.append(1) or companion(k)
    )
    for spread in (0.0, 1.0, 4.0):
        roots = rng.normal(size=(50, 4)) * 10.0 ** rng.uniform(-spread, spread, (50, 4))
        for r in roots:
            k = np.poly(r) * rng.uniform(0.1, 10.0)
            got = np.sort_complex(np.array(pieper_single.quartic_roots(tuple(k.tolist()))))
            assert np.abs(got - np.sort_complex(r + 0j)).max() < 1e-9 * (1.0 + np.abs(r).max())
    assert 0 < len(fallbacks) < 100
