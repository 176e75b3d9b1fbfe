"""Roots of cubics and quartics inside kernels.

:func:`quartic_roots` is Ferrari's closed form: the quartic is made monic,
scaled so that its roots are O(1), depressed (``x = y - b/4``) and split by
the largest root ``m >= 0`` of its resolvent cubic into two quadratics
``y² ∓ √(2m) y + p/2 + m ± w``. Ferrari loses small roots next to much larger
ones; a root whose backward error ``|P(x)| / Σ|k_i||x|^i`` exceeds
``QUARTIC_CHECK`` sends the quartic to Aberth-Ehrlich iterations started from
Ferrari's roots (simultaneous Newton steps that converge to every root,
backward stable; no LAPACK, which numba only reaches through SciPy).
"""

from __future__ import annotations

import cmath
import math

import numpy as np

from kinematica.kernels._numba import Array, ComplexArray, kernel

__all__ = ["ABERTH_STEPS", "QUARTIC_CHECK", "largest_cubic_root", "quartic_roots"]

#: A Ferrari root whose backward error exceeds this sends the quartic to the
#: Aberth-Ehrlich iterations.
QUARTIC_CHECK = 1e-12
#: Aberth-Ehrlich steps at most (each step updates all four roots; from
#: Ferrari's roots convergence takes a handful).
ABERTH_STEPS = 50

#: Below this ``s = sqrt(2m)`` (roots scaled to O(1)), ``w = q / 2s`` is 0/0.
_SMALL_S = 1e-8


@kernel
def largest_cubic_root(A: float, B: float, C: float) -> float:
    """Largest real root of ``m³ + A m² + B m + C``, polished by two Newton steps."""
    A3 = A / 3.0
    P = B - A * A3
    Q = (2.0 / 27.0) * A * A * A - A3 * B + C
    disc = 0.25 * Q * Q + P * P * P / 27.0
    if disc > 0.0:  # one real root (Cardano)
        sq = math.sqrt(disc)
        z = np.cbrt(-0.5 * Q + sq) + np.cbrt(-0.5 * Q - sq)
    else:  # three real roots (trigonometric form): the largest
        rho = math.sqrt(max(P * (-1.0 / 3.0), 0.0))
        den = rho * rho * rho
        if den == 0.0:
            den = 1.0
        cos3 = min(max(-0.5 * Q / den, -1.0), 1.0)
        z = 2.0 * rho * math.cos(math.acos(cos3) / 3.0)
    m = z - A3
    for _ in range(2):
        df = (3.0 * m + 2.0 * A) * m + B
        if df != 0.0:
            m -= (((m + A) * m + B) * m + C) / df
    return m


@kernel
def _backward_ok(k: Array, roots: ComplexArray) -> bool:
    """True when every root's backward error is within ``QUARTIC_CHECK``."""
    for i in range(4):
        x = roots[i]
        size = math.sqrt(x.real * x.real + x.imag * x.imag)  # |x|² overflows where x⁴ has
        value = complex(k[0])
        bound = abs(k[0])
        for j in range(1, 5):
            value = value * x + k[j]
            bound = bound * size + abs(k[j])
        if not value.real * value.real + value.imag * value.imag <= (QUARTIC_CHECK * bound) ** 2:
            return False
    return True


@kernel
def _aberth(k: Array, roots: ComplexArray) -> None:
    """Refine all four roots of ``k`` together (Aberth-Ehrlich), in place.

    Real starting values of a real polynomial would stay real: each start is
    first moved off the real axis by a different small amount, so that the
    iterates can reach complex pairs.
    """
    for i in range(4):
        roots[i] = roots[i] * complex(1.0, 1e-3 * (i + 1)) + complex(0.0, 1e-3 * (i + 1))
    for _ in range(ABERTH_STEPS):
        largest = 0.0
        for i in range(4):
            x = roots[i]
            p = complex(k[0])
            dp = 0j
            for j in range(1, 5):
                dp = dp * x + p
                p = p * x + k[j]
            if p == 0:
                continue
            ratio = p / dp if dp != 0 else 1e300 + 0j
            s = 0j
            for j in range(4):
                if j != i:
                    diff = x - roots[j]
                    if diff != 0:
                        s += 1.0 / diff
            den = 1.0 - ratio * s
            w = ratio / den if den != 0 else ratio
            roots[i] = x - w
            largest = max(largest, abs(w) / (1.0 + abs(x)))
        if largest < 1e-17:
            return


@kernel
def quartic_roots(k: Array, roots: ComplexArray) -> None:
    """The four complex roots of ``k[0] x⁴ + k[1] x³ + ... + k[4]``.

    Args:
        k: ``(5,)`` real coefficients, highest power first, ``k[0] != 0``.
        roots: ``(4,)`` complex out, in no particular order; NaN when a
            coefficient is not finite.
    """
    finite = True
    for j in range(5):
        finite &= np.isfinite(k[j])
    if not finite or k[0] == 0.0:
        for i in range(4):
            roots[i] = complex(math.nan, math.nan)
        return
    k0 = k[0]
    # x = λ z with λ the largest |k_i / k_0|^(1/i) (Fujiwara's bound without
    # its factor 2): the roots z are O(1) however large the x are.
    r1, r2, r3, r4 = abs(k[1] / k0), abs(k[2] / k0), abs(k[3] / k0), abs(k[4] / k0)
    lam = max(r1, math.sqrt(r2), np.cbrt(r3), math.sqrt(math.sqrt(r4)))  # no pow calls
    if lam == 0.0:
        lam = 1.0
    inv = 1.0 / lam
    b = k[1] / k0 * inv
    c = k[2] / k0 * inv * inv
    d = k[3] / k0 * inv * inv * inv
    e = k[4] / k0 * inv * inv * inv * inv
    b4 = 0.25 * b
    b42 = b4 * b4
    p = c - 6.0 * b42
    q = d - 2.0 * b4 * c + 8.0 * b42 * b4
    r = e - b4 * d + b42 * c - 3.0 * b42 * b42
    m = max(largest_cubic_root(p, 0.25 * p * p - r, -0.125 * q * q), 0.0)
    s = math.sqrt(2.0 * m)
    if s > _SMALL_S * (1.0 + math.sqrt(abs(p))):
        w = 0.5 * q / s
    else:  # w = q / 2s is 0/0; w² = m² + m p + p²/4 - r instead
        w = math.copysign(math.sqrt(max(m * m + m * p + 0.25 * p * p - r, 0.0)), q)
    # y² - s y + (p/2 + m + w) = 0 and y² + s y + (p/2 + m - w) = 0
    d1 = cmath.sqrt(complex(s * s - 4.0 * (0.5 * p + m) - 4.0 * w, 0.0))
    d2 = cmath.sqrt(complex(s * s - 4.0 * (0.5 * p + m) + 4.0 * w, 0.0))
    roots[0] = (0.5 * (s + d1) - b4) * lam
    roots[1] = (0.5 * (s - d1) - b4) * lam
    roots[2] = (0.5 * (-s + d2) - b4) * lam
    roots[3] = (0.5 * (-s - d2) - b4) * lam
    if not _backward_ok(k, roots):
        _aberth(k, roots)
