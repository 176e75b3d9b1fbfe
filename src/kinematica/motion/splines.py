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
IntArray = NDArray[np.intp]
Ends = Literal["clamped", "natural"]

# What each Hermite basis weight is: (end of the segment, derivative order);
# the weight is that derivative times h**order.
_SLOTS = {
    2: ((0, 0), (0, 1), (1, 1), (1, 0)),
    3: ((0, 0), (0, 1), (0, 2), (1, 2), (1, 1), (1, 0)),
}
_BASIS = {2: CUBIC_BASIS, 3: QUINTIC_BASIS}


def _inverse(A: FloatArray) -> FloatArray:
    """Inverse of a 1x1 or 2x2 block (closed form: a library call costs more than the sum)."""
    if A.shape == (1, 1):
        out: FloatArray = 1.0 / A
        return out
    a, b, c, d = A[0, 0], A[0, 1], A[1, 0], A[1, 1]
    return np.array([[d, -b], [-c, a]]) / (a * d - b * c)


def spline_derivatives(
    t: FloatArray, y: FloatArray, m: int, ends: Ends, start: FloatArray, end: FloatArray
) -> FloatArray:
    """Knot derivatives of the spline through ``(t, y)``.

    The conditions at knot ``i`` involve the derivatives at knots ``i - 1``,
    ``i`` and ``i + 1`` only: the system is block tridiagonal (blocks of
    ``m - 1``), solved by block elimination in O(k) time and memory.

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
    if ends == "natural" and k == 2 and m == 3:
        # Through two knots every quadratic has no jerk and zero jerk and snap at both ends:
        # the least-jerk interpolant is not unique (the system below is singular). The one
        # of least acceleration among them is taken: the line, as the natural cubic's.
        line = np.zeros((2, w, n))
        line[:, 0] = (y[1] - y[0]) / h[0]
        return line
    # Rows of knot i: L[i] x[i-1] + D[i] x[i] + U[i] x[i+1] = R[i], x[i] its w derivatives.
    L, D, U = np.zeros((k, w, w)), np.zeros((k, w, w)), np.zeros((k, w, w))
    R = np.zeros((k, w, n))
    blocks = {-1: L, 0: D, 1: U}
    # at[r][e][j]: the r-th s-derivative of basis polynomial j at s = e (0 or 1)
    at = [
        [[float(npoly.polyval(e, npoly.polyder(b, r))) for b in basis] for e in (0.0, 1.0)]
        for r in range(2 * m - 1)
    ]

    def add(i: IntArray, row: int, seg: IntArray, e: int, r: int, sign: float) -> None:
        """Add to the rows of knots ``i`` the r-th derivative of segments ``seg`` at end ``e``."""
        if i.size == 0:  # two waypoints: no interior knot
            return
        for j, (ew, ow) in enumerate(slots):
            c = sign * at[r][e][j] * h[seg] ** (ow - r)
            knot = seg + ew
            if ow == 0:
                R[i, row] -= c[:, None] * y[knot]
            else:
                blocks[int(knot[0] - i[0])][i, row, ow - 1] += c

    inner = np.arange(1, k - 1)
    for row, r in enumerate(range(m, 2 * m - 1)):
        add(inner, row, inner - 1, 1, r, 1.0)
        add(inner, row, inner, 0, r, -1.0)
    for i, seg, e, given in ((0, 0, 0, start), (k - 1, k - 2, 1, end)):
        for row, o in enumerate(range(1, m)):
            if ends == "clamped":
                D[i, row, o - 1] = 1.0
                R[i, row] = given[o - 1]
            else:
                add(np.array([i]), row, np.array([seg]), e, m + o - 1, 1.0)
    # Block elimination forward, then back substitution.
    Up, Rp = np.zeros_like(U), np.zeros_like(R)
    for i in range(k):
        Di = D[i] if i == 0 else D[i] - L[i] @ Up[i - 1]
        Ri = R[i] if i == 0 else R[i] - L[i] @ Rp[i - 1]
        inv = _inverse(Di)
        Up[i] = inv @ U[i]
        Rp[i] = inv @ Ri
    x = np.zeros((k, w, n))
    x[-1] = Rp[-1]
    for i in range(k - 2, -1, -1):
        x[i] = Rp[i] - Up[i] @ x[i + 1]
    return x


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
