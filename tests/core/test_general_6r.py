"""The general 6R solver's header (cpp/include/kinematica/solvers/general_6r.hpp) as bound.

Its Params refuse fields the solver cannot run with (a ValueError naming the field),
its tolerances are exported under the names the header gives them, and each named
tolerance decides a case just inside its boundary one way and one just outside the
other (through the binding's hooks real_root, null_vector and trace, which run the
header's own code).
"""

from __future__ import annotations

import math
from typing import Any

import kinematica._core as _core
import numpy as np
import pytest
from support.general6r import G, field, labelling

import kinematica as km
from kinematica.ik.analytic import general_6r as g6


def _chain() -> km.core.Chain:
    arm = g6.sample_arm(np.random.default_rng(2), False)
    return km.Robot.from_dh(arm.links, convention=arm.convention).chain


def test_params_fields_are_checked() -> None:
    p = G.blank()
    T = np.eye(4)
    chain = _chain()
    G.set(p, t_link=6)
    with pytest.raises(ValueError, match="t_link"):
        p.candidates(chain.core, T)
    G.set(p, t_link=5)
    G.set(p, order=np.array([0, 0, 1, 2, 3, 4]))
    with pytest.raises(ValueError, match="permutation"):
        p.candidates(chain.core, T)
    with pytest.raises(ValueError, match=r"N must have shape \(6, 14\)"):
        G.set(p, N=np.zeros((14, 6)))


def test_the_header_s_constants_are_exported() -> None:
    g = G
    assert g.SLOTS == g.CLASSES * g.PER_CLASS + g.FURTHER == len(g6.LABELS)
    assert (g.EQUATIONS, g.PRODUCTS, g.REDUCED) == (14, 8, 6)
    assert 0 < g.LEADING_RCOND_TOL < g.CLOSURE_TOL < 1
    # a candidate that closes is one the check polishes (its POLISH_LIMIT: 1e-5)
    assert g.CLOSURE_TOL < 1e-5


# ------------------------------------------------- the tolerances, from both sides
#: Just inside / just outside a boundary: the tolerance times (1 ∓ this).
EDGE = 1e-6

# The documented values (general_6r.hpp), which the boundary cases below are made from.
REAL_ROOT_TOL = 1e-4
LEADING_RCOND_TOL = 1e-8
SECOND_SHIFT = 1.1
CLOSURE_TOL = 5e-6
REFINE_LIMIT = 1e-1
SPLIT_CLOSURE_TOL = 1e-12
REFINE_STEPS = 8


def test_the_documented_values_are_the_core_s() -> None:
    g = G
    assert g.REAL_ROOT_TOL == REAL_ROOT_TOL
    assert g.LEADING_RCOND_TOL == LEADING_RCOND_TOL
    assert g.SECOND_SHIFT == SECOND_SHIFT
    assert g.CLOSURE_TOL == CLOSURE_TOL
    assert (g.REFINE_LIMIT, g.SPLIT_CLOSURE_TOL, g.REFINE_STEPS) == (
        REFINE_LIMIT,
        SPLIT_CLOSURE_TOL,
        REFINE_STEPS,
    )


def _robot_and_params(seed: int) -> tuple[km.Robot, Any]:
    """A random general 6R arm and Params of its own (not the cached solver's: tests edit
    them), of its first labelling (the builder's choice may change with its ranking)."""
    arm = g6.sample_arm(np.random.default_rng(seed), False)
    robot = km.Robot.from_dh(arm.links, convention=arm.convention, base=arm.base, tool=arm.tool)
    built = labelling(robot.chain, 0, False)
    assert built is not None
    return robot, built[0]


def test_real_root_tol_bounds_the_imaginary_part_relative_to_1_plus_the_modulus() -> None:
    g = G
    for re in (0.0, 2.0, -50.0):
        for im_scale in (1.0, -1.0):
            # |Im x| = t (1 + |x|) solved for t's boundary: |x| depends on Im x itself
            im = REAL_ROOT_TOL * (1.0 + abs(re))
            for _ in range(50):  # fixed point of im = tol (1 + |re + i im|)
                im = REAL_ROOT_TOL * (1.0 + abs(complex(re, im)))
            assert g.real_root(re, im_scale * im * (1.0 - EDGE))
            assert not g.real_root(re, im_scale * im * (1.0 + EDGE))
    assert g.real_root(3.0, 0.0)


def test_the_null_vector_spans_m_s_null_space() -> None:
    # M: a well-conditioned 10 x 10 block R, a pivot s and a zero one, rows and columns
    # permuted; full pivoting takes R's pivots first (largest |R_ij| first), then s, then 0
    g = G
    rng = np.random.default_rng(3)
    R = np.eye(10) + 0.1 * rng.standard_normal((10, 10))
    rows, cols = rng.permutation(12), rng.permutation(12)
    for s in (1e-3, 1e-9):
        D = np.zeros((12, 12))
        D[:10, :10], D[10, 10] = R, s
        M = D[rows][:, cols]
        u = g.null_vector(M)
        # u spans the zero column's direction: M u = 0 (independent: the matrix built)
        assert np.abs(M @ u).max() <= 1e-12 * np.abs(u).max()
        assert np.abs(u[cols != 11]).max() <= 1e-12 * abs(u[cols == 11][0])


def test_leading_rcond_tol_chooses_the_second_shift_just_below_it() -> None:
    # q'6 = phi6 + π + d puts a root of det M at x6 = -cot(d/2) ≈ -2/d: A2's rcond is
    # proportional to d (below d ~ 1e-4). Measured slope, then d for rcond at 3x and 1/3x
    # the tolerance: the first shift is kept above it, the second taken below; the loop
    # closes either way.
    g = G
    rng = np.random.default_rng(9)
    robot, params = _robot_and_params(9)
    q = rng.uniform(-math.pi, math.pi, 6)
    j = int(field(params, "order")[5])

    def trace(d: float) -> tuple[float, float, float, bool]:
        q[j] = math.remainder(field(params, "sign") * (G.PHI[2] + math.pi + d), 2 * math.pi)
        return g.trace(params, robot.fk(q))[:4]

    slope = trace(1e-6)[0] / 1e-6
    assert trace(1e-7)[0] == pytest.approx(slope * 1e-7, rel=0.01)
    for factor, shift in ((3.0, G.PHI[2]), (1.0 / 3.0, G.PHI[2] + SECOND_SHIFT)):
        rcond, shift6, closure, near = trace(factor * LEADING_RCOND_TOL / slope)
        assert rcond == pytest.approx(factor * LEADING_RCOND_TOL, rel=0.01)
        assert shift6 == pytest.approx(shift, abs=1e-15)
        assert closure <= 1e-10 and not near


def _opened(seed: int, refine: bool = False) -> tuple[km.Robot, Any, np.ndarray, Any]:
    """A random arm, its Params, a pose, and ``miss(eps)``: c0 moved by eps along a row of
    N, so that the elimination's equations hold where the loop is open, its candidates'
    smallest miss (the pose they make against the target, m or rad) proportional to eps.
    The pose is reachable (FK of a random q): Newton's method on the full pose from a
    candidate (``refine``) finds the solution the elimination missed."""
    g = G
    robot, params = _robot_and_params(seed)
    G.set(params, refine_misses=refine)
    T = robot.fk(np.random.default_rng(1).uniform(-math.pi, math.pi, 6))
    # the direction: the left null space's projection of a fixed vector (whatever basis
    # of that space the SVD gives N)
    N = np.array(field(params, "N"))
    row = N.T @ (N @ np.linspace(1.0, 2.0, 14))
    c0, row = np.array(field(params, "c0")), row / np.linalg.norm(row)

    def miss(eps: float) -> tuple[float, bool]:
        G.set(params, c0=c0 + eps * row)
        _, _, c, near, _, _ = g.trace(params, T)
        return c, near

    return robot, params, T, miss


def test_closure_tol_separates_a_loop_that_closes_from_one_that_cannot() -> None:
    # With eps for a miss of 1/2 and 2 times CLOSURE_TOL, near flips; unperturbed the
    # loop closes to round-off.
    robot, params, T, miss = _opened(9)
    assert miss(0.0)[0] <= 1e-12
    slope = miss(1e-8)[0] / 1e-8
    assert miss(1e-7)[0] == pytest.approx(slope * 1e-7, rel=0.05)
    for factor in (0.5, 2.0):
        c, near = miss(factor * CLOSURE_TOL / slope)
        assert c == pytest.approx(factor * CLOSURE_TOL, rel=0.1)
        assert near == (factor > 1.0)
        _, _, flag, _, _ = params.candidates(robot.chain.core, T)  # the public raw call agrees
        assert flag == near


def test_the_miss_is_the_pose_error_the_check_measures() -> None:
    # the candidate of smallest miss, through forward kinematics: the same number
    robot, params, T, miss = _opened(9)
    c, _ = miss(3e-6)
    Q = params.candidates(robot.chain.core, T)[0]
    Q = Q[np.isfinite(Q[:, 0])]
    F = robot.fk(Q)
    pos = np.linalg.norm(F[:, :3, 3] - T[:3, 3], axis=1)
    rot = np.array([km.rotation_angle(f[:3, :3], T[:3, :3]) for f in F])
    assert np.maximum(pos, rot).min() == pytest.approx(c, rel=1e-6)


def test_candidates_that_miss_beyond_the_polish_make_no_unreachable_without_a_gap() -> None:
    # Every candidate 2e-5 off (beyond the check's polish, 1e-5) and no reach gap: the
    # elimination proves nothing, so the closed form's own answer (the core's, before
    # any search) is not_found, near raised; never "unreachable" with no gap.
    robot, params, T, miss = _opened(9)
    c, near = miss(0.0)
    slope = miss(1e-8)[0] / 1e-8
    c, near = miss(2e-5 / slope)
    assert 1.5e-5 < c < 3e-5 and near
    opts = _core.CheckOptions()
    opts.complete = True
    one = params.ik(robot.chain.core, T, opts, None, tuple(g6.LABELS))
    assert one.status == _core.STATUS["not_found"] and one.gap is None and one.near_singular


def _eps_for(miss: Any, target: float) -> float:
    """eps for which the smallest miss is ``target`` (to 1 %): the first eps of a log grid
    past it, then bisection on log scale (the miss is linear only near 0)."""
    grid = np.geomspace(1e-8, 10.0, 91)
    above = next(i for i, e in enumerate(grid) if miss(e)[0] >= target)
    lo, hi = math.log(grid[above - 1]), math.log(grid[above])
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        now = miss(math.exp(mid))[0]
        if abs(now / target - 1.0) < 0.01:
            return math.exp(mid)
        lo, hi = (mid, hi) if now < target else (lo, mid)
    raise AssertionError(f"no eps gives a miss of {target}")


def test_refine_limit_bounds_the_candidates_newton_takes_to_a_solution() -> None:
    # Without refinement the smallest miss is 1/2 or 2 times REFINE_LIMIT; with it, the
    # first is carried to the solution (the pose is reachable), the second left alone.
    g = G
    _, params, T, miss = _opened(9)
    for factor in (0.5, 2.0):
        eps = _eps_for(miss, factor * REFINE_LIMIT)
        G.set(params, refine_misses=True)
        _, _, closure, near, _, _ = g.trace(params, T)
        G.set(params, refine_misses=False)
        if factor < 1.0:
            assert closure <= 1e-12 and not near
        else:
            assert closure == pytest.approx(miss(eps)[0], rel=1e-12) and near


def test_every_candidate_below_refine_limit_is_taken_to_round_off() -> None:
    # A smallest miss of 1e-13 or 1e-11 (the check would take either as it is: its
    # tolerance 1e-10; at σmin = 1e-5 that is 1e-8 or 1e-6 in the joints) is taken by
    # Newton's method to round-off (eps from a grid: near round-off the miss is not linear).
    g = G
    _, params, T, miss = _opened(9)
    for target in (1e-13, 1e-11):
        # (the search leaves c0 moved by the eps it stops at)
        next(e for e in np.geomspace(1e-15, 1e-8, 400) if target < miss(e)[0] < 5 * target)
        G.set(params, refine_misses=True)
        closure = g.trace(params, T)[2]
        G.set(params, refine_misses=False)
        assert closure < 2e-15 < target


def test_split_closure_tol_keeps_a_split_pair_s_candidate_newton_closes() -> None:
    # The decision at its boundary; and the margins it sits between: a candidate Newton
    # takes to a solution is at round-off (measured: the smallest miss of refined
    # candidates on random poses), a fold's near miss split into a pair is about 1e-8 or
    # more off the target (|Im x| past REAL_ROOT_TOL = 1e-4 grows as the miss's square
    # root: the header's estimate, not measured here).
    g = G
    assert g.split_closes(SPLIT_CLOSURE_TOL * (1 - EDGE))
    assert not g.split_closes(SPLIT_CLOSURE_TOL * (1 + EDGE))
    robot, params = _robot_and_params(4)
    G.set(params, refine_misses=True)
    q = np.random.default_rng(2).uniform(-math.pi, math.pi, (5, 6))
    closures = [g.trace(params, T)[2] for T in robot.fk(q)]
    assert max(closures) < 1e-2 * g.SPLIT_CLOSURE_TOL
    assert 1e2 * g.SPLIT_CLOSURE_TOL < 1e-8


def test_candidates_that_miss_beyond_the_polish_are_carried_to_the_solutions() -> None:
    # The case above of candidates 2e-5 off, refined: every candidate's solution found,
    # the configuration that made the pose among them, the loop closed to round-off.
    robot, params, T, miss = _opened(9)
    q = np.random.default_rng(1).uniform(-math.pi, math.pi, 6)
    plain = params.candidates(robot.chain.core, T)[0]
    eps = _eps_for(miss, 2e-5)
    G.set(params, refine_misses=True)
    c, near = miss(eps)
    assert c <= 1e-12 and not near
    opts = _core.CheckOptions()
    opts.complete = True
    one = params.ik(robot.chain.core, T, opts, None, tuple(g6.LABELS))
    sols = one.solutions
    assert one.status == _core.STATUS["ok"]
    assert len(sols) == np.isfinite(plain[:, 0]).sum()
    d = np.abs(np.remainder(sols - q + math.pi, 2 * math.pi) - math.pi).max(axis=1)
    assert d.min() <= 1e-9
