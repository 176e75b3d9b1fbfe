"""The 72 makers' arms of ssik 8.2.0: their URDFs, and every IK solution of the 6R ones.

Data: tests/data/makers (PROVENANCE.md; ``make_makers.py`` made it with ssik, which
the tests never import). For each 6-joint arm, 20 poses of random configurations
within the limits (``q_gen``) and ssik's solutions of each: the ones its default
``solve(T)`` returns (within the limits; one per class modulo 2 pi) and, apart,
the further ones it finds with ``respect_limits=False``.

Per 6R arm, ``robot.ik(T, respect_limits=False)`` (every solution, the limits
ignored) must: (a) be a closed form (``res.method`` ``"analytic:..."``); (b)
reproduce T with every solution to 1e-10 m and rad; (c) hold every ssik solution
that reaches T to 1e-9 by our FK, modulo 2 pi to 1e-6 rad; (d) hold ``q_gen``
modulo 2 pi to 1e-6 rad unless the arm is singular there (σmin/σmax of our
Jacobian below 1e-6). Every arm's URDF loads and its FK equals ssik's (``T_HOME``
at q = 0; the stored T at q_gen).
"""

from __future__ import annotations

import functools
import json
import math
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import kinematica as km
from kinematica.ik import IKResult

MAKERS = Path(__file__).resolve().parents[1] / "data" / "makers"
ARMS: list[dict[str, Any]] = json.loads((MAKERS / "ssik_reference.json").read_text())["arms"]
SIX_R = [arm for arm in ARMS if arm["dof"] == 6]

#: A solution of ours reaches its pose to this (m, rad).
TOL = 1e-10
#: An ssik solution is a reference if it reaches its pose to this by our FK (m, rad).
SSIK_TOL = 1e-9
#: Two solutions are one if every joint agrees to this modulo 2 pi (rad).
SAME = 1e-6
#: σmin / σmax of the Jacobian below this: the arm is singular at q_gen.
SINGULAR_REL = 1e-6


def _ids(arms: list[dict[str, Any]]) -> list[str]:
    return [arm["arm"] for arm in arms]


@dataclass(frozen=True)
class Solved:
    """One arm's robot and our answer for each of its reference poses."""

    robot: km.Robot
    targets: np.ndarray
    results: list[IKResult]


def load(arm: dict[str, Any]) -> km.Robot:
    """The arm's URDF through ``km.load``."""
    return km.load(MAKERS / arm["urdf"])


@functools.cache
def solved(name: str) -> Solved:
    """Every pose of a 6R arm solved once, whatever the limits (shared by the four checks)."""
    arm = next(a for a in SIX_R if a["arm"] == name)
    robot = load(arm)
    targets = np.array(arm["T"])
    return Solved(robot, targets, [robot.ik(T, respect_limits=False) for T in targets])


def misses(robot: km.Robot, q: np.ndarray, T: np.ndarray) -> np.ndarray:
    """``(k,)``: the larger of the position (m) and rotation (rad) error of each ``q`` at T."""
    with warnings.catch_warnings():  # solutions outside the limits are meant here
        warnings.simplefilter("ignore", km.KinematicaWarning)
        Ts = robot.fk(q)
    position = np.linalg.norm(Ts[..., :3, 3] - T[:3, 3], axis=-1)
    return np.maximum(position, km.rotation_angle(Ts[..., :3, :3], T[:3, :3]))


def among(q: np.ndarray, solutions: np.ndarray) -> bool:
    """Whether ``q`` is one of ``solutions`` modulo 2 pi."""
    if len(solutions) == 0:
        return False
    d = (solutions - q + math.pi) % (2.0 * math.pi) - math.pi
    return bool(np.abs(d).max(axis=1).min() <= SAME)


@pytest.mark.parametrize("arm", ARMS, ids=_ids(ARMS))
def test_urdf_loads_and_its_fk_is_ssiks(arm):
    robot = load(arm)
    assert robot.dof == arm["dof"]
    with warnings.catch_warnings():  # q = 0 is outside some arms' limits
        warnings.simplefilter("ignore", km.KinematicaWarning)
        home = robot.fk(np.zeros(robot.dof))
    np.testing.assert_allclose(home, arm["T_home"], rtol=0, atol=1e-12)
    if "q_gen" in arm:
        np.testing.assert_allclose(robot.fk(np.array(arm["q_gen"])), arm["T"], rtol=0, atol=1e-12)


@pytest.mark.parametrize("arm", SIX_R, ids=_ids(SIX_R))
def test_closed_form(arm):
    methods = [res.method for res in solved(arm["arm"]).results]
    numeric = [(i, m) for i, m in enumerate(methods) if not m.startswith("analytic:")]
    assert not numeric, f"poses not solved in closed form (pose, method): {numeric}"


@pytest.mark.parametrize("arm", SIX_R, ids=_ids(SIX_R))
def test_every_solution_reaches_the_pose(arm):
    s = solved(arm["arm"])
    bad = []
    for i, (T, res) in enumerate(zip(s.targets, s.results, strict=True)):
        if res.count:
            worst = float(misses(s.robot, res.solutions, T).max())
            if worst > TOL:
                bad.append((i, worst))
    assert not bad, f"poses whose solutions miss T by more than {TOL} (pose, miss): {bad}"


@pytest.mark.parametrize("arm", SIX_R, ids=_ids(SIX_R))
def test_ssiks_solutions_are_ours(arm):
    s = solved(arm["arm"])
    lost, checked = [], 0
    for i, (T, res) in enumerate(zip(s.targets, s.results, strict=True)):
        theirs = np.array(arm["ssik"][i] + arm["ssik_beyond_limits"][i]).reshape(-1, 6)
        good = theirs[misses(s.robot, theirs, T) < SSIK_TOL] if len(theirs) else theirs
        checked += len(good)
        lost += [(i, np.round(q, 6).tolist()) for q in good if not among(q, res.solutions)]
    assert checked > 0
    assert not lost, f"{len(lost)} of {checked} ssik solutions not among ours (pose, q): {lost}"


@pytest.mark.parametrize("arm", SIX_R, ids=_ids(SIX_R))
def test_generating_configuration_is_ours(arm):
    s = solved(arm["arm"])
    q_gen = np.array(arm["q_gen"])
    sv = np.linalg.svd(s.robot.jacobian(q_gen), compute_uv=False)
    regular = sv[:, -1] >= SINGULAR_REL * sv[:, 0]
    lost = [
        i
        for i, (q, res) in enumerate(zip(q_gen, s.results, strict=True))
        if regular[i] and not among(q, res.solutions)
    ]
    assert not lost, f"poses whose q_gen is not among our solutions: {lost} of {int(regular.sum())}"
