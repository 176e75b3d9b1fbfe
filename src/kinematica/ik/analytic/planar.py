"""TRANSITIONAL: numpy planar geometry still used by the legacy UR-type solvers.

The planar arms and the SCARA are solved by the kernel of
:mod:`kinematica.kernels.solvers.planar_arms`. What is left here (complex
coordinates in a plane, the 2R triangle on numpy arrays) serves
:mod:`kinematica.ik.analytic.parallel` and ``parallel_general`` until they are
ported; it goes with them.
"""

from __future__ import annotations

import cmath
import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from kinematica.errors import DimensionError

__all__ = [
    "Plane",
    "TwoLink",
    "as_complex",
    "skew",
    "targets_array",
    "two_link_one",
]

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]
BoolArray = NDArray[np.bool_]

#: A cosine (or sine) argument up to this far beyond ±1 is taken as ±1: the
#: target is on the workspace boundary up to rounding (a relative measure).
REACH_TOL = 1e-12
#: Distance (m) or angle (rad) below which a target is taken as exactly on a
#: singular set (e.g. the wrist on axis 1 with equal links: q1 is free).
SINGULAR_TOL = 1e-12
#: Links shorter than this (m) make the arm degenerate: no solver is built.
LENGTH_TOL = 1e-9


def targets_array(targets: FloatArray, position_only: bool) -> FloatArray:
    """Targets as a float array ``(N, 3)`` or ``(N, 4, 4)``, checked."""
    t = np.asarray(targets, dtype=float)
    want = (3,) if position_only else (4, 4)
    if t.shape[1:] != want or t.ndim != len(want) + 1:
        raise DimensionError(f"targets must have shape (N, {', '.join(map(str, want))})")
    return t


def skew(h: FloatArray) -> FloatArray:
    """``(3, 3)`` matrix ``K`` with ``v @ K == h × v`` for row vectors ``v``."""
    return np.array([[0.0, h[2], -h[1]], [-h[2], 0.0, h[0]], [h[1], -h[0], 0.0]])


@dataclass(frozen=True)
class Plane:
    """Complex coordinates in the plane normal to a unit direction ``k``.

    Attributes:
        k: ``(3,)`` unit normal.
        basis: ``(3, 2)`` columns ``e1, e2 = k × e1``; the coordinate of ``x``
            is ``x·e1 + i x·e2``.
    """

    k: FloatArray
    basis: FloatArray

    @classmethod
    def normal_to(cls, k: FloatArray) -> Plane:
        """The plane normal to ``k`` with some fixed basis ``e1, e2 = k × e1``."""
        k = np.asarray(k, dtype=float) / np.linalg.norm(k)
        e1 = np.cross(k, np.eye(3)[int(np.argmin(np.abs(k)))])
        e1 /= np.linalg.norm(e1)
        return cls(k, np.stack([e1, np.cross(k, e1)], axis=1))

    def c(self, x: FloatArray) -> ComplexArray:
        """The complex coordinate ``(...)`` of vectors ``x (..., 3)``."""
        return as_complex(x @ self.basis)


def as_complex(xy: FloatArray) -> ComplexArray:
    """Pairs ``(..., 2)`` (last axis contiguous) as complex numbers ``(...)``, no copy.

    A real matrix product followed by this view costs a tenth of a product
    of real vectors with a complex matrix.
    """
    if xy.strides[-1] != xy.itemsize:
        xy = np.ascontiguousarray(xy)
    return xy.view(np.complex128)[..., 0]


@dataclass(frozen=True)
class TwoLink:
    """The planar 2R triangle: a shoulder, an elbow and a wrist point.

    Attributes:
        a0: Shoulder to elbow at q = 0 (complex, in the plane).
        b0: Elbow to wrist at q = 0.
    """

    a0: complex
    b0: complex

    @property
    def valid(self) -> bool:
        """Both links longer than ``LENGTH_TOL``."""
        return min(abs(self.a0), abs(self.b0)) > LENGTH_TOL

    def solve(self, t: ComplexArray) -> tuple[FloatArray, FloatArray, FloatArray, BoolArray]:
        """Rotations that take the wrist to ``t``.

        Args:
            t: ``(...)`` wrist targets relative to the shoulder (complex).

        Returns:
            ``d1, d2`` ``(..., 2)``: rotation of the shoulder and of the elbow
            (about ``k``, from q = 0), branches ``[ψ <= 0, ψ >= 0]`` where ψ is
            the angle of link 2 relative to link 1; NaN without a real solution.
            ``gap (...)``: distance of ``t`` outside the annulus (0 inside).
            ``singular (...)``: ``t`` at the shoulder with equal links (d1 free, 0 given).
        """
        L1, L2 = abs(self.a0), abs(self.b0)
        r2 = t.real**2 + t.imag**2
        c = (r2 - L1 * L1 - L2 * L2) / (2.0 * L1 * L2)
        ok = np.abs(c) <= 1.0 + REACH_TOL
        c = np.where(ok, np.minimum(np.maximum(c, -1.0), 1.0), np.nan)
        s = np.sqrt(1.0 - c * c)[..., None] * np.array([-1.0, 1.0])
        cb = c[..., None]
        v = self.a0 * (1.0 + (L2 / L1) * (cb + 1j * s))  # shoulder -> wrist after the elbow
        d1 = np.angle(t[..., None] * np.conj(v))
        psi0 = np.angle(self.b0 / self.a0)
        d2 = np.arctan2(s, cb) - psi0
        r = np.sqrt(r2)
        gap = np.maximum(np.maximum(r - (L1 + L2), abs(L1 - L2) - r), 0.0)
        singular = (r < SINGULAR_TOL) & (abs(L1 - L2) < SINGULAR_TOL)
        return d1, d2, gap, singular


def two_link_one(arm: TwoLink, t: complex) -> tuple[list[float], list[float], bool]:
    """:meth:`TwoLink.solve` for one target, on Python floats (no numpy overhead).

    Returns:
        ``d1, d2`` (two branches each, NaN without a real solution) and ``singular``.
    """
    L1, L2 = abs(arm.a0), abs(arm.b0)
    r2 = t.real * t.real + t.imag * t.imag
    c = (r2 - L1 * L1 - L2 * L2) / (2.0 * L1 * L2)
    if abs(c) > 1.0 + REACH_TOL:
        return [math.nan, math.nan], [math.nan, math.nan], False
    c = min(max(c, -1.0), 1.0)
    s0 = math.sqrt(1.0 - c * c)
    psi0 = cmath.phase(arm.b0 / arm.a0)
    d1, d2 = [], []
    for s in (-s0, s0):
        v = arm.a0 * (1.0 + (L2 / L1) * complex(c, s))
        d1.append(cmath.phase(t * v.conjugate()))
        d2.append(math.atan2(s, c) - psi0)
    return d1, d2, math.sqrt(r2) < SINGULAR_TOL and abs(L1 - L2) < SINGULAR_TOL
