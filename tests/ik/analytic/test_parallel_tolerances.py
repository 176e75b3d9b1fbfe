"""The three-parallel family's named tolerances, each tested on both sides of its value.

As in the other tolerance tests, every case sits a factor 10 below or above
the value the constant's documentation states, written here as a literal (a test
that read the constant would move with it). The cases go to the family's internals
(``kinematica._core_testing.parallel``, the test-only module: the roots of
``a cos θ + b sin θ = c``, the q5 of a meeting wrist, the elbow triangle, Newton on
equations (1) and (2)) with inputs the test controls exactly; ``test_parallel_edges.py``
pins the same constants through ``robot.ik`` on targets placed by construction.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.typing import NDArray
from support import parallel_arms

from kinematica import _core, _core_testing
from kinematica.dh import Revolute
from kinematica.robot import Robot

parallel = _core.parallel
hooks = _core_testing.parallel
FloatArray = NDArray[np.float64]

# The documented values, one per constant (cpp/include/kinematica/solvers/parallel_*.hpp).
CONTINUUM_TOL = 1e-12
NEAR_TOL = 1e-6
DOUBLE_ROOT_TOL = 1e-14
NEWTON_QUIET = 1e-14
NEWTON_STEPS = 50
FREE_Q1_SAMPLES = 64
TRIG_TOL = 1e-10  # geometry.hpp: a miss below it is a root, above it near

#: A case a factor 10 inside a tolerance, and one a factor 10 outside it.
FACTORS = [(0.1, True), (10.0, False)]


def test_the_binding_exposes_the_documented_values() -> None:
    assert hooks.CONTINUUM_TOL == CONTINUUM_TOL
    assert hooks.NEAR_TOL == NEAR_TOL
    assert hooks.DOUBLE_ROOT_TOL == DOUBLE_ROOT_TOL
    assert hooks.NEWTON_QUIET == NEWTON_QUIET
    assert hooks.NEWTON_STEPS == NEWTON_STEPS
    assert hooks.FREE_Q1_SAMPLES == FREE_Q1_SAMPLES


# --- parallel_pairs.hpp: a cos θ + b sin θ = c (q1, or q5 of parallel axes 5 and 6) ---


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_double_root_tol_merges_two_angles(factor: float, inside: bool) -> None:
    """DOUBLE_ROOT_TOL: the two θ of a cos θ + b sin θ = c are one double root when
    r² - c² is below it times r² (r = hypot(a, b)): the branches merge, and the target
    is marked near.

    Tested on the internals: through robot.ik the check's deduplication (1e-7)
    merges roots ~sqrt(1e-15) apart as well, and hides the constant.
    """
    a, b = 3.0, 4.0
    r2 = a * a + b * b
    c = math.sqrt(r2 * (1.0 - factor * DOUBLE_ROOT_TOL))
    found, rise, fall, near = hooks.roots(a, b, c, 5.0)
    assert found and near is inside
    assert bool(rise == fall) is inside
    for theta in (rise, fall):
        assert a * math.cos(theta) + b * math.sin(theta) == pytest.approx(c, rel=1e-12)


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_near_tol_proposes_the_least_squares_angle(factor: float, inside: bool) -> None:
    """NEAR_TOL: |c| above r by less than it (times the equation's size) gives the
    least-squares angle twice and marks the target near; beyond it, no root.
    """
    a, b, size = 3.0, 4.0, 2.0
    c = 5.0 + factor * NEAR_TOL * size
    found, rise, fall, near = hooks.roots(a, b, c, size)
    assert found is inside
    if inside:
        assert near
        np.testing.assert_allclose([rise, fall], math.atan2(b, a), atol=1e-12)


# --- parallel_pairs.hpp: q5 of a wrist whose axes 5 and 6 meet -------------------------


def wrist_arm() -> tuple[float, ...]:
    """k·R5 h6 = 0.6 cos q5 + 0.2: it ranges over [-0.4, 0.8] (wlo, whi exact):
    ``(D1, E1, F1, wlo, whi)``."""
    return 0.6, 0.0, 0.2, 1.0 - 0.6 - 0.2, 1.0 - 0.6 + 0.2  # wlo, whi: 1 - |D1, E1| ∓ F1


@pytest.mark.parametrize(
    ("miss", "code"),
    [(-1e-3, 1), (0.1 * TRIG_TOL, 0), (0.1 * NEAR_TOL, 0), (10.0 * NEAR_TOL, -1)],
)
def test_wrist_beyond_its_range(miss: float, code: int) -> None:
    """k1·R_G h6 = d above the largest k·R5 h6 (0.8) by ``miss``: below it two roots;
    at it to round-off, or above by up to NEAR_TOL, near (the double root proposed:
    the wrist's two branches merge there); beyond it none.
    """
    d = 0.8 + miss
    got, q5_no_flip, q5_flip = hooks.wrist(*wrist_arm(), d, (1.0 - d) * (1.0 + d))
    assert got == code
    if code >= 0:  # the extremum: q5 = 0 both times (or ±0.05 rad for miss = -1e-3)
        assert abs(q5_no_flip) < 0.1 and abs(q5_flip) < 0.1
        assert (abs(q5_no_flip) < 1e-5) is (code == 0)
    else:
        assert math.isnan(q5_no_flip) and math.isnan(q5_flip)


def test_wrist_inside_its_range_has_two_roots() -> None:
    d = 0.5  # 0.6 cos q5 + 0.2 = 0.5: q5 = ±acos(0.5)
    got, q5_no_flip, q5_flip = hooks.wrist(*wrist_arm(), d, (1.0 - d) * (1.0 + d))
    assert got == 1
    assert q5_no_flip == pytest.approx(math.acos(0.5), abs=1e-15)
    assert q5_flip == pytest.approx(-math.acos(0.5), abs=1e-15)


# --- parallel.hpp: the elbow triangle -----------------------------------------------


def triangle(a: float, b: float, u: float, slack: float = 0.0) -> tuple[float, ...]:
    """The elbow triangle of links a, b along the plane's x axis, up along y, q2rep 0.25,
    putting axis 4 at (u, 0)."""
    return tuple(hooks.triangle(a, b, 0.0, 0.0, [0.0, 1.0], 0.25, slack, u, 0.0))


@pytest.mark.parametrize(
    ("miss", "flags"),
    [(-1e-3, 0), (0.1 * TRIG_TOL, 2), (0.1 * NEAR_TOL, 2), (10.0 * NEAR_TOL, -1)],
)
def test_triangle_beyond_the_stretched_arm(miss: float, flags: int) -> None:
    """Axis 4 beyond the stretched elbow (span a + b) by ``miss`` times the span: short
    of it two elbows; past it by up to NEAR_TOL near (the stretched elbow proposed, the
    two elbows merging there); none beyond.
    """
    a, b = 0.5, 0.4
    got, q2_up, psi_up, q2_down, psi_down = triangle(a, b, (a + b) * (1.0 + miss))
    assert got == flags
    if flags == 2:  # stretched: q2 = 0, ψ = 0 for both elbows
        np.testing.assert_allclose([q2_up, psi_up, q2_down, psi_down], 0.0, atol=1e-4)
    elif flags == 0:  # short of it by 1e-3 of the span: two elbows a few degrees apart
        assert abs(psi_up - psi_down) > 1e-2
    else:
        assert math.isnan(q2_up) and math.isnan(q2_down)


@pytest.mark.parametrize(
    ("factor", "inside"), [(0.1, True), (10.0, False), (-0.5, True), (-2.0, False)]
)
@pytest.mark.parametrize("folded", [False, True])
def test_triangle_straddles_the_fold_within_the_slack(
    factor: float, inside: bool, folded: bool
) -> None:
    """A near-degenerate arm's triangle (slack 1e-9 m): where 1 - cos γ (stretched) or
    1 + cos γ (folded) is below slack (2 |tx| + slack) / (2 a b), the two elbows are
    put either side of the fold, that side raised by as much (beyond the reach by half of
    it too: factor -0.5); above it, or beyond the reach by more (-2), the elbows of the
    exact arm (there its least-squares fold, twice)."""
    a, b, slack = 0.5, 0.4, 1e-9
    edge = abs(a - b) if folded else a + b
    margin = slack * (2.0 * edge + slack) / (2.0 * a * b)  # |tx| at the fold
    n = math.sqrt(edge * edge + (1.0 if folded else -1.0) * factor * margin * 2.0 * a * b)
    exact = triangle(a, b, n)
    got = triangle(a, b, n, slack)
    assert got[0] == exact[0]  # the exact triangle's flags
    if not inside:
        assert got == exact
        return
    psi_up, psi_down = got[2], got[4]
    assert psi_up == pytest.approx(-psi_down, rel=1e-12)  # one on each side of the fold
    side = (1.0 + math.cos(psi_up)) if folded else (1.0 - math.cos(psi_up))
    assert side == pytest.approx((factor + 1.0) * margin, rel=1e-4)


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_continuum_tol_folds_equal_links(factor: float, inside: bool) -> None:
    """CONTINUUM_TOL: with equal links, axis 4 within it (of the span) from axis 2 is
    the folded elbow (q2 free: its representative, then NaN); beyond it two elbows.
    """
    a = 0.4
    got, q2_up, psi_up, q2_down, psi_down = triangle(a, a, factor * CONTINUUM_TOL * 2.0 * a)
    if inside:
        assert got == 1 and q2_up == 0.25 and psi_up == pytest.approx(math.pi)
        assert math.isnan(q2_down) and math.isnan(psi_down)
    else:
        assert got == 0
        assert abs(abs(psi_up) - math.pi) < 1e-9 and abs(abs(psi_down) - math.pi) < 1e-9
        assert q2_up != q2_down


# --- parallel_quartic.hpp: polishing the quartic's roots ----------------------------


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_newton_quiet_makes_a_small_step_the_last(factor: float, inside: bool) -> None:
    """NEWTON_QUIET: Newton on equations (1) and (2) started ``factor * NEWTON_QUIET``
    (rad) from a root takes that step and stops when it is below the constant (one
    evaluation), and evaluates once more above it. Either way it lands on the root
    (the q5 and q1 that made the target) to round-off, with the cosines and sines of
    where it lands.

    (1) and (2) are set up here from the family's equations: ``G = T M⁻¹``,
    ``x6 = R_G h6``, ``w6 = G(p6) - p1``, sides ``(k⊥·y, (h1 × k)·y, k∥·y)``.
    """
    robot = parallel_arms.UR5_A5
    P = hooks.values(robot.chain.core)  # the built arm's Params, as a dict
    assert P is not None and P["mode"] == parallel.Mode.general
    T, M = robot.fk(np.array([0.4, -1.1, 1.3, 0.2, 0.9, -0.5])), robot.fk(np.zeros(6))
    RG = T[:3, :3] @ M[:3, :3].T
    x6 = RG @ P["h6"]
    w6 = RG @ P["p6"] + T[:3, 3] - RG @ M[:3, 3] - P["p1"]
    L1, L2 = (np.array([P[v] @ y for v in ("kperp", "hk", "kpar")]) for y in (x6, w6))
    core = robot.chain.core
    q1, q5, res, *_ = hooks.newton(core, x6, L1, L2, 0.4 + 1e-3, 0.9 - 1e-3)
    assert res < 1e-14
    assert abs(q1 - 0.4) < 1e-15 and abs(q5 - 0.9) < 1e-15  # the q that made T
    a1, a5, _, evaluations, c1, s1, c5, s5 = hooks.newton(
        core, x6, L1, L2, q1, q5 + factor * NEWTON_QUIET
    )
    assert evaluations == (1 if inside else 2)
    assert abs(a1 - 0.4) < 1e-15 and abs(a5 - 0.9) < 1e-15
    # the cosines and sines returned are those of the angles returned (turned by the
    # last step to first order when it was that small)
    for got, want in (
        (c1, math.cos(a1)),
        (s1, math.sin(a1)),
        (c5, math.cos(a5)),
        (s5, math.sin(a5)),
    ):
        assert abs(got - want) <= 4e-16  # a few ulps


def test_newton_stops_where_there_is_no_root() -> None:
    """Far from every root the steps stop shrinking: Newton gives up well before
    NEWTON_STEPS and says how far (1) and (2) are from holding."""
    robot = parallel_arms.UR5_A5
    x6 = np.array([0.0, 0.0, 1.0])
    L1 = np.array([0.0, 0.0, 5.0])  # (1) misses by about 4: no root
    L2 = np.array([0.0, 0.0, 0.0])
    *_, res, evaluations, _c1, _s1, _c5, _s5 = hooks.newton(robot.chain.core, x6, L1, L2, 0.3, 0.2)
    assert res > 1.0
    assert 1 <= evaluations < NEWTON_STEPS


# --- parallel.hpp: the representative of a continuum in which q1 turns ----------------


def narrow_arc_arm(rep: float) -> Robot:
    """The UR5 with axes 5 and 6 parallel 1 cm apart (α5 = 0, a5 = 0.01), q1's limits
    about ``rep`` (the q1 a continuum in q1 is first represented at: their middle)."""
    rows = [*parallel_arms.UR5_ROWS[:4], Revolute(d=0.09465, a=0.01), parallel_arms.UR5_ROWS[5]]
    rows[0] = Revolute(d=0.089159, alpha=math.pi / 2, qlim=(rep - 1.0, rep + 1.0))
    return Robot.from_dh(rows, convention="standard")


#: Axes 5 and 6 parallel to axis 1 (q2 + q3 + q4 = 0): (1) holds for every q1, and (2)
#: gives q5 while |its left side| <= its amplitude (about a5 = 1 cm): an arc of q1.
NARROW_Q = np.array([0.4, -1.2, 1.5, -0.3, 0.8, -0.6])


def arc_of_q1(robot: Robot, q: FloatArray) -> tuple[float, float]:
    """The arc of q1 about q[0] over which (2), k1·(G(p6) - p1) = D2 cos q5 + E2 sin q5 +
    F2, has a root q5 (the arm's equation (2): parallel_pairs.hpp), found on a fine grid."""
    P = hooks.values(robot.chain.core)
    assert P is not None and P["mode"] == parallel.Mode.parallel
    G = robot.fk(q) @ np.linalg.inv(P["home"])
    w6 = G[:3, :3] @ P["p6"] + G[:3, 3] - P["p1"]
    a, b, c = (float(P[v] @ w6) for v in ("kperp", "hk", "kpar"))
    x = q[0] + np.linspace(-0.5, 0.5, 1_000_001)
    ok = np.abs(a * np.cos(x) + b * np.sin(x) + c - P["F2"]) <= math.hypot(P["D2"], P["E2"])
    mid = len(x) // 2
    assert ok[mid]
    lo = mid - int(np.argmin(ok[mid::-1]))
    hi = mid + int(np.argmin(ok[mid:]))
    return float(x[lo + 1]), float(x[hi - 1])


@pytest.mark.parametrize("inside", [True, False])
def test_free_q1_samples_steps_over_an_arc_shorter_than_its_step(inside: bool) -> None:
    """FREE_Q1_SAMPLES: a continuum in q1 is represented at the first of q1rep, q1rep ±
    2π/64, ± 2·2π/64, ... that the other joints follow. Its arc here is 0.038 rad long,
    shorter than the step (0.098 rad). With q1rep a step and 0.005 rad beyond the arc's
    middle, the step back lands in it (inside); with q1rep half a step from the middle,
    the grid's points fall 0.049 rad either side of the middle, past the arc's ends: the
    target is not found (and near, never unreachable). A grid a thousand times finer
    finds it there; one of q1rep alone does not, inside either."""
    step = 2.0 * math.pi / FREE_Q1_SAMPLES
    lo, hi = arc_of_q1(narrow_arc_arm(0.0), NARROW_Q)
    assert 0.03 < hi - lo < step / 2  # between two grid points, either side of the middle
    middle = 0.5 * (lo + hi)
    rep = middle + step + 0.005 if inside else middle + step / 2
    robot = narrow_arc_arm(rep)
    T = robot.fk(NARROW_Q)
    res = robot.ik(T, respect_limits=False)
    if inside:
        assert res.status == "singular" and 0 in res.free_joints
        assert lo <= res.solutions[0, 0] <= hi
        assert abs(res.solutions[0, 0] - (rep - step)) < 1e-12
        parallel_arms.assert_reaches(robot, res, T)
    else:
        assert res.status == "not_found" and res.near_singular


def test_internals_reject_bad_input() -> None:
    with pytest.raises(ValueError, match="size"):
        hooks.roots(3.0, 4.0, 5.0, 0.0)
    with pytest.raises(ValueError, match="finite"):
        hooks.roots(math.nan, 4.0, 5.0, 1.0)
    core = parallel_arms.UR5_A5.chain.core
    with pytest.raises(ValueError, match="L1"):
        hooks.newton(core, [0.0, 0.0, 1.0], [1.0, 2.0], [0.0, 0.0, 0.0], 0.0, 0.0)
    with pytest.raises(ValueError, match="zup"):
        hooks.triangle(0.5, 0.4, 0.0, 0.0, np.zeros(3), 0.0, 0.0, 0.5, 0.0)
    planar = Robot.from_dh([Revolute(a=0.3)] * 6, convention="standard")  # declined
    assert hooks.values(planar.chain.core) is None
    with pytest.raises(ValueError, match="declines"):
        hooks.newton(planar.chain.core, [0.0, 0.0, 1.0], [0.0] * 3, [0.0] * 3, 0.0, 0.0)
    with pytest.raises(TypeError):  # the core's builder alone fills a family's Params
        parallel.ParallelParams()
