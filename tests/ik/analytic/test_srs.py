"""Closed-form IK of SRS 7R arms (KUKA iiwa type) at an arm angle.

Independent references: forward kinematics of every solution; the arm angle of
every solution measured from the joint frames (and, on the iiwa, from its DH
origins by the textbook formula); the configuration that made a pose; hand-derived
reach bounds (|S-W| between |upper - fore| and upper + fore); Shimizu's reference
plane (q3 = 0 puts the elbow in the plane of S-W and axis 1: ψ = 0 or π).
"""

from __future__ import annotations

import math

import kinematica._core as _core
import numpy as np
import pytest
from numpy.typing import NDArray
from support.helpers import assert_transform_close
from support.ik_search import joint_distance

import kinematica as km
from kinematica.errors import ArgumentError, DimensionError, KinematicaError
from kinematica.ik.analytic import srs
from kinematica.robot import classify

FloatArray = NDArray[np.float64]
PI = math.pi
#: Every solution reaches its target to this (m, rad): the check's default tolerances.
REACH = 1e-10
#: The generating configuration is among the solutions to this (rad).
FOUND = 1e-9
#: The arm angle of every solution equals the one asked for to this (rad).
ANGLE = 1e-10
#: iiwa 14: shoulder height, upper arm, forearm, flange (m), from its DH table.
D1, UPPER, FORE, FLANGE = 0.36, 0.42, 0.4, 0.126

pytestmark = pytest.mark.filterwarnings("ignore::kinematica.KinematicaWarning")


@pytest.fixture(scope="module")
def iiwa() -> km.Robot:
    return km.load("iiwa14")


def _wrapped(a: FloatArray) -> FloatArray:
    return np.asarray(np.abs(np.angle(np.exp(1j * np.asarray(a)))))


def _generic_q(rng: np.random.Generator, n: int) -> FloatArray:
    """iiwa configurations away from its singular sets (|q2|, |q4|, |q6| >= 0.2)."""
    q = rng.uniform(-2.9, 2.9, (n, 7))
    for j in (1, 3, 5):
        q[:, j] = rng.choice([-1.0, 1.0], n) * rng.uniform(0.2, 2.0, n)
    return q


def _check_all(
    robot: km.Robot, q: FloatArray, res: km.ik.IKBatchResult, rows: FloatArray | None = None
) -> None:
    """The generating q among the solutions, each reaching its target at its arm angle."""
    psi = robot.arm_angle(q)
    T = robot.fk(q)
    for i in range(len(q)) if rows is None else rows:
        one = res[i]
        assert one.status == "ok", one.message
        sols = one.solutions
        assert float(joint_distance(robot, sols, q[i]).min()) <= FOUND
        F = robot.fk(sols)
        assert np.linalg.norm(F[:, :3, 3] - T[i, :3, 3], axis=-1).max() <= REACH
        assert km.rotation_angle(F[:, :3, :3], T[i, :3, :3]).max() <= REACH
        assert _wrapped(robot.arm_angle(sols) - psi[i]).max() <= ANGLE


def test_iiwa_all_eight_at_the_generating_arm_angle(iiwa: km.Robot) -> None:
    q = _generic_q(np.random.default_rng(1), 200)
    res = iiwa.ik(iiwa.fk(q), arm_angle=iiwa.arm_angle(q), respect_limits=False)
    assert res.method == "analytic:srs"
    assert np.all(res.count == 8)
    _check_all(iiwa, q, res)
    for i in range(len(q)):  # eight distinct solutions
        sols = res[i].solutions
        d = joint_distance(iiwa, sols[:, None, :], sols[None, :, :]) + np.eye(8)
        assert d.min() > 1e-6


@pytest.mark.parametrize("degenerate", [False, True], ids=["generic", "edges"])
def test_random_srs_arms(degenerate: bool) -> None:
    rng = np.random.default_rng(2 + degenerate)
    for _ in range(6):
        arm = srs.sample_arm(rng, degenerate)
        if "1e-10" in arm.note:  # near-degenerate: checked in test_near_degenerate_arm
            continue
        robot = km.Robot.from_dh(arm.links, base=arm.base, tool=arm.tool, convention="standard")
        q = rng.uniform(-PI, PI, (40, 7))
        res = robot.ik(robot.fk(q), arm_angle=robot.arm_angle(q), respect_limits=False)
        keep = np.flatnonzero(~res.near_singular)  # near a fold: q to round-off over it
        assert keep.size >= 35
        _check_all(robot, q, res, keep)


def test_near_degenerate_arm_keeps_the_arm_angle_to_the_repair() -> None:
    # axes 1-3 miss their common point by 1e-10: the closed form of the exact arm,
    # carried onto this one by the check's repair, which may turn it a little along the
    # self-motion; the answer says it may be incomplete
    rng = np.random.default_rng(4)
    robot = km.Robot.from_dh(
        srs.random_srs_rows(rng, "shoulder offset 1e-10"), convention="standard"
    )
    q = rng.uniform(-PI, PI, (30, 7))
    T, psi = robot.fk(q), robot.arm_angle(q)
    res = robot.ik(T, arm_angle=psi, respect_limits=False)
    for i in range(len(q)):
        one = res[i]
        assert not one.complete and one.notes
        F = robot.fk(one.solutions)
        assert np.linalg.norm(F[:, :3, 3] - T[i, :3, 3], axis=-1).max() <= REACH
        assert _wrapped(robot.arm_angle(one.solutions) - psi[i]).max() <= 1e-6


def test_arm_angle_from_the_iiwa_dh_origins(iiwa: km.Robot) -> None:
    # On the iiwa's DH frames S, E and W are the origins of frames 1, 3 and 5 (a = 0,
    # d2 = d4 = d6 = 0): ψ = atan2(n · (r × e), r · e), r and e the parts of z0 and E - S
    # across n = (W - S)/|W - S|
    q = _generic_q(np.random.default_rng(5), 50)
    frames = iiwa.fk(q, all_frames=True)
    S, E, W = frames[:, 1, :3, 3], frames[:, 3, :3, 3], frames[:, 5, :3, 3]
    n = (W - S) / np.linalg.norm(W - S, axis=1, keepdims=True)
    z0 = np.array([0.0, 0.0, 1.0])
    r = z0 - (n @ z0)[:, None] * n
    e = (E - S) - np.sum((E - S) * n, axis=1, keepdims=True) * n
    want = np.arctan2(np.sum(n * np.cross(r, e), axis=1), np.sum(r * e, axis=1))
    assert _wrapped(iiwa.arm_angle(q) - want).max() <= 1e-13


def test_q3_zero_is_shimizus_reference_plane(iiwa: km.Robot) -> None:
    # q3 = 0 keeps axes 2 and 4 parallel: S, E, W lie in a plane containing axis 1
    rng = np.random.default_rng(6)
    q = _generic_q(rng, 40)
    q[:, 2] = 0.0
    psi = iiwa.arm_angle(q)
    assert np.minimum(_wrapped(psi), _wrapped(psi - PI)).max() <= 1e-12
    # elbow up (the elbow's part across S-W along +z0) is ψ = 0: q2 > 0, q4 < 0, q1 = 0
    # puts the upper arm leaning forward and the forearm back towards the vertical
    up = iiwa.arm_angle(np.array([0.0, 0.6, 0.0, -1.2, 0.0, 0.0, 0.0]))
    down = iiwa.arm_angle(np.array([0.0, 0.6, 0.0, 1.2, 0.0, 0.0, 0.0]))
    frames = iiwa.fk(np.array([0.0, 0.6, 0.0, -1.2, 0.0, 0.0, 0.0]), all_frames=True)
    S, E, W = frames[1, :3, 3], frames[3, :3, 3], frames[5, :3, 3]
    t = float((E - S) @ (W - S)) / float((W - S) @ (W - S))
    assert (E - S - t * (W - S))[2] > 0.0  # that elbow is above the line S-W
    assert abs(float(up)) <= 1e-12
    assert _wrapped(float(down) - PI) <= 1e-12 or _wrapped(float(down)) <= 1e-12


def test_labels_are_the_joint_signs_on_the_iiwa(iiwa: km.Robot) -> None:
    # shoulder no-flip: q2 > 0; elbow bent positive: q4 > 0; wrist no-flip: q6 > 0
    q = _generic_q(np.random.default_rng(7), 20)
    res = iiwa.ik(iiwa.fk(q), arm_angle=0.4, respect_limits=False)
    for i in range(len(q)):
        one = res[i]
        for sol, label in zip(one.solutions, one.branches, strict=True):
            shoulder, elbow, wrist = label.split(", ")
            assert (sol[3] > 0) == (elbow == "elbow bent positive"), label
            assert (sol[1] > 0) == (shoulder == "shoulder no-flip"), label
            assert (sol[5] > 0) == (wrist == "wrist no-flip"), label
    assert srs.LABELS[0] == "shoulder no-flip, elbow bent positive, wrist no-flip"


def test_batch_equals_single_calls(iiwa: km.Robot) -> None:
    q = _generic_q(np.random.default_rng(8), 6).reshape(3, 2, 7)
    T = iiwa.fk(q)
    psi = iiwa.arm_angle(q)
    for angle in (psi, 0.7):  # one per target, or one for all
        batch = iiwa.ik(T, arm_angle=angle)
        assert batch.status.shape == (3, 2)
        for idx in np.ndindex(3, 2):
            a = angle if np.ndim(angle) == 0 else float(angle[idx])
            one = iiwa.ik(T[idx], arm_angle=a)
            assert batch[idx].status == one.status and batch[idx].branches == one.branches
            np.testing.assert_array_equal(batch[idx].solutions, one.solutions)
    one_row = iiwa.ik(T[:1, 0], arm_angle=psi[:1, 0])
    assert one_row.status.shape == (1,)
    np.testing.assert_array_equal(
        one_row[0].solutions, iiwa.ik(T[0, 0], arm_angle=psi[0, 0]).solutions
    )


def test_a_malformed_row_leaves_the_others(iiwa: km.Robot) -> None:
    q = _generic_q(np.random.default_rng(9), 4)
    T, psi = iiwa.fk(q), iiwa.arm_angle(q)
    bad = T.copy()
    bad[2, 0, 0] = np.nan
    res, good = iiwa.ik(bad, arm_angle=psi), iiwa.ik(T, arm_angle=psi)
    assert res.status[2] == "invalid" and (2,) in res.errors
    for i in (0, 1, 3):
        np.testing.assert_array_equal(res[i].solutions, good[i].solutions)


def _pose_with_wrist_at(w: FloatArray, R: FloatArray | None = None) -> FloatArray:
    """An iiwa flange pose whose wrist centre is w (the flange is 0.126 m along z7)."""
    T = np.eye(4)
    if R is not None:
        T[:3, :3] = R
    T[:3, 3] = w + FLANGE * T[:3, 2]
    return T


@pytest.mark.parametrize(
    ("distance", "gap"),
    [(UPPER + FORE + 0.05, 0.05), (0.01, UPPER - FORE - 0.01)],
    ids=["beyond the reach", "inside the hole"],
)
def test_unreachable_with_the_hand_derived_gap(iiwa: km.Robot, distance: float, gap: float) -> None:
    direction = np.array([0.6, 0.0, 0.8])
    T = _pose_with_wrist_at(np.array([0.0, 0.0, D1]) + distance * direction)
    res = iiwa.ik(T, arm_angle=0.2)
    assert res.status == "unreachable", res.message
    assert res.gap == pytest.approx(gap, abs=1e-12)


def test_stretched_elbow_is_a_continuum(iiwa: km.Robot) -> None:
    # q4 = 0: the elbow on the line S-W, the arm angle undefined
    q = np.array([0.3, 0.5, -0.4, 0.0, 0.6, 0.7, -0.2])
    assert np.isnan(iiwa.arm_angle(q))
    T = iiwa.fk(q)
    res = iiwa.ik(T, arm_angle=1.0, respect_limits=False)
    assert res.status == "singular", res.message
    assert {0, 1, 2, 4, 5, 6} <= set(res.free_joints)
    assert_transform_close(iiwa.fk(res.solutions), np.broadcast_to(T, (res.count, 4, 4)), 1e-10)


@pytest.mark.parametrize(("sine", "singular"), [(0.5e-12, True), (2e-12, False)])
def test_shoulder_wrist_line_along_axis_1(iiwa: km.Robot, sine: float, singular: bool) -> None:
    # REFERENCE_TOL: S-W within 1e-12 (sine) of axis 1 leaves ψ without a reference;
    # turning the arm about axis 1 (q1 and the wrist) solves
    assert _core.srs.REFERENCE_TOL == 1e-12
    s = np.array([0.0, 0.0, D1])
    w = s + 0.6 * np.array([sine, 0.0, math.sqrt(1.0 - sine * sine)])
    T = _pose_with_wrist_at(w)
    res = iiwa.ik(T, arm_angle=0.3, respect_limits=False)
    assert res.count
    assert_transform_close(iiwa.fk(res.solutions), np.broadcast_to(T, (res.count, 4, 4)), 1e-10)
    if singular:
        assert res.status == "singular" and {0, 4, 5, 6} <= set(res.free_joints)
    else:  # ψ is then measured from a direction known to round-off over the sine
        assert res.status == "ok" and res.near_singular and res.count == 8


@pytest.mark.parametrize(("fraction", "defined"), [(0.5, False), (2.0, True)])
def test_collinear_tolerance_of_the_arm_angle(
    iiwa: km.Robot, fraction: float, defined: bool
) -> None:
    # COLLINEAR_TOL: the elbow within 1e-12 of the arm's size from S-W leaves ψ
    # undefined. Bent by β, the elbow is UPPER FORE sin β / |S-W| from that line.
    assert _core.srs.COLLINEAR_TOL == 1e-12
    size = D1 + UPPER + FORE + FLANGE  # the arm's size: its translations
    beta = fraction * 1e-12 * size * (UPPER + FORE) / (UPPER * FORE)
    q = np.array([0.2, 0.7, 0.1, beta, 0.3, 0.4, 0.5])
    assert np.isfinite(iiwa.arm_angle(q)) == defined


def test_exactly_stretched_target_is_singular_just_past_it_not(iiwa: km.Robot) -> None:
    # the solver's own edge: |S-W| at the reach within round-off is the double root
    # β = 0 (the elbow on S-W: singular); the first |S-W| the fold's tolerance no longer
    # rounds to it bends the elbow by ~1e-6 rad, far from S-W: 8 regular solutions
    s, n = np.array([0.0, 0.0, D1]), np.array([0.6, 0.0, 0.8])
    at_reach = iiwa.ik(_pose_with_wrist_at(s + (UPPER + FORE) * n), arm_angle=0.3)
    assert at_reach.status == "singular", at_reach.message
    folded = iiwa.ik(_pose_with_wrist_at(s + (UPPER - FORE) * n), arm_angle=0.3,
                     respect_limits=False)  # fmt: skip
    assert folded.status == "singular" and {0, 1, 2, 4, 5, 6} <= set(folded.free_joints)
    inside = iiwa.ik(
        _pose_with_wrist_at(s + (UPPER + FORE) * (1 - 1e-13) * n),
        arm_angle=0.3,
        respect_limits=False,
    )
    assert inside.status == "ok" and inside.count == 8
    assert 1e-7 < float(np.abs(inside.solutions[:, 3]).min()) < 1e-5


def test_the_arm_angle_asked_of_other_arms_and_bad_values(iiwa: km.Robot) -> None:
    puma = km.load("puma560")
    T = puma.fk(np.zeros(6))
    with pytest.raises(KinematicaError, match="SRS 7R arms") as err:
        puma.ik(T, arm_angle=0.1)
    assert err.value.arg == "arm_angle"
    with pytest.raises(KinematicaError, match="SRS 7R arms"):
        puma.arm_angle(np.zeros(6))
    Ti = iiwa.fk(np.full(7, 0.3))
    with pytest.raises(KinematicaError, match="method='numeric'"):
        iiwa.ik(Ti, arm_angle=0.1, method="numeric")
    with pytest.raises(KinematicaError, match=r"without an arm angle; use arm_angle=0\.0"):
        iiwa.ik(Ti, method="analytic")
    with pytest.raises(KinematicaError, match="SRS 7R arms"):  # a position target
        iiwa.ik(Ti[:3, 3], arm_angle=0.1)
    with pytest.raises(ArgumentError, match="arm_angle must be finite"):
        iiwa.ik(Ti, arm_angle=math.nan)
    with pytest.raises(ArgumentError, match="arm_angle must be a number"):
        iiwa.ik(Ti, arm_angle="up")
    with pytest.raises(DimensionError, match="one per target"):
        iiwa.ik(np.stack([Ti, Ti]), arm_angle=[0.1, 0.2, 0.3])


def test_auto_holds_the_arm_angle_of_q0_or_zero(iiwa: km.Robot) -> None:
    # auto on an SRS arm with no parameter: all 8 at q0's arm angle, else at 0, said so;
    # both parameters at once are refused
    q = np.array([0.3, 0.5, -0.2, 1.0, 0.4, -0.6, 0.2])
    T = iiwa.fk(q)
    own = float(iiwa.arm_angle(q))
    at_q0 = iiwa.ik(T, q0=q)
    assert at_q0.method == "analytic:srs" and at_q0.parameter == ("arm angle", own)
    assert np.abs(at_q0.solutions[0] - q).max() < 1e-9  # sorted by distance to q0
    assert np.allclose(iiwa.arm_angle(at_q0.solutions), own, atol=1e-10)
    default = iiwa.ik(T)
    assert default.parameter == ("arm angle", 0.0)
    assert any("arm angle = 0 rad" in n and "arm_angle=" in n for n in default.notes)
    assert np.allclose(iiwa.arm_angle(default.solutions), 0.0, atol=1e-10)
    with pytest.raises(KinematicaError, match="arm_angle or fixed, not both"):
        iiwa.ik(T, arm_angle=0.2, fixed={6: 0.3})
    assert classify(iiwa).kind == "srs-7R"


@pytest.mark.parametrize(
    ("joint", "free"), [(1, {0, 2}), (5, {4, 6})], ids=["shoulder q2 = 0", "wrist q6 = 0"]
)
def test_aligned_shoulder_or_wrist_axes(iiwa: km.Robot, joint: int, free: set[int]) -> None:
    # q2 = 0 aligns axes 1 and 3 (only q1 + q3 counts), q6 = 0 axes 5 and 7
    q = np.array([0.3, 0.5, -0.4, 1.1, 0.6, 0.7, -0.2])
    q[joint] = 0.0
    T = iiwa.fk(q)
    res = iiwa.ik(T, arm_angle=iiwa.arm_angle(q), respect_limits=False)
    assert res.status == "singular" and free <= set(res.free_joints), res.message
    assert_transform_close(iiwa.fk(res.solutions), np.broadcast_to(T, (res.count, 4, 4)), 1e-10)
    sums = res.solutions[:, min(free)] + res.solutions[:, max(free)]
    assert float(_wrapped(sums - (q[min(free)] + q[max(free)])).min()) <= FOUND


def test_the_arm_angle_is_undefined_within_the_collinear_tolerance(iiwa: km.Robot) -> None:
    # the elbow a distance d off the line S-W (q4 small: d grows as q4): undefined (NaN)
    # for d at half of COLLINEAR_TOL times the arm's size, defined at twice it
    tiny = _core.srs.COLLINEAR_TOL * classify(iiwa).features.size

    def offset(q: FloatArray) -> float:  # the elbow's distance from S-W, from the DH origins
        frames = iiwa.fk(q, all_frames=True)
        S, E, W = frames[1, :3, 3], frames[3, :3, 3], frames[5, :3, 3]
        n = (W - S) / np.linalg.norm(W - S)
        return float(np.linalg.norm((E - S) - ((E - S) @ n) * n))

    q = np.array([0.3, 0.5, -0.4, 1e-6, 0.6, 0.7, -0.2])
    per_radian = offset(q) / q[3]
    for share, defined in ((0.5, False), (2.0, True)):
        q[3] = share * tiny / per_radian
        assert math.isfinite(float(iiwa.arm_angle(q))) == defined, share
    # q not finite: NaN; q of another length: an error naming q
    assert np.isnan(iiwa.arm_angle(np.full(7, np.nan)))
    with pytest.raises(DimensionError, match="7 joint angles"):
        srs.arm_angle(iiwa.chain, np.zeros(6))


def test_wrist_on_the_shoulder_of_equal_links() -> None:
    # an iiwa-type arm with upper arm = forearm folds W onto S: no line S-W at all
    rows = [
        km.Revolute(d=D1, alpha=-PI / 2),
        km.Revolute(alpha=PI / 2),
        km.Revolute(d=FORE, alpha=PI / 2),
        km.Revolute(alpha=-PI / 2),
        km.Revolute(d=FORE, alpha=-PI / 2),
        km.Revolute(alpha=PI / 2),
        km.Revolute(d=FLANGE),
    ]
    arm = km.Robot.from_dh(rows, convention="standard")
    q = np.array([0.2, 0.5, 0.3, PI, 0.4, 0.6, 0.1])
    T = arm.fk(q)
    assert np.isnan(arm.arm_angle(q))
    res = arm.ik(T, arm_angle=0.3)
    assert res.status == "singular" and {0, 1, 2, 4, 5, 6} <= set(res.free_joints)
    assert_transform_close(arm.fk(res.solutions), np.broadcast_to(T, (res.count, 4, 4)), 1e-10)


def test_arm_angle_of_any_batch_shape(iiwa: km.Robot) -> None:
    q = _generic_q(np.random.default_rng(10), 6)
    flat = iiwa.arm_angle(q)
    assert np.shape(iiwa.arm_angle(q[0])) == () and float(iiwa.arm_angle(q[0])) == flat[0]
    assert iiwa.arm_angle(q[:1]).shape == (1,)
    np.testing.assert_array_equal(iiwa.arm_angle(q.reshape(3, 2, 7)), flat.reshape(3, 2))
