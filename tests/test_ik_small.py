"""Closed-form IK of the small arms: planar 2R/3R/PR/PRR, SCARA, 3R anthropomorphic/elbow.

Independent references: the seeds' hand formulas (000: the PR arm's q2A/q2B,
002: the anthropomorphic arm's algebra), forward kinematics of every candidate,
and a multi-start damped-least-squares search written here on the robot's
Jacobian (completeness). Random arms draw lengths, offsets, twists, base and
tool, in both DH conventions.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from helpers import assert_transform_close, transform_from
from numpy.typing import NDArray
from scipy.spatial.transform import Rotation

from kinematica.dh import Prismatic, Revolute
from kinematica.errors import DimensionError
from kinematica.ik.analytic.arm3r import make_arm3r_solver
from kinematica.ik.analytic.planar import make_planar_solver
from kinematica.robot import Robot, classify

FloatArray = NDArray[np.float64]
PI = math.pi

#: A candidate is "exact" when forward kinematics reproduces the target to this.
EXACT = 1e-12


# ------------------------------------------------------------------- helpers
def random_frame(rng: np.random.Generator) -> FloatArray:
    return transform_from(rng.normal(size=4), rng.uniform(-0.5, 0.5, 3))


def length(rng: np.random.Generator) -> float:
    return float(rng.uniform(0.2, 1.0) * rng.choice([-1.0, 1.0]))


def flip(rng: np.random.Generator) -> float:
    return float(rng.choice([0.0, PI]))


def random_arm(kind: str, rng: np.random.Generator) -> Robot:
    """A random arm of one structural class, random base and tool, either convention."""
    u = rng.uniform
    if kind == "planar-2R":
        rows = [
            Revolute(d=u(-0.3, 0.3), a=length(rng), alpha=flip(rng), offset=u(-PI, PI)),
            Revolute(d=u(-0.3, 0.3), a=length(rng), alpha=u(-PI, PI), offset=u(-PI, PI)),
        ]
    elif kind == "planar-3R":
        rows = [
            Revolute(d=u(-0.3, 0.3), a=length(rng), alpha=flip(rng), offset=u(-PI, PI)),
            Revolute(d=u(-0.3, 0.3), a=length(rng), alpha=flip(rng), offset=u(-PI, PI)),
            Revolute(d=u(-0.3, 0.3), a=length(rng), alpha=u(-PI, PI), offset=u(-PI, PI)),
        ]
    elif kind == "scara":
        rows = [
            Revolute(d=u(0.2, 0.5), a=length(rng), alpha=flip(rng), offset=u(-PI, PI)),
            Revolute(d=u(-0.1, 0.1), a=length(rng), alpha=flip(rng), offset=u(-PI, PI)),
            Prismatic(theta=u(-PI, PI), a=u(-0.1, 0.1), alpha=flip(rng), offset=u(-0.2, 0.2)),
            Revolute(d=u(-0.1, 0.1), a=u(-0.2, 0.2), alpha=u(-PI, PI), offset=u(-PI, PI)),
        ]
    elif kind in ("planar-PR", "planar-PRR"):
        rows = [
            Prismatic(theta=u(-PI, PI), a=u(-0.3, 0.3), alpha=PI / 2 * rng.choice([-1, 1])),
            Revolute(d=u(-0.3, 0.3), a=length(rng), alpha=flip(rng), offset=u(-PI, PI)),
        ]
        if kind == "planar-PRR":
            rows.append(Revolute(d=u(-0.2, 0.2), a=length(rng), alpha=u(-PI, PI)))
    else:  # anthropomorphic-3R, elbow-3R
        a1 = 0.0 if kind == "anthropomorphic-3R" else length(rng) / 3
        rows = [
            Revolute(d=u(0.2, 0.6), a=a1, alpha=PI / 2 * rng.choice([-1, 1]), offset=u(-PI, PI)),
            Revolute(d=u(-0.2, 0.2), a=length(rng), alpha=flip(rng), offset=u(-PI, PI)),
            Revolute(d=u(-0.2, 0.2), a=length(rng), alpha=u(-PI, PI), offset=u(-PI, PI)),
        ]
    robot = Robot.from_dh(rows, base=random_frame(rng), tool=random_frame(rng), name=kind)
    if rng.random() < 0.5:
        robot = robot.to_convention("modified")
    assert classify(robot).kind == kind
    return robot


def random_q(robot: Robot, rng: np.random.Generator, n: int) -> FloatArray:
    q = rng.uniform(-PI, PI, (n, robot.dof))
    return np.where(robot.is_prismatic, rng.uniform(-0.5, 0.5, (n, robot.dof)), q)


def joint_distance(robot: Robot, q1: FloatArray, q2: FloatArray) -> FloatArray:
    """Largest joint difference, revolute joints compared modulo 2π."""
    d = q1 - q2
    d = np.where(robot.is_prismatic, np.abs(d), np.abs(np.angle(np.exp(1j * d))))
    return np.asarray(d.max(axis=-1))


def target_of(robot: Robot, q: FloatArray, position_only: bool) -> FloatArray:
    T = robot.fk(q)
    return T[..., :3, 3] if position_only else T


def check_candidates(robot: Robot, solver: object, targets: FloatArray) -> FloatArray:
    """Solve; assert every real candidate is exact; return the candidates ``(N, m, n)``."""
    cand = solver.solve(targets)  # type: ignore[attr-defined]
    position_only = solver.position_only  # type: ignore[attr-defined]
    q = cand.q
    assert q.shape[:2] == (len(targets), len(cand.labels))
    real = ~np.isnan(q).any(axis=2)
    assert not (np.isnan(q).any(axis=2) & ~np.isnan(q).all(axis=2)).any(), "partly NaN branch"
    reached = target_of(robot, np.where(real[..., None], q, 0.0), position_only)
    want = np.broadcast_to(targets[:, None], reached.shape)
    if position_only:
        err = np.abs(reached - want).max(axis=-1)
        assert err[real].max(initial=0.0) <= EXACT
    else:
        assert_transform_close(reached[real], want[real], atol=EXACT)
    assert np.isnan(cand.gap[real.any(axis=1)]).all()
    return q


def dls_solutions(
    robot: Robot, target: FloatArray, rng: np.random.Generator, starts: int = 200
) -> FloatArray:
    """Every distinct solution a multi-start damped-least-squares search finds.

    Args:
        robot: The robot.
        target: ``(3,)`` position or ``(4, 4)`` pose of the tool.
        rng: Random starts.
        starts: Number of random starts.

    Returns:
        ``(k, n)`` distinct solutions (revolute joints wrapped to (-π, π]).
    """
    position_only = target.shape == (3,)
    q = random_q(robot, rng, starts)

    def error(q: FloatArray) -> FloatArray:
        T = robot.fk(q)
        e = target[:3] - T[:, :3, 3] if position_only else target[:3, 3] - T[:, :3, 3]
        if position_only:
            return e
        rot = Rotation.from_matrix(target[:3, :3] @ np.swapaxes(T[:, :3, :3], 1, 2))
        return np.concatenate([e, rot.as_rotvec()], axis=1)

    for it in range(300):
        e = error(q)
        J = robot.jacobian(q)[:, : e.shape[1]]
        if it < 200:  # damped least squares, then Gauss-Newton steps to polish
            Jt = np.swapaxes(J, 1, 2)
            step = Jt @ np.linalg.solve(J @ Jt + 1e-4 * np.eye(e.shape[1]), e[..., None])
        else:
            step = np.linalg.pinv(J) @ e[..., None]
        q = q + step[..., 0]
    done = np.abs(error(q)).max(axis=1) < 1e-10
    found: list[FloatArray] = []
    for qi in q[done]:
        qi = np.where(robot.is_prismatic, qi, np.angle(np.exp(1j * qi)))
        if all(joint_distance(robot, qi, f) > 1e-6 for f in found):
            found.append(qi)
    return np.array(found).reshape(-1, robot.dof)


# ------------------------------------------------------------------- classes
KINDS = (
    "planar-2R",
    "planar-3R",
    "planar-PR",
    "planar-PRR",
    "scara",
    "anthropomorphic-3R",
    "elbow-3R",
)


def solver_for(robot: Robot) -> object:
    solver = make_planar_solver(robot) or make_arm3r_solver(robot)
    assert solver is not None
    return solver


@pytest.mark.parametrize("kind", KINDS)
def test_round_trip_random_arms(kind: str) -> None:
    rng = np.random.default_rng(KINDS.index(kind))
    for _ in range(6):
        robot = random_arm(kind, rng)
        solver = solver_for(robot)
        assert solver.name == kind  # type: ignore[attr-defined]
        q = random_q(robot, rng, 300)
        targets = target_of(robot, q, solver.position_only)  # type: ignore[attr-defined]
        cand = check_candidates(robot, solver, targets)
        dist = joint_distance(robot, cand, q[:, None, :])
        assert (np.nan_to_num(dist, nan=np.inf).min(axis=1) < 1e-8).all(), "original q not found"


@pytest.mark.parametrize(
    ("kind", "position_only", "branches"),
    [
        ("planar-2R", True, 2),
        ("planar-3R", False, 2),
        ("planar-PR", True, 2),
        ("planar-PRR", False, 2),
        ("scara", False, 2),
        ("anthropomorphic-3R", True, 4),
        ("elbow-3R", True, 4),
    ],
)
def test_solver_kind_and_shapes(kind: str, position_only: bool, branches: int) -> None:
    rng = np.random.default_rng(7)
    robot = random_arm(kind, rng)
    solver = solver_for(robot)
    assert solver.position_only is position_only  # type: ignore[attr-defined]
    q = random_q(robot, rng, 3)
    for N in (1, 3):
        cand = solver.solve(target_of(robot, q[:N], position_only))  # type: ignore[attr-defined]
        assert cand.q.shape == (N, branches, robot.dof)
        assert len(cand.labels) == branches
        assert cand.singular.shape == (N,) and cand.free.shape == (N, robot.dof)
        assert cand.gap.shape == (N,)
    with pytest.raises(DimensionError):
        solver.solve(np.zeros((2, 4) if position_only else (2, 3)))  # type: ignore[attr-defined]


@pytest.mark.parametrize("kind", KINDS)
def test_complete_against_multistart_search(kind: str) -> None:
    rng = np.random.default_rng(1000 + KINDS.index(kind))
    robot = random_arm(kind, rng)
    solver = solver_for(robot)
    for q in random_q(robot, rng, 2):
        target = target_of(robot, q, solver.position_only)  # type: ignore[attr-defined]
        cand = check_candidates(robot, solver, target[None])[0]
        ours = cand[~np.isnan(cand).any(axis=1)]
        theirs = dls_solutions(robot, target, rng)
        assert len(theirs) >= 1
        for s in theirs:
            assert joint_distance(robot, ours, s).min() < 1e-6, f"missed {s}"
        assert len(theirs) <= len(ours)


def test_factories_refuse_other_structures() -> None:
    puma = Robot.from_dh(
        [
            Revolute(alpha=PI / 2),
            Revolute(a=0.4318),
            Revolute(d=0.15005, a=0.0203, alpha=-PI / 2),
            Revolute(d=0.4318, alpha=PI / 2),
            Revolute(alpha=-PI / 2),
            Revolute(),
        ]
    )
    assert make_planar_solver(puma) is None
    assert make_arm3r_solver(puma) is None
    skew_3r = Robot.from_dh([Revolute(alpha=1.0), Revolute(a=0.5, alpha=0.3), Revolute(a=0.4)])
    assert make_arm3r_solver(skew_3r) is None
    # a planar 2R whose tool sits on axis 2 is degenerate (q2 moves nothing)
    assert make_planar_solver(Robot.from_dh([Revolute(a=0.5), Revolute()])) is None


# ------------------------------------------------------- seeds' hand formulas
L1, L2 = 0.3, 0.5  # seed 000's l1, l2


def seed_pr_arm() -> Robot:
    """Seed 000's PR mechanism: x = q1 + l1 + l2 cos q2, y = l2 sin q2 (world x, y).

    DH: the slide along z0 = world x (base), then the revolute axis z1 = world z.
    """
    base = np.array([[0, 0, 1, 0], [-1, 0, 0, 0], [0, -1, 0, 0], [0, 0, 0, 1]], dtype=float)
    return Robot.from_dh(
        [Prismatic(alpha=PI / 2, offset=L1), Revolute(a=L2, offset=PI / 2)], base=base
    )


def test_seed_pr_arm_matches_the_slide() -> None:
    robot = seed_pr_arm()
    rng = np.random.default_rng(0)
    q = random_q(robot, rng, 50)
    p = robot.fk(q)[:, :3, 3]
    np.testing.assert_allclose(p[:, 0], q[:, 0] + L1 + L2 * np.cos(q[:, 1]), atol=1e-15)
    np.testing.assert_allclose(p[:, 1], L2 * np.sin(q[:, 1]), atol=1e-15)
    np.testing.assert_allclose(p[:, 2], 0.0, atol=1e-15)


def test_seed_pr_two_solutions_are_q2a_q2b() -> None:
    robot = seed_pr_arm()
    solver = make_planar_solver(robot)
    assert solver is not None and solver.labels == ("link forward", "link backward")
    rng = np.random.default_rng(1)
    x = rng.uniform(-1.0, 1.0, 200)
    y = rng.uniform(-L2, L2, 200)
    cand = check_candidates(robot, solver, np.stack([x, y, 0 * x], axis=1))
    q2a = np.arcsin(y / L2)
    q2b = PI - np.arcsin(y / L2)
    q1a = x - L1 - L2 * np.cos(q2a)
    q1b = x - L1 - L2 * np.cos(q2b)
    np.testing.assert_allclose(cand[:, 0, 0], q1a, atol=1e-14)
    np.testing.assert_allclose(cand[:, 1, 0], q1b, atol=1e-14)
    assert joint_distance(robot, cand[:, 0], np.stack([q1a, q2a], 1)).max() < 1e-14
    assert joint_distance(robot, cand[:, 1], np.stack([q1b, q2b], 1)).max() < 1e-14


D1, A2, A3 = 0.4, 0.35, 0.3  # seed 002's L1, L2, L3


def seed_anthropomorphic() -> Robot:
    """Seed 002's table: q1, L1, 0, 90° / q2, 0, L2, 0 / q3, 0, L3, 0."""
    return Robot.from_dh([Revolute(d=D1, alpha=PI / 2), Revolute(a=A2), Revolute(a=A3)])


def test_seed_anthropomorphic_four_solutions_are_the_seed_algebra() -> None:
    robot = seed_anthropomorphic()
    solver = make_arm3r_solver(robot)
    assert solver is not None and solver.name == "anthropomorphic-3R"
    rng = np.random.default_rng(2)
    p = robot.fk(random_q(robot, rng, 300))[:, :3, 3]
    cand = check_candidates(robot, solver, p)
    px, py, pz = p.T
    for slot, (shoulder, elbow) in enumerate([(0, 1), (0, -1), (1, 1), (1, -1)]):
        # seed 002: q1 = atan2(py, px) and q1 + π ("two solutions for q1")
        q1 = np.arctan2(py, px) + shoulder * PI
        s1, c1 = np.sin(q1), np.cos(q1)
        r = px * c1 + py * s1  # the seed's py / s1, written to avoid s1 = 0
        z = pz - D1
        c3 = (r**2 + z**2 - A2**2 - A3**2) / (2 * A2 * A3)  # the seed's cos(q3)
        q3 = -elbow * np.arccos(c3) if shoulder == 0 else elbow * np.arccos(c3)
        s3 = np.sin(q3)
        den = (A2 + A3 * c3) ** 2 + A3**2 * s3**2
        s2 = (z * (A2 + A3 * c3) - r * A3 * s3) / den  # the seed's sin(q2)
        c2 = (r * (A2 + A3 * c3) + z * A3 * s3) / den  # from its first equation
        want = np.stack([q1, np.arctan2(s2, c2), q3], axis=1)
        assert joint_distance(robot, cand[:, slot], want).max() < 1e-9, solver.labels[slot]
    assert solver.labels[0] == "shoulder right, elbow up"


def _side(h: FloatArray, a: FloatArray, b: FloatArray) -> FloatArray:
    """``h·(a × b)`` row by row."""
    return np.einsum("ij,ij->i", h, np.cross(a, b))


def test_labels_planar_2r_elbow_up_is_left_of_the_reach_line() -> None:
    rng = np.random.default_rng(3)
    robot = random_arm("planar-2R", rng)
    solver = solver_for(robot)
    q = random_q(robot, rng, 200)
    p = robot.fk(q)[:, :3, 3]
    cand = check_candidates(robot, solver, p)
    for slot, sign in ((0, 1.0), (1, -1.0)):  # elbow up: elbow to the left (about +h1)
        h, pts = robot.joint_axes(cand[:, slot])
        h1, s, e = h[:, 0], pts[:, 0], pts[:, 1]
        assert (sign * _side(h1, p - s, e - s) >= -1e-12).all()


@pytest.mark.parametrize("kind", ["anthropomorphic-3R", "elbow-3R"])
def test_labels_3r_shoulder_and_elbow(kind: str) -> None:
    rng = np.random.default_rng(4)
    for robot in (seed_anthropomorphic(), random_arm(kind, rng), random_arm(kind, rng)):
        solver = make_arm3r_solver(robot)
        assert solver is not None
        p = robot.fk(random_q(robot, rng, 300))[:, :3, 3]
        cand = check_candidates(robot, solver, p)
        for slot, label in enumerate(solver.labels):
            q = cand[:, slot]
            real = ~np.isnan(q).any(axis=1)
            h, pts = robot.joint_axes(q[real])
            h1, k1, w = h[:, 0], h[:, 1], p[real]
            sigma = np.einsum("ij,ij->i", w - pts[:, 0], np.cross(h1, k1))
            assert ((sigma >= -1e-12) if "right" in label else (sigma <= 1e-12)).all(), label

            def across(x: FloatArray, k1: FloatArray = k1) -> FloatArray:
                return x - np.einsum("ij,ij->i", x, k1)[:, None] * k1

            s, e = pts[:, 1], pts[:, 2]  # points on axes 2 and 3
            n = np.cross(k1, across(w - s))  # left normal of the shoulder-wrist line
            up = np.einsum("ij,ij->i", across(e - s), n) * np.einsum("ij,ij->i", h1, n)
            assert ((up >= -1e-12) if "up" in label else (up <= 1e-12)).all(), label


# ------------------------------------------------------------ special targets
def test_planar_2r_singular_at_the_base_and_unreachable() -> None:
    robot = Robot.from_dh([Revolute(a=0.5), Revolute(a=0.5, offset=0.2)])
    solver = make_planar_solver(robot)
    assert solver is not None
    far = np.array([[1.3, 0.0, 0.0], [0.0, 0.0, 0.0], [0.3, 0.4, 0.25]])
    cand = solver.solve(far)
    assert np.isnan(cand.q[0]).all() and cand.gap[0] == pytest.approx(0.3, abs=1e-15)
    assert cand.singular[1] and cand.free[1].tolist() == [True, False]
    assert np.isnan(cand.q[2]).all() and cand.gap[2] == pytest.approx(0.25, abs=1e-15)
    check_candidates(robot, solver, far[1:2])
    unequal = Robot.from_dh([Revolute(a=0.5), Revolute(a=0.3)])
    inner = make_planar_solver(unequal).solve(np.array([[0.1, 0.0, 0.0], [0.3, 0.5, 0.0]]))  # type: ignore[union-attr]
    assert np.isnan(inner.q[0]).all() and inner.gap[0] == pytest.approx(0.1, abs=1e-15)
    assert not np.isnan(inner.q[1]).any() and np.isnan(inner.gap[1])


def test_planar_pose_solvers_refuse_tilted_and_off_plane_targets() -> None:
    rng = np.random.default_rng(5)
    for kind in ("planar-3R", "planar-PRR", "scara"):
        robot = random_arm(kind, rng)
        solver = solver_for(robot)
        T = robot.fk(random_q(robot, rng, 1))[0]
        h, _ = robot.joint_axes()
        k = h[1]
        tilt = Rotation.from_rotvec(0.01 * np.cross(k, [0.3, 0.5, 0.7]) / 0.5).as_matrix()
        tilted = T.copy()
        tilted[:3, :3] = tilt @ T[:3, :3]
        cand = solver.solve(tilted[None])  # type: ignore[attr-defined]
        assert np.isnan(cand.q).all() and 0 < cand.gap[0] < 0.05
        if kind != "scara":  # the SCARA's slide reaches any height
            lifted = T.copy()
            lifted[:3, 3] += 0.2 * k
            cand = solver.solve(lifted[None])  # type: ignore[attr-defined]
            assert np.isnan(cand.q).all() and cand.gap[0] >= 0.2 - 1e-12


def test_planar_pr_unreachable_gap() -> None:
    solver = make_planar_solver(seed_pr_arm())
    assert solver is not None
    cand = solver.solve(np.array([[0.2, L2 + 0.1, 0.0]]))
    assert np.isnan(cand.q).all() and cand.gap[0] == pytest.approx(0.1, abs=1e-15)


def test_3r_singular_on_axis_1_and_unreachable() -> None:
    robot = seed_anthropomorphic()
    solver = make_arm3r_solver(robot)
    assert solver is not None
    on_axis = np.array([[0.0, 0.0, D1 + 0.5], [0.0, 0.0, D1 + 2.0], [1.0, 1.0, 1.0]])
    cand = solver.solve(on_axis)
    assert cand.singular[0] and cand.free[0].tolist() == [True, False, False]
    check_candidates(robot, solver, on_axis[:1])
    # beyond reach: the tool lies on a sphere shell about the shoulder (axes 1, 2 meet)
    assert np.isnan(cand.q[1:]).all()
    assert cand.gap[1] == pytest.approx(2.0 - (A2 + A3), abs=1e-12)
    d = np.linalg.norm(on_axis[2] - [0, 0, D1])
    assert cand.gap[2] == pytest.approx(d - (A2 + A3), abs=1e-12)


def test_scara_and_3r_planar_singular() -> None:
    scara = Robot.from_dh(
        [Revolute(d=0.4, a=0.3), Revolute(a=0.3, alpha=PI), Prismatic(), Revolute(d=0.1)]
    )
    solver = make_planar_solver(scara)
    assert solver is not None and solver.labels == ("right-handed", "left-handed")
    T = scara.fk([0.3, PI, 0.05, 0.2])  # the wrist folded back onto axis 1
    cand = check_candidates(scara, solver, T[None])
    assert cand.shape == (1, 2, 4)
    got = solver.solve(T[None])
    assert got.singular[0] and got.free[0].tolist() == [True, False, False, True]


def test_scara_right_handed_has_positive_elbow_turn() -> None:
    scara = Robot.from_dh([Revolute(d=0.4, a=0.3), Revolute(a=0.25), Prismatic(), Revolute()])
    solver = make_planar_solver(scara)
    assert solver is not None
    T = scara.fk(np.array([[0.2, 0.7, 0.1, 0.0], [0.2, -0.7, 0.1, 0.0]]))
    cand = check_candidates(scara, solver, T)
    assert (np.sin(cand[:, 0, 1]) > 0).all() and (np.sin(cand[:, 1, 1]) < 0).all()
