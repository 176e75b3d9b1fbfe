"""TRANSITIONAL: numpy subproblem helpers still used by the legacy UR-type solvers.

The 3R anthropomorphic and elbow arms are solved by the kernel of
:mod:`kinematica.kernels.solvers.elbow_arms`. What is left here (Paden-Kahan
subproblem 4 on numpy arrays, the common normal of two axes) serves
:mod:`kinematica.ik.analytic.parallel` and ``parallel_general`` until they are
ported; it goes with them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from kinematica.ik.analytic.elbow_arms import common_normal
from kinematica.ik.analytic.planar import REACH_TOL, SINGULAR_TOL

__all__ = ["AxisHeight", "common_normal", "height_angles", "height_angles_one"]

FloatArray = NDArray[np.float64]
BoolArray = NDArray[np.bool_]


@dataclass(frozen=True)
class AxisHeight:
    """Paden-Kahan subproblem 4 about one axis: ``k·rot(h, θ)·v = d``.

    Attributes:
        h: ``(3,)`` unit rotation axis.
        k: ``(3,)`` unit direction along which the height is measured.
        W: ``(3, 3)`` columns ``k - (k·h) h``, ``k × h``, ``(k·h) h``: the
            coefficients ``A, B, C = v @ W`` of ``A cos θ + B sin θ + C``.
    """

    h: FloatArray
    k: FloatArray
    W: FloatArray

    @classmethod
    def about(cls, h: FloatArray, k: FloatArray) -> AxisHeight:
        """The subproblem for axis ``h`` and direction ``k`` (not parallel)."""
        kh = float(k @ h)
        return cls(h, k, np.stack([k - kh * h, np.cross(k, h), kh * h], axis=1))

    def solve(
        self, v: FloatArray, d: FloatArray | float
    ) -> tuple[FloatArray, FloatArray, FloatArray, BoolArray]:
        """Both angles θ for vectors ``v (..., 3)``, heights ``d (...)`` (:func:`height_angles`)."""
        A, B, C = np.moveaxis(v @ self.W, -1, 0)
        return height_angles(A, B, C, d)


def height_angles(
    A: FloatArray, B: FloatArray, C: FloatArray, d: FloatArray | float
) -> tuple[FloatArray, FloatArray, FloatArray, BoolArray]:
    """Subproblem 4 from its coefficients: ``A cos θ + B sin θ + C = d``, batched.

    Returns:
        ``cos θ, sin θ`` ``(..., 2)``: branch 0 is θ = φ + δ, where the left
        side decreases with θ, branch 1 θ = φ - δ; NaN without a real root.
        ``gap (...)``: how far ``d`` lies outside the range ``C ± |(A, B)|``
        (0 when solvable). ``singular (...)``: ``A = B = 0`` and ``C = d``, any
        θ solves (θ = 0 given for both branches).
    """
    rho, e = np.hypot(A, B), d - C
    singular = (rho < SINGULAR_TOL) & (np.abs(e) < SINGULAR_TOL)
    safe = np.where(rho > 0.0, rho, 1.0)
    cd = e / safe
    cd = np.where((np.abs(cd) <= 1.0 + REACH_TOL) & (rho > 0.0), cd, np.nan)
    cd = np.minimum(np.maximum(cd, -1.0), 1.0)
    sd = np.sqrt(1.0 - cd * cd)[..., None] * np.array([1.0, -1.0])
    cf, sf, cd = (A / safe)[..., None], (B / safe)[..., None], cd[..., None]
    c = np.where(singular[..., None], 1.0, cf * cd - sf * sd)
    s = np.where(singular[..., None], 0.0, sf * cd + cf * sd)
    return c, s, np.maximum(np.abs(e) - rho, 0.0), singular


def height_angles_one(A: float, B: float, e: float, rho: float) -> list[tuple[float, float]]:
    """:func:`height_angles` for one equation ``A cos θ + B sin θ = e``, ``rho = |(A, B)|``.

    Returns:
        ``(cos θ, sin θ)`` of branches 0 and 1 (NaN without a real root).
    """
    cd = e / rho if rho > 0.0 else math.inf
    if abs(cd) > 1.0 + REACH_TOL:
        return [(math.nan, math.nan)] * 2
    cd = min(max(cd, -1.0), 1.0)
    sd = math.sqrt(1.0 - cd * cd)
    cf, sf = A / rho, B / rho
    return [(cf * cd - sf * sd, sf * cd + cf * sd), (cf * cd + sf * sd, sf * cd - cf * sd)]
