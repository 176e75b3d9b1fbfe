"""The numeric search says what it is where ``auto`` falls back to it, and which solver an arm gets.

Where no closed form applies, ``robot.ik(T)`` answers by the numeric search: a
local search giving one solution where more may exist. Its answers say so in a
note with the reason (the arm's structure, or a mask), on each of ``robot.ik``'s
paths (one pose straight to the core, a held joint of a redundant arm, the general
path, a batch), and :func:`~kinematica.ik.choice.pose_choice` names the solver the
results name (``kinematica show`` prints it).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from support.helpers import assert_same_result

import kinematica as km
from kinematica.ik import IKOptions
from kinematica.ik.choice import pose_choice
from kinematica.ik.fallback import FALLBACK_NOTE, PARTIAL_NOTE, searched_note
from kinematica.ik.local_search import LOCAL_SEARCH, numeric_reason, search_note

PI = math.pi


def slide_6() -> km.Robot:
    """A 6-joint arm whose slide (joint 2) is outside every closed-form family."""
    return km.Robot.from_dh(
        [
            km.Revolute(d=0.4, alpha=PI / 2),
            km.Prismatic(theta=0.3, a=0.1, alpha=-PI / 3, qlim=(0.0, 1.0)),
            km.Revolute(d=0.05, a=0.3, alpha=PI / 2),
            km.Revolute(d=0.3, a=0.02, alpha=-PI / 2),
            km.Revolute(a=0.01, alpha=PI / 2),
            km.Revolute(d=0.1),
        ],
        name="RPRRRR",
        convention="standard",
    )


def slides_7() -> km.Robot:
    """A 7-joint arm (two slides) no joint of which, held, leaves an arm with a closed form."""
    return km.Robot.from_dh(
        [
            km.Revolute(d=0.4, alpha=PI / 2),
            km.Prismatic(theta=0.3, a=0.1, alpha=-PI / 3, qlim=(0.0, 1.0)),
            km.Revolute(d=0.05, a=0.3, alpha=PI / 2),
            km.Prismatic(theta=0.2, a=0.02, alpha=-PI / 2, qlim=(0.0, 1.0)),
            km.Revolute(d=0.1, a=0.01, alpha=PI / 2),
            km.Revolute(d=0.1, a=0.05, alpha=0.7),
            km.Revolute(d=0.1),
        ],
        name="RPRPRRR",
        convention="standard",
    )


def eight_r() -> km.Robot:
    """An 8R arm: two joints more than a pose fixes."""
    return km.Robot.from_dh(
        [km.Revolute(d=0.3, a=0.1, alpha=PI / 2) for _ in range(8)], convention="standard"
    )


# the arm, a mask or None, and what the note's reason says
NUMERIC_ARMS = {
    "6-joint slide": (slide_6, None, "revolute joints only (joint 2 slides)"),
    "7 joints, none held": (
        slides_7,
        None,
        "7 joints and no joint held (auto holds one only where",
    ),
    "8R": (eight_r, None, "8 joints, 2 more than a pose fixes"),
    "PUMA, a mask": (lambda: km.load("puma560"), [1, 1, 1, 0, 0, 1], "a mask"),
}


def _q(robot: km.Robot) -> np.ndarray:
    lo, hi = np.maximum(robot.qlim[:, 0], -1.0), np.minimum(robot.qlim[:, 1], 1.0)
    return lo + (hi - lo) * np.linspace(0.3, 0.7, robot.dof)


@pytest.mark.parametrize("name", NUMERIC_ARMS)
def test_auto_s_search_says_it_is_one_local_solution_and_why(name: str) -> None:
    make, mask, why = NUMERIC_ARMS[name]
    robot = make()
    T = robot.fk(_q(robot))
    one = robot.ik(T, mask=mask)
    general = robot.ik(T, options=IKOptions(mask=mask))
    many = robot.ik(np.stack([T, T, T]), mask=mask)
    for res in (one, general, many[0], many[2]):
        assert res.status == "ok" and res.count == 1  # a solution: "ok" claims no more
        assert res.method == "numeric:lm" and not res.complete
        (note,) = res.notes
        assert note.startswith("no closed form applies: ") and why in note
        assert note.endswith(f"the numeric search answered, {LOCAL_SEARCH}")
        assert note in res.message
    assert_same_result(one, general)
    assert many.method == "numeric:lm" and all(many[i].notes == one.notes for i in range(3))


def test_the_note_is_made_from_the_reason_show_prints() -> None:
    robot = slide_6()
    reason = numeric_reason(robot.chain, "pose", False)
    assert robot.ik(robot.fk(_q(robot))).notes == (search_note(reason),)
    assert pose_choice(robot.chain).reason == reason
    assert search_note(reason) == (
        "no closed form applies: a slide outside the closed-form families (6 joints, RPRRRR), "
        "and the general 6R elimination takes revolute joints only (joint 2 slides); the "
        "numeric search answered, a local search that finds one solution at most; "
        "more may exist"
    )


def test_one_pose_straight_to_the_core_carries_the_note_as_the_general_path_does() -> None:
    # one rigid pose with every default, as keywords or as options: one answer, note
    # included
    for make in (slide_6, slides_7, eight_r):
        robot = make()
        T = robot.fk(_q(robot))
        assert_same_result(robot.ik(T), robot.ik(T, options=IKOptions()))
        p = np.ascontiguousarray(T[:3, 3])
        assert_same_result(robot.ik(p), robot.ik(p, options=IKOptions()))


def test_a_position_target_no_closed_form_places_says_so() -> None:
    robot = slide_6()
    p = np.ascontiguousarray(robot.fk(_q(robot))[:3, 3])
    res = robot.ik(p)
    assert res.status == "ok" and res.method == "numeric:lm"
    assert res.notes == (search_note(numeric_reason(robot.chain, "position", False)),)
    assert "position targets of this structure (6 joints (RPRRRR))" in res.notes[0]


def test_asked_for_the_search_says_nothing_more() -> None:
    # method="numeric" was asked for: its answers are one local solution by definition
    # (IKStatus.OK, IKResult.complete), not said again target by target
    for make, mask, _ in NUMERIC_ARMS.values():
        robot = make()
        T = robot.fk(_q(robot))
        one = robot.ik(T, method="numeric", mask=mask)
        many = robot.ik(np.stack([T, T]), method="numeric", mask=mask)
        assert one.status == "ok" and one.notes == () and not one.complete
        assert dict(many.notes) == {}


def test_a_held_joint_leaving_an_arm_without_a_closed_form_says_why() -> None:
    robot = slides_7()
    T = robot.fk(_q(robot))
    for k in (0, 3, 6):  # first (target moved), middle, last joint held
        value = float(_q(robot)[k])
        one = robot.ik(T, fixed={k: value})
        assert_same_result(one, robot.ik(T, options=IKOptions(fixed={k: value})))
        assert one.status == "ok" and one.method == "numeric:lm"
        assert one.parameter == (f"q{k + 1}", value)
        (note,) = one.notes
        assert "a slide outside the closed-form families (6 joints," in note
        assert note.endswith(LOCAL_SEARCH)
        assert robot.ik(np.stack([T, T]), fixed={k: value})[1].notes == one.notes


def test_a_closed_form_s_answers_have_no_such_note() -> None:
    for name in ("puma560", "ur5", "panda"):
        robot = km.load(name)
        res = robot.ik(robot.fk(_q(robot)))
        assert res.method.startswith("analytic:")
        assert not any(LOCAL_SEARCH in n for n in res.notes)


def test_a_search_after_a_closed_form_found_nothing_says_it_is_local_too() -> None:
    # a partial closed form (joints 4 onwards at 0) that misses the target: its note
    # says why, and that the answer is one local solution
    robot = eight_r()
    p = np.ascontiguousarray(robot.fk(np.full(8, 0.3))[:3, 3])
    for res in (robot.ik(p), robot.ik(p[None])[0]):
        assert res.method == "numeric:lm" and res.notes == (PARTIAL_NOTE,)
    for note in (FALLBACK_NOTE, PARTIAL_NOTE):
        assert note.endswith(f"the numeric search answered, {LOCAL_SEARCH}")
    said = "no candidate: the numeric search answered"  # a closed form's search_note
    assert searched_note(said) == f"{said}, {LOCAL_SEARCH}"


# ------------------------------------------------------------------ pose_choice
@pytest.mark.parametrize("name", km.builtin_names())
def test_the_choice_names_the_method_and_parameter_the_results_name(name: str) -> None:
    robot = km.load(name)
    choice = pose_choice(robot.chain, robot.joint_names)
    res = robot.ik(robot.fk(_q(robot)), respect_limits=False)
    assert res.success
    assert choice.method == res.method and choice.reason is None
    assert choice.complete == res.complete
    assert choice.parameter == (None if res.parameter is None else res.parameter[0])


def test_the_choice_of_arms_without_a_closed_form() -> None:
    for make, mask, why in NUMERIC_ARMS.values():
        if mask is not None:
            continue
        robot = make()
        choice = pose_choice(robot.chain, robot.joint_names)
        assert choice.method == "numeric:lm" and not choice.complete and choice.parameter is None
        assert choice.reason is not None and why in choice.reason
        assert robot.ik(robot.fk(_q(robot))).notes == (search_note(choice.reason),)


def test_the_choice_of_a_general_6r_and_a_near_degenerate_arm() -> None:
    rows = [(0.2, 0.25, 0.8), (-0.2, -0.35, -1.2), (-0.1, -0.35, 2.1), (0.4, 0.1, -0.7)]
    rows += [(-0.05, 0.4, 1.4), (0.3, -0.1, -2.6)]
    arm = km.Robot.from_dh(
        [km.Revolute(d=d, a=a, alpha=al) for d, a, al in rows], convention="standard"
    )
    choice = pose_choice(arm.chain)
    assert (choice.method, choice.complete) == ("analytic:general-6R", True)
    links = list(km.load("ur5").links)
    links[1] = dataclasses.replace(links[1], alpha=links[1].alpha + 5e-10)  # off by 5e-10
    near = km.Robot.from_dh(links, convention="standard")
    choice = pose_choice(near.chain)
    assert (choice.method, choice.complete) == ("analytic:three-parallel-6R", False)
    assert not near.ik(near.fk(_q(near))).complete
