"""The real roots of the general 6R's det M(x) (``solvers/general_6r_roots.hpp``).

Against matrix polynomials built with known roots: M(x) = U diag(d_k(x)) V with U, V
constant and well conditioned, so det M = det U det V Π d_k(x). Four d_k = 1 + x²
give the structure of the elimination (8 roots at ±i, M(i) of nullity 4; up to
MAX_NULLITY such factors are deflated), the others
(x - a)(x - b) or a complex pair: the real roots are exactly the real a, b. The
deflation's tolerance SPURIOUS_TOL is pinned from both sides on matrices whose
elimination's pivots are set by construction.
"""

from __future__ import annotations

import numpy as np
import pytest
from support.general6r import G

#: The documented value (general_6r_roots.hpp).
SPURIOUS_TOL = 1e-9
#: Just inside / just outside a boundary: the tolerance times (1 ∓ this).
EDGE = 1e-6
#: Roots of a well-conditioned M agree with the constructed ones to this.
ROOT_TOL = 1e-10


def test_the_documented_value_is_the_core_s() -> None:
    assert G.SPURIOUS_TOL == SPURIOUS_TOL


def _quadratic(rng: np.random.Generator, factors: list[tuple[float, float, float]]) -> list:
    """A0, A1, A2 of U diag(c + b x + a x²) V for the 12 factors (c, b, a)."""
    U = np.linalg.qr(rng.standard_normal((12, 12)))[0] @ np.diag(rng.uniform(1, 2, 12))
    V = np.linalg.qr(rng.standard_normal((12, 12)))[0]
    return [U @ np.diag([f[k] for f in factors]) @ V for k in range(3)]


def _real_pair(a: float, b: float) -> tuple[float, float, float]:
    return (a * b, -(a + b), 1.0)


SPURIOUS_FACTOR = (1.0, 0.0, 1.0)  # 1 + x²


def test_the_roots_at_plus_minus_i_are_deflated_and_the_real_ones_found() -> None:
    rng = np.random.default_rng(1)
    for trial in range(5):
        real = np.sort(rng.uniform(-4.0, 4.0, 2 * (3 + trial % 3)))
        pairs = [_real_pair(real[2 * k], real[2 * k + 1]) for k in range(len(real) // 2)]
        # complex pairs (x - p)² + s², s not small: never a real root
        pairs += [
            (p * p + s * s, -2 * p, 1.0) for p, s in rng.uniform(0.5, 2.0, (8 - len(pairs), 2))
        ]
        A = _quadratic(rng, [SPURIOUS_FACTOR] * 4 + pairs)
        roots, deflated = G.real_roots(*A)
        assert deflated
        np.testing.assert_allclose(np.sort(roots), real, atol=ROOT_TOL)


def test_without_the_spurious_structure_the_whole_problem_is_solved() -> None:
    # three factors 1 + x² only: M(i) has nullity 3, not 4; the 24 x 24 problem gives
    # the same real roots (the ±i ones, and a root at 1 + x² = 0 spare, are no real root)
    rng = np.random.default_rng(2)
    real = [-2.0, -0.5, 0.25, 1.5, 3.0, 3.5]
    pairs = [_real_pair(real[2 * k], real[2 * k + 1]) for k in range(3)]
    pairs += [(1.0, 0.5, 1.0)] * 6
    A = _quadratic(rng, [SPURIOUS_FACTOR] * 3 + pairs)
    roots, deflated = G.real_roots(*A)
    assert not deflated
    np.testing.assert_allclose(np.sort(roots), real, atol=ROOT_TOL)


def _pivots(r8: float, r9: float) -> list[np.ndarray]:
    """A0 (A1 = A2 = 0, so M(i) = A0) whose full-pivot elimination has pivots 1 (7 of them,
    first the largest entry 1), then r8, then r9, then zeros; rows and columns permuted."""
    rng = np.random.default_rng(3)
    D = np.zeros((12, 12))
    D[:7, :7] = np.eye(7)
    D[7, 7], D[8, 8] = r8, r9
    rows, cols = rng.permutation(12), rng.permutation(12)
    return [D[rows][:, cols], np.zeros((12, 12)), np.zeros((12, 12))]


@pytest.mark.parametrize("side", [1.0 - EDGE, 1.0 + EDGE])
def test_spurious_tol_bounds_the_ninth_pivot(side: float) -> None:
    # the ninth pivot just below the tolerance: a null space of 4, deflated; just above
    # it: 3 (the tenth is 0), the elimination's structure lost, not deflated
    nullity, last, small = G.spurious_pivots(*_pivots(0.5, SPURIOUS_TOL * side))
    if side < 1.0:
        assert nullity == 4
        assert last == pytest.approx(0.5) and small == pytest.approx(SPURIOUS_TOL * side, rel=1e-12)
    else:
        assert nullity == 0
        assert last == pytest.approx(SPURIOUS_TOL * side, rel=1e-12) and small == 0.0


@pytest.mark.parametrize("side", [1.0 - EDGE, 1.0 + EDGE])
def test_spurious_tol_bounds_the_eighth_pivot_from_below(side: float) -> None:
    # the eighth pivot just below the tolerance: a fifth null direction not at round-off
    # (a near-degenerate arm), not deflated; just above it: the four, deflated
    nullity, last, small = G.spurious_pivots(*_pivots(SPURIOUS_TOL * side, 0.0))
    assert nullity == (0 if side < 1.0 else 4)
    assert (small if side < 1.0 else last) == pytest.approx(SPURIOUS_TOL * side, rel=1e-12)


@pytest.mark.parametrize("side", [1.0 - EDGE, 1.0 + EDGE])
def test_extra_null_tol_bounds_a_fifth_null_direction(side: float) -> None:
    # a fifth null direction at EXTRA_NULL_TOL: just below, deflated with the others
    # (det M with (1 + x²)⁵); just above, not (a near-degenerate arm's)
    assert G.EXTRA_NULL_TOL == 1e-13  # the documented value
    nullity, _, small = G.spurious_pivots(*_pivots(G.EXTRA_NULL_TOL * side, 0.0))
    assert small == pytest.approx(G.EXTRA_NULL_TOL * side, rel=1e-12)
    assert nullity == (5 if side < 1.0 else 0)


@pytest.mark.parametrize("extra", [1, 2, 3])
def test_more_roots_at_plus_minus_i_are_deflated_up_to_max_nullity(extra: int) -> None:
    # det M with (1 + x²)^(4 + extra) (an exact arm's special structure: a Franka Panda
    # held at q1 has 6): deflated whole up to MAX_NULLITY, the 24 x 24 problem beyond;
    # the real roots the same either way
    assert G.MAX_NULLITY == 6  # the documented value
    rng = np.random.default_rng(5 + extra)
    real = [-2.0, -0.5, 0.25, 1.5]
    pairs = [_real_pair(-2.0, -0.5), _real_pair(0.25, 1.5)]
    pairs += [(1.0, 0.5, 1.0)] * (6 - extra)
    A = _quadratic(rng, [SPURIOUS_FACTOR] * (4 + extra) + pairs)
    nullity, _, _ = G.spurious_pivots(*A)
    assert nullity == (4 + extra if 4 + extra <= G.MAX_NULLITY else 0)
    roots, deflated = G.real_roots(*A)
    assert deflated == (nullity > 0)
    np.testing.assert_allclose(np.sort(roots), real, atol=ROOT_TOL)


def _split_boundary(x0: float) -> float:
    """s with s = SPLIT_ROOT_TOL (1 + |x0 + i s|): the pair x0 ± i s on the boundary."""
    s = 0.0
    for _ in range(60):
        s = G.SPLIT_ROOT_TOL * (1.0 + abs(complex(x0, s)))
    return s


@pytest.mark.parametrize("side", [1.0 - EDGE, 1.0 + EDGE])
def test_split_root_tol_turns_a_nearly_real_pair_into_two_candidates(side: float) -> None:
    # a pair x0 ± i s just inside the tolerance gives x0 - s and x0 + s; just outside,
    # nothing; the real roots come out either way
    assert G.SPLIT_ROOT_TOL == 1e-2  # the documented value
    rng = np.random.default_rng(4)
    x0 = 1.5
    s = _split_boundary(x0) * side
    real = [-2.0, -1.0, 0.5, 3.0]
    factors = [SPURIOUS_FACTOR] * 4 + [_real_pair(-2.0, -1.0), _real_pair(0.5, 3.0)]
    factors += [(x0 * x0 + s * s, -2 * x0, 1.0)] + [(1.0, 0.5, 1.0)] * 5
    roots, deflated = G.real_roots(*_quadratic(rng, factors))
    assert deflated
    expected = sorted(real + ([x0 - s, x0 + s] if side < 1.0 else []))
    np.testing.assert_allclose(np.sort(roots), expected, atol=ROOT_TOL)


def test_qz_finds_the_real_roots_and_the_one_at_infinity_where_a2_is_singular() -> None:
    # a factor x - 0.7 of degree 1: A2 of rank 11, det M of degree 23 (a root at x = ∞,
    # q' = shift + π); QZ forms no inverse of A2 and gives it as 1e300
    rng = np.random.default_rng(4)
    real = [-2.0, -0.5, 0.25, 0.7, 1.5, 3.0, 3.5]
    pairs = [_real_pair(a, b) for a, b in ((-2.0, -0.5), (0.25, 1.5), (3.0, 3.5))]
    A = _quadratic(rng, [SPURIOUS_FACTOR] * 4 + pairs + [(-0.7, 1.0, 0.0)] + [(1.0, 0.5, 1.0)] * 4)
    assert np.linalg.matrix_rank(A[2]) == 11
    roots, split = G.real_roots_qz(*A)
    assert not split.any()
    roots = np.sort(roots)
    assert roots[-1] == 1e300
    np.testing.assert_allclose(roots[:-1], real, atol=ROOT_TOL)
    # the same pencil with A2 regular (the factor (x - 0.7)(1 + x/10)): the companion
    # matrix's roots and QZ's agree
    A = _quadratic(rng, [SPURIOUS_FACTOR] * 4 + pairs + [(-0.7, 0.93, 0.1)] + [(1.0, 0.5, 1.0)] * 4)
    qz, companion = np.sort(G.real_roots_qz(*A)[0]), np.sort(G.real_roots(*A)[0])
    np.testing.assert_allclose(qz, companion, atol=ROOT_TOL)
    np.testing.assert_allclose(qz, np.sort([*real, -10.0]), atol=ROOT_TOL)


@pytest.mark.parametrize("side", [1.0 - EDGE, 1.0 + EDGE])
def test_qz_splits_a_nearly_real_pair_as_the_companion_matrix_does(side: float) -> None:
    # A2 singular (QZ, no companion matrix) and a pair x0 ± i s of the real Schur form's
    # 2 x 2 blocks: just inside SPLIT_ROOT_TOL it gives x0 - s and x0 + s, flagged split;
    # just outside, nothing; the real roots and the one at x = ∞ come out either way
    rng = np.random.default_rng(6)
    x0 = -0.8
    s = _split_boundary(x0) * side
    real = [-2.0, -0.5, 0.25, 1.5, 3.0, 3.5]
    pairs = [_real_pair(real[2 * k], real[2 * k + 1]) for k in range(3)]
    factors = [SPURIOUS_FACTOR] * 4 + pairs + [(-0.7, 1.0, 0.0), (x0 * x0 + s * s, -2 * x0, 1.0)]
    A = _quadratic(rng, factors + [(1.0, 0.5, 1.0)] * 3)
    assert np.linalg.matrix_rank(A[2]) == 11
    roots, split = G.real_roots_qz(*A)
    expected = sorted([*real, 0.7] + ([x0 - s, x0 + s] if side < 1.0 else []))
    finite = roots != 1e300
    assert (~finite).sum() == 1
    np.testing.assert_allclose(np.sort(roots[finite]), expected, atol=ROOT_TOL)
    near = np.abs(roots[:, None] - np.array([x0 - s, x0 + s])[None]).min(axis=1) <= ROOT_TOL
    assert list(split) == list(near)
    assert near.sum() == (2 if side < 1.0 else 0)


def test_qz_on_a_singular_pencil_keeps_the_regular_roots_among_spurious_ones() -> None:
    # a factor ≡ 0: det M ≡ 0 (the exact UR5's elimination); the regular part's real
    # roots are still found, with spurious ones of the singular part (anywhere: the
    # solver's closure and the shared check drop them)
    rng = np.random.default_rng(5)
    real = [-2.0, -0.5, 0.25, 1.5, 3.0, 3.5]
    pairs = [_real_pair(real[2 * k], real[2 * k + 1]) for k in range(3)]
    singular = [SPURIOUS_FACTOR] * 4 + pairs + [(0.0, 0.0, 0.0)] + [(1.0, 0.5, 1.0)] * 4
    spurious = 0
    for _ in range(3):
        A = _quadratic(rng, singular)
        roots = G.real_roots_qz(*A)[0]
        assert np.abs(roots[:, None] - np.array(real)[None]).min(axis=0).max() <= 1e-8
        spurious += len(roots) - len(real)
    assert spurious >= 1  # the singular part gave real eigenvalues that are no root
