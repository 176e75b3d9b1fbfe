"""The core's damped least squares (``linalg.hpp``): against numpy, and SCALE_FLOOR from both sides.

The core solves the normal equations of the smaller side of J by LDLᵀ (J Jᵀ for a
wide or square J, JᵀJ for a tall one); the reference here always solves the n x n
system (JᵀJ + λ s I) dq = Jᵀ e with numpy, s the mean diagonal of the core's
normal matrix (‖J‖²_F / min(r, n)), so both sides of the core's choice are checked
against one formula.
"""

from __future__ import annotations

import numpy as np
import pytest
from kinematica._core_testing import internals
from kinematica._core_testing.internals import SCALE_FLOOR


def reference(J: np.ndarray, e: np.ndarray, lam: float) -> np.ndarray:
    """dq minimising |J dq − e|² + λ s |dq|² (numpy, the n x n normal equations)."""
    r, n = J.shape
    s = float(np.sum(J * J)) / min(r, n)
    return np.linalg.solve(J.T @ J + lam * s * np.eye(n), J.T @ e)


@pytest.mark.parametrize("shape", [(6, 7), (6, 6), (3, 7), (1, 2), (6, 3), (5, 4), (2, 1)], ids=str)
@pytest.mark.parametrize("lam", [1e-3, 0.5, 20.0])
def test_damped_least_squares_matches_numpy(shape: tuple[int, int], lam: float) -> None:
    rng = np.random.default_rng(sum(shape))
    J = rng.normal(size=shape)
    e = rng.normal(size=shape[0])
    dq = internals.damped_least_squares(J, e, lam)
    expected = reference(J, e, lam)
    np.testing.assert_allclose(dq, expected, rtol=1e-11, atol=1e-13 * np.abs(expected).max())


def test_undamped_square_step_solves_the_system() -> None:
    # λ → 0 on a well-conditioned square J: the Gauss-Newton step J⁻¹ e.
    rng = np.random.default_rng(7)
    J = rng.normal(size=(6, 6)) + 4.0 * np.eye(6)
    e = rng.normal(size=6)
    dq = internals.damped_least_squares(J, e, 1e-21)
    np.testing.assert_allclose(J @ dq, e, atol=1e-13)


@pytest.mark.parametrize(("ratio", "relative"), [(2.0, True), (0.5, False)])
def test_scale_floor_both_sides(ratio: float, relative: bool) -> None:
    # J = c I (2 x 2), mean diagonal s = c². Above SCALE_FLOOR the damping is λ s:
    # dq = e / (c (1 + λ)); below it the damping is λ itself: dq = c e / (c² + λ) ≈ c e.
    c = float(np.sqrt(ratio * SCALE_FLOOR))
    e = np.array([1.0, -2.0])
    lam = 1.0
    dq = internals.damped_least_squares(c * np.eye(2), e, lam)
    expected = e / (c * (1.0 + lam)) if relative else c * e / (c * c + lam)
    np.testing.assert_allclose(dq, expected, rtol=1e-14)
