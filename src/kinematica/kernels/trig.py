"""Sine and cosine of one angle, written so that loops over angles vectorise.

numba's ``math.sin``/``math.cos`` call the C library one value at a time (about
23 ns for both on the development machine), and its pip build has no vector
math library. This is the classical scheme of fdlibm instead: reduce the
angle by multiples of π/2 (Cody-Waite, π/2 split in three parts so that
``n · P1`` is exact), then the minimax polynomials of ``__kernel_sin`` and
``__kernel_cos`` on [-π/4, π/4], then a branch-free choice of sign and
quadrant. The results are within 1 ulp of the C library's for ``|x| < 10``
(joint angles) and within 2 ulps up to ``REDUCTION_LIMIT`` (the reduced
angle's rounding tail, which fdlibm carries on, is dropped);
``tests/test_kernels_scalar.py`` compares them on millions of angles. Beyond
the limit :func:`sincos` falls back to the C library. Branch-free, a loop over
angles compiles to AVX2 code (about 1.5 ns for both).
"""

from __future__ import annotations

import math

import numpy as np

from kinematica.kernels._numba import inline_kernel

__all__ = ["REDUCTION_LIMIT", "sincos", "sincos_reduced"]

#: Largest |x| the three-part reduction handles exactly (``n < 2**20``).
REDUCTION_LIMIT = 1.0e6

_TWO_OVER_PI = 6.36619772367581382433e-01
# π/2 = P1 + P2 + P3 (fdlibm's pio2_1, pio2_2, pio2_2t); P1 and P2 have 33
# significant bits, so n · P1 and n · P2 are exact for n < 2**20.
_P1 = 1.57079632673412561417e00
_P2 = 6.07710050630396597660e-11
_P3 = 2.02226624879595063154e-21
# fdlibm's __kernel_sin and __kernel_cos coefficients.
_S1, _S2, _S3 = -1.66666666666666324348e-01, 8.33333333332248946124e-03, -1.98412698298579493134e-04
_S4, _S5, _S6 = 2.75573137070700676789e-06, -2.50507602534068634195e-08, 1.58969099521155010221e-10
_C1, _C2, _C3 = 4.16666666666666019037e-02, -1.38888888888741095749e-03, 2.48015872894767294178e-05
_C4, _C5, _C6 = -2.75573143513906633035e-07, 2.08757232129817482790e-09, -1.13596475577881948265e-11


@inline_kernel
def sincos_reduced(x: float) -> tuple[float, float]:
    """``(sin x, cos x)`` for ``|x| <= REDUCTION_LIMIT``, branch-free (NaN stays NaN)."""
    n = math.floor(x * _TWO_OVER_PI + 0.5)
    r = ((x - n * _P1) - n * _P2) - n * _P3
    z = r * r
    s = r + r * z * (_S1 + z * (_S2 + z * (_S3 + z * (_S4 + z * (_S5 + z * _S6)))))
    hz = 0.5 * z
    w = 1.0 - hz
    c = w + (
        ((1.0 - w) - hz) + z * z * (_C1 + z * (_C2 + z * (_C3 + z * (_C4 + z * (_C5 + z * _C6)))))
    )
    k = np.int64(n) if n == n else np.int64(0)
    swap = (k & 1) != 0
    so = c if swap else s
    co = s if swap else c
    so = -so if (k & 2) != 0 else so
    co = -co if ((k + 1) & 2) != 0 else co
    return so, co


@inline_kernel
def sincos(x: float) -> tuple[float, float]:
    """``(sin x, cos x)`` for any ``x`` (the C library beyond ``REDUCTION_LIMIT``)."""
    if abs(x) <= REDUCTION_LIMIT:
        return sincos_reduced(x)
    return math.sin(x), math.cos(x)
