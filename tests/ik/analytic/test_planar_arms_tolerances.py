"""The small arms' named tolerances, each tested on both sides (planar, SCARA, elbow arms).

A case a factor 10 inside a tolerance and one a factor 10 outside it (or as close as
round-off allows), through the public API and through the subproblems the core exposes
(``kinematica._core_testing.planar.two_link``, ``slide_link``) and the raw candidates of a closed
form (``params.candidates``). The documented values are written out here: a change of
one is a visible change of a test.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from support import small_arms as ik_small

import kinematica as km
from kinematica import _core, _core_testing
from kinematica.ik import closed_form

TRIANGLE_SINGULAR_TOL = 1e-12  # triangle.hpp SINGULAR_TOL (relative to the reach)
MERGE_TOL = 1e-7  # triangle.hpp MERGE_TOL (rad)
AXIS_LENGTH_TOL = 1e-9  # dh/lines.py: lines meet within it times 1 + the arm's size (m)
FREE_SAMPLES = 33  # planar.hpp FREE_SAMPLES

#: A case a factor 10 inside a tolerance, and one a factor 10 outside it.
FACTORS = [(0.1, True), (10.0, False)]


def test_the_documented_values() -> None:
    assert _core_testing.planar.SINGULAR_TOL == TRIANGLE_SINGULAR_TOL
    assert _core_testing.planar.MERGE_TOL == MERGE_TOL
    assert _core_testing.planar.FREE_SAMPLES == FREE_SAMPLES
    assert km.dh.lines.AXIS_LENGTH_TOL == AXIS_LENGTH_TOL


# --- the triangle's subproblems, directly ----------------------------------------


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_two_link_fold_within_singular_tol(factor: float, inside: bool) -> None:
    """two_link says FOLD for a target within SINGULAR_TOL (times the reach) of the first
    axis of a folded triangle whose links differ by at most as much; else two branches.
    """
    r = factor * TRIANGLE_SINGULAR_TOL * 1.0  # links 0.5 and 0.5: the reach is 1 m
    code, out = _core_testing.planar.two_link(0.5, 0.0, 0.5, 0.0, r, 0.0)
    assert code == (_core_testing.planar.FOLD if inside else _core_testing.planar.NEAR)
    assert np.isfinite(out).all()
    # unequal links by as much: the fold holds within the tolerance only
    code, _ = _core_testing.planar.two_link(0.5, 0.0, 0.5 + r, 0.0, 0.0, 0.0)
    assert (code == _core_testing.planar.FOLD) is inside


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_two_link_near_within_merge_tol_of_folded(factor: float, inside: bool) -> None:
    """two_link says NEAR when ψ is within MERGE_TOL of π (the branches merging):
    4 L1 L2 cos²(ψ/2) = (r − |L1 − L2|)(r + |L1 − L2|) below MERGE_TOL² L1 L2.

    Placed by the target's distance r from the inner edge of the reach (unequal links):
    at the outer edge the same criterion asks for r within an ulp of L1 + L2.
    """
    L1, L2 = 0.6, 0.4
    inner = abs(L1 - L2)
    merge = MERGE_TOL * MERGE_TOL * L1 * L2
    delta = factor * merge / (2.0 * inner)  # (r - inner)(r + inner) = factor * merge
    code, out = _core_testing.planar.two_link(L1, 0.0, L2, 0.0, inner + delta, 0.0)
    assert (code == _core_testing.planar.NEAR) is inside
    assert code != _core_testing.planar.FOLD
    psi = np.abs(out[:, 1])  # link 2's turn from q = 0 is ±ψ here
    assert (abs(psi - math.pi) < 1e-6).all()


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_two_link_near_within_merge_tol_of_the_first_axis(factor: float, inside: bool) -> None:
    """two_link says NEAR for a target within MERGE_TOL (times the reach) of the first axis."""
    r = factor * MERGE_TOL * 1.0
    code, _ = _core_testing.planar.two_link(0.5, 0.0, 0.5, 0.0, 0.0, r)
    assert (code == _core_testing.planar.NEAR) is inside


@pytest.mark.parametrize(
    ("factor", "inside"), [(0.1, True), (10.0, False), (-0.5, True), (-2.0, False)]
)
@pytest.mark.parametrize("folded", [False, True])
def test_two_link_straddles_the_fold_within_its_slack(
    factor: float, inside: bool, folded: bool
) -> None:
    """A nearby arm's triangle (slack 1e-9 m): where 4 L1 L2 sin²(ψ/2) (stretched) or
    cos²(ψ/2) (folded) is below slack (2 r + slack), the real arm's branches may
    lie on either side of the fold, so the rows are raised by that much, one on each
    side (beyond the reach by half of it too: factor -0.5); above it, or beyond the reach
    by more (-2), the plain rows (there the least-squares fold, twice)."""
    L1, L2, slack = 0.6, 0.4, 1e-9
    edge = abs(L1 - L2) if folded else L1 + L2
    margin = slack * (2.0 * edge + slack)  # (2 r + slack) slack, r at the fold
    r = math.sqrt(edge * edge + (factor if folded else -factor) * margin)
    _, plain = _core_testing.planar.two_link(L1, 0.0, L2, 0.0, r, 0.0)
    _, rows = _core_testing.planar.two_link(L1, 0.0, L2, 0.0, r, 0.0, slack)
    fold = math.pi if folded else 0.0
    psi = np.abs(np.angle(np.exp(1j * (rows[:, 1] - fold))))  # distance from the fold
    if not inside:
        np.testing.assert_array_equal(rows, plain)
        return
    plain_psi = np.abs(np.angle(np.exp(1j * (plain[:, 1] - fold))))
    assert (psi > plain_psi).all()  # farther from the fold than the plain rows
    assert rows[0, 1] != rows[1, 1]  # one on each side
    # S (or C) raised by the margin: 4 L1 L2 sin²(|ψ - fold| / 2) = (factor + 1) margin
    np.testing.assert_allclose(
        4.0 * L1 * L2 * np.sin(psi / 2) ** 2, (factor + 1) * margin, rtol=1e-4
    )


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_slide_link_merges_within_merge_tol(factor: float, inside: bool) -> None:
    """slide_link merges when the link is within MERGE_TOL of across the slide."""
    e = factor * MERGE_TOL
    L = 0.5
    t = (0.2 + L * math.sin(e), L * math.cos(e))  # the link at e from across the slide (x)
    merging, out = _core_testing.planar.slide_link(1.0, 0.0, 0.0, L, *t)
    assert merging is inside
    # s = along ∓ L sin e: the slide where the link is at ±e from across it
    np.testing.assert_allclose(out[:, 0], [0.2, 0.2 + 2 * L * math.sin(e)], atol=1e-8)


def test_subproblem_inputs_are_validated() -> None:
    with pytest.raises(TypeError):
        _core_testing.planar.two_link(0.5, 0.0, 0.5, 0.0, "x", 0.0)  # type: ignore[arg-type]
    with pytest.raises(TypeError):  # the core's builder alone fills a family's Params
        _core.planar.PlanarParams()
    with pytest.raises(TypeError):
        _core.elbow.ElbowParams()


# --- through robot.ik -------------------------------------------------------------


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_triangle_singular_tol_is_the_fold_continuum(factor: float, inside: bool) -> None:
    """SINGULAR_TOL: a target this close (relative to the reach) to the first axis of a
    folded 2R arm with equal links is on the fold: every turn of joint 1 reaches it
    (status "singular", q1 free); farther, two solutions.
    """
    robot = km.Robot.from_dh([km.Revolute(a=0.5), km.Revolute(a=0.5)], convention="standard")
    r = factor * TRIANGLE_SINGULAR_TOL * 1.0  # the reach is 1 m
    res = robot.ik(np.array([r, 0.0, 0.0]))
    if inside:
        assert res.status == "singular" and res.free_joints == (0,)
    else:
        assert res.status == "ok" and len(res.solutions) == 2


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_merge_tol_says_branches_merge(factor: float, inside: bool) -> None:
    """MERGE_TOL: branches within it (rad) of each other are merging: the result is
    near_singular.

    The PR arm of test_ik_small (x = q1 + l1 + l2 cos q2, y = l2 sin q2): at
    q2 = π/2 - e its two branches are 2e apart in q2. (On a 2R arm stretched
    by e the two solutions are also within the check's DEDUP_TOL of each
    other, which flags them near by itself and hides MERGE_TOL.)
    """
    pr = ik_small.seed_pr_arm()
    res = pr.ik(pr.fk([0.1, math.pi / 2 - factor * MERGE_TOL])[:3, 3])
    assert res.status == "ok"
    assert res.near_singular is inside


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_merge_tol_near_the_first_axis(factor: float, inside: bool) -> None:
    """MERGE_TOL, its second use: a target within it (relative to the reach) of the
    first axis of a 2R arm with equal links makes the first turn uncertain:
    near_singular. Its two solutions differ by π in q1, so the check's
    deduplication plays no part (unlike a merge at the stretched arm, where the
    angle ψ is round-off below ~1e-8 and cannot be placed inside).
    """
    robot = km.Robot.from_dh([km.Revolute(a=0.5), km.Revolute(a=0.5)], convention="standard")
    res = robot.ik(np.array([factor * MERGE_TOL * 1.0, 0.0, 0.0]))  # the reach is 1 m
    assert res.status == "ok" and len(res.solutions) == 2
    assert res.near_singular is inside


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_length_tol_is_a_link_that_moves_nothing(factor: float, inside: bool) -> None:
    """AXIS_LENGTH_TOL: a planar 2R whose tool is within it (times 1 + the arm's
    size, m) of axis 2 (q2 moves nothing) has no closed form; the numeric method answers.
    """
    tol = AXIS_LENGTH_TOL * (1.0 + 0.5)  # the arm's size: its 0.5 m link (and the tiny one)
    arm = km.Robot.from_dh([km.Revolute(a=0.5), km.Revolute(a=factor * tol)], convention="standard")
    assert km.classify(arm).kind == "planar-2R"
    assert km.classify(arm).features.length_tol == pytest.approx(tol, rel=1e-8)
    res = arm.ik(arm.fk([0.3, 0.4])[:3, 3], seed=0)
    assert res.status in ("ok", "singular")
    assert res.method.startswith("numeric" if inside else "analytic")


# --- the elbow arms' uses -----------------------------------------------------------


def _elbow_candidates(robot: km.Robot, p: np.ndarray) -> tuple[np.ndarray, bool, bool, float]:
    closed = closed_form(robot.chain, "position")
    assert closed is not None and closed.name in ("anthropomorphic-3R", "elbow-3R")
    T = np.eye(4)
    T[:3, 3] = p
    Q, singular, near, gap, _ = closed.params.candidates(robot.chain.core, T)
    return Q, singular, near, gap


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_elbow_merge_tol_near_axis_1(factor: float, inside: bool) -> None:
    """MERGE_TOL in the elbow arms: a target within it (times the arm's size) of axis 1
    leaves q1 uncertain (near); the four candidates are still exact.
    """
    robot = ik_small.seed_anthropomorphic()  # size 0.65 m (links 0.35 and 0.3)
    p = np.array([factor * MERGE_TOL * 0.65, 0.0, ik_small.D1 + 0.5])
    Q, singular, near, _ = _elbow_candidates(robot, p)
    assert near is inside and not singular
    err = np.linalg.norm(robot.fk(Q)[:, :3, 3] - p, axis=1)
    assert (err < 1e-12).all()


@pytest.mark.parametrize("tangent", [True, False])
def test_elbow_merge_tol_of_the_height_equation(tangent: bool) -> None:
    """MERGE_TOL of the height equation A cos θ + B sin θ = e: its two roots merge when
    |e| / hypot(A, B) is within MERGE_TOL² of 1 (the target as far from axis 1 as the
    tool's height along k): near there; 1e-6 away from it (relative), not.
    """
    height = 0.1  # the tool's offset along axes 2 and 3
    robot = km.Robot.from_dh(
        [km.Revolute(d=0.4, alpha=math.pi / 2), km.Revolute(d=height, a=0.35), km.Revolute(a=0.3)],
        convention="standard",
    )
    assert km.classify(robot).kind == "anthropomorphic-3R"
    closed = closed_form(robot.chain, "position")
    assert closed is not None
    rho = height * (1.0 if tangent else 1.0 + 1e-6)  # distance of the target from axis 1
    p = np.array([0.0, rho, 0.4 + 0.3])
    _, singular, near, _ = _elbow_candidates(robot, p)
    assert near is tangent and not singular


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_elbow_singular_tol_frees_q1_on_axis_1(factor: float, inside: bool) -> None:
    """SINGULAR_TOL in the elbow arms: a target within it (times the arm's size) of axis 1
    (the tool's height 0) leaves q1 free: singular, joint 0 free, representatives at q1 = 0
    and π.
    """
    robot = ik_small.seed_anthropomorphic()
    p = np.array([factor * TRIANGLE_SINGULAR_TOL * 0.65, 0.0, ik_small.D1 + 0.5])
    res = robot.ik(p)
    assert (res.status == "singular") is inside
    assert (0 in res.free_joints) is inside


@pytest.mark.parametrize(("factor", "free"), [(0.1, False), (10.0, True)])
def test_singular_tol_tells_a_free_last_joint_from_one_solution(factor: float, free: bool) -> None:
    """SINGULAR_TOL, its third use: a position target of a planar 3R arm frees the last
    joint when a range of its turns wider than SINGULAR_TOL (times the reach) reaches it;
    closer to the stretched reach than that, the arm has one configuration.
    """
    robot = km.Robot.from_dh(
        [km.Revolute(a=0.4), km.Revolute(a=0.3), km.Revolute(a=0.2)], convention="standard"
    )
    reach = 0.9
    r = reach - factor * TRIANGLE_SINGULAR_TOL * reach  # the free range of lengths: reach - r
    closed = closed_form(robot.chain, "position")
    assert closed is not None
    T = np.eye(4)
    T[0, 3] = r
    _, singular, _, gap, free_mask = closed.params.candidates(robot.chain.core, T)
    assert singular is free and bool(free_mask & 0b100) is free
    assert math.isnan(gap)
    res = robot.ik(T[:3, 3])
    assert res.status == ("singular" if free else "ok"), res.message
