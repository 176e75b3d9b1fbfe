"""The pose audit (``benchmarks/audit_ik.py``) on a few poses per class, and its checks.

The audit's own functions (``tests/support/ik_pose_audit.py``) run on 30 poses of
each arm class, and each check is shown to count what it should: a target moved by
half and twice its tolerance, a configuration moved off the solutions, a reference
solution near and far from ours, a batch whose single calls answer otherwise.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from support.audit_arms import CALIBRATION, CLASSES, calibrated_ur, robot_from
from support.ik_pose_audit import (
    DISTINCT_TOL,
    FOUND_TOL,
    SCALED,
    SINGULAR_REL,
    TOL,
    audit_arm,
    audit_class,
    check_answer,
    check_complete,
    check_far,
    check_scaled,
    eaik_model,
    far_target,
    fk_error,
    numeric_search,
    scaled_target,
)
from support.ik_search import distinct, joint_distance

import kinematica as km
from kinematica.ik.structure import arm_size

pytestmark = pytest.mark.filterwarnings("ignore::kinematica.KinematicaWarning")

#: The classes the general 6R solves.
GENERAL = ("generic", "equal links", "offsets 1e-10", "parallel 1e-9", "calibrated UR")
#: The checks each class is held to: every one.
CHECKS = dict.fromkeys((*GENERAL, "spherical wrist", "spherical shoulder", "three parallel"),
                       ("a", "b", "c", "d", "e"))  # fmt: skip
#: The solver each class is made for.
SOLVER = dict.fromkeys(GENERAL, "analytic:general-6R") | {
    "spherical wrist": "analytic:spherical-wrist",
    "spherical shoulder": "analytic:spherical-shoulder",
    "three parallel": "analytic:three-parallel",
}


@pytest.mark.parametrize("name", list(CLASSES))
def test_no_check_fails_on_30_poses_of_each_class(name: str) -> None:
    report = audit_class(name, 30, seed=3, per_arm=15)
    c = report.counts
    assert c["poses"] == 30 and report.arms == 2 and c["scaled"] == 4
    failed = {k: c[k] for k in CHECKS[name]}
    assert not any(failed.values()), (failed, [(f.check, f.detail) for f in report.findings])
    assert c["singular"] <= 3  # random q: a singular arm is rare


def test_the_general_6r_finds_every_solution_of_a_calibrated_ur() -> None:
    # found by the audit (calibrated UR, seed 1): "ok" with 5 solutions, an odd count
    rows = [
        (0.08835115634406379, 0.0007288513866183192, 1.571780715151819),
        (-0.0006646202868276405, -0.42450434118161023, -6.994052337989715e-05),
        (-0.0005807520374433216, -0.39209213078836286, -0.00021394309582998812),
        (0.10905918370733657, -0.0006752456789382503, 1.5712795597151417),
        (0.09558752564631177, 0.0009296292198194374, -1.5699880398569237),
        (0.08255102483032208, 0.0009190695007869787, -0.00043774502714685954),
    ]
    base = [
        [-0.031181359835956934, 0.7515839350784065, -0.6589000768939386, 0.08564330363261241],
        [-0.40218171201771924, -0.6129337409975573, -0.6801191804862113, 0.030865625675435715],
        [-0.9150287390663077, 0.24379052007573432, 0.321385421268492, -0.43018326264466256],
        [0.0, 0.0, 0.0, 1.0],
    ]
    tool = [
        [-0.4353303816474212, -0.21714921006281138, -0.8736896928451244, 0.1913796045590232],
        [-0.5618615350363143, -0.6927395533851706, 0.4521322003820909, 0.011222091624029595],
        [-0.70341955777569, 0.6877195153147915, 0.17956278565961603, -0.005945028491750742],
        [0.0, 0.0, 0.0, 1.0],
    ]
    links = [km.Revolute(d=d, a=a, alpha=al) for d, a, al in rows]
    robot = km.Robot.from_dh(links, base=np.array(base), tool=np.array(tool), convention="standard")
    q = np.array([1.198739643342586, -2.166245331097235, 1.6436931343575854,
                  2.438595817867922, 0.030105794920242346, -0.5220349259662291])  # fmt: skip
    other = np.array([0.9718718962933703, -1.0343418537366595, -1.1958359921840909,
                      2.118750022319137, -0.23977236943367242, 1.5020815971864394])  # fmt: skip
    T = robot.fk(q)
    assert fk_error(robot, other[None], T)[0] <= TOL  # another solution of the pose
    res = robot.ik(T, respect_limits=False)
    assert joint_distance(robot, res.solutions, other).min() <= DISTINCT_TOL


@pytest.mark.parametrize("name", list(CLASSES))
def test_each_class_draws_arms_of_its_solver(name: str) -> None:
    rng = np.random.default_rng(7)
    for _ in range(3):
        arm = CLASSES[name](rng)
        robot = robot_from(arm, name)
        q = rng.uniform(-1.0, 1.0, 6)
        res = robot.ik(robot.fk(q))
        assert res.method.startswith(SOLVER[name]), (res.method, arm.note)
        assert (arm.note == "") == (name == "generic")


def test_a_calibrated_ur_is_off_the_ur5_by_up_to_the_calibration() -> None:
    ur5 = km.load("ur5").links
    seen = set()
    for seed in range(8):
        arm = calibrated_ur(np.random.default_rng(seed))
        seen.add(arm.convention)
        d = [j.d - u.d for j, u in zip(arm.links, ur5, strict=True)]
        if arm.convention == "standard":
            pairs = zip(arm.links, ur5, strict=True)
        else:  # Craig's table of the same arm: row i + 1 holds row i's a and alpha
            assert arm.links[0].a == arm.links[0].alpha == 0.0
            pairs = zip(arm.links[1:], ur5[:-1], strict=True)
        off = np.array(d + [v for j, u in pairs for v in (j.a - u.a, j.alpha - u.alpha)])
        assert np.all(np.abs(off) <= CALIBRATION) and np.all(off != 0.0)
        assert np.abs(off).max() > CALIBRATION / 2
    assert seen == {"standard", "modified"}


def _arm() -> tuple[km.Robot, np.ndarray, np.ndarray, km.ik.IKResult]:
    robot = km.load("puma560")
    q = np.array([0.3, 0.4, -0.5, 0.6, 0.7, 0.8])
    T = robot.fk(q)
    return robot, q, T, robot.ik(T, respect_limits=False)


def test_check_b_counts_a_solution_off_by_more_than_tol() -> None:
    robot, q, T, one = _arm()
    assert one.status == "ok" and one.count == 8
    cond = 0.1
    assert check_answer(robot, T, q, one, cond) == []
    for shift, failing in ((0.5 * TOL, False), (2 * TOL, True)):
        moved = T.copy()
        moved[0, 3] += shift  # every solution is off by `shift` from this target
        checks = [c for c, _ in check_answer(robot, moved, q, one, cond)]
        assert checks == (["b", "e"] if failing else []), shift


def test_check_a_counts_q_off_the_solutions_by_more_than_found_tol() -> None:
    robot, q, T, one = _arm()
    for shift, checks in (
        (0.5 * FOUND_TOL, []),
        (2 * FOUND_TOL, ["a"]),
        (0.5 * DISTINCT_TOL, ["a"]),
        (2 * DISTINCT_TOL, ["a", "a_far"]),
    ):
        moved = q + np.array([shift, 0, 0, 0, 0, 0])
        assert [c for c, _ in check_answer(robot, T, moved, one, 0.1)] == checks, shift


def test_check_a_skips_a_q_where_the_arm_is_singular() -> None:
    robot, q, T, one = _arm()
    far = q + 1.0
    assert [c for c, _ in check_answer(robot, T, far, one, 2 * SINGULAR_REL)] == ["a", "a_far"]
    assert check_answer(robot, T, far, one, 0.5 * SINGULAR_REL) == []


def test_check_e_counts_a_pose_made_by_fk_called_unreachable() -> None:
    robot, q, T, one = _arm()
    false = dataclasses.replace(one, status=km.ik.IKStatus("unreachable"))
    assert [c for c, _ in check_answer(robot, T, q, false, 0.1)] == ["e"]


def test_check_c_matches_reference_solutions_within_distinct_tol() -> None:
    robot, _, _, one = _arm()
    sols = one.solutions
    size = arm_size(robot.chain)
    assert check_complete(robot, sols, sols, size) == ([], 0)
    near = sols + 0.5 * DISTINCT_TOL
    assert check_complete(robot, sols, near, size) == ([], 0)
    far = sols + 2 * DISTINCT_TOL
    missed, extra = check_complete(robot, sols, far, size)
    assert len(missed) == 8 and extra == 8
    assert all(math.isclose(m[1], 2 * DISTINCT_TOL, rel_tol=1e-6) for m in missed)
    missed, extra = check_complete(robot, sols[1:], sols, size)  # one of ours dropped
    assert len(missed) == 1 and np.array_equal(missed[0][0], sols[0]) and extra == 0
    assert check_complete(robot, sols, sols[:0], size) == ([], 8)


def test_check_e_of_far_targets_wants_unreachable_or_not_found_with_a_reason() -> None:
    assert check_far("unreachable", "0.3 m beyond the reach") is None
    assert check_far("not_found", "not proven unreachable") is None
    assert check_far("unreachable", "") is not None
    assert check_far("ok", "8 solutions") is not None


def test_check_e_of_scaled_targets_wants_no_unreachable_the_search_reaches() -> None:
    robot, _, T, _ = _arm()
    rng = np.random.default_rng(0)
    origin = robot.chain.start[:3, 3]
    S = scaled_target(robot, T, rng)
    ratio = np.linalg.norm(S[:3, 3] - origin) / np.linalg.norm(T[:3, 3] - origin)
    assert SCALED[0] <= ratio <= SCALED[1]
    size = arm_size(robot.chain)
    one = robot.ik(T, respect_limits=False)  # reachable: the search finds its solutions
    ref = numeric_search(robot, T, rng, starts=50)
    assert len(ref) and check_scaled(robot, T, one, ref, size) == []
    for status in ("unreachable", "not_found"):
        false = dataclasses.replace(one, status=km.ik.IKStatus(status))
        assert [c for c, _ in check_scaled(robot, T, false, ref, size)] == ["e"]
        assert check_scaled(robot, T, false, ref[:0], size) == []  # nothing found: honest
    unreachable = robot.ik(far_target(robot, T, rng))
    assert unreachable.status == "unreachable" and unreachable.message
    assert check_scaled(robot, T, unreachable, ref[:0], size) == []


def test_far_targets_are_beyond_the_reach_and_unreachable() -> None:
    robot, _, T, _ = _arm()
    rng = np.random.default_rng(0)
    far = np.array([far_target(robot, T, rng) for _ in range(5)])
    origin = robot.chain.start[:3, 3]
    assert np.all(np.linalg.norm(far[:, :3, 3] - origin, axis=-1) > arm_size(robot.chain))
    np.testing.assert_array_equal(far[:, :3, :3], np.broadcast_to(T[:3, :3], (5, 3, 3)))
    assert np.all(robot.ik(far).status == "unreachable")


def test_the_numeric_search_finds_the_eight_solutions_of_a_puma() -> None:
    robot, _, T, one = _arm()
    found = numeric_search(robot, T, np.random.default_rng(0), starts=200)
    assert len(found) == 8
    assert joint_distance(robot, found[:, None], one.solutions[None]).min(axis=1).max() < 1e-8


def test_distinct_keeps_rows_more_than_tol_apart_modulo_a_turn() -> None:
    robot = km.load("puma560")
    tol = 1e-6
    q = np.zeros((4, 6))
    q[1, 0] = 0.5 * tol  # one with row 0
    q[2, 0] = 2 * tol  # another
    q[3, 0] = 2 * math.pi + 0.5 * tol  # row 0 a turn on
    kept = distinct(robot, q, tol)
    np.testing.assert_array_equal(kept, q[[0, 2]])


def test_check_d_counts_a_single_call_unlike_the_batch(monkeypatch: pytest.MonkeyPatch) -> None:
    robot, q, _, _ = _arm()
    arm = km.ik.registry.ArmSample(tuple(robot.links))
    ik = km.Robot.ik

    def other(self: km.Robot, target: np.ndarray, **kwargs: object) -> object:
        res = ik(self, target, **kwargs)
        if np.shape(target) == (4, 4) and kwargs.get("method") is None:
            return dataclasses.replace(res, notes=(*res.notes, "answered otherwise"))
        return res

    monkeypatch.setattr(km.Robot, "ik", other)
    qs = np.array([q, q + 0.1])
    counts, findings = audit_arm(robot, arm, qs, np.random.default_rng(0), starts=20)
    assert counts["d"] == 2 and {f.check for f in findings} == {"d"}


def test_eaik_answers_are_among_ours_where_it_takes_the_arm() -> None:
    pytest.importorskip("eaik")
    robot, _, T, one = _arm()
    eaik = eaik_model(robot)  # checked against our FK as it is made
    assert eaik is not None
    theirs = eaik.solutions(robot, T)
    assert len(theirs) == 8
    assert joint_distance(robot, theirs[:, None], one.solutions[None]).min(axis=1).max() < 1e-8
