"""A 6R arm's reach bounds: they never drop a held value with a solution, and most without.

``auto`` on a 7R arm skips the values of its held end joint that
:mod:`kinematica.ik.reach_bounds` proves out of reach. Checked against the closed form
itself (the screen it saves), against configurations (a target at its own value is
reached), and against ``auto`` with the bounds switched off (the same answers).
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from kinematica._core_testing.internals import reach_fields
from support import DATA

import kinematica as km
from kinematica.ik import IKBatchResult, IKOptions, nearest_value, redundancy
from kinematica.ik.moved import end_arm, lever, move_parts, moved_targets, on_axis
from kinematica.ik.parameter import JointParameter
from kinematica.ik.reach_bounds import ROUNDOFF_SLACK, may_reach, reach_bounds, violation
from kinematica.ik.redundancy import PARAMETER_SWEEP, choose
from kinematica.ik.request import IKRequest
from kinematica.ik.solve import solve_ik
from kinematica.ik.tolerance import Tolerance

MAKERS = ("kinova_gen3", "realman_gen72", "realman_rm75")


def _arm(name: str) -> km.Robot:
    if name == "random 7R":  # a 7R arm of no maker: random twists, offsets and lengths
        rng = np.random.default_rng(1)
        rows = [
            km.Revolute(
                d=rng.uniform(-0.3, 0.4),
                a=rng.uniform(0, 0.4) * (rng.random() < 0.6),
                alpha=float(
                    rng.choice([math.pi / 2, -math.pi / 2, rng.uniform(-math.pi, math.pi)])
                ),
            )
            for _ in range(7)
        ]
        return km.Robot.from_dh(rows, convention="standard")
    return km.load(str(DATA / "makers" / f"{name}.urdf"))


def _held(
    robot: km.Robot, limits: bool = True, k: int | None = None
) -> tuple[int, km.core.Chain, np.ndarray, tuple]:
    """The end joint ``k`` (None: the one ``auto`` holds), its arm, bounds and move's parts."""
    if k is None:
        joint = choose(robot.chain)
        assert isinstance(joint, JointParameter) and joint.index in (0, 6)
        k = joint.index
    arm = end_arm(robot.chain, k)
    bounds = reach_bounds(arm, limits)
    assert bounds is not None
    return k, arm, bounds, move_parts(robot.chain, k)


@pytest.mark.parametrize(
    ("name", "k", "share"), [("kinova_gen3", 6, 0.95), ("realman_gen72", 6, 0.85),
                             ("realman_gen72", 0, 0.7), ("realman_rm75", 6, 0.95),
                             ("random 7R", None, 0.5)]
)  # fmt: skip
def test_no_value_with_a_solution_is_dropped_and_most_without_are(
    name: str, k: int | None, share: float
) -> None:
    robot = _arm(name)
    k, arm, bounds, move = _held(robot, k=k)
    lo, hi = robot.chain.qlim[k]
    grid = np.linspace(lo, hi, PARAMETER_SWEEP)
    T = robot.fk(robot.random_q(12, seed=3))
    moved = moved_targets(robot.chain, k, np.repeat(T, grid.size, axis=0), np.tile(grid, len(T)))
    dropped = {}
    for limits in (False, True):
        bounds = _held(robot, limits, k)[2]
        kept = may_reach(bounds, T, Tolerance(), grid, move, limits)  # (12, 73)
        # the closed form: every value where it finds a solution is kept
        found = solve_ik(arm, moved, IKOptions(workers=1, respect_limits=limits))
        assert isinstance(found, IKBatchResult)
        has = (np.asarray(found.count) > 0).reshape(kept.shape)
        assert has.any() and (~has).any()
        assert not (has & ~kept).any()
        dropped[limits] = ~kept
    # and most values without one are dropped (on 12 poses: 90-100 % on the makers' arms);
    # with the limits, more, never fewer
    assert (dropped[True] & ~has).sum() >= share * (~has).sum()
    assert not (dropped[False] & ~dropped[True]).any()
    if name == "realman_gen72" and k == 6:  # q2, q4 and q6 limited: the limits drop more
        assert (dropped[True] & ~dropped[False]).any()


@pytest.mark.parametrize("name", [*MAKERS, "random 7R"])
def test_a_target_at_its_own_value_is_kept(name: str) -> None:
    # FK of random configurations, the whole circle of every joint: each target has a
    # solution with the held joint at its own value, some at the edge of the ranges
    robot = _arm(name)
    k, _, bounds, move = _held(robot)
    rng = np.random.default_rng(2)
    q = rng.uniform(-math.pi, math.pi, size=(3000, 7))
    with warnings.catch_warnings():  # beyond the joints' limits: the bounds ignore them
        warnings.simplefilter("ignore", km.KinematicaWarning)
        T = robot.fk(q)
    inside = robot.random_q(3000, seed=2)  # within the limits: the arcs of q1 and q6 too
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", km.KinematicaWarning)
        T_in = robot.fk(inside)
    for Q, poses, limits in ((q, T, False), (inside, T_in, True)):
        bounds = _held(robot, limits)[2]
        own = np.array([violation(bounds, poses[i : i + 1], Tolerance(), Q[i, k : k + 1], move,
                                  limits)[0, 0] for i in range(len(Q))])  # fmt: skip
        assert own.max() <= ROUNDOFF_SLACK
        assert own.max() > -0.05  # some of them near the edge of a range (within 5 cm)


def test_the_roundoff_slack_is_the_boundary() -> None:
    robot = _arm("kinova_gen3")
    _, _, bounds, move = _held(robot)
    T = robot.fk(robot.random_q(40, seed=4))
    grid = np.linspace(-math.pi, math.pi, PARAMETER_SWEEP)
    # with no rotation tolerance the violation is the largest gap less the position's
    gap = violation(bounds, T, Tolerance(0.0, 0.0), grid, move)
    i, j = np.unravel_index(np.argmax(gap), gap.shape)
    g = float(gap[i, j])
    assert g > 10 * ROUNDOFF_SLACK
    one, at = T[i : i + 1], grid[j : j + 1]
    inside = Tolerance(g - 0.5 * ROUNDOFF_SLACK, 0.0)
    outside = Tolerance(g - 2.0 * ROUNDOFF_SLACK, 0.0)
    assert may_reach(bounds, one, inside, at, move)[0, 0]
    assert not may_reach(bounds, one, outside, at, move)[0, 0]
    # a rotation tolerance widens it by its lever: the farthest point checked
    assert may_reach(bounds, one, Tolerance(g - 2.0 * ROUNDOFF_SLACK, 1e-3), at, move)[0, 0]


def test_distance_and_height_are_asked_of_one_q6_together() -> None:
    # GEN72 (q7 held): targets whose x circle meets the distance range at some q6 and the
    # height range at another, never both at one; the violation is the least widening of
    # both that does, at most what a fine sampling of q6 over its arc finds (and close to it)
    robot = _arm("realman_gen72")
    k, _, bounds, move = _held(robot, k=6)
    T = robot.fk(robot.random_q(40, seed=12))
    grid = np.linspace(*robot.chain.qlim[k], PARAMETER_SWEEP)
    gap = violation(bounds, T, Tolerance(0.0, 0.0), grid, move)
    moved = moved_targets(robot.chain, k, np.repeat(T, grid.size, axis=0), np.tile(grid, len(T)))
    moved = moved.reshape(len(T), grid.size, 4, 4)
    b = {key: np.asarray(v, dtype=float) for key, v in reach_fields(bounds).items()}
    q6 = np.linspace(*b["arc6"], 4001)  # its arc
    c, u, v = (np.asarray(w) for w in reach_fields(bounds)["x"])
    x = c + np.outer(np.cos(q6), u) + np.outer(np.sin(q6), v)
    S, a1 = b["shoulder"], b["a1"]
    together = []
    for i, j in np.ndindex(gap.shape):
        M = moved[i, j]
        xs = x @ M[:3, :3].T + M[:3, 3]
        d, h = np.linalg.norm(xs - S, axis=1), (xs - S) @ a1
        far = np.maximum(b["reach"][0] - d, d - b["reach"][1])
        high = np.maximum(b["height"][0] - h, h - b["height"][1])
        sampled = float(np.maximum(far, high).min())  # how far, sampled: an upper bound
        if far.min() > 0.0 or high.min() > 0.0 or sampled < 1e-3:
            continue  # a range missed alone, or both met at one q6 (to the sampling's step)
        assert gap[i, j] >= sampled - 1e-3  # the sampling's step: 0.9 mrad, 0.4 m from S
        if gap[i, j] <= sampled:
            together.append((float(gap[i, j]), i, j))
    assert len(together) >= 3
    # the round-off slack is its boundary too: a tolerance just under the gap drops the
    # target, one just over keeps it
    g, i, j = max(together)
    one, at = T[i : i + 1], grid[j : j + 1]
    assert may_reach(bounds, one, Tolerance(g - 0.5 * ROUNDOFF_SLACK, 0.0), at, move)[0, 0]
    assert not may_reach(bounds, one, Tolerance(g - 2.0 * ROUNDOFF_SLACK, 0.0), at, move)[0, 0]


def test_past_a_last_joint_whose_axis_misses_the_tool_point_the_move_widens_the_slack() -> None:
    # the tool 0.2 m off the last axis: a pose within (P, R) of the target is within
    # (P + R |t_Y|, R) of the target moved past the joint, so a value is proved out only
    # where the moved target misses the bounds by more than that (the move's lever)
    base = _arm("random 7R")
    tool = np.eye(4)
    tool[:3, 3] = [0.2, 0.0, 0.05]
    robot = km.Robot.from_dh(base.links, convention="standard", tool=tool)
    chain = robot.chain
    assert not on_axis(chain)
    joint = JointParameter(6, "q7", False)
    _, _, bounds, move = _held(robot, k=6)
    grid = np.linspace(*chain.qlim[6], PARAMETER_SWEEP)
    reach = lever(chain, 6, grid)
    G = chain.fixed_parts[-1] @ chain.tool  # the tool point in joint 7's frame
    assert reach == pytest.approx(2.0 * math.hypot(G[0, 3], G[1, 3]), abs=1e-12)  # half a turn
    T = robot.fk(robot.random_q(60, seed=8))
    tol = Tolerance(1e-6, 1e-2)
    request = IKRequest.parse(tol=(tol.position, tol.rotation), workers=1)
    kept = nearest_value.possible(chain, joint, T, grid, request)
    plain = violation(bounds, T, tol, grid, move) > ROUNDOFF_SLACK
    wide = Tolerance(tol.position + tol.rotation * reach, tol.rotation)
    widened = violation(bounds, T, wide, grid, move) > ROUNDOFF_SLACK
    assert (plain & ~widened).sum() >= 5  # values the move's lever keeps
    assert np.array_equal(kept, ~widened)
    # the tool point on the axis: no lever, the tolerance as given
    on = km.Robot.from_dh(base.links, convention="standard")
    assert on_axis(on.chain) and lever(on.chain, 6, grid) < 1e-12


def test_a_target_not_finite_is_never_dropped() -> None:
    robot = _arm("kinova_gen3")
    _, _, bounds, move = _held(robot)
    T = robot.fk(robot.random_q(1, seed=1))
    T[0, 0, 3] = np.nan
    assert np.isnan(violation(bounds, T, Tolerance(), np.zeros(3), move)).all()
    assert may_reach(bounds, T, Tolerance(), np.zeros(3), move).all()


def test_an_arm_with_a_slide_has_no_bounds() -> None:
    rows = [km.Revolute(d=0.3, alpha=math.pi / 2)] * 5 + [km.Prismatic(theta=0.0, alpha=0.0)]
    robot = km.Robot.from_dh(rows, convention="standard")
    assert reach_bounds(robot.chain, False) is None


def _fields(res: km.ik.IKResult) -> tuple:
    return (str(res.status), res.count, res.method, res.notes, res.parameter)


@pytest.mark.parametrize("name", ["kinova_gen3", "random 7R"])
def test_auto_answers_as_it_would_without_the_bounds(
    name: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    robot = _arm(name)
    T = robot.fk(robot.random_q(16, seed=6))
    new_batch = robot.ik(T, workers=1)
    new = [robot.ik(t) for t in T]
    with monkeypatch.context() as m:  # every value possible: the screen decides alone
        every = lambda c, j, p, g, r: np.ones((len(p), g.size), bool)  # noqa: E731
        m.setattr(redundancy, "possible", every)
        m.setattr(nearest_value, "possible", every)
        m.setattr(nearest_value, "reach_bounds", lambda arm, limits: None)  # the core's sweep
        old_batch = robot.ik(T, workers=1)
        old = [robot.ik(t) for t in T]
    assert isinstance(new_batch, IKBatchResult) and isinstance(old_batch, IKBatchResult)
    moved = 0
    for i in range(len(T)):
        assert _fields(new[i]) == _fields(old[i])
        np.testing.assert_array_equal(new[i].solutions, old[i].solutions)
        # a batch row as its single call, with the bounds and without
        assert _fields(new_batch[i]) == _fields(new[i])
        assert _fields(old_batch[i]) == _fields(old[i])
        np.testing.assert_array_equal(new_batch[i].solutions, old_batch[i].solutions)
        moved += any("the nearest of" in n for n in new[i].notes)
    assert moved  # some targets held at another value than the default


def test_a_batch_of_targets_all_out_of_reach_at_the_value_or_with_q0_is_its_single_calls() -> None:
    # GEN72 at its default q7: targets proved out of reach there are left unsolved at it,
    # every one of a batch (its first solved for the batch's method alone), or some of a
    # batch with one q0 for all
    robot = _arm("realman_gen72")
    k, _, bounds, move = _held(robot)
    value = choose(robot.chain).default(robot.chain)  # type: ignore[union-attr]
    T = robot.fk(robot.random_q(30, seed=8))
    out = ~may_reach(bounds, T, Tolerance(), np.array([value]), move)[:, 0]
    assert 3 <= out.sum() < len(T) and out[:8].any() and not out[:8].all()
    q0 = robot.random_q(1, seed=9)[0]
    q0[k] = value
    for batch, kwargs in ((T[out][:3], {}), (T[:8], {"q0": q0})):
        many = robot.ik(batch, workers=1, **kwargs)
        assert isinstance(many, IKBatchResult)
        for i, t in enumerate(batch):
            one = robot.ik(t, **kwargs)
            assert _fields(many[i]) == _fields(one)
            np.testing.assert_array_equal(many[i].solutions, one.solutions)
