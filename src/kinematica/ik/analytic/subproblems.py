"""Geometric subproblems of closed-form IK (numpy), and the roots they lead to.

TRANSITIONAL: what the numpy solvers still being ported to kernels use
(:mod:`kinematica.kernels.geometry` and :mod:`kinematica.kernels.polynomial`
hold the kernel versions). The subproblems are those of Paden and Kahan,
numbered as in IK-Geo (Elias and Wen, "IK-Geo: Unified robot inverse
kinematics using subproblem decomposition", 2022). Every rotation axis passes
through the origin and is a unit vector; ``R(k, θ)`` is the rotation by ``θ``
about ``k`` (right hand)::

    SP1  R(k, θ) p1 = p2                      one θ

:func:`solve_quartic` finds the four complex roots of a batch of quartics, as
closed-form solvers whose elimination ends in a degree-4 polynomial need.
Everything broadcasts over leading batch axes and is pure numpy.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "COMPANION_BELOW",
    "QUARTIC_CHECK",
    "cross",
    "rotation_matrix",
    "solve_quartic",
    "subproblem1",
]

FloatArray = NDArray[np.float64]
BoolArray = NDArray[np.bool_]

#: Batches of fewer quartics than this go straight to the companion-matrix
#: eigenvalues: numpy's per-call cost makes the closed form slower there.
COMPANION_BELOW = 48

#: A root of :func:`solve_quartic` whose backward error ``|P(x)| / Σ|k_i||x|^i``
#: exceeds this sends its quartic to the companion-matrix fallback.
QUARTIC_CHECK = 1e-12


def _f(x: ArrayLike) -> FloatArray:
    return np.asarray(x, dtype=float)


def _dot(u: FloatArray, v: FloatArray) -> FloatArray:
    return np.sum(u * v, axis=-1)


def cross(u: ArrayLike, v: ArrayLike) -> FloatArray:
    """Cross products over the last axis, broadcast.

    ``np.cross`` without its per-call overhead, which dominates for small batches.

    Args:
        u: ``(..., 3)``.
        v: ``(..., 3)``.

    Returns:
        ``(..., 3)`` ``u × v``.
    """
    u, v = _f(u), _f(v)
    u0, u1, u2 = u[..., 0], u[..., 1], u[..., 2]
    v0, v1, v2 = v[..., 0], v[..., 1], v[..., 2]
    out = np.empty(np.broadcast_shapes(u.shape, v.shape))
    out[..., 0] = u1 * v2 - u2 * v1
    out[..., 1] = u2 * v0 - u0 * v2
    out[..., 2] = u0 * v1 - u1 * v0
    return out


def rotation_matrix(k: ArrayLike, theta: ArrayLike) -> FloatArray:
    """Rotation matrices about a unit axis (Rodrigues).

    Args:
        k: ``(..., 3)`` unit axis.
        theta: ``(...)`` angle (rad).

    Returns:
        ``(..., 3, 3)`` ``R(k, θ) = I + sin θ [k]× + (1 - cos θ) [k]×²``.
    """
    k, t = _f(k), _f(theta)
    shape = np.broadcast_shapes(k.shape[:-1], t.shape)
    k = np.broadcast_to(k, (*shape, 3))
    K = np.zeros((*shape, 3, 3))
    K[..., 0, 1], K[..., 0, 2], K[..., 1, 2] = -k[..., 2], k[..., 1], -k[..., 0]
    K = K - np.swapaxes(K, -1, -2)
    s, c = np.sin(t)[..., None, None], np.cos(t)[..., None, None]
    return np.eye(3) + s * K + (1.0 - c) * (K @ K)


def subproblem1(p1: ArrayLike, p2: ArrayLike, k: ArrayLike) -> FloatArray:
    """SP1: the angle ``θ`` with ``R(k, θ) p1 = p2``.

    Exact when ``kᵀp1 = kᵀp2`` and ``|p1| = |p2|``; otherwise the angle that
    brings ``p1`` closest to ``p2``. If ``p1`` or ``p2`` lies on the axis every
    angle is as good and 0 is returned (``atan2(0, 0)``).

    Args:
        p1: ``(..., 3)`` vector to rotate.
        p2: ``(..., 3)`` vector to reach.
        k: ``(..., 3)`` unit axis.

    Returns:
        ``(...)`` angle in ``(-π, π]``.
    """
    p1, p2, k = _f(p1), _f(p2), _f(k)
    a = p1 - _dot(k, p1)[..., None] * k
    return np.arctan2(_dot(k, cross(a, p2)), _dot(a, p2))


def _largest_cubic_root(A: FloatArray, B: FloatArray, C: FloatArray) -> FloatArray:
    """Largest real root of ``m³ + A m² + B m + C``, polished by two Newton steps."""
    A3 = A / 3.0
    P = B - A * A3
    Q = (2.0 / 27.0) * A * A * A - A3 * B + C
    disc = 0.25 * Q * Q + P * P * P / 27.0
    # one real root (Cardano) where disc > 0, three (trigonometric form) otherwise
    sq = np.sqrt(np.maximum(disc, 0.0))
    z1 = np.cbrt(-0.5 * Q + sq) + np.cbrt(-0.5 * Q - sq)
    rho = np.sqrt(np.maximum(P * (-1.0 / 3.0), 0.0))
    cos3 = np.minimum(np.maximum(-0.5 * Q / (rho * rho * rho + (rho == 0.0)), -1.0), 1.0)
    z3 = 2.0 * rho * np.cos(np.arccos(cos3) / 3.0)
    m = np.where(disc > 0.0, z1, z3) - A3
    for _ in range(2):
        f = ((m + A) * m + B) * m + C
        df = (3.0 * m + 2.0 * A) * m + B
        m = m - f / (df + (df == 0.0)) * (df != 0.0)
    return m


def solve_quartic(coeffs: ArrayLike) -> NDArray[np.complex128]:
    """All four complex roots of a batch of quartics (Ferrari, vectorised).

    The quartic is made monic, scaled, depressed (``x = y - b/4``) and split by
    the largest root ``m >= 0`` of its resolvent cubic into two quadratics
    ``y² ∓ √(2m) y + p/2 + m ± w``. Accuracy is that of a closed form (a few
    ulps times the conditioning); callers polish the roots they keep on their
    own equation. Rows where a root fails a backward-error check (widely
    spread roots) are solved again, batched, by ``np.linalg.eigvals`` on the
    companion matrix; so are batches smaller than :data:`COMPANION_BELOW`.

    Args:
        coeffs: ``(..., 5)`` real coefficients, highest power first; the
            leading one must not be 0.

    Returns:
        ``(..., 4)`` complex roots, in no particular order.
    """
    k = _f(coeffs)
    if k.size < 5 * COMPANION_BELOW:
        return _companion_roots(k.reshape(-1, 5)).reshape(*k.shape[:-1], 4)
    monic = k[..., 1:] / k[..., :1]
    # x = λ z with λ the largest |k_i / k_0|^(1/i) (Fujiwara's bound without
    # its factor 2): the roots z are O(1) however large the x are.
    lam = np.max(np.abs(monic) ** _ROOT_POWERS, axis=-1)
    lam = lam + (lam == 0.0)
    inv = 1.0 / lam
    b, c, d, e = (monic[..., i] * inv ** (i + 1) for i in range(4))
    b4 = 0.25 * b
    b42 = b4 * b4
    p = c - 6.0 * b42
    q = d - 2.0 * b4 * c + 8.0 * b42 * b4
    r = e - b4 * d + b42 * c - 3.0 * b42 * b42
    m = np.maximum(_largest_cubic_root(p, 0.25 * p * p - r, -0.125 * q * q), 0.0)
    s = np.sqrt(2.0 * m)
    # w = q / (2 s) (from the factorisation); where s is ~0 (relative to the
    # scaled roots, O(1)) the quotient is 0/0 and w² = m² + m p + p²/4 - r instead
    w_small = np.copysign(np.sqrt(np.maximum(m * m + m * p + 0.25 * p * p - r, 0.0)), q)
    big = s > _SMALL_S * (1.0 + np.sqrt(np.abs(p)))
    w = np.where(big, 0.5 * q / (s + ~big), w_small)
    # y² - s y + (p/2 + m + w) = 0 and y² + s y + (p/2 + m - w) = 0
    S = s[..., None] * _PM
    disc = np.sqrt((S * S - 4.0 * (0.5 * p + m)[..., None] - 4.0 * w[..., None] * _PM) + 0j)
    roots = np.empty((*b.shape, 4), dtype=complex)
    roots[..., 0::2] = 0.5 * (S + disc)
    roots[..., 1::2] = 0.5 * (S - disc)
    roots = (roots - b4[..., None]) * lam[..., None]
    # Ferrari loses small roots next to a much larger one (the shift b/4 is
    # then large); a backward error above QUARTIC_CHECK flags those rows, which
    # are solved again as eigenvalues of the companion matrix (backward stable).
    value = roots * k[..., :1] + k[..., 1:2]
    size = np.abs(roots)
    bound = size * np.abs(k[..., :1]) + np.abs(k[..., 1:2])
    for i in range(2, 5):
        value = value * roots + k[..., i : i + 1]
        bound = bound * size + np.abs(k[..., i : i + 1])
    bad = (np.abs(value) > QUARTIC_CHECK * bound).any(axis=-1)
    if bad.any():
        roots[bad] = _companion_roots(k[bad])
    return roots


def _companion_roots(k: FloatArray) -> NDArray[np.complex128]:
    """Roots of quartics ``k (m, 5)`` as eigenvalues of their companion matrices."""
    companion = np.zeros((len(k), 4, 4))
    companion[:, 0, :] = -k[:, 1:] / k[:, :1]
    companion[:, 1, 0] = companion[:, 2, 1] = companion[:, 3, 2] = 1.0
    return np.linalg.eigvals(companion).astype(complex)


_ROOT_POWERS = 1.0 / np.arange(1.0, 5.0)
#: Below this ``s = sqrt(2m)`` (roots scaled to O(1)), ``w = q / 2s`` is 0/0.
_SMALL_S = 1e-8
_PM = np.array([1.0, -1.0])
