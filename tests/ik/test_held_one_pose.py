"""One pose of a redundant arm at one parameter value: how its target and settings are read.

``robot.ik(T, fixed={k: v})``, ``robot.ik(T, arm_angle=psi)`` and ``robot.ik(T)`` of a
7-joint arm: a pose not rigid to round-off is projected (with a note), a view the
core does not read as it is (Fortran order, strided) is copied, a bad key or value
says what is wrong, and a sweep over many held values gives, at each, solutions
that hold the joint at the value and reach the pose by our own FK.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
from support.helpers import assert_same_result

import kinematica as km
from kinematica.errors import KinematicaError
from kinematica.ik import IKOptions

#: A solution reaches the pose when our FK puts the tool this close (m, and rotation entries).
REACHED = 1e-9


def test_a_pose_not_rigid_or_not_as_the_core_reads_it_is_read_as_the_general_path_does() -> None:
    robot = km.load("iiwa14")
    T = robot.fk(np.array([0.3, 0.5, 0.3, -1.2, 0.3, 0.8, 0.3]))
    skewed = T.copy()
    skewed[:3, :3] *= 1.0 + 1e-6  # not rigid to round-off: projected, with a note
    for kwargs in ({}, {"fixed": {0: 0.3}}, {"fixed": {6: 0.3}}, {"arm_angle": 0.3}):
        res = robot.ik(skewed, **kwargs)
        assert res.status == "ok" and "projected" in res.message
        assert_same_result(res, robot.ik(skewed, options=IKOptions(**kwargs)))
    # a view the core does not read as it is (Fortran order, strided): copied, same answer
    wide = np.zeros((8, 8))
    wide[::2, ::2] = T
    for view in (np.asfortranarray(T), wide[::2, ::2]):
        for kwargs in ({}, {"fixed": {6: 0.3}}, {"arm_angle": 0.3}):
            assert_same_result(robot.ik(view, **kwargs), robot.ik(T, options=IKOptions(**kwargs)))
        puma = km.load("puma560")
        P = puma.fk(np.full(6, 0.3))
        assert_same_result(puma.ik(np.asfortranarray(P)), puma.ik(P))


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"fixed": {True: 0.3}}, "0-based index or a name"),  # True == 1, never joint 1
        ({"fixed": {7: 0.3}}, "out of range"),
        ({"fixed": {"elbow": 0.3}}, "no joint is named"),
        ({"fixed": {6: 5.0}}, "outside its limits"),
        ({"fixed": {6: float("nan")}}, "finite"),
        ({"fixed": {6: "0.3"}}, "must be a number"),
        ({"fixed": {6: 0.3, 5: 0.1}}, "one joint"),
        ({"arm_angle": float("inf")}, "finite"),
        ({"arm_angle": True}, "must be a number"),
        ({"fixed": {6: 0.3}, "arm_angle": 0.3}, "not both"),
    ],
)
def test_bad_parameters_say_what_is_wrong_as_keywords_and_as_options(
    kwargs: dict[str, Any], match: str
) -> None:
    robot = km.load("iiwa14")
    T = robot.fk(np.array([0.3, 0.5, 0.3, -1.2, 0.3, 0.8, 0.3]))
    robot.ik(T, fixed={1: 0.5})  # joint 1 seen before: True must not find it
    with pytest.raises(KinematicaError, match=match) as keywords:
        robot.ik(T, **kwargs)
    with pytest.raises(KinematicaError, match=match) as options:
        robot.ik(T, options=IKOptions(**kwargs))
    assert str(keywords.value) == str(options.value) and keywords.value.arg == options.value.arg


@pytest.mark.parametrize("joint", [0, 6])
def test_a_sweep_over_held_values_holds_each_and_reaches_the_pose(joint: int) -> None:
    robot = km.load("iiwa14")
    q = np.array([0.3, 0.5, 0.3, -1.2, 0.3, 0.8, 0.3])
    T = robot.fk(q)
    values = np.linspace(-1.0, 1.0, 19).tolist()
    answered = 0
    for _ in range(2):  # the second pass: values seen before
        for v in values:
            res = robot.ik(T, fixed={joint: v})
            assert res.parameter == (f"q{joint + 1}", v) and type(res.parameter[1]) is float
            if res.count:
                answered += 1
                assert np.all(res.solutions[:, joint] == v)
                assert np.abs(robot.fk(res.solutions) - T).max() < REACHED
    assert answered >= len(values)  # most values hold a solution, every pass
    # the configuration that made the pose is among the solutions at its own value
    at = robot.ik(T, fixed={joint: 0.3})
    assert np.min(np.abs(at.solutions - q).max(axis=1)) < REACHED
