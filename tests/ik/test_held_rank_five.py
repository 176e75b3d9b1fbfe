"""A middle joint held where the arm left is of rank 5 at every value: read from the axes once."""

from __future__ import annotations

import dataclasses

import numpy as np

import kinematica as km
from kinematica.ik.analytic import general_6r
from kinematica.ik.moved import locked_chain
from kinematica.ik.rank_five import RANK_EXACT_TOL, RANK_FIVE_HELD, held_rank_five, rank_five
from kinematica.ik.solvers import closed_form
from kinematica.ik.structure import features


def sigma_ratio(chain: km.core.Chain, q: np.ndarray) -> np.ndarray:
    """``(N,)`` σ6 / σ1 of the Jacobian at ``q (N, 6)`` (lengths in metres: arms of about 1 m)."""
    s = np.linalg.svd(np.array(chain.jacobian(q)[0]), compute_uv=False)
    return s[:, -1] / s[:, 0]


def test_an_srs_arm_s_elbow_held_is_of_rank_5_whatever_its_value() -> None:
    chain = km.load("iiwa14").chain
    five = held_rank_five(chain, 3)
    assert five is not None and five.kind == "shoulder-wrist"
    assert five.groups == ((0, 3), (3, 6))  # each triple on one side of the elbow
    assert held_rank_five(chain, 3) is five  # read once per chain and joint
    assert [held_rank_five(chain, k) for k in (0, 1, 2, 4, 5, 6)] == [None] * 6
    rng = np.random.default_rng(4)
    for v in rng.uniform(-2.9, 2.9, 4):
        arm = locked_chain(chain, 3, float(v))
        assert arm.memo[RANK_FIVE_HELD] is True
        assert closed_form(arm, "pose") is None
        # independent of the structure read: the Jacobian's rank at random configurations
        assert sigma_ratio(arm, rng.uniform(-3.0, 3.0, (6, 6))).max() <= RANK_EXACT_TOL
        # what lets the builder be skipped: it declines the arm when it is tried
        fresh = chain.locked(3, float(v))
        assert general_6r.build(fresh, features(fresh), "pose") is None


def test_an_arm_only_near_one_of_rank_5_is_not_marked() -> None:
    # the Panda's elbow offsets: the arm left is of rank 6, its closed form is built
    panda = km.load("panda").chain
    assert held_rank_five(panda, 3) is None
    arm = locked_chain(panda, 3, 0.7)
    assert RANK_FIVE_HELD not in arm.memo
    assert closed_form(arm, "pose") is not None
    assert sigma_ratio(arm, np.random.default_rng(2).uniform(-3.0, 3.0, (4, 6))).min() > 1e-6
    # an SRS arm whose shoulder offset is 1e-6 m: near one of rank 5, not exactly (RANK_EXACT_TOL)
    iiwa = km.load("iiwa14")
    rows = list(iiwa.links)
    rows[1] = dataclasses.replace(rows[1], d=rows[1].d + 1e-6)
    near = km.Robot.from_dh(rows, base=iiwa.base, tool=iiwa.tool, convention=iiwa.convention)
    near = near.chain
    assert held_rank_five(near, 3) is None
    five = rank_five(near.locked(3, 1.0))
    assert five is None or not five.exact
    Q = np.random.default_rng(3).uniform(-3.0, 3.0, (4, 6))
    assert sigma_ratio(near.locked(3, 1.0), Q).max() > RANK_EXACT_TOL


def test_an_srs_elbow_held_at_a_new_value_keeps_the_pose_s_solution() -> None:
    robot = km.load("iiwa14")
    Q = robot.random_q(3, seed=8)
    for q in Q:
        res = robot.ik(robot.fk(q), fixed={3: float(q[3])})
        found = res.solutions
        assert len(found) and np.allclose(found[:, 3], q[3])
        assert np.abs(robot.fk(found)[:, :3, 3] - robot.fk(q)[:3, 3]).max() <= 1e-9
