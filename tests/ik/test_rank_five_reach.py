"""Poses an arm of rank 5 cannot reach: proved ``unreachable`` by the quantity it keeps.

Three hand-built arms of rank 5 everywhere (a spherical shoulder and wrist; axes 1-3
parallel before a spherical wrist; a spherical shoulder before axes 4-6 parallel). The
quantity each keeps is computed here from the arm's frames by forward kinematics (the
centres are the origins of the DH frames where the axes meet, by the tables'
construction), not from :mod:`kinematica.ik.rank_five_reach`, and checked to be the
same at random configurations. A pose made by FK is moved so that the quantity changes
by a multiple of the call's tolerance carried to it (position tolerance plus the
centre's distance times the rotation tolerance): at half of it the answer is not
``unreachable``; at twice, it is, with the quantity's value in the note.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import kinematica as km
from kinematica.dh.joints import Revolute
from kinematica.ik.continuum_6r import METHOD
from kinematica.ik.rank_five import rank_five
from kinematica.ik.rank_five_reach import INVARIANT_ROUNDOFF
from kinematica.ik.result import IKResult

PI = math.pi
#: The default tolerance of ``robot.ik`` (m, rad).
TOL = 1e-10
KINDS = ("shoulder-wrist", "parallel-wrist", "shoulder-parallel")


def _robot(kind: str) -> km.Robot:
    """The arm of ``kind`` (standard DH)."""
    R = Revolute
    if kind == "shoulder-wrist":  # axes 1-3 meet at frame 1's origin, 4-6 at frame 4's
        rows = [
            R(d=0.3, a=0.0, alpha=PI / 2),
            R(d=0.0, a=0.0, alpha=-PI / 2),
            R(d=0.5, a=0.1, alpha=PI / 2),
            R(d=0.4, a=0.0, alpha=-PI / 2),
            R(d=0.0, a=0.0, alpha=PI / 2),
            R(d=0.1, a=0.0, alpha=0.0),
        ]
    elif kind == "parallel-wrist":  # axes 1-3 parallel, 4-6 meet at frame 4's origin
        rows = [
            R(d=0.3, a=0.4, alpha=0.0),
            R(d=0.0, a=0.35, alpha=0.0),
            R(d=0.1, a=0.2, alpha=PI / 2),
            R(d=0.3, a=0.0, alpha=-PI / 2),
            R(d=0.0, a=0.0, alpha=PI / 2),
            R(d=0.1, a=0.0, alpha=0.0),
        ]
    else:  # axes 1-3 meet at frame 1's origin, 4-6 parallel
        rows = [
            R(d=0.3, a=0.0, alpha=PI / 2),
            R(d=0.0, a=0.0, alpha=-PI / 2),
            R(d=0.2, a=0.3, alpha=PI / 2),
            R(d=0.1, a=0.4, alpha=0.0),
            R(d=0.0, a=0.35, alpha=0.0),
            R(d=0.1, a=0.0, alpha=0.0),
        ]
    return km.Robot.from_dh(rows, convention="standard")


def _kept(kind: str, robot: km.Robot, q: np.ndarray) -> tuple[float, np.ndarray, float]:
    """``(value, direction, r)`` at q, from the frames: the kept quantity, the direction
    (base frame) a move of the target's origin changes it by one for one, and the
    centre's distance from the tool origin (r, m)."""
    F = robot.fk(q, all_frames=True)
    tool = F[-1]
    if kind == "shoulder-wrist":
        S, W = F[1][:3, 3], F[4][:3, 3]
        u = (W - S) / np.linalg.norm(W - S)
        return float(np.linalg.norm(W - S)), u, float(np.linalg.norm(W - tool[:3, 3]))
    if kind == "parallel-wrist":
        h, W = F[0][:3, 2], F[4][:3, 3]
        return float(h @ W), h, float(np.linalg.norm(W - tool[:3, 3]))
    S, h6 = F[1][:3, 3], tool[:3, 2]
    return (
        float(h6 @ (S - tool[:3, 3])),
        -h6,
        float(np.linalg.norm(S - tool[:3, 3])),
    )


@pytest.mark.parametrize("kind", KINDS)
def test_the_quantity_is_kept_and_the_arm_is_of_rank_5(kind: str) -> None:
    robot = _robot(kind)
    five = rank_five(robot.chain)
    assert five is not None and five.exact
    values = [_kept(kind, robot, q)[0] for q in np.random.default_rng(3).uniform(-PI, PI, (6, 6))]
    assert max(values) - min(values) <= 1e-12


@pytest.mark.parametrize("kind", KINDS)
def test_a_pose_off_the_quantity_is_unreachable_and_within_the_tolerance_is_not(kind: str) -> None:
    robot = _robot(kind)
    q = np.random.default_rng(11).uniform(-PI, PI, 6)
    T = robot.fk(q)
    value, u, r = _kept(kind, robot, q)
    margin = TOL + r * TOL  # the tolerance carried to the centre (round-off aside)
    assert 0.1 * margin >= INVARIANT_ROUNDOFF * 2.0  # (round-off is a small part of it)
    res = robot.ik(T)
    assert res.status == "singular" and res.method == METHOD
    for factor, out in ((0.5, False), (-0.5, False), (2.0, True), (-2.0, True)):
        moved = T.copy()
        moved[:3, 3] += factor * margin * u
        assert abs(_kept(kind, robot, q)[0] - value) == 0.0
        res = robot.ik(moved)
        assert isinstance(res, IKResult)
        assert (res.status == "unreachable") == out, (factor, res.status, res.notes)
        if out:
            assert res.method == METHOD and len(res.solutions) == 0
            note = str(res.notes[-1])
            assert f"{value:.9g} m at every configuration" in note
            assert f"misses by {abs(factor) * margin:.3g} m" in note


def test_a_pose_far_off_is_unreachable_for_every_kind() -> None:
    for kind in KINDS:
        robot = _robot(kind)
        q = np.random.default_rng(5).uniform(-PI, PI, 6)
        T = robot.fk(q)
        T[:3, 3] += 0.05 * _kept(kind, robot, q)[1]
        res = robot.ik(T)
        assert res.status == "unreachable", kind
