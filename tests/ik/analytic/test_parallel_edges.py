"""UR-type arms at the edges: singular sets, near misses, huge targets, batch = single.

Targets made by ``robot.fk(q)`` are never ``unreachable`` or ``not_found``,
however close q is to a singular set; a continuum is ``singular`` with its free
joints; a double root is one solution. Each singular set is derived by hand
below, reached by construction, then left by 1e-8 to 1e-12 rad.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.typing import NDArray
from support.helpers import SPECIAL_ANGLES
from support.parallel_arms import (
    MODES,
    PI,
    UR5,
    UR5_A5,
    UR5_P56,
    assert_honest,
    assert_reaches,
    joint_gap,
    random_arm,
)

from kinematica import _core_testing
from kinematica.dh import Revolute
from kinematica.ik.result import IKBatchResult, IKResult
from kinematica.ik.solvers import closed_form
from kinematica.robot import Robot

FloatArray = NDArray[np.float64]
OFF = (1e-8, 1e-10, 1e-12)  # how far q is moved off a singular set (rad)
#: The UR5 in each mode. Tests are parametrized by the name: a robot held by pytest's
#: parametrization lives until the interpreter's very end, past the core's teardown.
BY_MODE = {"meet": UR5, "apart": UR5_A5, "parallel": UR5_P56}

#: UR type, equal links 2 and 3, the elbow folded onto axis 2 at q3 = 0.
FOLD = Robot.from_dh(
    [
        Revolute(d=0.3, alpha=PI / 2),
        Revolute(a=0.4),
        Revolute(a=0.4, offset=PI),
        Revolute(d=0.11, alpha=PI / 2),
        Revolute(d=0.09, alpha=-PI / 2),
        Revolute(d=0.08),
    ],
    name="fold",
    convention="standard",
)
#: UR type whose axes 4, 5, 6 meet (d5 = 0): axis 4 is where the wrist point
#: is, for every branch alike. Stretched at q3 = 0.
STRETCH = Robot.from_dh(
    [
        Revolute(d=0.3, alpha=PI / 2),
        Revolute(a=0.5),
        Revolute(a=0.4),
        Revolute(d=0.1, alpha=PI / 2),
        Revolute(alpha=-PI / 2),
        Revolute(d=0.08),
    ],
    name="stretch",
    convention="standard",
)


def one(robot: Robot, T: FloatArray, **kw: object) -> IKResult:
    res = robot.ik(T, respect_limits=False, **kw)  # type: ignore[arg-type]
    assert isinstance(res, IKResult)
    return res


def size_of(robot: Robot) -> float:
    """The arm's size as the solver measures it (its reach bound, m)."""
    P = _core_testing.parallel.values(robot.chain.core)
    assert P is not None
    return float(P["scale"])


# ------------------------------------------------------------ the aligned wrist
def test_wrist_aligned_is_singular_with_q6_free() -> None:
    """q5 = 0 or π on the UR5 (also with a5 != 0): axis 6 along axes 2-4, q6 turns with q2-q4."""
    rng = np.random.default_rng(40)
    for robot in (UR5, UR5_A5):
        q = rng.uniform(-PI, PI, (30, 6))
        q[:, 4] = rng.choice([0.0, PI], 30)
        many = robot.ik(robot.fk(q), respect_limits=False)
        assert isinstance(many, IKBatchResult)
        assert (many.status == "singular").all()
        assert (many.free == [False, True, True, True, False, True]).all()
        assert (many.count >= 2).all()
        for i in range(30):
            assert_reaches(robot, many[i], robot.fk(q[i]))


@pytest.mark.parametrize("mode", ["meet", "apart"])
def test_near_aligned_wrist_is_honest(mode: str) -> None:
    """Axis 6 within 1e-12..1e-3 rad of axes 2-4 (where the first release lost roots)."""
    robot = BY_MODE[mode]
    rng = np.random.default_rng(41)
    for beta in 10.0 ** np.arange(-12, -2):
        q = rng.uniform(-PI, PI, (25, 6))
        q[:, 4] = rng.choice([0.0, PI], 25) + rng.choice([-1, 1], 25) * beta
        many = robot.ik(robot.fk(q), respect_limits=False)
        assert isinstance(many, IKBatchResult)
        for i in range(25):
            assert_honest(robot, q[i], many[i])
            if beta >= 1e-6:
                assert many.status[i] == "ok" and joint_gap(many[i].solutions, q[i]) < 1e-6


def test_near_aligned_wrist_random_arms() -> None:
    rng = np.random.default_rng(42)
    for mode in ("meet", "apart"):
        for modified in (False, True):
            robot = random_arm(rng, mode, modified, square=True)
            # where the wrist aligns: q5 making axis 6 parallel to axis 2
            grid = np.zeros((3601, 6))
            grid[:, 4] = np.linspace(-PI, PI, 3601)
            h, _ = robot.joint_axes(grid)
            q5 = grid[np.argmin(np.linalg.norm(np.cross(h[:, 1], h[:, 5]), axis=-1)), 4]
            for off in (0.0, *OFF, 1e-6):
                q = rng.uniform(-PI, PI, (10, 6))
                q[:, 4] = q5 + off
                many = robot.ik(robot.fk(q), respect_limits=False)
                assert isinstance(many, IKBatchResult)
                for i in range(10):
                    assert_honest(robot, q[i], many[i])


def test_aligned_wrist_tolerance() -> None:
    """Axis 6 within ``CONTINUUM_TOL`` = 1e-12 (sine) of axes 2-4 is the continuum; beyond, not."""
    q = np.array([0.4, -1.1, 1.3, -0.6, 0.0, 0.9])
    for robot in (UR5, UR5_A5):
        for q5, status in ((1e-13, "singular"), (1e-11, "ok")):
            q[4] = q5
            res = one(robot, robot.fk(q))
            assert res.status == status, (robot.name, q5, res.message)
            assert_honest(robot, q, res)


# --------------------------------------------------------------------- the elbow
def test_folded_elbow_with_equal_links_is_singular() -> None:
    """Axis 4 on axis 2 (equal links, q3 = 0 here): q2 turns with q4."""
    rng = np.random.default_rng(43)
    q = rng.uniform(-PI, PI, (20, 6))
    q[:, 2] = 0.0
    many = FOLD.ik(FOLD.fk(q), respect_limits=False)
    assert isinstance(many, IKBatchResult)
    assert (many.status == "singular").all()
    assert many.free[:, [1, 3]].all()
    for i in range(20):
        assert_reaches(FOLD, many[i], FOLD.fk(q[i]))
    for off in OFF:
        q[:, 2] = off * rng.choice([-1, 1], 20)
        many = FOLD.ik(FOLD.fk(q), respect_limits=False)
        assert isinstance(many, IKBatchResult)
        for i in range(20):
            assert_honest(FOLD, q[i], many[i])


def test_folded_elbow_tolerance() -> None:
    """|axis 4 - axis 2| = 2 a sin(q3 / 2): within ``CONTINUUM_TOL`` = 1e-12 of the span 2 a."""
    q = np.array([0.3, -0.8, 0.0, 1.1, 0.7, -0.4])
    for q3, status in ((2e-13, "singular"), (2e-11, "ok")):
        q[2] = q3
        res = one(FOLD, FOLD.fk(q))
        assert res.status == status, (q3, res.message)
        assert_honest(FOLD, q, res)


def test_stretched_and_folded_elbow_are_double_roots() -> None:
    """q3 = 0 (stretched) and π (folded, unequal links) on the UR5: the elbows coincide."""
    rng = np.random.default_rng(44)
    for q3 in (0.0, PI):
        q = rng.uniform(-PI, PI, (20, 6))
        q[:, 2] = q3
        q[:, 4] = rng.uniform(0.3, 2.8, 20)  # away from the aligned wrist
        many = UR5.ik(UR5.fk(q), respect_limits=False)
        assert isinstance(many, IKBatchResult)
        assert (many.status == "ok").all()
        for i in range(20):
            sols = many[i].solutions
            assert joint_gap(sols, q[i]) < 1e-4
            # q's shoulder and wrist branch: the double root once, or split by
            # round-off into two solutions next to each other; never none
            same = np.abs(np.angle(np.exp(1j * (sols[:, [0, 4]] - q[i, [0, 4]])))).max(axis=1)
            branch = sols[same < 1e-6]
            assert 1 <= len(branch) <= 2
            assert np.abs(np.angle(np.exp(1j * (branch - branch[0])))).max() < 1e-4
            for off in OFF:
                qo = q[i] + np.array([0, 0, off, 0, 0, 0])
                assert_honest(UR5, qo, one(UR5, UR5.fk(qo)))


def test_reach_near_tolerance() -> None:
    """A target beyond the stretched arm: touching (``TRIG_TOL`` = 1e-10 of the span),
    near (``NEAR_TOL`` = 1e-6: the least-squares elbow is checked, ``not_found``), or out
    of reach (``unreachable``).

    With axes 4-6 meeting, every branch puts axis 4 at the wrist point: moving
    the target along the stretched arm moves it out of the triangle's reach by
    exactly that distance, in every branch.
    """
    q = np.array([0.3, -0.7, 0.0, 0.9, 1.2, -0.5])
    T = STRETCH.fk(q)
    _, p = STRETCH.joint_axes(q)
    h, _ = STRETCH.joint_axes(q)
    out = p[3] - p[1]
    out -= (out @ h[1]) * h[1]
    span = float(np.linalg.norm(out))
    assert span == pytest.approx(0.9, abs=1e-12)
    out /= span
    for miss, status in (
        (1e-11, "ok"),
        (1e-7, "not_found"),
        (1e-5, "unreachable"),
    ):
        moved = T.copy()
        moved[:3, 3] += miss * span * out
        res = one(STRETCH, moved)
        assert res.status == status, (miss, res.message)


# ------------------------------------------------------------------ the shoulder
def ur5_shoulder_double_root(rng: np.random.Generator) -> FloatArray:
    """A UR5 configuration whose two shoulder branches coincide.

    The shoulder equation is ``k1·(c - p1) = d4`` (c the wrist point, k1 axis
    2's direction after q1, d4 the offset along k1); its two roots merge where
    its derivative ``(h1 × k1)·(c - p1)`` vanishes: the wrist point lies on the
    plane through axis 1 parallel to axis 2. In frame 1 of the UR5's table that
    is x = 0: ``a2 cos q2 + a3 cos(q2 + q3) + d5 sin(q2 + q3 + q4) = 0``, linear
    in ``cos q2``, ``sin q2`` once q3 and θ234 = q2 + q3 + q4 are chosen.
    """
    a2, a3, d5 = -0.425, -0.39225, 0.09465
    q3, th = rng.uniform(-2.5, 2.5), rng.uniform(-PI, PI)
    A, B, C = a2 + a3 * math.cos(q3), -a3 * math.sin(q3), -d5 * math.sin(th)
    r = math.hypot(A, B)
    q2 = math.atan2(B, A) + math.acos(C / r)
    return np.array([rng.uniform(-PI, PI), q2, q3, th - q2 - q3, rng.uniform(0.3, 2.8), 0.4])


def test_shoulder_double_root_is_one_solution() -> None:
    rng = np.random.default_rng(45)
    for _ in range(10):
        q = ur5_shoulder_double_root(rng)
        h, p = UR5.joint_axes(q)
        c = UR5.fk(q, all_frames=True)[5, :3, 3]  # UR5 frame 5: where axes 5 and 6 meet
        assert abs((c - p[0]) @ np.cross(h[0], h[1])) < 1e-15  # the derivation above
        res = one(UR5, UR5.fk(q))
        assert res.status == "ok" and res.count <= 4, res.message
        assert np.ptp(np.angle(np.exp(1j * (res.solutions[:, 0] - q[0])))) < 1e-7
        assert joint_gap(res.solutions, q) < 1e-7
        for off in OFF:
            qo = q + np.array([0, off, 0, 0, 0, 0])
            assert_honest(UR5, qo, one(UR5, UR5.fk(qo)))


def shoulder_discriminant(q: FloatArray) -> float:
    """``1 - d4² / |w⊥|²``: the UR5 shoulder equation's discriminant over its scale.

    ``k1·w = d4`` with ``w = c - p1`` has roots ``±acos(d4 / |w⊥|)`` about the
    direction of ``w⊥`` (w across axis 1): they merge when ``|w⊥| = d4``.
    """
    h, p = UR5.joint_axes(q)
    w = UR5.fk(q, all_frames=True)[5, :3, 3] - p[0]
    across = w - (w @ h[0]) * h[0]
    return float(1.0 - 0.10915**2 / (across @ across))


def test_shoulder_double_root_tolerance() -> None:
    """Roots within ``DOUBLE_ROOT_TOL`` = 1e-14 (discriminant over scale) are one; beyond, two
    candidates. Either way the shoulders, 6e-7 rad apart at 1e-13, are one solution to
    tolerance in the answer (the check's MERGE_SPAN), and the target is near_singular."""
    rng = np.random.default_rng(48)
    q = ur5_shoulder_double_root(rng)
    dq = np.array([0.0, 1e-6, 0.0, 0.0, 0.0, 0.0])
    per = shoulder_discriminant(q + dq)  # the discriminant grows as q2's offset squared
    params = closed_form(UR5.chain, "pose").params
    for rel, shoulders in ((1e-15, 1), (1e-13, 2)):
        qo = q + dq * math.sqrt(rel / per)
        assert shoulder_discriminant(qo) == pytest.approx(rel, rel=0.05)
        T = UR5.fk(qo)
        Q = params.candidates(UR5.chain.core, T)[0]
        Q = Q[np.isfinite(Q).all(axis=1)]
        q1 = np.angle(np.exp(1j * (Q[:, 0] - qo[0])))
        assert len(np.unique(np.round(q1, 12))) == shoulders, (rel, q1)
        res = one(UR5, T)
        assert res.status == "ok" and res.near_singular
        q1 = np.angle(np.exp(1j * (res.solutions[:, 0] - qo[0])))
        assert len(np.unique(np.round(q1, 12))) == 1, (rel, q1)
        assert joint_gap(res.solutions, qo) < 1e-6


ZERO_OFFSET_ROWS = [
    Revolute(d=0.1, alpha=PI / 2),
    Revolute(a=0.4),
    Revolute(a=0.3),
    Revolute(alpha=PI / 2),
    Revolute(d=0.1, alpha=-PI / 2),
    Revolute(d=0.08),
]


def wrist_point_at(distance: float) -> FloatArray:
    """A configuration of the zero-offset arm with the wrist point ``distance`` from axis 1.

    No offset along axis 2 (d2 + d3 + d4 = 0): the wrist point (frame 5's
    origin of the first five rows) can reach axis 1 (the base z axis), where
    q1 turns freely. q2, q3, q4 move it in the arm's plane (through axis 1 at
    angle q1): Newton steps drive it to ``distance`` from the axis there.
    """
    first5 = Robot.from_dh(ZERO_OFFSET_ROWS[:5], convention="standard")
    q = np.array([0.3, 0.9, -1.2, 0.4, 0.7, -0.5])
    goal = distance * np.array([math.cos(q[0]), math.sin(q[0])])
    for _ in range(30):
        e = goal - first5.fk(q[:5])[:2, 3]
        J = first5.jacobian(q[:5])[:2, 1:4]
        q[1:4] += np.linalg.pinv(J) @ e
    assert np.abs(first5.fk(q[:5])[:2, 3] - goal).max() < 1e-15
    return q


def test_wrist_point_on_axis_1_is_singular_with_q1_free() -> None:
    robot = Robot.from_dh(ZERO_OFFSET_ROWS, convention="standard")
    first5 = Robot.from_dh(ZERO_OFFSET_ROWS[:5], convention="standard")
    for distance in (0.0, 1e-12, 1e-10, 1e-8):
        q = wrist_point_at(distance)
        res = one(robot, robot.fk(q))
        if distance == 0.0:
            assert res.status == "singular" and 0 in res.free_joints, res.message
            assert_reaches(robot, res, robot.fk(q))
        else:
            assert_honest(robot, q, res)
    # CONTINUUM_TOL = 1e-12 of the arm's size: targets whose wrist point is ``distance``
    # from axis 1
    q = wrist_point_at(0.0)
    T0 = robot.fk(q)
    size = size_of(robot)
    for distance, status in ((1e-13 * size, "singular"), (1e-11 * size, "ok")):
        T = T0.copy()
        T[:2, 3] += np.array([distance, 0.0]) - first5.fk(q[:5])[:2, 3]  # wrist point at (d, 0)
        res = one(robot, T)
        assert res.status == status, (distance, res.message)
        assert (0 in res.free_joints) == (status == "singular")
        assert_reaches(robot, res, T)


def test_quartic_vanishing_is_singular_with_q1_free() -> None:
    """Axes 5 and 6 apart, axis 6 along axis 1 through it: (1) and (2) hold for every q1.

    Both left sides ``k1·y`` are constant in q1 when ``y`` lies along axis 1
    (here ``k ⊥ h1``: zero), so every q1 solves, with the q5 making
    ``k·R5 h6 = 0`` if that q5 also puts p6 at axis 1's height: the offset d4
    (along k) is chosen for it.
    """

    def arm(d4: float) -> Robot:
        return Robot.from_dh(
            [
                Revolute(d=0.1, alpha=PI / 2),
                Revolute(a=0.4),
                Revolute(a=0.3),
                Revolute(d=d4, alpha=1.2),
                Revolute(d=0.1, a=0.05, alpha=-0.9),
                Revolute(d=0.08),
            ],
            convention="standard",
        )

    P = _core_testing.parallel.values(arm(0.0).chain.core)
    assert P is not None and P["mode"] == 2  # axes 5 and 6 apart: the quartic
    D1, E1, F1, D2, E2, F2 = (P[name] for name in ("D1", "E1", "F1", "D2", "E2", "F2"))
    q5 = math.atan2(E1, D1) + math.acos(-F1 / math.hypot(D1, E1))  # k·R5 h6 = 0
    robot = arm(-(D2 * math.cos(q5) + E2 * math.sin(q5) + F2))
    P = _core_testing.parallel.values(robot.chain.core)
    assert P is not None
    M, h6, p6 = robot.fk(np.zeros(6)), robot.joint_axes()[0][5], P["p6"]

    def off_axis_1(v: FloatArray) -> FloatArray:  # axis 6 and p6 off the base z axis
        T = robot.fk(np.array([0.3, *v[:3], q5, v[3]]))
        R = T[:3, :3] @ M[:3, :3].T  # G = T M⁻¹
        return np.array([*(R @ h6)[:2], *(R @ (p6 - M[:3, 3]) + T[:3, 3])[:2]])

    v = np.array([1.0, -1.0, 0.5, 0.2])
    for _ in range(40):  # Newton (finite differences) on the four conditions
        J = np.stack(
            [(off_axis_1(v + 1e-7 * e) - off_axis_1(v - 1e-7 * e)) / 2e-7 for e in np.eye(4)], 1
        )
        v -= np.linalg.lstsq(J, off_axis_1(v), rcond=None)[0]
    assert np.abs(off_axis_1(v)).max() < 1e-13
    q = np.array([0.3, *v[:3], q5, v[3]])
    res = one(robot, robot.fk(q))
    assert res.status == "singular" and res.free_joints[0] == 0 and 4 not in res.free_joints
    assert_reaches(robot, res, robot.fk(q))


#: The zero-offset arm with a wrist twist of 1 rad: k·R5 h6 spans [-sin 1, sin 1] only, so
#: with the wrist point on axis 1, q5 has a root over part of q1's turn only.
NARROW_WRIST_ROWS = [*ZERO_OFFSET_ROWS[:4], Revolute(d=0.1, alpha=-1.0), ZERO_OFFSET_ROWS[5]]


def wrist_point_on_axis_1(rows: list[Revolute], q: FloatArray) -> FloatArray:
    """q with q2, q3, q4 moved (Newton) to put the wrist point (frame 5's origin of the
    first five rows) on axis 1, the base z axis."""
    first5 = Robot.from_dh(rows[:5], convention="standard")
    q = q.copy()
    for _ in range(40):
        J = first5.jacobian(q[:5])[:2, 1:4]
        q[1:4] -= np.linalg.pinv(J) @ first5.fk(q[:5])[:2, 3]
    assert np.abs(first5.fk(q[:5])[:2, 3]).max() < 1e-15
    return q


@pytest.mark.parametrize("where", ["wrist point on axis 1", "axes 5, 6 parallel to axis 1"])
def test_a_continuum_in_q1_is_represented_where_the_other_joints_follow(where: str) -> None:
    """Where q1 turns freely, the continuum spans an arc of q1 only: the other joints
    follow it while q5 has a root and the triangle closes. With the wrist point on axis
    1 of an arm whose wrist cannot point everywhere (NARROW_WRIST_ROWS), or axes 5 and
    6 parallel to axis 1 (the UR5 with α5 = 0, a5 = 6 cm: q2 + q3 + q4 = 0), q1 = 0 (the
    middle of its limits) may lie off the arc: those poses made by FK were answered
    "unreachable" (issue 32, item 4a: 3 and 18 of these 20). The representative is
    now a q1 of the arc (FREE_Q1_SAMPLES)."""
    rng = np.random.default_rng(60)
    robot = (
        Robot.from_dh(NARROW_WRIST_ROWS, convention="standard")
        if where.startswith("wrist")
        else UR5_P56
    )
    for _ in range(20):
        q = rng.uniform(-PI, PI, 6)
        if where.startswith("wrist"):
            q = wrist_point_on_axis_1(NARROW_WRIST_ROWS, q)
        else:
            q[3] = -(q[1] + q[2])
        T = robot.fk(q)
        res = one(robot, T)
        assert res.status == "singular" and 0 in res.free_joints, (q.tolist(), res.message)
        assert_reaches(robot, res, T)


# ----------------------------------------------------- issue 13, item 4 (UR type)
def test_issue13_item4_equal_links_folded_is_singular() -> None:
    """a2 = a3, folded at q3 = 0 (joint 3 offset π): was ``unreachable``; q2 is free."""
    robot = Robot.from_dh(
        [
            Revolute(d=1, alpha=PI / 2),
            Revolute(a=1),
            Revolute(a=1, offset=PI),
            Revolute(alpha=PI / 2),
            Revolute(alpha=-PI / 2),
            Revolute(),
        ],
        convention="standard",
    )
    rng = np.random.default_rng(46)
    qs = np.vstack([np.zeros(6), rng.uniform(-PI, PI, (10, 6))])
    qs[:, 2] = 0.0
    for q in qs:
        res = one(robot, robot.fk(q))
        assert res.method == "analytic:three-parallel-6R"
        assert res.status == "singular" and {1, 3} <= set(res.free_joints), res.message
        assert_reaches(robot, res, robot.fk(q))
    for q in rng.uniform(-PI, PI, (10, 6)):  # away from the fold: the generating q
        assert_honest(robot, q, one(robot, robot.fk(q)))


def test_issue13_item4_continuum_is_not_four_points() -> None:
    """a2 = a3 = 0.8968000212840725, d4 = 1, q = 0: was ``ok`` with 4 solutions; q2 is free."""
    a = 0.8968000212840725
    robot = Robot.from_dh(
        [
            Revolute(d=1, alpha=PI / 2),
            Revolute(a=a),
            Revolute(a=a, offset=PI),
            Revolute(d=1, alpha=PI / 2),
            Revolute(alpha=-PI / 2),
            Revolute(),
        ],
        convention="standard",
    )
    res = one(robot, robot.fk(np.zeros(6)))
    assert res.status == "singular", res.message
    assert {1, 3} <= set(res.free_joints)
    assert "q2" in res.message
    assert_reaches(robot, res, robot.fk(np.zeros(6)))


# ------------------------------------------------------- unreachable, and huge
def test_unreachable_poses_have_a_gap() -> None:
    T = UR5.fk(np.array([0.1, -1.0, 1.2, 0.3, 0.8, 0.2]))
    far = T.copy()
    far[:3, 3] += [5.0, 0.0, 0.0]  # 5 m away: the distance to reach is under 5 m
    res = one(UR5, far)
    assert res.status == "unreachable" and res.gap is not None and 0.0 < res.gap <= 5.0
    # the wrist point 0.05 m from axis 1, inside the d4 = 0.10915 m shoulder cylinder
    c = UR5.joint_axes()[1][5]  # UR5 DH frame 5: where axes 5 and 6 meet, at q = 0
    Minv = np.linalg.inv(UR5.fk(np.zeros(6)))
    cM = Minv[:3, :3] @ c + Minv[:3, 3]  # c in the tool frame: G(c) = p + R cM
    inside = T.copy()
    inside[:3, 3] = np.array([0.05, 0.0, 0.3]) - T[:3, :3] @ cM
    res = one(UR5, inside)
    assert res.status == "unreachable" and res.gap == pytest.approx(0.10915 - 0.05, abs=1e-12)


@pytest.mark.parametrize("mode", MODES)
def test_huge_targets_are_unreachable_without_warnings(mode: str) -> None:
    """Issue 13 item 6: positions of 1.4e154 and more overflowed ``x * x``."""
    robot = BY_MODE[mode]
    for x in (1.4e154, 1e300, 1.7e308, -1e200):
        T = np.eye(4)
        T[0, 3] = x
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            res = one(robot, T)
            many = robot.ik(T[None])
        assert res.status == "unreachable" and res.gap is not None
        assert res.gap == pytest.approx(abs(x), rel=1e-12)
        assert isinstance(many, IKBatchResult)
        assert many.status[0] == "unreachable" and many.gap[0] == res.gap


# ---------------------------------------------------------- batch equals single
def test_batch_equals_single_on_every_kind_of_target() -> None:
    """Solution by solution, message by message: reachable, unreachable, singular, out of limits."""
    rng = np.random.default_rng(47)
    for robot in (UR5, UR5_A5, UR5_P56, FOLD):
        q = rng.uniform(-PI, PI, (8, 6))
        q[2, 4] = 0.0  # aligned wrist (UR5, UR5 a5)
        q[3, 2] = 0.0  # folded elbow (FOLD)
        T = robot.fk(q)
        T[4, :3, 3] += [3.0, 0.0, 0.0]  # out of reach
        T[5, :3, 3] *= 1e200  # far out of reach
        limited = robot.with_limits([(v + 0.5 - 0.01, v + 0.5 + 0.01) for v in q[6]])
        for arm, targets in ((robot, T), (limited, T[6:])):
            many = arm.ik(targets)
            assert isinstance(many, IKBatchResult)
            statuses = set()
            for i in range(len(targets)):
                single, row = arm.ik(targets[i]), many[i]
                assert isinstance(single, IKResult)
                statuses.add(single.status)
                assert row.status == single.status and row.message == single.message
                np.testing.assert_array_equal(row.solutions, single.solutions)
                np.testing.assert_array_equal(row.out_of_limits, single.out_of_limits)
                assert row.branches == single.branches
                assert row.free_joints == single.free_joints
                assert row.gap == single.gap
            if arm is limited:
                assert "out_of_limits" in statuses
            else:
                assert {"ok", "unreachable"} <= statuses
                assert "singular" in statuses or robot is UR5_P56


# ------------------------------------------------------------ random arms, properties
@st.composite
def arm_and_q(draw: st.DrawFn) -> tuple[Robot, FloatArray]:
    """A random UR-type arm (degenerate geometry drawn in) and a q, often near singular sets."""
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    robot = random_arm(
        rng,
        draw(st.sampled_from(MODES)),
        modified=draw(st.booleans()),
        square=draw(st.booleans()),
        equal=draw(st.booleans()),
        tiny=draw(st.booleans()),
    )
    angle = st.one_of(st.floats(-PI, PI), st.sampled_from(SPECIAL_ANGLES))
    off = st.sampled_from([0.0, 0.0, 1e-12, -1e-10, 1e-8])
    q = np.array([draw(angle) + draw(off) for _ in range(6)])
    return robot, q


@settings(max_examples=150, deadline=None, database=None, derandomize=True)
@given(arm_and_q())
def test_property_fk_targets_are_solved_honestly(case: tuple[Robot, FloatArray]) -> None:
    robot, q = case
    assert_honest(robot, q, one(robot, robot.fk(q)))


@pytest.mark.parametrize("shape", [(), (1,), (3, 2)])
def test_batch_shapes(shape: tuple[int, ...]) -> None:
    rng = np.random.default_rng(49)
    q = rng.uniform(-PI, PI, (*shape, 6))
    res = UR5_A5.ik(UR5_A5.fk(q), respect_limits=False)
    if shape == ():
        assert isinstance(res, IKResult)
        assert joint_gap(res.solutions, q) < 1e-9
        return
    assert isinstance(res, IKBatchResult)
    assert res.status.shape == shape and res.solutions.shape[: len(shape)] == shape
    for idx in np.ndindex(*shape):
        single = one(UR5_A5, UR5_A5.fk(q[idx]))
        np.testing.assert_array_equal(res[idx].solutions, single.solutions)
        assert joint_gap(single.solutions, q[idx]) < 1e-9
