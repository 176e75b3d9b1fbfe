"""The general 6R's alternate labellings: a target the chosen one proves nothing for.

The builder keeps, beside the labelling it chooses, up to ALTERNATES others that pass
its probes (general_6r_build.hpp); the solve tries them in turn where none of the
chosen one's candidates closes the loop and its elimination was ill-conditioned there
(ALTERNATE_RCOND; general_6r.hpp). The case: the one failure of the
perturbed-arm audits (docs/ik-audit.md), a Kawasaki RS007N 2.7e-8 from its spherical
wrist, where the chosen labelling's pencil is nearly singular for every x6 (M(x6)'s
second smallest singular value 1.5e-11 of its largest), A2's reciprocal condition
1.2e-8 (just above LEADING_RCOND_TOL, so the companion matrix is used), and the
eigenvalues near the generating root off by 5e-5: no candidate closes, and the answer
was the numeric search's one solution. Checked against the exact arm's closed form
(the spherical-wrist family: the arms differ by 2.7e-8, their solutions by about that
over the Jacobian's conditioning).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from support.general6r import G, field
from support.kawasaki import Q_GEN, UNREACHED, perturbed

import kinematica as km
from kinematica.dh.joints import Revolute
from kinematica.ik.solve import closed_form

pytestmark = pytest.mark.filterwarnings("ignore::kinematica.KinematicaWarning")

#: Every solution's FK reaches its target to this (m, rad).
FK_TOL = 1e-10
#: Two solutions are one when every joint agrees to this modulo 2π (rad).
SAME = 1e-8
#: The perturbed arm's solutions are within this of the exact arm's (rad): ε = 2.7e-8
#: over σmin/σmax = 1.1e-4 at the generating configuration, with margin.
NEARBY = 1e-3
#: Just inside / just outside a boundary: the tolerance times (1 ∓ this).
EDGE = 1e-3

MAKERS = Path(__file__).parents[2] / "data" / "makers"


def _distance(q: np.ndarray, solutions: np.ndarray) -> float:
    """The largest joint difference (rad, modulo 2π) of q to the nearest of solutions."""
    d = np.remainder(solutions - q + math.pi, 2 * math.pi) - math.pi
    return float(np.abs(d).max(axis=1).min()) if len(solutions) else math.inf


def _misses(robot: km.Robot, q: np.ndarray, T: np.ndarray) -> np.ndarray:
    F = robot.fk(q)
    return np.maximum(
        np.linalg.norm(F[..., :3, 3] - T[:3, 3], axis=-1),
        km.rotation_angle(F[..., :3, :3], T[:3, :3]),
    )


def test_the_documented_value_is_the_core_s() -> None:
    assert G.ALTERNATES == 2


def test_a_pose_the_chosen_labelling_proves_nothing_for_is_answered_by_an_alternate() -> None:
    robot = perturbed()
    q_gen = np.array(Q_GEN)
    T = robot.fk(q_gen)
    res = robot.ik(T, respect_limits=False)
    assert (str(res.status), res.method) == ("ok", "analytic:general-6R")
    assert _distance(q_gen, res.solutions) <= SAME
    assert _misses(robot, res.solutions, T).max() <= FK_TOL
    # a batch goes through the same scalar solve: the same answer at each of its targets
    batch = robot.ik(np.stack([T, T]), respect_limits=False, workers=1)
    for i in range(2):
        assert batch[i].method == res.method and batch[i].count == res.count
        assert _distance(q_gen, batch[i].solutions) <= SAME
    # the same solutions as the exact arm's closed form (the spherical-wrist family), one
    # for one: the arms differ by 2.7e-8
    exact = km.load(MAKERS / "kawasaki_rs007n.urdf")
    ref = exact.ik(T, respect_limits=False)
    assert ref.method.startswith("analytic:") and ref.method != res.method
    assert res.count == ref.count == 8
    assert all(_distance(q, res.solutions) <= NEARBY for q in ref.solutions)
    assert all(_distance(q, ref.solutions) <= NEARBY for q in res.solutions)
    # the chosen labelling's candidates close nothing there; its first alternate answers
    params = closed_form(robot.chain, "pose").params
    assert len(field(params, "alternates")) >= 1
    assert G.attempts(params, T) == (1, 1)
    # without its alternates it proves nothing (near, no candidate within CLOSURE_TOL)
    G.set(params, alternates=[])
    _, _, closure, near, _, _ = G.trace(params, T)
    assert near and closure > G.CLOSURE_TOL
    assert G.attempts(params, T) == (0, 0)


def test_alternates_run_only_where_the_chosen_elimination_is_ill_conditioned() -> None:
    # ALTERNATE_RCOND on both sides, on the arm above: the audit's pose (A2's reciprocal
    # condition 1.2e-8; a constant a thousand times smaller would leave it to the search)
    # and a target no labelling reaches (6.3e-4; a constant a thousand times larger would
    # run the alternates there, two more eliminations for nothing)
    robot = perturbed()
    params = closed_form(robot.chain, "pose").params
    inside = robot.fk(np.array(Q_GEN))
    rcond = G.trace(params, inside)[0]
    assert G.ALTERNATE_RCOND / 1e3 < rcond < G.ALTERNATE_RCOND
    assert G.attempts(params, inside)[1] >= 1
    outside = np.array(UNREACHED)
    rcond, _, closure, near, _, _ = G.trace(params, outside)
    assert G.ALTERNATE_RCOND < rcond < 1e3 * G.ALTERNATE_RCOND
    assert near and closure > G.CLOSURE_TOL
    assert G.attempts(params, outside) == (0, 0)
    assert str(robot.ik(outside, respect_limits=False).status) == "not_found"


def test_may_alternate_asks_the_probes_within_probe_tol() -> None:
    bound = math.log10(G.PROBE_TOL)
    assert G.may_alternate(bound + math.log10(1 - EDGE))
    assert not G.may_alternate(bound + math.log10(1 + EDGE))


def test_a_generic_arm_keeps_alternates_that_pass_the_probes() -> None:
    # a random arm of general geometry: every alternate holds the probes' configurations
    # to PROBE_TOL after Newton's step, as the chosen labelling does, and no two share a
    # labelling (order, sign)
    rng = np.random.default_rng(3)
    rows = [
        Revolute(d=rng.uniform(-0.4, 0.4), a=rng.uniform(-0.4, 0.4), alpha=rng.uniform(-3, 3))
        for _ in range(6)
    ]
    robot = km.Robot.from_dh(rows, convention="standard")
    params = closed_form(robot.chain, "pose").params
    alternates = field(params, "alternates")
    assert len(alternates) == G.ALTERNATES
    seen = {(tuple(field(params, "order")), field(params, "sign"))}
    for alt in alternates:
        assert G.probe(alt, robot.chain.core, True).max() <= G.PROBE_TOL
        assert field(alt, "alternates") == []
        seen.add((tuple(field(alt, "order")), field(alt, "sign")))
    assert len(seen) == 1 + G.ALTERNATES
