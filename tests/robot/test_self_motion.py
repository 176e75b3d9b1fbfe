"""robot.self_motion: the families of a redundant arm at one pose, over its parameter.

Every sample's configuration is checked by the arm's forward kinematics; families
must keep one branch and move by at most ``max_jump`` between adjacent samples;
their intervals must agree with the joint limits sample by sample.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np
import pytest
from support.helpers import assert_transform_close

import kinematica as km
from kinematica.core import Chain
from kinematica.errors import KinematicaError
from kinematica.ik import IKBatchResult, IKOptions, IKResult
from kinematica.ik.parameter import JointParameter
from kinematica.robot.self_motion import (
    MAX_JUMP,
    SAME_TOL,
    SelfMotion,
    families,
    joint_jump,
)

TOL = 1e-10
Q_IIWA = np.array([0.3, 0.5, -0.2, -1.2, 0.4, 0.9, 0.2])
Q_PANDA = np.array([0.3, 0.5, -0.2, -1.8, 0.4, 1.9, 0.2])


def check_motion(robot: km.Robot, T: np.ndarray, sm: SelfMotion, k: int) -> None:
    """FK of every sample, the parameter's own joint, continuity, intervals vs limits."""
    lo, hi = robot.chain.own_limits[:, 0], robot.chain.own_limits[:, 1]
    assert np.all(np.diff(sm.values) > 0)
    for fam in sm.families:
        rows = np.flatnonzero(fam.present)
        assert rows.size
        Q = fam.q[rows]
        assert_transform_close(robot.fk(Q), np.broadcast_to(T, (rows.size, 4, 4)), atol=TOL)
        np.testing.assert_allclose(Q[:, k], sm.values[rows], atol=1e-12)
        # adjacent samples of a family: no gap, no jump beyond max_jump
        assert np.all(np.diff(rows) == 1)
        if rows.size > 1:
            jumps = joint_jump(Q[:-1], Q[1:], robot.chain.prismatic)
            assert float(jumps.max()) <= sm.max_jump
        inside = fam.present & np.all((fam.q >= lo) & (fam.q <= hi), axis=1)
        np.testing.assert_array_equal(fam.within, inside)
        for a, b in fam.feasible:
            span = (sm.values >= a) & (sm.values <= b)
            assert np.all(fam.within[span])
        covered = np.zeros(sm.values.size, dtype=bool)
        for a, b in fam.feasible:
            covered |= (sm.values >= a) & (sm.values <= b)
        np.testing.assert_array_equal(covered, fam.within)


def test_iiwa_over_its_first_joint_every_family_whole_and_the_pose_met() -> None:
    robot = km.load("iiwa14")
    T = robot.fk(Q_IIWA)
    sm = robot.self_motion(T, "q1", samples=73)
    assert sm.parameter == "q1" and sm.unit == "rad"
    assert sm.method.startswith("analytic:")  # the spherical wrist of joints 2..7
    np.testing.assert_allclose(sm.values, np.linspace(*robot.qlim[0], 73))
    check_motion(robot, T, sm, 0)
    # 8 branches, each a family in every stretch of q1 that reaches the pose
    assert len(sm.families) % 8 == 0 and len(sm.families) >= 8
    # the configuration that made the pose lies on a family near q1 = 0.3
    near = int(np.argmin(np.abs(sm.values - 0.3)))
    assert any(fam.present[near] for fam in sm.families)
    html = sm._repr_html_()
    assert "self-motion over q1" in html and "within limits" in html


def test_panda_over_its_last_joint_by_name_and_index_the_same() -> None:
    robot = km.load("panda")
    T = robot.fk(Q_PANDA)
    values = np.linspace(0.0, 0.4, 5)
    a = robot.self_motion(T, 6, values=values)
    b = robot.self_motion(T, "q7", values=values)
    check_motion(robot, T, a, 6)
    assert [f.branch for f in a.families] == [f.branch for f in b.families]
    for fa, fb in zip(a.families, b.families, strict=True):
        np.testing.assert_array_equal(fa.q, fb.q)


def test_a_middle_joint_sweep_solves_each_value_on_its_own_arm() -> None:
    robot = km.load("iiwa14")
    T = robot.fk(Q_IIWA)
    values = Q_IIWA[2] + np.linspace(-0.2, 0.15, 5)
    sm = robot.self_motion(T, 2, values=values)
    assert sm.method.startswith("analytic:")  # joints 1, 2 and 4..7: a spherical wrist
    check_motion(robot, T, sm, 2)
    assert len(sm.families) == 8  # every branch along the whole sweep
    # at q3 = 0 axes 2 and 4 of the locked arm lie in one plane: another closed form,
    # whose branches have other names, so other families
    names = {f.branch for f in robot.self_motion(T, 2, values=[-0.1, 0.0]).families}
    assert len(names) == 16


@pytest.mark.parametrize(("step", "whole"), [(0.49, True), (0.51, False)])
def test_a_family_splits_where_it_jumps_beyond_max_jump(step: float, whole: bool) -> None:
    # one branch whose joint 2 moves by `step` between the 2nd and 3rd samples
    q = np.zeros((4, 1, 3))
    q[2:, 0, 1] = step
    labels = np.full((4, 1), "up")
    fams = families(np.arange(4.0), q, labels, np.zeros(3, bool), np.full((3, 2), [-1.0, 1.0]))
    assert len(fams) == (1 if whole else 2)
    assert MAX_JUMP == 0.5


def test_families_keep_their_branch_and_take_the_nearest_solution() -> None:
    # two solutions of one branch cross paths: each family keeps to its own
    values = np.arange(3.0)
    q = np.full((3, 3, 2), np.nan)
    q[:, 0] = [[0.0, 0.0], [0.1, 0.0], [0.2, 0.0]]
    q[:, 1] = [[1.0, 0.0], [0.9, 0.0], [0.8, 0.0]]
    q[1, 2] = [0.1, 0.05]  # another branch at the same place: not joined to "a"
    labels = np.array([["a", "a", ""], ["a", "a", "b"], ["a", "a", ""]])
    limits = np.array([[-np.inf, 0.95], [-np.inf, np.inf]])
    fams = families(values, q, labels, np.zeros(2, bool), limits)
    assert [f.branch for f in fams] == ["a", "a", "b"]
    np.testing.assert_array_equal(fams[0].q[:, 0], [0.0, 0.1, 0.2])
    np.testing.assert_array_equal(fams[1].q[:, 0], [1.0, 0.9, 0.8])
    assert fams[1].feasible == ((1.0, 2.0),)  # beyond 0.95 at the first sample
    assert fams[2].feasible == ((1.0, 1.0),)


def test_turns_are_compared_across_the_wrap() -> None:
    near_pi = np.array([[math.pi - 0.05, 0.0]])
    across = np.array([[-math.pi + 0.05, 0.0]])
    assert joint_jump(near_pi, across, np.zeros(2, bool))[0] == pytest.approx(0.1)
    assert joint_jump(near_pi, across, np.array([True, False]))[0] == pytest.approx(
        2 * math.pi - 0.1
    )


@pytest.mark.parametrize(
    ("kwargs", "arg"),
    [
        ({"parameter": 7}, "parameter"),
        ({"parameter": "elbow"}, "parameter"),
        ({"parameter": 6, "samples": 1}, "samples"),
        ({"parameter": 6, "samples": 2.5}, "samples"),
        ({"parameter": 6, "values": [0.2, 0.1]}, "values"),
        ({"parameter": 6, "values": [0.1]}, "values"),
        ({"parameter": 6, "max_jump": 0.0}, "max_jump"),
        ({"parameter": 6, "max_jump": math.inf}, "max_jump"),
    ],
)
def test_bad_arguments_name_themselves(kwargs: dict[str, object], arg: str) -> None:
    robot = km.load("panda")
    with pytest.raises(KinematicaError) as info:
        robot.self_motion(robot.fk(Q_PANDA), **kwargs)  # type: ignore[arg-type]
    assert info.value.arg == arg


def test_a_position_target_is_refused() -> None:
    robot = km.load("panda")
    with pytest.raises(KinematicaError, match="one pose") as info:
        robot.self_motion(robot.fk(Q_PANDA)[:3, 3], 6)
    assert info.value.arg == "target"


def test_the_search_is_carried_from_sample_to_sample() -> None:
    # one answer a call: seeded with its neighbours' configurations, a family
    # holds at every sample
    robot = km.load("panda")
    T = robot.fk(Q_PANDA)
    values = np.linspace(0.0, 0.4, 5)
    sm = robot.self_motion(T, 6, values=values, method="numeric")
    assert sm.method == "numeric:lm"
    check_motion(robot, T, sm, 6)
    assert max(int(f.present.sum()) for f in sm.families) == values.size


@dataclasses.dataclass(frozen=True)
class Nudged:
    """A parameter (the Panda's q7, searched) whose seeded answers come back moved by ``by``."""

    by: float
    joint: JointParameter = dataclasses.field(default_factory=lambda: JointParameter(6, "q7"))
    name: str = "q7"
    unit: str = "rad"

    def span(self, chain: Chain) -> tuple[float, float]:
        return self.joint.span(chain)

    def default(self, chain: Chain) -> float:
        return self.joint.default(chain)

    def value_of(self, chain: Chain, q: np.ndarray) -> np.ndarray:
        return self.joint.value_of(chain, q)

    def describe(self, value: float) -> str:
        return self.joint.describe(value)

    def solve(
        self, chain: Chain, target: Any, values: Any, options: IKOptions
    ) -> IKResult | IKBatchResult:
        res = self.joint.solve(
            chain, target, values, dataclasses.replace(options, method="numeric")
        )
        if isinstance(res, IKResult):  # a seeded call: its answer nudged in joint 1
            return dataclasses.replace(
                res, solutions=res.solutions + np.array([self.by, 0, 0, 0, 0, 0, 0])
            )
        return res


@pytest.mark.parametrize(("by", "same"), [(5e-7, True), (2e-6, False)])
def test_the_search_counts_answers_within_same_tol_once(by: float, same: bool) -> None:
    # any object with the Parameter protocol's members is a parameter
    robot = km.load("panda")
    T = robot.fk(Q_PANDA)
    values = np.linspace(0.0, 0.4, 5)
    plain = robot.self_motion(T, Nudged(0.0), values=values)
    nudged = robot.self_motion(T, Nudged(by), values=values)
    assert SAME_TOL == 1e-6
    assert nudged.parameter == "q7"
    assert (len(nudged.families) == len(plain.families)) == same


def test_the_carried_search_finds_configurations_of_the_closed_forms_families() -> None:
    # two methods on the Panda over q7: every configuration the seeded search finds
    # is one of the closed form's (spherical shoulder) at the same sample
    robot = km.load("panda")
    T = robot.fk(Q_PANDA)
    values = np.linspace(0.0, 0.4, 5)
    closed = robot.self_motion(T, 6, values=values)
    searched = robot.self_motion(T, 6, values=values, method="numeric")
    assert closed.method.startswith("analytic:") and searched.method == "numeric:lm"
    for fam in searched.families:
        for i in np.flatnonzero(fam.present):
            mine = np.array([f.q[i] for f in closed.families if f.present[i]])
            gaps = joint_jump(mine, fam.q[i], robot.chain.prismatic)
            assert float(gaps.min()) < 1e-8


def test_the_arm_angle_of_an_srs_arm_is_swept_whole() -> None:
    # every sample by FK and by its own arm angle (an independent reading, from the
    # shoulder, elbow and wrist points), 8 branches each continuous over the turn
    robot = km.load("iiwa14")
    T = robot.fk(Q_IIWA)
    sm = robot.self_motion(T, "arm_angle", samples=37)
    assert sm.parameter == "arm angle" and sm.unit == "rad" and sm.method == "analytic:srs"
    np.testing.assert_allclose(sm.values[[0, -1]], [-math.pi, math.pi])
    assert len({fam.branch for fam in sm.families}) == 8
    for fam in sm.families:
        at = fam.present
        assert_transform_close(
            robot.fk(fam.q[at]), np.broadcast_to(T, (int(at.sum()), 4, 4)), atol=TOL
        )
        turn = np.angle(np.exp(1j * (robot.arm_angle(fam.q[at]) - sm.values[at])))
        assert np.abs(turn).max() < 1e-9
        rows = fam.q[at]
        assert joint_jump(rows[:-1], rows[1:], robot.is_prismatic).max() <= sm.max_jump
    # the configuration that made the pose lies on a family, at its own arm angle
    own = float(robot.arm_angle(Q_IIWA))
    again = robot.self_motion(T, "arm-angle", values=[own - 0.1, own, own + 0.1])
    found = [fam.q[1] for fam in again.families if fam.present[1]]
    assert min(float(joint_jump(q, Q_IIWA, robot.is_prismatic)) for q in found) < 1e-9


def test_the_arm_angle_of_an_arm_that_has_none_is_refused() -> None:
    panda = km.load("panda")
    with pytest.raises(KinematicaError, match="SRS 7R arms") as err:
        panda.self_motion(panda.fk(Q_PANDA), "arm_angle")
    assert err.value.arg == "parameter"
