"""Closed-form IK of the small arms: planar 2R/3R/PR/PRR, SCARA, 3R anthropomorphic/elbow.

Independent references: the seeds' hand formulas (000: the PR arm's q2A/q2B,
002: the anthropomorphic arm's algebra), forward kinematics of every
candidate, geometric definitions of the branch labels, and a multi-start
damped-least-squares search written here on the robot's Jacobian
(completeness). Random arms draw lengths, offsets, twists, base and tool, in
both DH conventions. The property tests over degenerate arms are in
``test_small_samples.py``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pytest
from numpy.typing import NDArray
from scipy.spatial.transform import Rotation
from support.helpers import transform_from
from support.ik_search import dls_solutions, joint_distance, random_q
from support.small_arms import A2, A3, D1, KINDS, reached, seed_anthropomorphic, seed_pr_arm

import kinematica as km
from kinematica import _core_testing
from kinematica.dh import Prismatic, Revolute
from kinematica.dh.lines import AXIS_LENGTH_TOL
from kinematica.ik import IKBatchResult, IKResult, closed_form
from kinematica.robot import Robot, classify

FloatArray = NDArray[np.float64]
PI = math.pi
SINGULAR_TOL: float = _core_testing.planar.SINGULAR_TOL
MERGE_TOL: float = _core_testing.planar.MERGE_TOL

#: A candidate is "exact" when forward kinematics reproduces the target to this.
EXACT = 1e-12
#: robot.ik's default acceptance tolerance (m and rad).
TOL = 1e-10

SUMMARIES = {
    "planar-2R": "2R planar",
    "planar-PR": "PR planar (prismatic then revolute)",
    "planar-3R": "3R planar",
    "planar-PRR": "PRR planar (prismatic then two parallel revolute)",
    "scara": "SCARA (RRPR, all axes parallel)",
    "anthropomorphic-3R": "3R anthropomorphic (shoulder axes meet)",
    "elbow-3R": "3R elbow arm with shoulder offset",
}
#: Kinds whose position targets leave the last joint free (a continuum).
FREE_LAST = ("planar-3R", "planar-PRR", "scara")


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
    robot = Robot.from_dh(
        rows, base=random_frame(rng), tool=random_frame(rng), name=kind, convention="standard"
    )
    if rng.random() < 0.5:
        robot = robot.to_convention("modified")
    assert classify(robot).kind == kind
    return robot


def as_poses(targets: FloatArray) -> FloatArray:
    """Position targets ``(N, 3)`` as poses with identity rotation; poses unchanged."""
    if targets.shape[-1] == 3:
        T = np.broadcast_to(np.eye(4), (*targets.shape[:-1], 4, 4)).copy()
        T[..., :3, 3] = targets
        return T
    return targets


@dataclass(frozen=True)
class Info:
    """What the closed form says of each target besides its candidates (``(N,)`` arrays)."""

    singular: NDArray[np.bool_]
    near: NDArray[np.bool_]
    gap: FloatArray  # NaN: none beyond round-off
    free: NDArray[np.bool_]  # (N, n)


def raw_candidates(robot: Robot, targets: FloatArray) -> tuple[tuple[str, ...], FloatArray, Info]:
    """The closed form's labels, raw candidates ``(N, m, n)`` and what it says (no check)."""
    kind = "position" if targets.shape[-1] == 3 else "pose"
    closed = closed_form(robot.chain, kind)
    assert closed is not None
    T = np.ascontiguousarray(as_poses(targets))
    out = [closed.params.candidates(robot.chain.core, t) for t in T]
    Q = np.array([o[0] for o in out]).reshape(len(T), closed.slots, robot.dof)
    free = np.array([[(o[4] >> j) & 1 for j in range(robot.dof)] for o in out], dtype=bool)
    info = Info(
        singular=np.array([o[1] for o in out], dtype=bool),
        near=np.array([o[2] for o in out], dtype=bool),
        gap=np.array([o[3] for o in out], dtype=float),
        free=free.reshape(len(T), robot.dof),
    )
    return closed.labels, Q, info


def exact_candidates(robot: Robot, targets: FloatArray) -> FloatArray:
    """The closed form's exact candidates (NaN for the others); a branch is real in full or not.

    Out of reach a branch holds its least-squares configuration, which the
    check rejects: only the exact ones are kept here.
    """
    _, Q, _ = raw_candidates(robot, targets)
    real = ~np.isnan(Q).any(axis=2)
    assert not (np.isnan(Q).any(axis=2) & ~np.isnan(Q).all(axis=2)).any(), "partly NaN branch"
    err = reached(robot, np.where(real[..., None], Q, 0.0), targets[:, None])
    exact = real & (err.max(axis=-1) <= EXACT)
    return np.where(exact[..., None], Q, np.nan)


def target_of(robot: Robot, q: FloatArray, position: bool) -> FloatArray:
    T = robot.fk(q)
    return T[..., :3, 3] if position else T


# ------------------------------------------------------------------- classes
@pytest.mark.parametrize("kind", KINDS)
def test_classification_kind_summary_and_labels(kind: str) -> None:
    robot = random_arm(kind, np.random.default_rng(7))
    structure = classify(robot)
    assert (structure.kind, structure.summary) == (kind, SUMMARIES[kind])
    for target in ("pose", "position"):
        closed = closed_form(robot.chain, target)  # type: ignore[arg-type]
        assert closed is not None and closed.name == kind
        assert closed.slots == (4 if kind.endswith("-3R") and "planar" not in kind else 2)


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("position", [False, True])
def test_round_trip_random_arms(kind: str, position: bool) -> None:
    rng = np.random.default_rng(KINDS.index(kind) + 10 * position)
    for _ in range(4):
        robot = random_arm(kind, rng)
        q = random_q(robot, rng, 200)
        targets = target_of(robot, q, position)
        cand = exact_candidates(robot, targets)
        res = robot.ik(targets, respect_limits=False)
        assert isinstance(res, IKBatchResult)
        want = "singular" if position and kind in FREE_LAST else "ok"
        assert (res.status == want).all(), set(res.status)
        err = reached(robot, np.nan_to_num(res.solutions), targets[:, None])
        assert (err[res.count[:, None] > np.arange(res.solutions.shape[1])] <= TOL).all()
        if position and kind in FREE_LAST:  # the last joint free: representatives
            assert res.free[:, -1].all() and not res.free[:, :-1].any()
            continue
        dist = joint_distance(robot, cand, q[:, None, :])
        assert (np.nan_to_num(dist, nan=np.inf).min(axis=1) < 1e-8).all(), "original q not found"
        dist = joint_distance(robot, res.solutions, q[:, None, :])
        assert (np.nan_to_num(dist, nan=np.inf).min(axis=1) < 1e-8).all()


@pytest.mark.parametrize("kind", KINDS)
def test_complete_against_multistart_search(kind: str) -> None:
    rng = np.random.default_rng(1000 + KINDS.index(kind))
    robot = random_arm(kind, rng)
    for position in (False, True):
        if position and kind in FREE_LAST:
            continue
        for q in random_q(robot, rng, 1):
            target = target_of(robot, q, position)
            res = robot.ik(target, respect_limits=False)
            assert res.status == "ok"
            theirs = dls_solutions(robot, target, rng, starts=60)
            assert len(theirs) >= 1
            for s in theirs:
                assert joint_distance(robot, res.solutions, s).min() < 1e-6, f"missed {s}"
            assert len(theirs) == res.count


@pytest.mark.parametrize("shape", [(), (1,), (3, 2)])
@pytest.mark.parametrize("kind", ["planar-2R", "scara", "elbow-3R"])
def test_batch_shapes(kind: str, shape: tuple[int, ...]) -> None:
    rng = np.random.default_rng(8)
    robot = random_arm(kind, rng)
    q = random_q(robot, rng, max(1, math.prod(shape))).reshape(*shape, robot.dof)
    for position in (False, True):
        res = robot.ik(target_of(robot, q, position), respect_limits=False)
        if shape == ():
            assert isinstance(res, IKResult) and res.status in ("ok", "singular")
        else:
            assert isinstance(res, IKBatchResult) and res.shape == shape
            assert res.solutions.shape[:-2] == shape and res.free.shape == (*shape, robot.dof)


def test_other_structures_and_degenerate_links_fall_back() -> None:
    puma = km.load("puma560")
    assert classify(puma).kind not in KINDS
    skew_3r = Robot.from_dh(
        [Revolute(alpha=1.0), Revolute(a=0.5, alpha=0.3), Revolute(a=0.4)], convention="standard"
    )
    assert classify(skew_3r).kind == "general"
    # A planar 2R whose tool sits on axis 2 (q2 moves nothing), or within the line
    # geometry's length tolerance of it (AXIS_LENGTH_TOL · (1 + size), size 0.5 m here):
    # no closed form, the numeric method answers; just beyond it the closed form does.
    for a2, method in (
        (0.0, "numeric"),
        (AXIS_LENGTH_TOL / 10, "numeric"),
        (AXIS_LENGTH_TOL * 10, "analytic"),
    ):
        arm = Robot.from_dh([Revolute(a=0.5), Revolute(a=a2)], convention="standard")
        assert classify(arm).kind == "planar-2R"
        target = arm.fk([0.3, 0.4])[:3, 3]
        res = arm.ik(target, seed=0)
        assert res.method.startswith(method) and res.status in ("ok", "singular"), res.message
    with pytest.raises(km.KinematicaError, match="numeric"):
        Robot.from_dh([Revolute(a=0.5), Revolute()], convention="standard").ik(
            np.zeros(3), method="analytic"
        )


# ------------------------------------------------------- seeds' hand formulas
L1, L2 = 0.3, 0.5  # seed 000's l1, l2


def test_seed_pr_arm_matches_the_slide() -> None:
    robot = seed_pr_arm()
    q = random_q(robot, np.random.default_rng(0), 50)
    p = robot.fk(q)[:, :3, 3]
    np.testing.assert_allclose(p[:, 0], q[:, 0] + L1 + L2 * np.cos(q[:, 1]), atol=1e-15)
    np.testing.assert_allclose(p[:, 1], L2 * np.sin(q[:, 1]), atol=1e-15)
    np.testing.assert_allclose(p[:, 2], 0.0, atol=1e-15)


def test_seed_pr_two_solutions_are_q2a_q2b() -> None:
    robot = seed_pr_arm()
    rng = np.random.default_rng(1)
    x = rng.uniform(-1.0, 1.0, 200)
    y = rng.uniform(-L2, L2, 200)
    labels, cand, _ = raw_candidates(robot, np.stack([x, y, 0 * x], axis=1))
    assert labels == ("link forward", "link backward")
    q2a = np.arcsin(y / L2)
    q2b = PI - np.arcsin(y / L2)
    q1a = x - L1 - L2 * np.cos(q2a)
    q1b = x - L1 - L2 * np.cos(q2b)
    np.testing.assert_allclose(cand[:, 0, 0], q1a, atol=1e-14)
    np.testing.assert_allclose(cand[:, 1, 0], q1b, atol=1e-14)
    assert joint_distance(robot, cand[:, 0], np.stack([q1a, q2a], 1)).max() < 1e-14
    assert joint_distance(robot, cand[:, 1], np.stack([q1b, q2b], 1)).max() < 1e-14
    # A pose fixes q2 (the link's direction): one solution, on its branch.
    for qa in ([0.1, 0.4], [0.2, PI - 0.4]):
        res = robot.ik(robot.fk(qa))
        assert res.status == "ok" and res.count == 1
        assert joint_distance(robot, res.solutions[0], np.array(qa)) < 1e-12
        assert res.branches == (("link forward",) if qa[1] < PI / 2 else ("link backward",))


def test_seed_anthropomorphic_four_solutions_are_the_seed_algebra() -> None:
    robot = seed_anthropomorphic()
    rng = np.random.default_rng(2)
    p = robot.fk(random_q(robot, rng, 300))[:, :3, 3]
    labels, cand, _ = raw_candidates(robot, p)
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
        assert joint_distance(robot, cand[:, slot], want).max() < 1e-9, labels[slot]
    assert labels[0] == "shoulder right, elbow up"
    res = robot.ik(p[0])
    assert res.status == "ok" and res.count == 4  # seed 002: two q1 times two q3


def _side(h: FloatArray, a: FloatArray, b: FloatArray) -> FloatArray:
    """``h·(a × b)`` row by row."""
    return np.einsum("ij,ij->i", h, np.cross(a, b))


@pytest.mark.parametrize("position", [True, False])
def test_labels_planar_2r_elbow_up_is_left_of_the_reach_line(position: bool) -> None:
    rng = np.random.default_rng(3)
    robot = random_arm("planar-2R", rng)
    q = random_q(robot, rng, 60)
    res = robot.ik(target_of(robot, q, position), respect_limits=False)
    p = robot.fk(q)[:, :3, 3]
    for i in range(len(q)):
        for sol, label in zip(res[i].solutions, res[i].branches, strict=True):
            h, pts = robot.joint_axes(sol)
            sign = 1.0 if label == "elbow up" else -1.0  # elbow up: to the left, about +h1
            assert sign * _side(h[:1], p[i : i + 1] - pts[:1], pts[1:2] - pts[:1])[0] >= -1e-12


@pytest.mark.parametrize("kind", ["anthropomorphic-3R", "elbow-3R"])
@pytest.mark.parametrize("position", [True, False])
def test_labels_3r_shoulder_and_elbow(kind: str, position: bool) -> None:
    rng = np.random.default_rng(4)
    for robot in (seed_anthropomorphic(), random_arm(kind, rng), random_arm(kind, rng)):
        q = random_q(robot, rng, 30)
        res = robot.ik(target_of(robot, q, position), respect_limits=False)
        p = robot.fk(q)[:, :3, 3]
        for i in range(len(q)):
            for sol, label in zip(res[i].solutions, res[i].branches, strict=True):
                (h1, k1, _), (s1, s, e) = robot.joint_axes(sol)
                w = p[i]
                sigma = (w - s1) @ np.cross(h1, k1)
                assert (sigma >= -1e-12) if "right" in label else (sigma <= 1e-12), label

                def across(x: FloatArray, k1: FloatArray = k1) -> FloatArray:
                    return x - (x @ k1) * k1

                n = np.cross(k1, across(w - s))  # left normal of the shoulder-wrist line
                up = (across(e - s) @ n) * (h1 @ n)
                assert (up >= -1e-12) if "up" in label else (up <= 1e-12), label


def test_scara_right_handed_has_positive_elbow_turn() -> None:
    scara = Robot.from_dh(
        [Revolute(d=0.4, a=0.3), Revolute(a=0.25), Prismatic(), Revolute()], convention="standard"
    )
    T = scara.fk(np.array([[0.2, 0.7, 0.1, 0.0], [0.2, -0.7, 0.1, 0.0]]))
    labels, cand, _ = raw_candidates(scara, T)
    assert labels == ("right-handed", "left-handed")
    assert (np.sin(cand[:, 0, 1]) > 0).all() and (np.sin(cand[:, 1, 1]) < 0).all()


# ------------------------------------------------------------ special targets
def test_planar_2r_singular_at_the_base_and_unreachable() -> None:
    robot = Robot.from_dh([Revolute(a=0.5), Revolute(a=0.5, offset=0.2)], convention="standard")
    res = robot.ik(np.array([[1.3, 0.0, 0.0], [0.0, 0.0, 0.0], [0.3, 0.4, 0.25], [0.3, 0.4, 0]]))
    assert list(res.status) == ["unreachable", "singular", "unreachable", "ok"]
    assert res.gap[0] == pytest.approx(0.3, abs=1e-15)  # beyond the reach
    assert res.gap[2] == pytest.approx(0.25, abs=1e-15)  # off the plane
    assert res.free[1].tolist() == [True, False]
    assert "at least 0.3 m outside the reach" in res[0].message
    unequal = Robot.from_dh([Revolute(a=0.5), Revolute(a=0.3)], convention="standard")
    res = unequal.ik(np.array([[0.1, 0.0, 0.0], [0.3, 0.5, 0.0]]))
    assert list(res.status) == ["unreachable", "ok"]
    assert res.gap[0] == pytest.approx(0.1, abs=1e-15)  # inside the hole


def test_folded_equal_2r_near_the_base() -> None:
    """The report: l1 = l2 = 0.5, targets 1e-9 m from the base gave not_found for 3 of 7."""
    robot = Robot.from_dh([Revolute(a=0.5), Revolute(a=0.5)], convention="standard")
    angles = np.linspace(-PI, PI, 7, endpoint=False) + 0.1
    for r in (1e-7, 1e-9, 1e-11):
        targets = r * np.stack([np.cos(angles), np.sin(angles), 0 * angles], axis=1)
        res = robot.ik(targets)
        assert (res.status == "ok").all() and (res.count == 2).all(), res.message
        for i in range(len(targets)):
            err = reached(robot, res[i].solutions, targets[i])
            assert (err <= 1e-15).all()
            # the two solutions: elbow folded by π ∓ 2r/L, the arm turned by π
            q2 = np.sort(np.abs(km.wrap_angle(res[i].solutions[:, 1])))
            np.testing.assert_allclose(q2, PI - 2 * r, rtol=0, atol=1e-15 + 1e-7 * r)
    # On the base itself (within SINGULAR_TOL of the reach): q1 free.
    for r in (0.0, 0.1 * SINGULAR_TOL):
        res = robot.ik(np.array([r, 0.0, 0.0]))
        assert res.status == "singular" and res.free_joints == (0,), res.message
    # Just outside SINGULAR_TOL (100x): two solutions, not a continuum.
    res = robot.ik(np.array([100 * SINGULAR_TOL, 0.0, 0.0]))
    assert res.status == "ok" and res.count == 2


def test_pose_targets_fix_the_fold_of_reduced_arms() -> None:
    """A pose fixes q1 of a folded 2R (the position alone does not): one solution."""
    robot = Robot.from_dh([Revolute(a=0.5), Revolute(a=0.5)], convention="standard")
    for q in ([0.7, PI], [-2.0, PI - 1e-9], [1.0, 0.0], [0.3, 1e-10]):
        res = robot.ik(robot.fk(q))
        assert res.status == "ok" and res.count == 1, res.message
        assert joint_distance(robot, res.solutions[0], np.array(q)) < 1e-7


@pytest.mark.parametrize("kind", ["planar-3R", "planar-PRR", "scara"])
def test_planar_pose_targets_tilted_or_off_the_plane(kind: str) -> None:
    rng = np.random.default_rng(5)
    robot = random_arm(kind, rng)
    T = robot.fk(random_q(robot, rng, 1))[0]
    h, _ = robot.joint_axes()
    k = h[1]
    tilt = Rotation.from_rotvec(0.01 * np.cross(k, [0.3, 0.5, 0.7]) / 0.5).as_matrix()
    tilted = T.copy()
    tilted[:3, :3] = tilt @ T[:3, :3]
    res = robot.ik(tilted, respect_limits=False)
    # A rotation is no distance in metres: the closest candidate says how far.
    assert res.status == "unreachable" and res.gap is None
    assert 0.005 < res.nearest_error[1] < 0.05 and "m outside" not in res.message
    if kind != "scara":  # the SCARA's slide reaches any height
        lifted = T.copy()
        lifted[:3, 3] += 0.2 * k
        res = robot.ik(lifted, respect_limits=False)
        assert res.status == "unreachable" and res.gap == pytest.approx(0.2, abs=1e-12)


def test_planar_pr_unreachable_gap() -> None:
    res = seed_pr_arm().ik(np.array([0.2, L2 + 0.1, 0.0]))
    assert res.status == "unreachable" and res.gap == pytest.approx(0.1, abs=1e-15)


def test_3r_singular_on_axis_1_and_unreachable() -> None:
    robot = seed_anthropomorphic()
    on_axis = np.array([[0.0, 0.0, D1 + 0.5], [0.0, 0.0, D1 + 2.0], [1.0, 1.0, 1.0], [0, 0.2, D1]])
    res = robot.ik(on_axis)
    assert list(res.status) == ["singular", "unreachable", "unreachable", "ok"]
    assert res.free[0].tolist() == [True, False, False]
    assert (reached(robot, res[0].solutions, on_axis[0]) <= EXACT).all()
    # beyond reach: the tool lies on a sphere shell about the shoulder (axes 1, 2 meet)
    assert res.gap[1] == pytest.approx(2.0 - (A2 + A3), abs=1e-12)
    d = np.linalg.norm(on_axis[2] - [0, 0, D1])
    assert res.gap[2] == pytest.approx(d - (A2 + A3), abs=1e-12)
    # SINGULAR_TOL, both sides: 0.1x from the axis is on it, 100x is not (four solutions).
    for r, status in ((0.1, "singular"), (100.0, "ok")):
        off = on_axis[0] + [r * SINGULAR_TOL * (A2 + A3 + D1), 0.0, 0.0]
        assert robot.ik(off).status == status


@pytest.mark.parametrize("name", ["anthropomorphic-3r", "rrr-geometric"])
def test_tool_on_axis_1_pose_is_solved_position_is_singular(name: str) -> None:
    """Issue 13 item 3: with the tool on axis 1 the orientation fixes q1."""
    robot = km.load(name)
    for q in ([0.3, PI / 2, 0.0], [-2.1, PI / 2, 0.0], [0.3, -PI / 2, 0.0]):
        T = robot.fk(q)
        res = robot.ik(T)
        assert res.status == "ok" and res.count == 1, res.message
        assert joint_distance(robot, res.solutions[0], np.array(q)) < 1e-9
        res = robot.ik(T[:3, 3])
        assert res.status == "singular" and 0 in res.free_joints, res.message
        assert (reached(robot, res.solutions, T[:3, 3]) <= TOL).all()


def test_scara_and_3r_planar_fold_is_singular() -> None:
    scara = Robot.from_dh(
        [Revolute(d=0.4, a=0.3), Revolute(a=0.3, alpha=PI), Prismatic(), Revolute(d=0.1)],
        convention="standard",
    )
    T = scara.fk([0.3, PI, 0.05, 0.2])  # the wrist folded back onto axis 1
    res = scara.ik(T)
    assert res.status == "singular" and res.free_joints == (0, 3)
    assert (reached(scara, res.solutions, T) <= TOL).all()
    planar = Robot.from_dh(
        [Revolute(a=0.4), Revolute(a=0.4), Revolute(a=0.2)], convention="standard"
    )
    T = planar.fk([1.0, PI, 0.5])
    res = planar.ik(T)
    assert res.status == "singular" and res.free_joints == (0, 2)


def test_free_last_representatives_respect_the_limits() -> None:
    """A PRR whose slide allows one narrow window: the middle representative misses it."""
    free = Robot.from_dh(
        [Prismatic(alpha=PI / 2), Revolute(a=0.5, offset=PI / 2), Revolute(a=0.4)],
        name="PRR",
        convention="standard",
    )
    p = free.fk([0.0, 0.3, 0.9])[:3, 3]
    base = free.ik(p, respect_limits=False)
    assert base.status == "singular"
    slide = base.solutions[:, 0]
    # limits that exclude the unconstrained representatives but keep q1 = 0 (the generating q)
    window = (-0.02, 0.02)
    assert not ((slide > window[0]) & (slide < window[1])).any()
    tight = free.with_limits([window, None, None])
    res = tight.ik(p)
    assert res.status == "singular", res.message
    assert ((res.solutions[:, 0] >= window[0]) & (res.solutions[:, 0] <= window[1])).all()
    assert (reached(tight, res.solutions, p) <= TOL).all()


@pytest.mark.parametrize("name", ["scara", "planar-pr", "anthropomorphic-3r", "planar-3r"])
def test_huge_targets_are_unreachable_with_their_gap(name: str) -> None:
    robot = km.load(name)
    for x in (1.4e154, 1e300):
        T = np.eye(4)
        T[:3, 3] = [x, 0.5 * x, -x]
        for target in (T, T[:3, 3]):
            one = robot.ik(target)
            many = robot.ik(target[None])
            assert one.status == many.status[0] == "unreachable"
            assert one.gap is not None and one.gap > 0.1 * x
            assert one.message == many[0].message


def test_closed_form_reports_gap_only_outside_the_reach() -> None:
    robot = km.load("planar-3r")
    T = robot.fk([0.2, 0.3, 0.4])
    _, _, info = raw_candidates(robot, T[None])
    assert np.isnan(info.gap[0]) or info.gap[0] < 1e-15
    assert not info.singular[0]
    far = T.copy()
    far[:3, 3] *= 10
    _, _, info = raw_candidates(robot, far[None])
    assert info.gap[0] == pytest.approx(np.linalg.norm(far[:3, 3]) - 0.9, abs=1e-12)


@pytest.mark.parametrize("kind", ["planar-3R", "elbow-3R"])
def test_axes_parallel_within_tolerance_make_misses_no_proof(kind: str) -> None:
    """The closed forms solve the ideal arm; a real one off by more than round-off gets slack.

    Axis 3 twisted 1e-15 rad off parallel is round-off (below the threshold
    at this size): gaps are exact. Twisted 1e-10 (within the classification's
    1e-9), the ideal arm may put the tool up to ~2e-10 m away: the gap
    shrinks by that (a target 1e-9 m off the ideal reach is no longer proven
    that far), and the ideal arm's continua are ``near`` (a miss there
    is no proof). Generic targets get neither.
    """

    def arm(twist: float) -> Robot:
        if kind == "planar-3R":  # position targets: the last joint free (a continuum)
            rows = [Revolute(a=0.4), Revolute(a=0.3, alpha=twist), Revolute(a=0.2)]
        else:  # equal links folded: q2 free (a continuum)
            rows = [Revolute(d=0.3, a=0.1, alpha=PI / 2), Revolute(a=0.4, alpha=twist)]
            rows.append(Revolute(a=0.4))
        robot = Robot.from_dh(rows, convention="standard")
        assert classify(robot).kind == kind
        return robot

    for twist, tilted in ((1e-15, False), (1e-10, True)):
        robot = arm(twist)
        T = robot.fk(np.zeros(3))  # stretched: the reach's edge
        _, p = robot.joint_axes()
        beyond = T.copy()
        beyond[:3, 3] += 1e-9 * (T[:3, 3] - p[1]) / np.linalg.norm(T[:3, 3] - p[1])
        generic = robot.fk([0.3, 0.9, -0.7])
        folded = [0.3, 0.9, PI]  # the elbow arm's continuum; the planar one's is any position
        continuum = (generic if kind == "planar-3R" else robot.fk(folded))[:3, 3]
        _, _, info = raw_candidates(robot, np.stack([beyond, generic]))
        gap = info.gap[0]
        if tilted:
            assert math.isnan(gap) or gap < 1e-9 - 1e-10
        else:
            assert gap == pytest.approx(1e-9, abs=1e-12)
        assert not info.near[1]
        _, _, info = raw_candidates(robot, continuum[None])
        assert info.singular[0] and info.near[0] == tilted
        assert robot.ik(generic).status == "ok"


def test_gap_below_round_off_is_not_reported() -> None:
    """SINGULAR_TOL of the reach is the closed forms' round-off: a smaller gap is no gap.

    A pose tilted out of the plane, at the reach's edge, cannot be reached:
    0.1x the floor beyond the reach reports no distance (at the edge, where
    branches merge, that is no proof: ``not_found``), 100x reports it.
    """
    robot = Robot.from_dh(
        [Revolute(a=0.6), Revolute(a=0.4), Revolute(a=0.2)], convention="standard"
    )  # reach 1.2 m
    T = robot.fk(np.zeros(3))
    T[:3, :3] = Rotation.from_rotvec([0.0, 0.01, 0.0]).as_matrix()  # tilted out of the plane
    for factor, reported in ((0.1, False), (100.0, True)):
        target = T.copy()
        target[0, 3] += factor * SINGULAR_TOL * 1.2
        _, _, info = raw_candidates(robot, target[None])
        assert math.isnan(info.gap[0]) != reported
        res = robot.ik(target)
        assert res.status == ("unreachable" if reported else "not_found")
        assert (res.gap is not None) == reported


def test_merging_branches_are_said_so() -> None:
    """MERGE_TOL, both sides: 0.1x from stretched the branches merge (a note says so), 10x not."""
    robot = Robot.from_dh([Revolute(a=0.5), Revolute(a=0.3)], convention="standard")
    for factor, near in ((0.1, True), (10.0, False)):
        q = np.array([0.4, factor * MERGE_TOL])
        res = robot.ik(robot.fk(q)[:3, 3])
        assert res.status == "ok" and res.near_singular == near
        assert ("round-off" in res.message) == near
        assert joint_distance(robot, res.solutions, q).min() < 1e-7
    pr = seed_pr_arm()  # the link across the slide
    for factor, near in ((0.1, True), (10.0, False)):
        res = pr.ik(pr.fk([0.1, PI / 2 - factor * MERGE_TOL])[:3, 3])
        assert res.status == "ok" and res.near_singular == near


def test_double_root_is_one_solution() -> None:
    """Stretched arms (and 1e-12 rad from it): the two branches merge into one solution."""
    planar = Robot.from_dh([Revolute(a=0.5), Revolute(a=0.3)], convention="standard")
    arm = seed_anthropomorphic()
    pr = seed_pr_arm()
    for robot, q in (
        (planar, [0.4, 0.0]),
        (planar, [0.4, 1e-12]),
        (arm, [0.4, 0.3, 0.0]),
        (arm, [0.4, 0.3, -1e-12]),
        (pr, [0.1, PI / 2]),  # the link across the slide: s = along ± 0
    ):
        p = robot.fk(q)[:3, 3]
        res = robot.ik(p)
        assert res.status == "ok", res.message
        per_shoulder = 2 if robot is arm else 1  # the 3R arm: two shoulders, one elbow each
        assert res.count == per_shoulder
        assert joint_distance(robot, res.solutions, np.array(q)).min() < 1e-7


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("degenerate", [False, True])
def test_sample_arm_gives_arms_of_the_family(kind: str, degenerate: bool) -> None:
    """Each spec's sample_arm draws arms its spec handles, built and solved by its closed form."""
    from kinematica.ik.analytic import SOLVERS
    from kinematica.ik.structure import features

    spec = next(s for s in SOLVERS if s.kind == kind)
    assert set(spec.targets) == {"pose", "position"}
    rng = np.random.default_rng(50 + KINDS.index(kind) + 100 * degenerate)
    for _ in range(6):
        sample = spec.sample_arm(rng, degenerate)
        assert (sample.note != "") is degenerate
        robot = Robot.from_dh(
            sample.links, convention=sample.convention, base=sample.base, tool=sample.tool
        )
        assert spec.handles(features(robot.chain)) and classify(robot).kind == kind
        q = random_q(robot, rng, 5)
        for position in (False, True):
            closed = closed_form(robot.chain, "position" if position else "pose")
            assert closed is not None and closed.name == kind
            targets = target_of(robot, q, position)
            res = robot.ik(targets, respect_limits=False)
            assert np.isin(res.status, ["ok", "singular"]).all(), set(res.status)
            err = reached(robot, np.nan_to_num(res.solutions), targets[:, None])
            assert (err[res.count[:, None] > np.arange(res.solutions.shape[1])] <= TOL).all()
