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
at q = 0; the stored T at q_gen). The DH tables of the two arms whose nearly parallel
axes put their frames km away (``robot.to_dh()``) are solved as their URDFs, and the
size the general 6R's loop is built in is measured along the axes there.

The full audit (1,000 poses per arm, perturbed arms, ssik live) is
``benchmarks/audit_makers.py``.
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
from kinematica._core_testing import general6r

import kinematica as km
from kinematica.ik import IKResult
from kinematica.ik.rank_five import rank_five, rank_size
from kinematica.ik.structure import features

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


#: The arms whose URDF axes 2 and 3 are parallel but for a rounded rpy (Kinova Gen3 Lite:
#: 7.3e-6 rad), so that their DH table (``robot.to_dh()``) puts frames at the foot of the
#: common normal tens of km away (d2, d3 = -38 km; i2rt Big YAM: -26 km).
FAR_FEET = ("kinova_gen3_lite", "i2rt_big_yam")
#: A reference solution of a table whose FK is the file's to ``fk_error`` may lie this many
#: times its miss over σmin of our Jacobian from ours (rad).
DETERMINED = 10.0


@pytest.mark.parametrize("name", FAR_FEET)
def test_dh_table_with_far_feet_is_solved_as_its_urdf(name):
    # The table's frames 38 km out and back made the arm's size 76 km: the rank test saw a
    # Jacobian of rank 3 (near-rank-5 path: Newton from 64 guesses, 2 and 1 of ssik's
    # solutions lost on these poses) and the general 6R's loop lost its lengths to
    # round-off. Measured along the axes (loop_size), it is the general 6R's arm.
    arm = next(a for a in SIX_R if a["arm"] == name)
    table = load(arm).to_dh()
    robot = table.robot
    assert features(robot.chain).size < 2.0  # the arm's size along its axes, not 76 km
    q_gen = np.array(arm["q_gen"])
    targets = robot.fk(q_gen)
    sv = np.linalg.svd(robot.jacobian(q_gen), compute_uv=False)
    lost, missed = [], []
    for i, T in enumerate(targets):
        res = robot.ik(T, respect_limits=False)
        assert res.method == "analytic:general-6R", (i, res.method)
        assert misses(robot, res.solutions, T).max() <= TOL, i
        if sv[i, -1] >= SINGULAR_REL * sv[i, 0] and not among(q_gen[i], res.solutions):
            missed.append(i)
        theirs = np.array(arm["ssik"][i] + arm["ssik_beyond_limits"][i]).reshape(-1, 6)
        miss = misses(robot, theirs, T)
        sigma = np.linalg.svd(robot.jacobian(theirs), compute_uv=False)[:, -1]
        for q, e in zip(theirs[miss < SSIK_TOL], (DETERMINED * miss / sigma)[miss < SSIK_TOL],
                        strict=True):  # fmt: skip
            d = (res.solutions - q + math.pi) % (2.0 * math.pi) - math.pi
            if np.abs(d).max(axis=1).min() > SAME + e:
                lost.append((i, np.round(q, 6).tolist()))
    assert not missed, f"q_gen not among ours at poses {missed}"
    assert not lost, f"ssik solutions not among ours: {lost}"


def test_arm_size_is_measured_along_the_axes_where_the_frames_wander():
    # Axes 2 and 3 parallel (α2 = 0): d2 = +L, d3 = -L moves frame 2 along them, the same
    # arm for every L. Its size (the line tolerance's scale, the general 6R's loop) is
    # the one along the axes once the frames' (|d2| + |d3| counted) exceed it
    # 1 / WALK_SIZE_RATIO times, not before.
    def arm(L: float) -> km.Robot:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", km.UnitWarning)  # d of km, on purpose
            rows = [km.Revolute(d=0.3, a=0.05, alpha=math.pi / 2),
                    km.Revolute(d=L, a=0.4, alpha=0.0),
                    km.Revolute(d=-L, a=0.05, alpha=math.pi / 2),
                    km.Revolute(d=0.35, a=0.0, alpha=-1.2),
                    km.Revolute(d=0.1, a=0.02, alpha=0.9),
                    km.Revolute(d=0.08, a=0.0, alpha=0.0)]  # fmt: skip
        return km.Robot.from_dh(rows, convention="standard")

    walked = features(arm(1e4).chain).size
    assert walked < 2.0  # the geometry's, not the 20 km of frames
    own = features(arm(0.0).chain).size  # the frames' size without the excursion
    ratio = general6r.WALK_SIZE_RATIO
    for r, along in ((0.3 * ratio, True), (3.0 * ratio, False)):
        L = (walked / r - own) / 2.0
        assert L > 0.0
        robot = arm(L)
        size = features(robot.chain).size
        assert size == pytest.approx(walked if along else own + 2.0 * L)
        assert general6r.loop_size(robot.chain.core) == pytest.approx(size)
        assert rank_size(robot.chain) == size
        assert rank_five(robot.chain) is None
    assert general6r.loop_size(load(SIX_R[0]).chain.core) == features(load(SIX_R[0]).chain).size


def test_puma_560_moved_within_the_line_tolerance_is_solved_by_the_general_6r():
    # The PUMA 560's DH table with every d, a, α moved by ±2.7e-9 (audit_makers.py,
    # perturbed #7, seed 1): its wrist axes meet within the line geometry's tolerance
    # (slack 5e-9), so the spherical wrist's family took it, but its candidates reached
    # none of the poses and each was answered by the numeric search (one solution, the
    # generating configuration missed on 18 of 20). The family's probes fail there: the
    # general 6R answers, every solution.
    e = 2.6997917502605395e-09
    h = math.pi / 2
    rows = [(-e, e, h + e), (-e, 0.4318 - e, e), (0.15005 + e, 0.0203 - e, -h - e),
            (0.4318 - e, e, h + e), (e, -e, -h - e), (e, -e, -e)]  # fmt: skip
    robot = km.Robot.from_dh([km.Revolute(d=d, a=a, alpha=al) for d, a, al in rows],
                             convention="standard")  # fmt: skip
    q = np.random.default_rng(7).uniform(-3.0, 3.0, (30, 6))
    targets = robot.fk(q)
    res = robot.ik(targets, respect_limits=False)
    assert res.method == "analytic:general-6R" and not res.methods
    sv = np.linalg.svd(robot.jacobian(q), compute_uv=False)
    for i, T in enumerate(targets):
        assert misses(robot, res[i].solutions, T).max() <= TOL
        if sv[i, -1] >= SINGULAR_REL * sv[i, 0]:
            assert among(q[i], res[i].solutions), i


def test_a_probe_counts_its_configuration_found_within_near_probe_match():
    # The near-family probe asks for the configuration that made each pose among the
    # family's solutions (mod 2π), not only for some solution.
    from kinematica.ik.solvers import NEAR_PROBE_MATCH, generating_found

    made = np.array([[0.1, -0.2, 0.3, np.pi - 1e-9, 0.5, -0.6]])
    other = made + 0.7  # another branch: the pose solved, its configuration missed
    for step, found in ((0.5 * NEAR_PROBE_MATCH, True), (2.0 * NEAR_PROBE_MATCH, False)):
        near = made + step * np.array([1, -1, 1, 1, -1, 1])  # joint 4 across ±π
        near[0, 3] -= 2.0 * np.pi
        sols = np.stack([other, near], axis=1)  # (1, 2, 6)
        assert generating_found(sols, np.array([2]), made) is found
        assert generating_found(sols, np.array([1]), made) is False  # the first row only
    assert generating_found(np.zeros((1, 0, 6)), np.array([0]), made) is False
