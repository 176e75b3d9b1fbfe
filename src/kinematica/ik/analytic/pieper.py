"""Pieper's elimination: the wrist centre of a skew-shoulder arm as a quartic in q3.

When axes 1 and 2 are skew (distance ``a`` along their common normal, angle
``α``), joint 1 keeps ``|d|`` and ``ζ = h1ᵀd`` of the target, and the two
resulting equations are linear in ``(cos q2, sin q2)``: the part of ``R2 u``
normal to axis 2 must be ``v = (X / 2a, Y / sin α)`` in the basis ``(e1, e2)``
with ``X = |d|² - a² - L(q3)`` and ``Y = ζ - cos α · H(q3)``. Joint 2 keeps the
length of that part, so q3 must satisfy (Pieper 1968; Craig, "Introduction to
Robotics", §4.7)::

    F(q3) = sin²α · X² + 4a² · Y² - 4a² sin²α · (L - H²) = 0

``L`` and ``H`` are of degree 1 in ``(cos q3, sin q3)`` for a revolute joint 3,
so ``F`` is a trigonometric polynomial of degree 2: a quartic in ``tan(q3/2)``
(up to four real roots). For a slide ``L`` is quadratic and ``H`` linear in
q3: a quartic in q3. The roots come from the closed-form quartic solver, are
polished by Newton steps on ``F``, and finally by one Newton step of the full
position equation (3 × 3), which removes the error that the elimination
amplifies near double roots.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from kinematica.ik.analytic.subproblems import cross, rowmul, solve_quartic

if TYPE_CHECKING:
    from kinematica.ik.analytic.position import WristCentrePosition

__all__ = [
    "ACCEPT_TOL",
    "IMAG_TOL",
    "NEWTON_STEPS",
    "POLISH_FROM",
    "fourier_matrix",
    "polish_position",
    "revolute_roots",
    "slide_coefficients",
    "slide_roots",
]

FloatArray = NDArray[np.float64]
BoolArray = NDArray[np.bool_]

#: A quartic root with ``|Im t| <= IMAG_TOL (1 + |t|)`` is taken as real and
#: polished: a double root (target on the workspace boundary) splits into a
#: complex pair of size ~sqrt(ulp).
IMAG_TOL = 1e-6
#: After polishing, a quartic root that leaves the point farther than this
#: (times the arm's size) from the target was complex and is dropped.
ACCEPT_TOL = 1e-8
#: Newton steps on ``F`` for each quartic root.
NEWTON_STEPS = 2
#: Candidates whose point misses the target by more than this (times the
#: arm's size; a measure of the residual of ``F``) get a Newton step of the
#: full position equation.
POLISH_FROM = 1e-14
#: Newton steps on ``F`` longer than this (rad or m) are noise and are skipped.
MAX_NEWTON_STEP = 1e-4
#: ``F`` is identically 0 (a self-motion of joints 1-3) when its leading
#: quartic coefficient is below this fraction of its Fourier coefficients.
SELF_MOTION_TOL = 1e-14

# Quartic coefficients (t⁴ … t⁰) of (1 + t²)² F when F = [g0, a1, b1, a2, b2]
# (Fourier coefficients of 1, cos, sin, cos 2, sin 2) and q = 2 atan t.
_TAN_HALF = np.array(
    [
        [1.0, -1.0, 0.0, 1.0, 0.0],
        [0.0, 0.0, 2.0, 0.0, -4.0],
        [2.0, 0.0, 0.0, -6.0, 0.0],
        [0.0, 0.0, 2.0, 0.0, 4.0],
        [1.0, 1.0, 0.0, 1.0, 0.0],
    ]
)
#: Shifts tried for the tangent half-angle variable (q3 = shift + 2 atan t); the
#: one with the largest leading coefficient, ``F(shift + π)``, keeps every root
#: finite and well scaled (a degree-2 F vanishes at no more than 4 of the 8).
_SHIFTS = np.arange(8) * (np.pi / 4.0)


def _shift_matrix(theta: float) -> FloatArray:
    """Fourier coefficients of ``F(φ + θ)`` from those of ``F(q)``."""
    c1, s1, c2, s2 = math.cos(theta), math.sin(theta), math.cos(2 * theta), math.sin(2 * theta)
    return np.array(
        [
            [1.0, 0, 0, 0, 0],
            [0, c1, s1, 0, 0],
            [0, -s1, c1, 0, 0],
            [0, 0, 0, c2, s2],
            [0, 0, 0, -s2, c2],
        ]
    )


#: ``(5, 40)``: Fourier coefficients → quartic coefficients for all 8 shifts.
_QUARTIC_MAP = np.concatenate([(_TAN_HALF @ _shift_matrix(t)).T for t in _SHIFTS], axis=1)


def _trig_square(x0: float, xc: float, xs: float) -> FloatArray:
    """Fourier coefficients ``[g0, a1, b1, a2, b2]`` of ``(x0 + xc cos + xs sin)²``."""
    return np.array(
        [
            x0 * x0 + (xc * xc + xs * xs) / 2,
            2 * x0 * xc,
            2 * x0 * xs,
            (xc * xc - xs * xs) / 2,
            xc * xs,
        ]
    )


def _bounded(f: FloatArray, df: FloatArray) -> FloatArray:
    """The Newton step ``f / df``, or 0 where it exceeds :data:`MAX_NEWTON_STEP`.

    The roots come from a closed form, within far less than the bound; a
    larger step means ``df ≈ 0`` (a double root) and round-off in ``f``.
    """
    with np.errstate(invalid="ignore", divide="ignore"):
        step = f / df
    return np.where(np.abs(step) <= MAX_NEWTON_STEP, step, 0.0)


def fourier_matrix(a: float, sa: float, ca: float, L: FloatArray, H: FloatArray) -> FloatArray:
    """``(5, 5)``: rows turn ``[X0², X0, Y0², Y0, 1]`` into the Fourier coefficients of F.

    Args:
        a: Distance of axes 1 and 2.
        sa: ``sin α``; ``ca``: ``cos α`` (angle of axes 1 and 2).
        ca: See ``sa``.
        L: ``(3,)`` ``L(q3) = L0 + L1 cos q3 + L2 sin q3``.
        H: ``(3,)`` ``H(q3)`` likewise.

    ``X = X0 - L1 cos - L2 sin`` with ``X0 = |d|² - a² - L0`` and
    ``Y = Y0 - cα (H1 cos + H2 sin)`` with ``Y0 = ζ - cα H0``.
    """
    sa2, a2 = sa * sa, a * a
    F = np.zeros((5, 5))
    F[0, 0] = sa2
    F[1, 1:3] = -2 * sa2 * L[1:]
    F[2, 0] = 4 * a2
    F[3, 1:3] = -8 * a2 * ca * H[1:]
    F[4] = (
        sa2 * _trig_square(0.0, -L[1], -L[2])
        + 4 * a2 * _trig_square(0.0, -ca * H[1], -ca * H[2])
        - 4 * a2 * sa2 * (np.array([L[0], L[1], L[2], 0.0, 0.0]) - _trig_square(*H))
    )
    return F


def revolute_roots(F: FloatArray) -> tuple[FloatArray, BoolArray]:
    """Real roots of ``F(q) = g0 + a1 cos q + b1 sin q + a2 cos 2q + b2 sin 2q``.

    Args:
        F: ``(N, 5)`` Fourier coefficients.

    Returns:
        ``q (N, 4)`` the real roots in ``(-π, π]``, sorted, NaN-padded; and
        ``(N,)`` rows where F ≡ 0 (every q is a root: q holds 4 representatives).
    """
    quart = (F @ _QUARTIC_MAP).reshape(-1, 8, 5)
    k = np.argmax(np.abs(quart[:, :, 0]), axis=1)
    coeffs = quart[np.arange(len(k)), k]
    selfmotion = np.abs(coeffs[:, 0]) <= SELF_MOTION_TOL * np.abs(F).sum(axis=1)
    coeffs[selfmotion] = [1.0, 0.0, 0.0, 0.0, -1.0]  # placeholder, replaced below
    t = solve_quartic(coeffs)
    real = np.abs(t.imag) <= IMAG_TOL * (1.0 + np.abs(t))
    q = _SHIFTS[k][:, None] + 2.0 * np.arctan(np.where(real, t.real, np.nan))
    # Newton on F = f0 + Re(A e^{iq} + B e^{2iq}), A = f1 - i f2, B = f3 - i f4
    f0, A, B = F[:, :1], F[:, 1:2] - 1j * F[:, 2:3], F[:, 3:4] - 1j * F[:, 4:5]
    for _ in range(NEWTON_STEPS):
        e = np.exp(1j * q)
        Ae, Be2 = A * e, B * (e * e)
        q = q - _bounded(f0 + (Ae + Be2).real, -(Ae + 2.0 * Be2).imag)
    q = np.sort(np.arctan2(np.sin(q), np.cos(q)), axis=1)
    return np.where(selfmotion[:, None], _SHIFTS[::2], q), selfmotion


def slide_coefficients(
    a: float, g: float, ca: float, L: FloatArray, H: FloatArray, zeta: FloatArray, dd: FloatArray
) -> FloatArray:
    """``(N, 5)`` coefficients (highest first) of F(q3) for a slide.

    Args:
        a: Distance of axes 1 and 2.
        g: ``±sin α``.
        ca: ``cos α``.
        L: ``(3,)`` ``L(q) = L0 + L1 q + q²``.
        H: ``(2,)`` ``H(q) = H0 + H1 q``.
        zeta: ``(N,)`` height of the target along axis 1.
        dd: ``(N,)`` squared distance of the target from ``p1``.
    """
    sa2, a2 = g * g, a * a
    # X = -q² + x1 q + x0, Y = y1 q + y0
    x1, x0 = -L[1], dd - a2 - L[0]
    y1, y0 = -ca * H[1], zeta - ca * H[0]
    P = np.array([1.0 - H[1] ** 2, L[1] - 2 * H[1] * H[0], L[0] - H[0] ** 2])  # L - H²
    k = np.empty((len(dd), 5))
    k[:, 0] = sa2
    k[:, 1] = -2 * sa2 * x1
    k[:, 2] = sa2 * (x1 * x1 - 2 * x0) + 4 * a2 * y1 * y1 - 4 * a2 * sa2 * P[0]
    k[:, 3] = 2 * sa2 * x1 * x0 + 8 * a2 * y1 * y0 - 4 * a2 * sa2 * P[1]
    k[:, 4] = sa2 * x0 * x0 + 4 * a2 * y0 * y0 - 4 * a2 * sa2 * P[2]
    return k


def slide_roots(coeffs: FloatArray) -> FloatArray:
    """``(N, 4)`` real roots of the quartics ``coeffs (N, 5)``, Newton-polished, sorted."""
    t = solve_quartic(coeffs)
    real = np.abs(t.imag) <= IMAG_TOL * (1.0 + np.abs(t))
    q = np.where(real, t.real, np.nan)
    for _ in range(NEWTON_STEPS):
        f = np.zeros_like(q)
        df = np.zeros_like(q)
        for j in range(5):
            df = df * q + f
            f = f * q + coeffs[:, j : j + 1]
        q = q - _bounded(f, df)
    return np.sort(q, axis=1)


def _turn(k: FloatArray, c: FloatArray, s: FloatArray, v: FloatArray) -> FloatArray:
    """Rodrigues: ``v (..., 3)`` turned about the unit axis ``k (3,)`` by (cos, sin) ``(...)``."""
    c, s = c[..., None], s[..., None]
    return v * c + cross(k, v) * s + k * (rowmul(v, k[:, None]) * (1.0 - c))


def _residual(
    P: WristCentrePosition, q: FloatArray, d: FloatArray
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """``R1ᵀ d - y`` and the parts ``y``, ``w = R2 u``, ``R2 du/dq3`` (see below)."""
    c, s = np.cos(q), np.sin(q)
    if P.prismatic:
        u = P.U[0] + q[..., 2:3] * P.U[1]
        du = np.broadcast_to(P.U[1], u.shape)
    else:
        u = P.U[0] + c[..., 2:3] * P.U[1] + s[..., 2:3] * P.U[2]
        du = c[..., 2:3] * P.U[2] - s[..., 2:3] * P.U[1]
    W = _turn(P.h2, c[..., 1:2], s[..., 1:2], np.stack([u, du], axis=-2))
    w, dw = W[..., 0, :], W[..., 1, :]
    y = (P.p2 - P.p1) + w
    r = _turn(P.h1, c[..., 0], -s[..., 0], np.broadcast_to(d[:, None, :], y.shape)) - y
    return r, y, w, dw


def polish_position(P: WristCentrePosition, q: FloatArray, d: FloatArray) -> FloatArray:
    """One Newton step of the position equation ``x(q1, q2, q3) = d`` per candidate.

    With ``y = (p2 - p1) + R2 u`` and ``x - p1 = R1 y``, the equation read in
    the frame turned back by q1 is ``R1ᵀ d - y = 0``, whose Jacobian columns
    are ``h1 × y``, ``h2 × R2 u`` and ``R2 du/dq3``. The step is kept only
    where it lowers the residual: at a fold of the workspace (a double root)
    the Jacobian is singular and the step is noise.

    Args:
        P: The geometry.
        q: ``(N, k, 3)`` candidates (NaN rows pass through).
        d: ``(N, 3)`` target points minus ``p1``.

    Returns:
        ``(N, k, 3)`` polished candidates.
    """
    r, y, w, dw = _residual(P, q, d)
    # Cramer's rule on the columns j1 = h1 × y, j2 = h2 × w, j3 = dw
    j1, j2 = cross(P.h1, y), cross(P.h2, w)
    n23, n31, n12 = cross(j2, dw), cross(dw, j1), cross(j1, j2)
    det = np.sum(j1 * n23, axis=-1)
    step = np.stack([np.sum(r * n, axis=-1) for n in (n23, n31, n12)], axis=-1)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        new = q + step / det[..., None]
    better = np.sum(_residual(P, new, d)[0] ** 2, axis=-1) < np.sum(r * r, axis=-1)
    return np.where(better[..., None], new, q)
