"""Pieper's quartic for one pose on Python floats (the skew-shoulder geometry).

The single-pose path of :mod:`~kinematica.ik.analytic.wrist_single` for axes 1
and 2 skew and axis 3 not parallel to axis 2: the steps of
:meth:`WristCentrePosition.solve <kinematica.ik.analytic.position.WristCentrePosition.solve>`
and :mod:`~kinematica.ik.analytic.pieper` on floats. The quartic is solved by
the closed form of :func:`~kinematica.ik.analytic.subproblems.solve_quartic`
(Ferrari, with the same backward-error check and companion-matrix fallback),
its roots polished by the same Newton steps and accepted by the same tests,
then by the same Newton step of the full position equation where it is due.
"""

from __future__ import annotations

import cmath
import math
from typing import TYPE_CHECKING

import numpy as np

from kinematica.ik.analytic import pieper
from kinematica.ik.analytic.subproblems import QUARTIC_CHECK, _companion_roots

if TYPE_CHECKING:
    from kinematica.ik.analytic.wrist_single import SinglePose

__all__ = ["quartic_position", "quartic_roots"]

_SMALL_S = 1e-8  # as subproblems._SMALL_S
_SHIFTS = tuple(float(x) for x in pieper._SHIFTS)
#: ``[i][5 k + j]``: Fourier coefficient i → coefficient j of the quartic for shift k.
QMAP = tuple(tuple(float(x) for x in row) for row in pieper._QUARTIC_MAP)


def _cubic(A: float, B: float, C: float) -> float:
    """Largest real root of ``m³ + A m² + B m + C`` (as ``subproblems._largest_cubic_root``)."""
    A3 = A / 3.0
    P = B - A * A3
    Q = (2.0 / 27.0) * A * A * A - A3 * B + C
    disc = 0.25 * Q * Q + P * P * P / 27.0
    if disc > 0.0:
        sq = math.sqrt(disc)
        z = math.cbrt(-0.5 * Q + sq) + math.cbrt(-0.5 * Q - sq)
    else:
        rho = math.sqrt(max(P * (-1.0 / 3.0), 0.0))
        cos3 = min(max(-0.5 * Q / (rho * rho * rho + (rho == 0.0)), -1.0), 1.0)
        z = 2.0 * rho * math.cos(math.acos(cos3) / 3.0)
    m = z - A3
    for _ in range(2):
        df = (3.0 * m + 2.0 * A) * m + B
        if df != 0.0:
            m -= (((m + A) * m + B) * m + C) / df
    return m


def quartic_roots(k: tuple[float, ...]) -> list[complex]:
    """The four complex roots of ``k[0] x⁴ + … + k[4]`` (``solve_quartic`` for one row).

    Ferrari as in :func:`~kinematica.ik.analytic.subproblems.solve_quartic`;
    coefficients that are not finite or a root whose backward error exceeds
    :data:`~kinematica.ik.analytic.subproblems.QUARTIC_CHECK` go to the
    companion matrix, as there.
    """
    if not all(map(math.isfinite, k)):
        return [complex(x) for x in _companion_roots(np.array([k]))[0]]
    k0 = k[0]
    monic = [x / k0 for x in k[1:]]
    lam = max(abs(x) ** (1.0 / (i + 1)) for i, x in enumerate(monic))
    lam = lam if lam != 0.0 else 1.0
    inv = 1.0 / lam
    b, c, d, e = (x * inv ** (i + 1) for i, x in enumerate(monic))
    b4 = 0.25 * b
    b42 = b4 * b4
    p = c - 6.0 * b42
    q = d - 2.0 * b4 * c + 8.0 * b42 * b4
    r = e - b4 * d + b42 * c - 3.0 * b42 * b42
    m = max(_cubic(p, 0.25 * p * p - r, -0.125 * q * q), 0.0)
    s = math.sqrt(2.0 * m)
    if s > _SMALL_S * (1.0 + math.sqrt(abs(p))):
        w = 0.5 * q / s
    else:  # w = q / 2s is 0/0
        w = math.copysign(math.sqrt(max(m * m + m * p + 0.25 * p * p - r, 0.0)), q)
    roots = []
    for S, pm in ((s, 1.0), (-s, -1.0)):
        disc = cmath.sqrt(complex(S * S - 4.0 * (0.5 * p + m) - 4.0 * w * pm, 0.0))
        roots += [(0.5 * (S + disc) - b4) * lam, (0.5 * (S - disc) - b4) * lam]
    ak = [abs(x) for x in k]
    for x in roots:
        value, bound, size = complex(k0), ak[0], abs(x)
        for i in range(1, 5):
            value = value * x + k[i]
            bound = bound * size + ak[i]
        if abs(value) > QUARTIC_CHECK * bound:
            return [complex(x) for x in _companion_roots(np.array([k]))[0]]
    return roots


def _real(t: complex) -> float:
    """``t.real`` where ``t`` counts as real (``pieper.IMAG_TOL``), else NaN."""
    return t.real if abs(t.imag) <= pieper.IMAG_TOL * (1.0 + abs(t)) else math.nan


def _step(f: float, df: float) -> float:
    """``pieper._bounded`` on floats."""
    step = f / df if df != 0.0 else math.nan
    return step if abs(step) <= pieper.MAX_NEWTON_STEP else 0.0


def _sorted(q: list[float]) -> list[float]:
    """Ascending, NaN last (as ``np.sort``)."""
    real = sorted(x for x in q if not math.isnan(x))
    return real + [math.nan] * (len(q) - len(real))


def revolute_roots(F: list[float]) -> tuple[list[float], bool]:
    """``pieper.revolute_roots`` for one row ``F`` (Fourier coefficients)."""
    lead = [sum(F[i] * QMAP[i][5 * j] for i in range(5)) for j in range(8)]
    mags = [abs(x) for x in lead]
    k = mags.index(max(mags)) if not any(map(math.isnan, mags)) else 0
    coeffs = tuple(sum(F[i] * QMAP[i][5 * k + j] for i in range(5)) for j in range(5))
    if abs(coeffs[0]) <= pieper.SELF_MOTION_TOL * sum(abs(x) for x in F):
        return list(_SHIFTS[::2]), True
    f0, f1, f2, f3, f4 = F
    out = []
    for t in quartic_roots(coeffs):
        q = _SHIFTS[k] + 2.0 * math.atan(_real(t))
        for _ in range(pieper.NEWTON_STEPS):
            if math.isnan(q):
                break
            c, s = math.cos(q), math.sin(q)
            c2, s2 = c * c - s * s, c * s + s * c
            f = f0 + (f1 * c + f2 * s) + (f3 * c2 + f4 * s2)
            df = (f2 * c - f1 * s) + 2.0 * (f4 * c2 - f3 * s2)
            q -= _step(f, df)
        out.append(math.atan2(math.sin(q), math.cos(q)))
    return _sorted(out), False


def slide_roots(k: tuple[float, ...]) -> list[float]:
    """``pieper.slide_roots`` for one quartic ``k``."""
    out = []
    for t in quartic_roots(k):
        q = _real(t)
        for _ in range(pieper.NEWTON_STEPS):
            f = df = 0.0
            for kj in k:
                df = df * q + f
                f = f * q + kj
            q -= _step(f, df)
        out.append(q)
    return _sorted(out)


def _slide_coefficients(sp: SinglePose, zeta: float, dd: float) -> tuple[float, ...]:
    """``pieper.slide_coefficients`` for one target."""
    c0, c1, _ = sp.coef
    L, H = (c0[3], c1[3]), (c0[2], c1[2])
    sa2, a2 = sp.g * sp.g, sp.a * sp.a
    x1, x0 = -L[1], dd - a2 - L[0]
    y1, y0 = -sp.ca * H[1], zeta - sp.ca * H[0]
    P = (1.0 - H[1] ** 2, L[1] - 2 * H[1] * H[0], L[0] - H[0] ** 2)
    return (
        sa2,
        -2 * sa2 * x1,
        sa2 * (x1 * x1 - 2 * x0) + 4 * a2 * y1 * y1 - 4 * a2 * sa2 * P[0],
        2 * sa2 * x1 * x0 + 8 * a2 * y1 * y0 - 4 * a2 * sa2 * P[1],
        sa2 * x0 * x0 + 4 * a2 * y0 * y0 - 4 * a2 * sa2 * P[2],
    )


def quartic_position(
    sp: SinglePose, ct: list[float], dz: list[float]
) -> tuple[list[tuple[float, ...]], bool, bool]:
    """The 4 position branches, the q2-free flag and the self-motion flag.

    Args:
        sp: The single-pose constants.
        ct: Target wrist centre, base frame.
        dz: It in ``frame1`` coordinates, from ``p1``.
    """
    zeta, dd = dz[0], dz[0] ** 2 + dz[1] ** 2 + dz[2] ** 2
    a, ca, (c0, c1, c2) = sp.a, sp.ca, sp.coef
    selfmotion = False
    if sp.prismatic:
        q3s = slide_roots(_slide_coefficients(sp, zeta, dd))
        vals = [[(c2[j] * q3 + c1[j]) * q3 + c0[j] for j in range(4)] for q3 in q3s]
    else:
        X0 = dd - a * a - c0[3]
        Y0 = zeta - ca * c0[2]
        terms = (X0 * X0, X0, Y0 * Y0, Y0, 1.0)
        s4 = sp.scale**4
        F = [sum(terms[i] * sp.fourier[i][j] for i in range(5)) / s4 for j in range(5)]
        q3s, selfmotion = revolute_roots(F)
        vals = []
        for q3 in q3s:
            cq, sq = math.cos(q3), math.sin(q3)
            vals.append([cq * c1[j] + sq * c2[j] + c0[j] for j in range(4)])
    phi = math.atan2(dz[2], dz[1])
    X, accept, polish = sp.xframe, pieper.ACCEPT_TOL * sp.scale, False
    out: list[tuple[float, ...]] = []
    on2 = False
    for q3, (u1, u2, H, L) in zip(q3s, vals, strict=True):
        up2 = u1 * u1 + u2 * u2
        on2 = on2 or up2 < sp.tol2
        v1 = (dd - a * a - L) * (0.5 / a)
        v2 = (zeta - ca * H) * (1.0 / sp.g)
        miss = abs(math.sqrt(v1 * v1 + v2 * v2) - math.sqrt(up2))
        polish = polish or miss > pieper.POLISH_FROM * sp.scale
        q2 = math.atan2(u1 * v2 - u2 * v1, u1 * v1 + u2 * v2)
        xa = H * X[0][0] + v1 * X[1][0] + v2 * X[2][0] + X[3][0]
        xb = H * X[0][1] + v1 * X[1][1] + v2 * X[2][1] + X[3][1]
        out.append((phi - math.atan2(xb, xa), q2, q3 if miss <= accept else math.nan))
    if polish:
        out = _polish(sp, out, ct)
    return out, on2, selfmotion


Vec = tuple[float, float, float]


def _cross(u: Vec, v: Vec) -> Vec:
    return (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])


def _dot(u: Vec, v: Vec) -> float:
    return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]


def _turn(k: Vec, c: float, s: float, v: Vec) -> Vec:
    """Rodrigues, as ``pieper._turn``."""
    kx, kv = _cross(k, v), _dot(v, k) * (1.0 - c)
    return (
        v[0] * c + kx[0] * s + k[0] * kv,
        v[1] * c + kx[1] * s + k[1] * kv,
        v[2] * c + kx[2] * s + k[2] * kv,
    )


def _residual(sp: SinglePose, q: tuple[float, ...], d: Vec) -> tuple[Vec, Vec, Vec, Vec]:
    """``pieper._residual`` for one candidate: ``R1ᵀ d - y``, ``y``, ``w``, ``dw``."""
    h1, h2, p21, U0, U1, U2 = sp.polish
    c1, c2, c3 = (math.cos(x) for x in q)
    s1, s2, s3 = (math.sin(x) for x in q)
    if sp.prismatic:
        u = tuple(U0[i] + q[2] * U1[i] for i in range(3))
        du = U1
    else:
        u = tuple(U0[i] + c3 * U1[i] + s3 * U2[i] for i in range(3))
        du = tuple(c3 * U2[i] - s3 * U1[i] for i in range(3))
    w, dw = _turn(h2, c2, s2, u), _turn(h2, c2, s2, du)
    y = (p21[0] + w[0], p21[1] + w[1], p21[2] + w[2])
    x = _turn(h1, c1, -s1, d)
    return (x[0] - y[0], x[1] - y[1], x[2] - y[2]), y, w, dw


def _polish(sp: SinglePose, q: list[tuple[float, ...]], ct: list[float]) -> list[tuple[float, ...]]:
    """``pieper.polish_position`` for the candidates of one target."""
    p1 = sp.polish_p1
    d = (ct[0] - p1[0], ct[1] - p1[1], ct[2] - p1[2])
    out = []
    for qi in q:
        r, y, w, dw = _residual(sp, qi, d)
        j1, j2 = _cross(sp.polish[0], y), _cross(sp.polish[1], w)
        n23, n31, n12 = _cross(j2, dw), _cross(dw, j1), _cross(j1, j2)
        det = _dot(j1, n23)
        if det != 0.0 and not math.isnan(det):
            new = tuple(x + _dot(r, n) / det for x, n in zip(qi, (n23, n31, n12), strict=True))
            r2 = _residual(sp, new, d)[0]
            if _dot(r2, r2) < _dot(r, r):
                qi = new
        out.append(qi)
    return out
