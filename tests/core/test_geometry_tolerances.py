"""The core's geometry tolerances (``geometry.hpp``, ``polynomial.hpp``), both sides.

Each case sits a factor 10 inside or outside the documented value, written here as
a literal: a test that read the constant would move with it.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from kinematica._core_testing import internals

#: A case a factor 10 inside a tolerance, and one a factor 10 outside it.
FACTORS = [(0.1, True), (10.0, False)]


TRIG_TOL = 1e-10  # geometry.hpp


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_trig_tol_takes_a_near_miss_as_a_double_root(factor: float, inside: bool) -> None:
    """TRIG_TOL: a cos θ + b sin θ = c with |c| above r = hypot(a, b) by at most
    this (relative, r² - c² >= -2 TRIG_TOL r²) is a double root (1), beyond it
    no solution (0); ``out`` holds the least-squares angle atan2(b, a) either way.
    """
    a, b, r = 3.0, 4.0, 5.0
    c = r * math.sqrt(1.0 + 2.0 * factor * TRIG_TOL)  # r² - c² = -2 factor TRIG_TOL r²
    code, *out = internals.trig_linear(a, b, c)
    assert code == (1 if inside else 0)
    np.testing.assert_allclose(out, math.atan2(b, a), atol=1e-12)


QUARTIC_CHECK = 1e-12  # polynomial.hpp


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_quartic_check_accepts_a_backward_error_below_it(factor: float, inside: bool) -> None:
    """QUARTIC_CHECK: a root whose backward error ``|P(x)| / Σ|k_i||x|^i``
    is ``factor * QUARTIC_CHECK`` passes the check below the constant and sends
    the quartic to the Aberth-Ehrlich iterations above it.
    """
    exact = np.array([1.0, 2.0, -0.5, 3.0])
    k = np.poly(exact)  # highest power first
    r = exact[1]
    slope = abs(np.polyval(np.polyder(k), r))
    bound = float(np.polyval(np.abs(k), r))
    roots = exact.astype(np.complex128)
    roots[1] += factor * QUARTIC_CHECK * bound / slope  # |P(x)| ≈ slope · shift
    assert internals.quartic_backward_ok(k.tolist(), roots.tolist()) is inside
    assert internals.quartic_backward_ok(k.tolist(), exact.astype(np.complex128).tolist())
    assert internals.QUARTIC_CHECK == QUARTIC_CHECK
