"""Closed-form IK of spherical-wrist arms (6R with any first three axes, RRP).

Independent references: EAIK's solution sets for the PUMA 560 and a general
spherical-wrist arm (``data/reference/ik_reference.json``), the Stanford arm's
forward kinematics from the Robotics Toolbox (``fk_reference.json``), forward
kinematics of every candidate, the product-of-exponentials identity the solver
is built on (written here with scipy's rotations), and a multi-start
damped-least-squares search (completeness).
"""

from __future__ import annotations

import json
import math

import kinematica._core as _core
import numpy as np
import pytest
from numpy.typing import NDArray
from scipy.spatial.transform import Rotation
from support import DATA as TESTS_DATA
from support.helpers import assert_transform_close
from support.ik_search import dls_solutions, joint_distance, random_q
from support.wrist_arms import Info, arm_geometry, candidates, random_wrist_arm

from kinematica.dh import Prismatic, Revolute
from kinematica.ik import ClosedForm, IKBatchResult, IKResult, closed_form
from kinematica.ik.analytic.spherical_wrist import GEOMETRIES
from kinematica.robot import Robot, classify

FloatArray = NDArray[np.float64]
PI = math.pi
EXACT = 1e-12
DATA = TESTS_DATA / "reference"


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


def solver_of(robot: Robot) -> ClosedForm:
    solver = closed_form(robot.chain, "pose")
    assert solver is not None and solver.slots == 8
    return solver


def raw(robot: Robot, T: FloatArray) -> tuple[FloatArray, Info]:
    """The pose solver's candidates ``(N, 8, 6)`` and info for poses ``T (N, 4, 4)``."""
    return candidates(solver_of(robot), robot, T)


def solve_checked(robot: Robot, T: FloatArray, tol: float = EXACT) -> FloatArray:
    """Candidates ``(N, 8, 6)``; every real one reproduces its pose to ``tol``."""
    q, info = raw(robot, T)
    nan = np.isnan(q)
    assert (nan.any(axis=2) == nan.all(axis=2)).all(), "a branch is partly NaN"
    real = ~nan.any(axis=2)
    reached = robot.fk(np.where(real[..., None], q, 0.0))
    assert_transform_close(reached[real], np.broadcast_to(T[:, None], reached.shape)[real], tol)
    assert np.isnan(info.gap[real.any(axis=1)]).all()
    return q


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


def c_tool_of(robot: Robot) -> FloatArray:
    """The wrist centre in the tool frame (at q = 0)."""
    c = classify(robot).wrist_center
    assert c is not None
    M = robot.fk(np.zeros(robot.dof))
    return M[:3, :3].T @ (c - M[:3, 3])


def shoulder_of(robot: Robot) -> tuple[str, bool]:
    """The builder's reading of joints 1-3: shoulder kind, axes 2 ∥ 3."""
    f = classify(robot).features
    c = classify(robot).wrist_center
    assert c is not None
    arm = arm_geometry(f.directions[:3], f.points[:3], f.joint_types[2] == "P", c, f.size)
    assert arm is not None
    return arm.kind, arm.parallel23


def poe_fk(robot: Robot, q: FloatArray) -> FloatArray:
    """``T(q) = e1 ... en M`` from the axes at q = 0 (Brockett), rotations by scipy."""
    h, p = robot.joint_axes()
    T = np.broadcast_to(np.eye(4), (*q.shape[:-1], 4, 4)).copy()
    for i in range(robot.dof):
        E = np.zeros((*q.shape[:-1], 4, 4))
        E[..., 3, 3] = 1.0
        if robot.is_prismatic[i]:
            E[..., :3, :3] = np.eye(3)
            E[..., :3, 3] = q[..., i, None] * h[i]
        else:
            R = Rotation.from_rotvec(q[..., i, None] * h[i]).as_matrix()
            E[..., :3, :3] = R
            E[..., :3, 3] = p[i] - R @ p[i]
        T = T @ E
    return T @ robot.fk(np.zeros(robot.dof))


# ------------------------------------------------------------------ tests
@pytest.mark.parametrize(("shoulder", "joint3"), GEOMETRIES)
def test_product_of_exponentials_is_the_dh_forward_kinematics(shoulder: str, joint3: str) -> None:
    rng = np.random.default_rng(10)
    for _ in range(3):
        robot = random_wrist_arm(rng, shoulder, joint3)
        q = random_q(robot, rng, 50)
        assert_transform_close(poe_fk(robot, q), robot.fk(q), 1e-12)


def test_puma_has_eight_exact_solutions_and_finds_the_original() -> None:
    rng = np.random.default_rng(11)
    q0 = random_q(PUMA, rng, 300)
    q = solve_checked(PUMA, PUMA.fk(q0))
    assert not np.isnan(q).any()  # generic poses: all eight branches real
    assert_found(PUMA, q, q0)
    assert all(len(distinct(PUMA, qi)) == 8 for qi in q[:20])
    res = PUMA.ik(PUMA.fk(q0[:20]), respect_limits=False)
    assert (res.count == 8).all() and (res.status == "ok").all()
    assert res.method == "analytic:spherical-wrist"


@pytest.mark.parametrize("name", ["puma560", "general-spherical-wrist"])
def test_solution_sets_equal_eaik(name: str) -> None:
    arm = reference_arm("ik_reference.json", name)
    robot = robot_from_rows(arm, name)
    T = np.array([s["T"] for s in arm["samples"]])
    solve_checked(robot, T)
    res = robot.ik(T, respect_limits=False)
    for i, sample in enumerate(arm["samples"]):
        theirs = np.array(sample["solutions"])
        ours = res[i].solutions
        assert len(ours) == len(theirs), sample["q_generating"]
        d = joint_distance(robot, ours[:, None, :], theirs[None, :, :])
        assert (d.min(axis=0) < 1e-9).all() and (d.min(axis=1) < 1e-9).all()
    if name == "general-spherical-wrist":
        assert set(res.count.tolist()) == {4, 8}  # the quartic has 2 or 4 real roots there


@pytest.mark.parametrize(("shoulder", "joint3"), GEOMETRIES)
def test_random_arms_round_trip(shoulder: str, joint3: str) -> None:
    rng = np.random.default_rng(12)
    for _ in range(4):
        robot = random_wrist_arm(rng, shoulder, joint3)
        assert shoulder_of(robot) == (shoulder, joint3 == "R23")
        assert solver_of(robot).name == (
            "rrp-spherical-wrist" if joint3 == "P" else "spherical-wrist"
        )
        q0 = random_q(robot, rng, 80)
        q = solve_checked(robot, robot.fk(q0))
        assert_found(robot, q, q0)


def test_stanford_arm() -> None:
    arm = reference_arm("fk_reference.json", "stanford")
    q_ref = np.array([s["q"] for s in arm["samples"]])
    T_ref = np.array([s["T"] for s in arm["samples"]])
    assert_transform_close(STANFORD.fk(q_ref), T_ref, 1e-9)  # the model is the RTB's arm
    assert classify(STANFORD).kind == "rrp-spherical-wrist"
    assert classify(STANFORD).summary == "RRP + spherical wrist (Stanford type)"
    assert shoulder_of(STANFORD)[0] == "meet"
    solver = solver_of(STANFORD)
    assert solver.name == "rrp-spherical-wrist"
    assert solver.labels[:2] == (
        "shoulder right, slide out, wrist no-flip",
        "shoulder right, slide out, wrist flip",
    )
    q = solve_checked(STANFORD, T_ref, 1e-11)
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
    res = robot.ik(targets, respect_limits=False)
    for i, T in enumerate(targets):
        numeric = dls_solutions(robot, T, rng)
        assert len(numeric) >= 1
        ours = res[i].solutions
        d = joint_distance(robot, numeric[:, None, :], ours[None, :, :])
        assert (d.min(axis=1) < 1e-6).all(), "the search found a solution we miss"


def test_nearly_parallel_shoulder_axes_stay_exact() -> None:
    """Axes 1 and 2 at 0.7° (skew): the elimination divides by sin α, and near
    double roots of F lose digits that the check's polishing restores (a
    regression case found by a random search)."""
    rows = [
        Revolute(d=-0.39964551701430384, a=-0.23494747622759055, alpha=-0.0122188743799172),
        Revolute(d=-0.11579349535390293, alpha=-PI / 2, offset=-0.917807287996447),
        Revolute(d=-0.22004128595761935, a=-0.20509321793326424, offset=1.3617449446662127),
        Revolute(d=0.4087406157764789, alpha=0.44392020442861435, offset=-0.5425571608907469),
        Revolute(alpha=2.8464679704414912, offset=-PI / 2),
        Revolute(d=0.15652726621762514, alpha=-0.3451884803825527, offset=-1.5476061685567883),
    ]
    robot = Robot.from_dh(rows, name="nearly parallel shoulder", convention="standard")
    assert shoulder_of(robot)[0] == "general"
    q0 = np.array([[-2.63290526, -1.25548875, -2.16983424, 2.16527726, 2.13149496, 0.27287491]])
    rng = np.random.default_rng(23)
    q0 = np.concatenate([q0, random_q(robot, rng, 300)])
    solve_checked(robot, robot.fk(q0), 1e-11)  # every candidate exact before polishing
    res = robot.ik(robot.fk(q0), respect_limits=False)
    assert (res.status == "ok").all()
    # q1 and q2 nearly redundant: joint errors are the pose's (~1e-12) over
    # sin α and the arm's conditioning; within the check's duplicate threshold
    assert_found(robot, res.solutions, q0, 1e-7)


def centre_jacobian_det(robot: Robot, c_tool: FloatArray, q: FloatArray) -> FloatArray:
    """det of d(wrist centre)/d(q1, q2, q3), from the robot's own Jacobian."""
    T, J = robot.fk(q), robot.jacobian(q)
    r = T[..., :3, :3] @ c_tool  # wrist centre relative to the tool origin
    return np.linalg.det(J[..., :3, :3] + np.cross(J[..., 3:, :3], r[..., :, None], axis=-2))


def fold_configurations(robot: Robot, rng: np.random.Generator, n: int = 30) -> FloatArray:
    """Configurations where two position branches merge (det of the centre's Jacobian 0)."""
    c_tool = c_tool_of(robot)
    q = np.repeat(random_q(robot, rng, n), 2, axis=0)
    span = 1.5 if robot.is_prismatic[2] else PI
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
    """Targets where two position branches merge (a double root): still solved."""
    rng = np.random.default_rng(21)
    robot = random_wrist_arm(rng, shoulder, joint3)
    q = fold_configurations(robot, rng)
    res = robot.ik(robot.fk(q), respect_limits=False)
    assert set(res.status.tolist()) <= {"ok", "singular"}, res.message
    # the original is found, to within what a double root allows: along the
    # fold the pose moves only to second order, so exact solutions (1e-10)
    # can differ from it by ~sqrt(1e-10 / curvature): 3e-4 for a curvature of
    # 1e-3 m/rad² (the flattest fold of these arms; with the numpy of the day the
    # bisection lands one of them 1.008e-4 from its solution)
    assert_found(robot, res.solutions, q, 3e-4)


def test_singular_wrist_returns_a_representative() -> None:
    rng = np.random.default_rng(15)
    q0 = random_q(PUMA, rng, 20)
    q0[:10, 4] = 0.0  # axes 4 and 6 aligned
    q0[10:, 4] = PI  # ... or opposite
    T = PUMA.fk(q0)
    q = solve_checked(PUMA, T)
    _, info = raw(PUMA, T)
    assert info.singular.all()
    assert (info.free == [False, False, False, True, False, True]).all()
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
    res = PUMA.ik(T[0], respect_limits=False)
    assert res.status == "singular" and res.free_joints == (3, 5)


def test_regular_poses_are_not_singular() -> None:
    rng = np.random.default_rng(16)
    _, info = raw(PUMA, PUMA.fk(random_q(PUMA, rng, 50)))
    assert not info.singular.any() and not info.free.any()


def test_shoulder_singularity_frees_q1() -> None:
    rows = [
        Revolute(d=0.5, alpha=PI / 2),
        Revolute(a=0.4),
        Revolute(alpha=PI / 2),
        Revolute(d=0.35, alpha=-PI / 2),
        Revolute(alpha=PI / 2),
        Revolute(d=0.1),
    ]
    robot = Robot.from_dh(rows, name="no shoulder offset", convention="standard")
    q0 = np.array([[0.3, PI / 2, PI / 2, 0.2, 0.4, 0.5]])  # wrist centre on axis 1
    T = robot.fk(q0)
    centre = T[0, :3, 3] - 0.1 * T[0, :3, 2]
    assert np.hypot(centre[0], centre[1]) < 1e-12
    solve_checked(robot, T)
    _, info = raw(robot, T)
    assert info.singular[0] and info.free[0, 0] and not info.free[0, 3]
    res = robot.ik(T[0])
    assert res.status == "singular" and res.free_joints == (0,)


def test_unreachable_target_has_no_branch_and_a_gap() -> None:
    rng = np.random.default_rng(17)
    T = PUMA.fk(random_q(PUMA, rng, 5))
    T[:, :3, 3] += np.array([4.0, -3.0, 2.0])
    q, info = raw(PUMA, T)
    assert np.isnan(q).all()
    gap = info.gap
    # a lower bound of the distance of the wrist centre to those reachable
    samples = PUMA.fk(random_q(PUMA, rng, 20000))
    reach = samples[:, :3, 3]  # PUMA: no tool, the flange origin is the wrist centre
    centre = T[:, :3, 3]
    nearest = np.linalg.norm(centre[:, None] - reach[None], axis=-1).min(axis=1)
    assert (gap > 0).all()
    assert (gap <= nearest).all() and (gap > 0.99 * nearest).all()
    res = PUMA.ik(T)
    assert (res.status == "unreachable").all()
    np.testing.assert_allclose(res.gap, gap)
    robot = random_wrist_arm(rng, "general", "R")
    far = robot.fk(random_q(robot, rng, 3))
    far[:, :3, 3] += 10.0
    q, info = raw(robot, far)
    assert np.isnan(q).all() and (info.gap > 0).all()


def test_orientation_the_wrist_cannot_make() -> None:
    rows = [
        Revolute(d=0.4, alpha=PI / 2),
        Revolute(a=0.4),
        Revolute(alpha=PI / 2),
        Revolute(d=0.4, alpha=0.3),  # a wrist with small twists: a cone of directions
        Revolute(alpha=0.3),
        Revolute(d=0.1),
    ]
    robot = Robot.from_dh(rows, name="narrow wrist", convention="standard")
    rng = np.random.default_rng(18)
    T = robot.fk(np.array([0.2, 0.5, 1.0, 0.3, 0.2, 0.1]))
    flipped = T.copy()  # same wrist centre, tool axis reversed
    centre = T[:3, 3] - 0.1 * T[:3, 2]
    flipped[:3, :3] = T[:3, :3] @ np.diag([1.0, -1.0, -1.0])
    flipped[:3, 3] = centre + 0.1 * flipped[:3, 2]
    q, info = raw(robot, flipped[None])
    assert np.isnan(q).all() and info.gap[0] == 0.0  # position fine, rotation not
    assert len(dls_solutions(robot, flipped, rng)) == 0
    assert robot.ik(flipped).status == "unreachable"


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


def test_builders_refuse_other_arms() -> None:
    ur5 = robot_from_rows(reference_arm("ik_reference.json", "ur5"), "ur5")
    assert classify(ur5).kind != "spherical-wrist-6R"
    assert classify(PUMA).kind == "spherical-wrist-6R"
    assert classify(PUMA).summary == "6R, spherical wrist"
    # axes 1 and 2 coincide (twist 0, no offset): the wrist centre has 2 DOF only
    rows = [Revolute(d=0.3), Revolute(a=0.4), Revolute(alpha=PI / 2)]
    rows += [Revolute(d=0.3, alpha=-PI / 2), Revolute(alpha=PI / 2), Revolute(d=0.1)]
    flat = Robot.from_dh(rows, convention="standard")
    assert classify(flat).kind == "spherical-wrist-6R"
    assert closed_form(flat.chain, "pose") is None
    res = flat.ik(flat.fk(np.full(6, 0.3)), seed=0)  # only q1 + q2 counts: a continuum
    assert (res.method, res.status, res.free_joints) == (
        "analytic:coaxial-pair",
        "singular",
        (0, 1),
    )
    assert classify(Robot.from_dh(rows[:5], convention="standard")).kind == "general"


@pytest.mark.parametrize(("shoulder", "joint3"), [*GEOMETRIES, ("puma", "")])
def test_single_call_equals_the_batch(shoulder: str, joint3: str) -> None:
    """One pose through the solver's single call gives what its threaded batch gives."""
    rng = np.random.default_rng(22)
    robot = PUMA if shoulder == "puma" else random_wrist_arm(rng, shoulder, joint3)
    q0 = random_q(robot, rng, 140)
    q0[:8, 4] = 0.0  # the PUMA's wrist singularity (a regular pose on the others)
    T = robot.fk(q0)
    T[-4:, :3, 3] += 5.0  # out of reach
    T = T[rng.permutation(len(T))]  # blocks of 64 targets holding every kind
    solver = solver_of(robot)
    opts = _core.CheckOptions()
    opts.complete = True
    opts.respect_limits = False
    many = solver.params.ik_batch(robot.chain.core, T, opts, None, None, 4)
    Q, info = raw(robot, T)
    for i in range(len(T)):
        labels = tuple(str(j) for j in range(solver.params.slots))
        one = solver.params.ik(robot.chain.core, T[i], opts, None, labels)
        within, beyond = one.branches, one.out_of_limits_branches
        k, m = len(within), len(beyond)
        np.testing.assert_array_equal(one.solutions, many.q[i][:k])
        np.testing.assert_array_equal(one.out_of_limits, many.q[i][k : k + m])
        assert np.isnan(many.q[i][k + m :]).all()
        np.testing.assert_array_equal(one.residuals, many.res[i][:k])
        assert [int(s) for s in within + beyond] == [s for s in many.slot[i].tolist() if s >= 0]
        assert one.status == many.status[i] and k == many.count[i]
        assert m == many.out_count[i]
        assert one.near_singular == many.near[i] == info.near[i]
        gap = np.nan if one.gap is None else one.gap
        np.testing.assert_array_equal(gap, many.gap[i])
        Qi, *_ = solver.params.candidates(robot.chain.core, T[i])
        np.testing.assert_array_equal(Qi, Q[i])


def test_general_quartic_on_the_eaik_reference_is_exact() -> None:
    name = "general-spherical-wrist"
    arm = reference_arm("ik_reference.json", name)
    robot = robot_from_rows(arm, name)
    T = np.array([s["T"] for s in arm["samples"]])
    q = solve_checked(robot, T, 1e-11)
    for qi, sample in zip(q, arm["samples"], strict=True):
        ours = np.array(distinct(robot, qi))
        theirs = np.array(sample["solutions"])
        assert len(ours) == len(theirs)
        d = joint_distance(robot, ours[:, None, :], theirs[None, :, :])
        assert (d.min(axis=0) < 1e-8).all() and (d.min(axis=1) < 1e-8).all()


@pytest.mark.parametrize("batch", [(), (1,), (3, 2)])
def test_batch_shapes(batch: tuple[int, ...]) -> None:
    rng = np.random.default_rng(27)
    q = random_q(PUMA, rng, int(np.prod(batch, dtype=int))).reshape(*batch, 6)
    res = PUMA.ik(PUMA.fk(q), respect_limits=False)
    if batch == ():
        assert isinstance(res, IKResult) and res.solutions.shape == (8, 6)
        return
    assert isinstance(res, IKBatchResult)
    assert res.solutions.shape == (*batch, 8, 6) and res.status.shape == batch
    assert (res.count == 8).all()
    empty = PUMA.ik(np.zeros((0, 4, 4)))
    assert empty.solutions.shape[0] == 0
