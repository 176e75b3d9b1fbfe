"""Cubic and quintic splines through waypoints, in Hermite form.

Each segment between two knots is the Hermite polynomial of
:mod:`kinematica.motion.trajectory` (the same bases) fixed by the value and
the first ``m - 1`` derivatives at its two knots (``m = 2``: cubic, the
velocity; ``m = 3``: quintic, velocity and acceleration). The knot
derivatives are the unknowns; the spline asks derivatives ``m .. 2m - 2`` to
be continuous at every interior knot (the cubic's acceleration: C2; the
quintic's jerk and snap: C4), and two end conditions per end:

- ``"clamped"``: the derivatives ``1 .. m - 1`` given at both ends (zero by
  default: rest to rest);
- ``"natural"``: the derivatives ``m .. 2m - 2`` zero at both ends.

These are the interpolants of least ``∫ (q⁽ᵐ⁾)² dt``: the cubic spline
minimises the integral of the squared acceleration, the quintic one that of
the squared jerk (the Euler-Lagrange equation ``q⁽²ᵐ⁾ = 0`` between knots,
with continuity of ``q⁽ᵐ⁾ .. q⁽²ᵐ⁻²⁾`` across them).
"""

from __future__ import annotations

from typing import Literal

import numpy as np
from numpy.polynomial import polynomial as npoly
from numpy.typing import NDArray

from kinematica.motion.piecewise import PiecewisePolynomial
from kinematica.motion.trajectory import CUBIC_BASIS, QUINTIC_BASIS

__all__ = ["Ends", "hermite_pieces", "spline_derivatives"]

FloatArray = NDArray[np.float64]
Ends = Literal["clamped", "natural"]

# What each Hermite basis weight is: (end of the segment, derivative order);
# the weight is that derivative times h**order.
_SLOTS = {
    2: ((0, 0), (0, 1), (1, 1), (1, 0)),
    3: ((0, 0), (0, 1), (0, 2), (1, 2), (1, 1), (1, 0)),
}
_BASIS = {2: CUBIC_BASIS, 3: QUINTIC_BASIS}


def spline_derivatives(
    t: FloatArray, y: FloatArray, m: int, ends: Ends, start: FloatArray, end: FloatArray
) -> FloatArray:
    """Knot derivatives of the spline through ``(t, y)``.

    Args:
        t: ``(k,)`` increasing knot times (s), k >= 2.
        y: ``(k, n)`` values at the knots.
        m: 2 (cubic) or 3 (quintic).
        ends: ``"clamped"`` or ``"natural"``.
        start: ``(m - 1, n)`` derivatives 1 .. m-1 at the first knot (clamped).
        end: ``(m - 1, n)`` the same at the last knot.

    Returns:
        ``(k, m - 1, n)``: derivatives 1 .. m-1 at every knot.
    """
    k, n = y.shape
    w = m - 1
    basis, slots = _BASIS[m], _SLOTS[m]
    h = np.diff(t)
    N = w * k
    M = np.zeros((N, N))
    R = np.zeros((N, n))
    row = 0

    def add(seg: int, e: int, r: int, sign: float) -> None:
        """Add ``sign`` times the r-th derivative of segment ``seg`` at its end ``e``."""
        for b, (ew, ow) in zip(basis, slots, strict=True):
            c = sign * float(npoly.polyval(float(e), npoly.polyder(b, r))) * h[seg] ** (ow - r)
            knot = seg + ew
            if ow == 0:
                R[row] -= c * y[knot]
            else:
                M[row, knot * w + ow - 1] += c

    for i in range(1, k - 1):
        for r in range(m, 2 * m - 1):
            add(i - 1, 1, r, 1.0)
            add(i, 0, r, -1.0)
            row += 1
    for knot, seg, e, given in ((0, 0, 0, start), (k - 1, k - 2, 1, end)):
        for o in range(1, m):
            if ends == "clamped":
                M[row, knot * w + o - 1] = 1.0
                R[row] = given[o - 1]
            else:
                add(seg, e, m + o - 1, 1.0)
            row += 1
    out: FloatArray = np.linalg.solve(M, R).reshape(k, w, n)
    return out


def hermite_pieces(t: FloatArray, y: FloatArray, derivs: FloatArray) -> PiecewisePolynomial:
    """The piecewise Hermite polynomial with values ``y`` and ``derivs`` at the knots.

    Args:
        t: ``(k,)`` increasing knot times (s).
        y: ``(k, n)`` values.
        derivs: ``(k, m - 1, n)`` derivatives 1 .. m-1 at the knots (m = 2 or 3).

    Returns:
        Cubic (m = 2) or quintic (m = 3) pieces, one per knot interval.
    """
    m = derivs.shape[1] + 1
    basis, slots = _BASIS[m], _SLOTS[m]
    h = np.diff(t)
    full = np.concatenate([y[:, None, :], derivs], axis=1)  # (k, m, n): orders 0 .. m-1
    weights = np.stack(
        [full[e : e + h.size, o, :] * (h[:, None] ** o) for e, o in slots], axis=1
    )  # (p, slots, n)
    coef_s = np.einsum("wd,pwn->pdn", basis, weights)  # coefficients in s = τ / h
    powers = np.arange(basis.shape[1])
    coef = coef_s / (h[:, None, None] ** powers[None, :, None])
    coef[:, 0, :] = y[:-1]  # the basis gives it exactly too; state it
    return PiecewisePolynomial(np.asarray(t, dtype=float), coef, np.asarray(t, dtype=float))
