"""Identifiability (calibration/identify.py): ranks, the parameters left out and why."""

from __future__ import annotations

import numpy as np
import pytest

import kinematica as km
from kinematica import calibration
from kinematica.calibration.identify import (
    CORRELATION_LIMIT,
    RANK_RTOL,
    REASON_SHARE,
    correlated_pairs,
    identify,
)
from kinematica.calibration.words import correlation_text, finding_text


def _everett(robot, extra):
    r = robot.joint_types.count("R")
    p = robot.joint_types.count("P")
    return 4 * r + 2 * p + extra


@pytest.mark.parametrize("name", km.builtin_names())
def test_rank_is_everett_driels_mooring_count(name):
    robot = km.load(name)
    pose = calibration.identifiable(robot, "pose")
    assert pose.rank == _everett(robot, 6) == len(pose.chosen)
    # a point off the last axis (on it, the last joint cannot move it: a smaller count)
    offset = robot.with_tool(robot.tool @ km.transl(0.05, 0.03, 0.1))
    position = calibration.identifiable(offset, "position")
    assert position.rank == _everett(robot, 3) == len(position.chosen)


def test_a_point_on_the_last_axis_cannot_see_the_last_joint():
    ur5 = km.load("ur5")  # its tool frame's origin lies on axis 6
    ident = calibration.identifiable(ur5, "position")
    assert ident.rank < _everett(ur5, 3)
    on_axis = {f.name for f in ident.left_out if not f.partners}
    assert {"theta6", "alpha6"} <= on_axis | {"tool_rx", "tool_ry", "tool_rz"}


def test_puma_parameters_left_out_and_why():
    ident = calibration.identifiable(km.load("puma560"), "pose")
    why = {f.name: f.partners for f in ident.left_out}
    assert why["d1"] == ("base_z",)
    assert why["theta1"] == ("base_rz",)
    assert why["theta6"] == ("tool_rz",)
    assert why["d6"] == ("tool_z",)
    assert all(f.structural for f in ident.left_out)
    f = next(f for f in ident.left_out if f.name == "d1")
    assert (
        finding_text(f, "en")
        == "d1 and base z move the tool alike: the data cannot tell them apart."
    )
    assert finding_text(f, "es").startswith("d1 mueve la herramienta igual que base z")


def test_parallel_axes_keep_only_the_sum_of_their_d():
    # UR5: joints 2, 3, 4 parallel: d3 and d4 move the tool as d2 does (with the others)
    ident = calibration.identifiable(km.load("ur5"), "pose")
    names = {f.name for f in ident.left_out}
    chosen = set(ident.chosen.tolist())
    model = calibration.ErrorModel.of(km.load("ur5").chain)
    chosen_names = {model.names[k] for k in chosen}
    assert "d2" in chosen_names and {"d3", "d4"} <= names
    assert {"beta2", "beta3"} <= chosen_names  # Hayati's twist takes the tilt


def _columns(*cols):
    return np.array(cols, dtype=float).T


@pytest.mark.parametrize("factor, rank", [(10.0, 2), (0.1, 1)])
def test_rank_tolerance_either_side(factor, rank):
    s = factor * RANK_RTOL
    J = _columns([1.0, 0.0, 0.0], [1.0, s, 0.0])  # the second differs from the first by s
    ident = identify(J, ("p", "q"), [0, 1])
    assert ident.rank == rank == len(ident.chosen)
    if rank == 1:
        assert ident.left_out[0].name == "q" and ident.left_out[0].partners == ("p",)


@pytest.mark.parametrize("factor, named", [(2.0, True), (0.5, False)])
def test_reason_share_either_side(factor, named):
    c = factor * REASON_SHARE
    a, b = np.array([1.0, 0, 0]), np.array([0, 1.0, 0])
    J = _columns(a, b, a + c * b)
    ident = identify(J, ("a", "b", "c"), [0, 1, 2])
    partners = ident.left_out[0].partners
    assert partners == (("a", "b") if named else ("a",))


def test_a_parameter_that_does_not_move_the_tool():
    J = _columns([1.0, 0, 0], [0.0, 0, 0])
    ident = identify(J, ("a", "b"), [0, 1])
    assert ident.left_out[0].partners == ()
    assert (
        finding_text(ident.left_out[0], "en", "position") == "b does not move the measured point."
    )


@pytest.mark.parametrize("factor, reported", [(1.001, True), (0.999, False)])
def test_correlation_limit_either_side(factor, reported):
    r = min(factor * CORRELATION_LIMIT, 0.9999)
    cov = np.array([[4.0, -r * 2 * 3], [-r * 2 * 3, 9.0]])
    pairs = correlated_pairs(cov, ("a", "b"))
    assert bool(pairs) == reported
    if reported:
        assert pairs[0][2] == pytest.approx(-r)
        assert "their sum" in correlation_text(*pairs[0], "en")


def test_observability_indices_by_hand():
    J = np.diag([3.0, 2.0, 1.0])
    ident = identify(J / np.linalg.norm(J, axis=0) * [3.0, 2.0, 1.0], ("a", "b", "c"), [0, 1, 2])
    # columns are normalised: every singular value 1
    o = ident.observability(4)
    assert o == pytest.approx({"O1": 0.5, "O2": 1.0, "O3": 1.0, "O4": 1.0, "O5": 1 / 3})
    skew = identify(np.array([[1.0, 1.0], [0.0, 1.0]]), ("a", "b"), [0, 1])
    s = np.linalg.svd(np.array([[1.0, 1 / np.sqrt(2)], [0.0, 1 / np.sqrt(2)]]), compute_uv=False)
    assert skew.condition == pytest.approx(s[0] / s[1])
    o = skew.observability(1)
    assert o["O1"] == pytest.approx(np.sqrt(s[0] * s[1]))
    assert o["O4"] == pytest.approx(s[1] ** 2 / s[0])
    assert o["O5"] == pytest.approx(1 / (1 / s[0] + 1 / s[1]))


def test_a_lack_of_data_is_told_from_a_structural_redundancy():
    # the wrist never moves: its offsets cannot be told from the tool's, with these poses
    robot = km.load("puma560")
    q = robot.random_q(30, seed=9)
    q[:, 3:] = 0.2
    T = robot.fk(q)
    res = calibration.calibrate(robot, q, T, "pose")
    assert res.rank < res.generic_count == 30
    lacking = [f for f in res.undetermined if not f.structural]
    assert len(lacking) == res.generic_count - res.rank
    text = finding_text(lacking[0], "en")
    assert text.endswith("with these measurements (more varied poses would determine it).")
    assert finding_text(lacking[0], "es").endswith("lo determinarían).")
    # and the structural ones are those of a rich set
    structural = {f.name for f in res.undetermined if f.structural}
    assert structural == {f.name for f in calibration.identifiable(robot).left_out}
