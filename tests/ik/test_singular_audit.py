"""Statuses at targets within round-off of a singular set (issue 34, items 2-4).

The audit of ``tests/support/ik_singular_audit.py`` on a small sample (the issue's
200,000 targets: ``benchmarks/ik_singular.py``), each check shown to count what it
should, the target a UR-type arm called unreachable, the tolerances that decide
"near_singular" and "one solution" just inside and just outside, and an SRS arm's
``q0`` whose arm angle is undefined.
"""

from __future__ import annotations

import json
import math

import kinematica._core_testing as _core_testing
import numpy as np
import pytest
from support.helpers import run_cli
from support.ik_singular_audit import (
    COUNTS,
    FAILURES,
    FOUND_TOL,
    MAKERS,
    conditioning,
    duplicates,
    judge,
    run,
    singular_6r,
)

import kinematica as km
from kinematica.ik.redundancy import UNDEFINED_AT_Q0

pytestmark = pytest.mark.filterwarnings("ignore::kinematica.KinematicaWarning")

#: check.hpp's and spherical_wrist.hpp's constants, as the core has them.
MERGE_SPAN = 1e-6
NEAR_ALIGNED_TOL = 1e-7


def test_the_constants_are_the_cores() -> None:
    assert _core_testing.internals.MERGE_SPAN == MERGE_SPAN
    assert _core_testing.decoupled.NEAR_ALIGNED_TOL == NEAR_ALIGNED_TOL


def test_no_check_fails_on_a_sample_of_every_family() -> None:
    counts, findings = run(arms_per_family=10, targets_per_arm=150, seed=5)
    assert set(counts) == set(MAKERS)
    for family, c in counts.items():
        assert c["targets"] == 1500
        failed = {k: c[k] for k in FAILURES if c[k]}
        assert not failed, (family, failed, [(f.what, f.detail, f.q.tolist()) for f in findings])
        # the placements are singular: many answers flagged, some continua
        assert c["near"] + c["singular"] > c["targets"] // 6, (family, dict(c))
    assert set(COUNTS) >= set(FAILURES)


def test_singular_placements_are_within_the_offsets_of_a_singular_set() -> None:
    rng = np.random.default_rng(1)
    robot = MAKERS["spherical wrist"][2](rng)  # the PUMA 560, base and tool moved
    q = singular_6r(robot, rng, 40)
    cond = conditioning(robot, q)
    assert np.all(cond < 1e-5)  # 10^-6 rad off at most, a Jacobian of order 1
    assert np.median(cond) < 1e-8


# ------------------------------------------------------------ the checks count


def _puma() -> tuple[km.Robot, np.ndarray, np.ndarray, km.ik.IKResult]:
    robot = km.load("puma560")
    q = np.array([0.3, 0.4, -0.5, 0.6, 0.7, 0.8])
    T = robot.fk(q)
    return robot, q, T, robot.ik(T, respect_limits=False)


def test_judge_counts_an_ok_answer_without_q_unless_flagged() -> None:
    robot, q, T, one = _puma()
    cond = float(conditioning(robot, q[None])[0])
    assert judge(robot, q, T, one, cond) == []
    moved = q + np.array([0.0, 0.0, 0.0, 2 * FOUND_TOL, 0.0, 0.0])
    assert [w for w, _ in judge(robot, moved, T, one, cond)] == ["missing", "missing_fixed"]
    flagged = km.ik.IKResult(**{**one.__dict__, "near_singular": True})
    assert judge(robot, moved, T, flagged, cond) == []
    near = q + np.array([0.0, 0.0, 0.0, 0.5 * FOUND_TOL, 0.0, 0.0])
    assert judge(robot, near, T, one, cond) == []


def test_judge_counts_false_statuses_and_representatives_off_q() -> None:
    robot, q, T, one = _puma()
    for status in ("unreachable", "not_found"):
        false = km.ik.IKResult(**{**one.__dict__, "status": km.ik.IKStatus(status)})
        assert [w for w, _ in judge(robot, q, T, false, 1.0)] == [status]
    aligned = np.array([0.3, 0.4, -0.5, 0.6, 0.0, 0.8])  # axes 4 and 6 on one line
    T = robot.fk(aligned)
    singular = robot.ik(T, respect_limits=False)
    assert singular.status == "singular" and singular.free_joints == (3, 5)
    moved = aligned + np.array([0.0, 0.0, 0.0, 0.5, 0.0, -0.5])  # along the free joints
    assert judge(robot, moved, T, singular, 0.0) == []
    moved[1] += 1e-3  # another target: no walk along q4 and q6 reaches it
    assert [w for w, _ in judge(robot, moved, T, singular, 0.0)] == ["singular_missing"]


def test_duplicates_counts_two_rows_one_solution_to_tolerance() -> None:
    robot = km.Robot.from_dh([km.Revolute(a=1.0), km.Revolute(a=1.0)], convention="standard")
    for d, merged in ((0.5 * MERGE_SPAN, 1), (2 * MERGE_SPAN, 0)):
        rows = np.array([[0.3, d / 2], [0.3 + d / 2, -d / 2]])  # elbows ±d/2: d apart
        T = robot.fk(rows[0])[:3, 3]  # a position target
        assert np.linalg.norm(robot.fk(rows[1])[:3, 3] - T) < 1e-15
        assert duplicates(robot, rows, T)[0] == merged


# ------------------------------------------------------------ item 2


def test_a_ur_type_arm_at_a_double_root_of_its_wrist_pair_is_solved() -> None:
    """Found by the audit: an exact UR-type arm (axes 5 and 6 apart) at a fold of the
    (q1, q5) pair, where the quartic's double root split into a complex pair; a Newton
    step from it leapt away and the target was "unreachable: the closed form has no
    real solution" (issue 34 item 2). Newton now ends at its least residual."""
    R = km.Revolute
    links = [
        R(d=0.30901104445245814, offset=-0.4102211753935121),
        R(alpha=-1.5936362695018376),
        R(a=0.49961568394199585, alpha=math.pi),
        R(d=-0.018817848474717985, a=-0.3319486119708869, alpha=math.pi,
          offset=2.5027226975341454),
        R(d=-0.03541563166328757, a=-0.05191809184297272, alpha=-0.36397662457964214,
          offset=-1.2134532944200893),
        R(d=0.0859149342879208, a=-0.12479492866624028, alpha=0.9260473225561223),
    ]  # fmt: skip
    base = np.array([
        [-0.9751544248440189, -0.14565918555236027, 0.16690491116607015, 0.3177576161701541],
        [-0.16454629816115576, -0.028179759329910903, -0.9859667423019747, -0.3788149721858568],
        [0.1483184528930595, -0.9889334167821064, 0.0035119372257922388, 0.28284158820986116],
        [0.0, 0.0, 0.0, 1.0],
    ])  # fmt: skip
    tool = np.array([
        [-0.30709813556334686, 0.05966045596063891, 0.9498059618301438, -0.01843898195015145],
        [0.564944486414857, 0.8145837772965198, 0.13149523578741282, -0.013347653019902567],
        [-0.7658514623626237, 0.5769695830456772, -0.283862004919869, -0.16057199866542016],
        [0.0, 0.0, 0.0, 1.0],
    ])  # fmt: skip
    robot = km.Robot.from_dh(links, convention="modified", base=base, tool=tool)
    q = np.array([-2.266102103021211, -1.9661142326884544, 2.4372510558065708,
                  2.177896210424205, 1.3802760175006252, -0.2790990174246648])  # fmt: skip
    assert conditioning(robot, q[None])[0] < 1e-12  # the arm is singular there
    for dq in (0.0, 1e-10, -1e-10):
        moved = q + np.array([0, 0, 0, 0, dq, 0])
        res = robot.ik(robot.fk(moved), respect_limits=False)
        assert res.status == "ok" and res.method == "analytic:three-parallel-6R", res.message
        d = np.abs(np.remainder(res.solutions - moved + math.pi, 2 * math.pi) - math.pi)
        assert d.max(axis=1).min() < 1e-6


# ------------------------------------------------------------ item 3: the tolerances


@pytest.mark.parametrize(("factor", "near"), [(0.5, True), (2.0, False)])
def test_near_aligned_tol_flags_a_spherical_wrist_within_it(factor: float, near: bool) -> None:
    """NEAR_ALIGNED_TOL: the PUMA 560 with sin q5 below it is near_singular (the docs'
    promise: "where the wrist is aligned to within 1e-7 rad"), above it not; q is then
    among the solutions to round-off over the conditioning."""
    puma = km.load("puma560")
    q = np.array([0.3, -0.6, 0.2, 0.5, factor * NEAR_ALIGNED_TOL, -0.4])
    res = puma.ik(puma.fk(q), respect_limits=False)
    assert res.status == "ok" and res.near_singular is near
    d = np.abs(np.remainder(res.solutions - q + math.pi, 2 * math.pi) - math.pi)
    assert d.max(axis=1).min() < 1e-7


@pytest.mark.parametrize(("factor", "near"), [(0.5, True), (2.0, False)])
def test_near_aligned_tol_flags_the_iiwa_wrist_within_it(factor: float, near: bool) -> None:
    iiwa = km.load("iiwa14")
    q = np.array([0.3, 0.7, -0.4, 1.2, 0.5, factor * NEAR_ALIGNED_TOL, 0.2])
    res = iiwa.ik(iiwa.fk(q), arm_angle=float(iiwa.arm_angle(q)), respect_limits=False)
    assert res.status == "ok" and res.near_singular is near


@pytest.mark.parametrize(("factor", "count"), [(0.5, 1), (2.0, 2)])
def test_merge_span_makes_branches_at_a_stretched_elbow_one(factor: float, count: int) -> None:
    """MERGE_SPAN: elbow up and down, factor · MERGE_SPAN apart at a nearly stretched 2R
    arm (both exact), are one solution flagged near within it; beyond it, two."""
    robot = km.Robot.from_dh([km.Revolute(a=1.0), km.Revolute(a=1.0)], convention="standard")
    half = 0.5 * factor * MERGE_SPAN
    up, down = np.array([0.3, half]), np.array([0.3 + half, -half])
    T = robot.fk(up)
    assert np.linalg.norm(robot.fk(down)[:3, 3] - T[:3, 3]) < 1e-15
    res = robot.ik(T[:3, 3], respect_limits=False)
    assert res.status == "ok" and res.count == count, res.solutions
    assert res.near_singular is (count == 1)
    d = np.abs(res.solutions[:, None] - np.array([up, down])[None]).max(axis=-1)
    assert np.all(d.min(axis=1) < 1e-9)  # each is one of the two


def test_merge_needs_the_midpoint_to_solve() -> None:
    """Two exact solutions within MERGE_SPAN whose midpoint misses the tolerance (links of
    10 km: elbows ±4e-7 have the stretched arm as midpoint, 4e-10 m short) stay two."""
    robot = km.Robot.from_dh([km.Revolute(a=1e4), km.Revolute(a=1e4)], convention="standard")
    T = robot.fk([0.3, 4e-7])
    res = robot.ik(T[:3, 3], respect_limits=False)
    assert res.status == "ok" and res.count == 2, res.solutions


# ------------------------------------------------------------ item 4


def test_an_srs_q0_without_arm_angle_holds_the_default_and_says_so() -> None:
    iiwa = km.load("iiwa14")
    assert math.isnan(float(iiwa.arm_angle(np.zeros(7))))  # stretched: no arm angle
    T = iiwa.fk([0.3, 0.7, -0.4, 1.2, 0.5, -0.8, 0.2])
    res = iiwa.ik(T, q0=np.zeros(7), respect_limits=False)
    assert res.status == "ok" and res.parameter == ("arm angle", 0.0)
    assert UNDEFINED_AT_Q0 in res.message
    np.testing.assert_allclose(iiwa.arm_angle(res.solutions), 0.0, atol=1e-9)
    fine = iiwa.ik(T, q0=[0.3, 0.7, -0.4, 1.2, 0.5, -0.8, 0.2], respect_limits=False)
    assert UNDEFINED_AT_Q0 not in fine.message
    assert fine.parameter is not None and fine.parameter[1] != 0.0


def test_a_batch_with_one_q0_without_arm_angle_solves_every_target() -> None:
    iiwa = km.load("iiwa14")
    qs = np.array([[0.3, 0.7, -0.4, 1.2, 0.5, -0.8, 0.2], [0.1, -0.5, 0.3, -1.0, 0.2, 0.6, 0.0]])
    q0 = qs.copy()
    q0[1] = 0.0
    res = iiwa.ik(iiwa.fk(qs), q0=q0, respect_limits=False)
    assert list(res.status) == ["ok", "ok"]
    held = np.asarray(res.parameter[1])
    assert held[0] == pytest.approx(float(iiwa.arm_angle(qs[0])))
    assert held[1] == 0.0
    assert UNDEFINED_AT_Q0 in res[1].message and UNDEFINED_AT_Q0 not in res[0].message


def test_the_cli_solves_an_srs_target_from_a_q0_without_arm_angle(
    capsys: pytest.CaptureFixture[str],
) -> None:
    iiwa = km.load("iiwa14")
    T = iiwa.fk([0.3, 0.7, -0.4, 1.2, 0.5, -0.8, 0.2])
    code, out, err = run_cli(capsys, "ik", "iiwa14", "--matrix", *map(str, T.ravel()),
                             "--q0", *["0"] * 7, "--ignore-limits", "--json")  # fmt: skip
    assert code == 0 and "--arm-angle" not in err, err
    data = json.loads(out)
    assert data["method"] == "analytic:srs" and len(data["solutions"]) == 8
    np.testing.assert_allclose(iiwa.arm_angle(np.radians(data["solutions"])), 0.0, atol=1e-9)
