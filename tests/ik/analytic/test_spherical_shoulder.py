"""Closed-form IK of spherical-shoulder arms (Pieper's second case: axes 1-3 meet).

Independent references: forward kinematics of every solution; the inverse
transform composed with numpy (the DH reversal of the sample arms); the
spherical-wrist family solving the same arm given reversed; the built-in Panda's
forward kinematics (for the 6R Panda with q7 locked, whose table is written here by
hand); a multi-start damped-least-squares search (completeness); the geometry of
the joint axes at the solution (branch labels).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.typing import NDArray
from support.helpers import assert_transform_close, rot_x, rot_z, tras_x, tras_z
from support.ik_search import dls_solutions, joint_distance

import kinematica as km
from kinematica.dh import Prismatic, Revolute
from kinematica.dh.lines import length_tol
from kinematica.ik import closed_form
from kinematica.ik.analytic.spherical_shoulder import SPECS, reversed_arm, shoulder_labels
from kinematica.ik.analytic.spherical_wrist import sample_wrist_rows
from kinematica.ik.registry import SolverSpec
from kinematica.ik.structure import features
from kinematica.robot import classify

FloatArray = NDArray[np.float64]
PI = math.pi
#: Every solution reaches its target to this (m, rad: the default check).
REACH_TOL = 1e-10
#: The configuration that made a pose is among the solutions to this (rad, m).
FOUND_TOL = 1e-9

pytestmark = pytest.mark.filterwarnings("ignore::kinematica.KinematicaWarning")


def _robot(rows: list[Revolute | Prismatic], base: FloatArray, tool: FloatArray) -> km.Robot:
    return km.Robot.from_dh(rows, convention="modified", base=base, tool=tool, name="shoulder")


def _q(robot: km.Robot, rng: np.random.Generator, n: int) -> FloatArray:
    q = rng.uniform(-PI, PI, (n, robot.dof))
    return np.where(robot.is_prismatic, rng.uniform(-0.5, 0.8, (n, robot.dof)), q)


def _found(robot: km.Robot, solutions: FloatArray, q: FloatArray) -> float:
    """Distance of q (n,) to the nearest of the solutions (k, n)."""
    return float(np.min(joint_distance(robot, solutions, q), initial=np.inf))


# ------------------------------------------------------------- round trips
@pytest.mark.parametrize("spec", SPECS, ids=[s.kind for s in SPECS])
@pytest.mark.parametrize("degenerate", [False, True], ids=["generic", "degenerate"])
def test_fk_ik_fk_on_random_arms(spec: SolverSpec, degenerate: bool) -> None:
    rng = np.random.default_rng(31 + degenerate)
    for _ in range(6):
        arm = spec.sample_arm(rng, degenerate)
        robot = km.Robot.from_dh(
            arm.links, convention=arm.convention, base=arm.base, tool=arm.tool, name=spec.kind
        )
        assert classify(robot).kind == spec.kind, arm.note
        near = features(robot.chain).near_degenerate
        q = _q(robot, rng, 25)
        T = robot.fk(q)
        batch = robot.ik(T)
        assert batch.method.startswith("analytic:spherical-shoulder"), batch.method
        for i in range(len(q)):
            one = robot.ik(T[i])
            # complete unless the family holds only within the line geometry's tolerance
            assert one.status == "ok" and one.complete == (not near), arm.note
            np.testing.assert_array_equal(one.solutions, batch.solutions[i, : batch.count[i]])
            assert _found(robot, one.solutions, q[i]) <= FOUND_TOL, arm.note
            reached = robot.fk(one.solutions)
            assert_transform_close(reached, np.broadcast_to(T[i], reached.shape), atol=REACH_TOL)


def test_dh_reversal_is_the_inverse_transform() -> None:
    # the sample arms' reversal, checked against numpy's inverse
    rng = np.random.default_rng(32)
    for slide in (False, True):
        rows, _ = sample_wrist_rows(rng, slide, False)
        base, tool = rot_z(0.3) @ tras_x(0.2) @ rot_x(1.1), tras_z(0.1) @ rot_x(-0.4)
        wrist = km.Robot.from_dh(rows, base=base, tool=tool, name="wrist", convention="standard")
        shoulder = _robot(*reversed_arm(rows, base, tool))
        q = _q(wrist, rng, 10)
        assert_transform_close(shoulder.fk(-q[:, ::-1]), np.linalg.inv(wrist.fk(q)), atol=1e-14)


def test_an_arm_given_reversed_is_solved_alike_by_both_families() -> None:
    """A wrist arm's reversed arm (a shoulder arm) has the same solutions, mapped."""
    rng = np.random.default_rng(33)
    for _ in range(4):
        rows, _ = sample_wrist_rows(rng, False, False)
        base, tool = rot_x(0.5) @ tras_z(0.2), rot_z(-0.7) @ tras_x(0.05)
        wrist = km.Robot.from_dh(rows, base=base, tool=tool, name="wrist", convention="standard")
        shoulder = _robot(*reversed_arm(rows, base, tool))
        assert classify(wrist).kind == "spherical-wrist-6R"
        assert classify(shoulder).kind == "spherical-shoulder-6R"
        q = _q(shoulder, rng, 10)
        T = shoulder.fk(q)
        for Ti in T:
            by_shoulder = shoulder.ik(Ti)
            by_wrist = wrist.ik(np.linalg.inv(Ti))
            assert by_shoulder.method == "analytic:spherical-shoulder"
            assert by_wrist.method == "analytic:spherical-wrist"
            mapped = -by_wrist.solutions[:, ::-1]
            assert len(mapped) == len(by_shoulder.solutions)
            for qs in by_shoulder.solutions:
                assert _found(shoulder, mapped, qs) <= FOUND_TOL
            # q = 0 is no singular pose of these arms: the names map one to one
            names = dict(zip(by_wrist.branches, map(tuple, mapped.round(9)), strict=True))
            for label, qs in zip(by_shoulder.branches, by_shoulder.solutions, strict=True):
                pos, _, bend = _wrist_label(label)
                assert joint_distance(shoulder, np.array(names[f"{pos}, wrist {bend}"]), qs) < 1e-8


def _wrist_label(shoulder_label: str) -> tuple[str, str, str]:
    """(the wrist arm's position label, '', the bend) of a shoulder arm's label."""
    parts = shoulder_label.split(", ")
    bend = parts[0].removeprefix("shoulder ")
    if parts[1].startswith("wrist position"):
        return parts[1].removeprefix("wrist "), "", bend
    far = [p.replace("wrist", "shoulder") for p in parts[1:]][::-1]
    return ", ".join(far), "", bend


def test_labels_read_the_reversed_arm_from_base_to_tip() -> None:
    labels = shoulder_labels(("shoulder right, elbow up", "shoulder left, elbow down"))
    assert labels == (
        "shoulder no-flip, elbow up, wrist right",
        "shoulder flip, elbow up, wrist right",
        "shoulder no-flip, elbow down, wrist left",
        "shoulder flip, elbow down, wrist left",
    )
    assert shoulder_labels(("position 3",))[1] == "shoulder flip, wrist position 3"


def _triple(robot: km.Robot, q: FloatArray) -> FloatArray:
    """(z1 × z2) · z3 of the current axes: its sign is the side joint 2 bends the shoulder."""
    h, _ = robot.joint_axes(q)
    return np.einsum("...i,...i->...", np.cross(h[..., 0, :], h[..., 1, :]), h[..., 2, :])


def test_no_flip_bends_the_shoulder_as_at_home() -> None:
    rng = np.random.default_rng(34)
    spec = SPECS[0]
    for _ in range(4):
        arm = spec.sample_arm(rng, False)
        robot = km.Robot.from_dh(arm.links, convention="modified", base=arm.base, tool=arm.tool)
        home = float(_triple(robot, np.zeros(6)))
        assert abs(home) > 1e-3  # a generic arm: q = 0 is no singular pose
        res = robot.ik(robot.fk(_q(robot, rng, 1))[0])
        for label, q in zip(res.branches, res.solutions, strict=True):
            assert ("no-flip" in label) == (np.sign(_triple(robot, q)) == np.sign(home))


# ----------------------------------------------------- the Panda, q7 locked
def panda_6r(q7: float, tilt: float = 0.0, miss: float = 0.0) -> km.Robot:
    """The Panda's modified DH table (Franka's documentation), joint 7 at q7 in the tool.

    ``tilt`` turns axis 3 off axis 1 at q = 0 (an offset of joint 2); ``miss`` (m)
    moves axis 2 off axis 1 (a1).
    """
    rows = [
        Revolute(d=0.333),
        Revolute(a=miss, alpha=-PI / 2, offset=tilt),
        Revolute(d=0.316, alpha=PI / 2),
        Revolute(a=0.0825, alpha=PI / 2),
        Revolute(d=0.384, a=-0.0825, alpha=-PI / 2),
        Revolute(alpha=PI / 2),
    ]
    # joint 7's row (a6 = 0.088, α6 = 90°, d7 = 0) at q7, then the flange 0.107 m along z7
    tool = rot_x(PI / 2) @ tras_x(0.088) @ rot_z(q7) @ tras_z(0.107)
    return km.Robot.from_dh(rows, convention="modified", tool=tool, name="panda q7 locked")


def test_the_hand_written_panda_is_the_built_in_one() -> None:
    panda, six = km.load("panda"), panda_6r(0.3)
    q = np.random.default_rng(35).uniform(-2.0, 2.0, (8, 6))
    full = np.concatenate([q, np.full((8, 1), 0.3)], axis=1)
    assert_transform_close(six.fk(q), panda.fk(full), atol=1e-14)


def test_panda_with_q7_locked_gives_all_its_solutions() -> None:
    robot = panda_6r(0.3)
    assert classify(robot).kind == "spherical-shoulder-6R"
    rng = np.random.default_rng(36)
    counts = []
    for q in rng.uniform(-2.5, 2.5, (4, 6)):
        T = robot.fk(q)
        res = robot.ik(T)
        assert res.status == "ok" and res.method == "analytic:spherical-shoulder"
        assert len(res.solutions) <= 8
        assert _found(robot, res.solutions, q) <= FOUND_TOL
        reached = robot.fk(res.solutions)
        assert_transform_close(reached, np.broadcast_to(T, reached.shape), atol=REACH_TOL)
        # every solution a numeric search finds is one of them
        for qs in dls_solutions(robot, T, rng, starts=60):
            assert _found(robot, res.solutions, qs) <= 1e-7
        counts.append(len(res.solutions))
    assert max(counts) == 8, counts


@pytest.mark.parametrize(
    ("tilt", "home_decides"),
    [(0.0, False), (1e-10, False), (-1e-10, False), (1e-8, True), (-1e-8, True)],
)
def test_no_flip_of_a_singular_home_is_q2_positive(tilt: float, home_decides: bool) -> None:
    """At q = 0 axes 1 and 3 of the Panda are aligned: no-flip is then sin q2 > 0.

    An axis 3 turned off axis 1 by more than the line geometry's angle tolerance
    (1e-9) makes q = 0 a regular pose, whose bend no-flip then is, whichever sign
    sin q2 has there; within it, q = 0 is taken as singular.
    """
    robot = panda_6r(0.3, tilt)
    home = float(_triple(robot, np.zeros(6)))
    q = np.random.default_rng(37).uniform(-2.5, 2.5, (3, 6))
    for qi in q:
        res = robot.ik(robot.fk(qi))
        for label, qs in zip(res.branches, res.solutions, strict=True):
            no_flip = (
                np.sign(_triple(robot, qs)) == np.sign(home) if home_decides else np.sin(qs[1]) > 0
            )
            assert ("no-flip" in label) == no_flip, (label, qs)


@pytest.mark.parametrize("q13", [0.9, 3.0])
def test_a_singular_shoulder_frees_joints_1_and_3_within_the_limits(q13: float) -> None:
    """q2 = 0 aligns axes 1 and 3: only q1 + q3 is fixed; the representative is within limits.

    With q1 + q3 = 3.0 and |q1|, |q3| <= 2.8973 (the Panda's limits), q3 = 0 would put
    q1 outside: the family is followed into the limits.
    """
    robot = panda_6r(0.3).with_limits(km.load("panda").qlim[:6])
    q = np.array([q13 - 0.5, 0.0, 0.5, -1.2, 0.3, 1.5])
    T = robot.fk(q)
    res = robot.ik(T)
    assert res.status == "singular" and res.free_joints == (0, 2)
    lo, hi = robot.qlim.T
    assert ((res.solutions >= lo) & (res.solutions <= hi)).all()
    on_it = res.solutions[np.abs(res.solutions[:, 1]) < 1e-12]
    assert len(on_it) >= 1
    sums = np.angle(np.exp(1j * (on_it[:, 0] + on_it[:, 2] - q13)))
    assert np.abs(sums).max() < 1e-12
    reached = robot.fk(res.solutions)
    assert_transform_close(reached, np.broadcast_to(T, reached.shape), atol=REACH_TOL)


@pytest.mark.parametrize(("factor", "meet"), [(0.1, True), (10.0, False)])
def test_axes_meet_within_the_line_geometrys_length_tolerance(factor: float, meet: bool) -> None:
    """Axes 1 and 2 missing each other by a tenth of length_tol still meet; by 10x, not."""
    size = features(panda_6r(0.3).chain).size
    robot = panda_6r(0.3, miss=factor * length_tol(size))
    q = np.random.default_rng(38).uniform(-2.5, 2.5, 6)
    T = robot.fk(q)
    res = robot.ik(T, seed=0)
    if meet:
        # the exact shoulder's candidates, repaired to this arm's solutions
        assert classify(robot).kind == "spherical-shoulder-6R"
        assert res.method == "analytic:spherical-shoulder" and not res.complete
        assert _found(robot, res.solutions, q) <= FOUND_TOL
        reached = robot.fk(res.solutions)
        assert_transform_close(reached, np.broadcast_to(T, reached.shape), atol=REACH_TOL)
    else:  # no shoulder: the general 6R's elimination takes the arm
        assert classify(robot).kind == "general-6R"
        assert res.method == "analytic:general-6R"


def test_a_slide_after_the_shoulder_and_the_builders_refusals() -> None:
    stanford_reversed = _robot(*reversed_arm(*_stanford()))
    assert classify(stanford_reversed).kind == "spherical-shoulder-prr"
    assert classify(stanford_reversed).summary == "spherical shoulder + PRR"
    # "slide out" is the larger q4 (the reversed arm's smaller q'3 = -q4)
    for q4 in (-0.4, 0.3):
        res = stanford_reversed.ik(stanford_reversed.fk(np.array([0.3, 0.8, -0.5, q4, 1.0, 0.2])))
        slid = {label: q[3] for label, q in zip(res.branches, res.solutions, strict=True)}
        outs = [v for k, v in slid.items() if "slide out" in k]
        ins = [v for k, v in slid.items() if "slide in" in k]
        assert len(outs) == len(ins) == 4 and min(outs) > max(ins)
    # both a spherical wrist and a spherical shoulder: the wrist's solver takes it
    both = [Revolute(d=0.3, alpha=PI / 2), Revolute(alpha=PI / 2), Revolute(d=0.4, alpha=-PI / 2)]
    both += [Revolute(alpha=PI / 2), Revolute(alpha=-PI / 2), Revolute(d=0.1)]
    robot = km.Robot.from_dh(both, convention="standard")
    assert features(robot.chain).shoulder_center is not None
    assert classify(robot).kind == "spherical-wrist-6R"
    # axes 5 and 6 coincide (twist 0, no offset): the shoulder centre has 2 DOF from the
    # tool, and only q5 + q6 counts: a continuum (kinematica.ik.coaxial), not the search
    flat = [Revolute(d=0.3, alpha=PI / 2), Revolute(alpha=-PI / 2), Revolute(d=0.4, alpha=PI / 2)]
    flat += [Revolute(a=0.3, alpha=PI / 2), Revolute(d=0.3), Revolute(d=0.1)]
    robot = km.Robot.from_dh(flat, convention="standard")
    assert classify(robot).kind == "spherical-shoulder-6R"
    assert closed_form(robot.chain, "pose") is None
    res = robot.ik(robot.fk(np.full(6, 0.3)), seed=0)
    assert (res.method, res.status, res.free_joints) == (
        "analytic:coaxial-pair",
        "singular",
        (4, 5),
    )


def _stanford() -> tuple[list[Revolute | Prismatic], FloatArray, FloatArray]:
    rows: list[Revolute | Prismatic] = [
        Revolute(d=0.412, alpha=-PI / 2),
        Revolute(d=0.154, alpha=PI / 2),
        Prismatic(theta=-PI / 2),
        Revolute(alpha=-PI / 2),
        Revolute(alpha=PI / 2),
        Revolute(d=0.263),
    ]
    return rows, np.eye(4), np.eye(4)
