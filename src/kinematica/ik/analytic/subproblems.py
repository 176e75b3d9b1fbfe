"""Geometric subproblems of closed-form IK, and the roots they lead to.

The subproblems are those of Paden and Kahan, numbered as in IK-Geo (Elias and
Wen, "IK-Geo: Unified robot inverse kinematics using subproblem
decomposition", 2022). Every rotation axis passes through the origin and is a
unit vector; ``R(k, θ)`` is the rotation by ``θ`` about ``k`` (right hand)::

    SP1  R(k, θ) p1 = p2                      one θ
    SP2  R(k1, θ1) p1 = R(k2, θ2) p2          up to two (θ1, θ2)
    SP3  |R(k, θ) p1 - p2| = d                up to two θ
    SP4  hᵀ R(k, θ) p = d                     up to two θ

SP3 and SP4 reduce to :func:`solve_trig_linear` (``a cos θ + b sin θ = c``).
:func:`solve_quartic` finds the four complex roots of a batch of quartics, as
closed-form solvers whose elimination ends in a degree-4 polynomial need.

Everything broadcasts over leading batch axes and is pure numpy. Two-solution
functions return ``(..., 2)`` angles and an ``exact`` flag: where no exact
solution exists the angles hold a least-squares (SP1, SP3, SP4) or closest
(SP2) answer, duplicated in both slots, and ``exact`` is False. The caller
decides whether to keep it.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "COMPANION_BELOW",
    "QUARTIC_CHECK",
    "TRIG_TOL",
    "cross",
    "rotate",
    "rotation_matrix",
    "rowmul",
    "solve_quartic",
    "solve_trig_linear",
    "subproblem1",
    "subproblem2",
    "subproblem3",
    "subproblem4",
]

FloatArray = NDArray[np.float64]
BoolArray = NDArray[np.bool_]

#: ``a cos θ + b sin θ = c`` with ``|c|`` above ``hypot(a, b)`` by at most this
#: fraction is taken as touching (one double root) rather than unreachable: a
#: target on the boundary of the reachable set, computed by forward kinematics,
#: lands a few ulps on either side of it.
TRIG_TOL = 1e-10

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


def rowmul(A: FloatArray, B: FloatArray) -> FloatArray:
    """``A @ B`` for ``A (..., k)`` and a matrix ``B (k, m)``, as one matrix product.

    ``A @ B`` with a batch of rows goes through numpy's stacked-matmul loop,
    one tiny product per row (15x slower for 10⁴ rows); reshaping to one
    ``(rows, k)`` matrix hands the whole batch to BLAS at once.
    """
    A = np.ascontiguousarray(A)
    return (A.reshape(-1, A.shape[-1]) @ B).reshape(*A.shape[:-1], B.shape[-1])


def rotate(k: ArrayLike, theta: ArrayLike, v: ArrayLike) -> FloatArray:
    """Rotate vectors about a unit axis through the origin (Rodrigues).

    Args:
        k: ``(..., 3)`` unit axis.
        theta: ``(...)`` angle (rad).
        v: ``(..., 3)`` vectors.

    Returns:
        ``(..., 3)`` ``R(k, θ) v``.
    """
    k, v, t = _f(k), _f(v), _f(theta)[..., None]
    c, s = np.cos(t), np.sin(t)
    return v * c + cross(k, v) * s + k * (_dot(k, v)[..., None] * (1.0 - c))


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


def solve_trig_linear(
    a: ArrayLike, b: ArrayLike, c: ArrayLike, tol: float = TRIG_TOL
) -> tuple[FloatArray, BoolArray]:
    """The angles ``θ`` with ``a cos θ + b sin θ = c``.

    With ``r = hypot(a, b)`` and ``s = sqrt(r² - c²)`` the two solutions are
    ``θ = atan2(b c ± a s, a c ∓ b s)`` (no ``acos``, so no loss of accuracy
    away from the double root). Slot 0 takes the upper signs. When ``|c| > r``
    (beyond ``tol``) there is no solution: both slots hold the least-squares
    angle ``atan2(b c, a c)`` and ``exact`` is False. When ``a = b = 0`` every
    angle solves ``c = 0`` and none solves ``c ≠ 0``: both slots hold 0 and
    ``exact`` says whether ``c`` is 0.

    Args:
        a: ``(...)`` coefficient of ``cos θ``.
        b: ``(...)`` coefficient of ``sin θ``.
        c: ``(...)`` right-hand side.
        tol: Relative slack on ``|c| <= r``.

    Returns:
        ``(theta (..., 2), exact (...))``.
    """
    a, b, c = np.broadcast_arrays(_f(a), _f(b), _f(c))
    r2 = a * a + b * b
    disc = r2 - c * c
    exact = disc >= -2.0 * tol * r2
    s = np.sqrt(np.maximum(disc, 0.0))
    bs, as_ = b * s, a * s
    bc, ac = b * c, a * c
    theta = np.stack([np.arctan2(bc + as_, ac - bs), np.arctan2(bc - as_, ac + bs)], axis=-1)
    degenerate = r2 == 0.0
    if np.any(degenerate):
        theta[degenerate] = 0.0
        exact = np.where(degenerate, c == 0.0, exact)
    return theta, exact


def subproblem2(
    p1: ArrayLike, p2: ArrayLike, k1: ArrayLike, k2: ArrayLike
) -> tuple[FloatArray, FloatArray, BoolArray]:
    """SP2: the angles with ``R(k1, θ1) p1 = R(k2, θ2) p2``.

    The common vector ``v = R(k1, θ1) p1 = R(k2, θ2) p2`` has ``k1ᵀv = k1ᵀp1``,
    ``k2ᵀv = k2ᵀp2`` and ``|v| = |p1|``, so ``v = α k1 + β k2 ± γ (k1 × k2)``;
    slot 0 takes ``γ >= 0``. Then ``θ1`` turns ``p1`` onto ``v`` about ``k1``
    and ``θ2`` turns ``p2`` onto ``v`` about ``k2`` (two SP1). ``γ²`` is computed
    from the part of ``p1`` off ``k1`` (no cancellation when ``v`` nears ``k1``).
    Needs ``k1`` not parallel to ``k2``.

    Args:
        p1: ``(..., 3)``.
        p2: ``(..., 3)``, with ``|p2| = |p1|`` for an exact solution.
        k1: ``(..., 3)`` unit axis.
        k2: ``(..., 3)`` unit axis, not parallel to ``k1``.

    Returns:
        ``(theta1 (..., 2), theta2 (..., 2), exact (...))``; without an exact
        solution ``γ`` is taken as 0 (the closest common vector in the plane
        of the axes).
    """
    p1, p2, k1, k2 = _f(p1), _f(p2), _f(k1), _f(k2)
    k12 = _dot(k1, k2)
    n = cross(k1, k2)
    nn = 1.0 - k12 * k12  # |k1 × k2|²
    a1, a2 = _dot(k1, p1), _dot(k2, p2)
    beta = (a2 - k12 * a1) / nn
    alpha = a1 - k12 * beta
    # |v - (k1ᵀv) k1|² = |p1 - (k1ᵀp1) k1|² = β² |k1×k2|² + γ² |k1×k2|²
    off1 = p1 - a1[..., None] * k1
    g2 = _dot(off1, off1) / nn - beta * beta
    exact = g2 >= -2.0 * TRIG_TOL * (_dot(p1, p1) / nn)
    g = np.sqrt(np.maximum(g2, 0.0))[..., None]
    base = alpha[..., None] * k1 + beta[..., None] * k2
    v = np.stack([base + g * n, base - g * n], axis=-2)  # (..., 2, 3)
    kk1, kk2 = k1[..., None, :], k2[..., None, :]
    theta1 = subproblem1(p1[..., None, :], v, kk1)
    theta2 = subproblem1(p2[..., None, :], v, kk2)
    return theta1, theta2, exact


def subproblem3(
    p1: ArrayLike, p2: ArrayLike, k: ArrayLike, d: ArrayLike
) -> tuple[FloatArray, BoolArray]:
    """SP3: the angles with ``|R(k, θ) p1 - p2| = d``.

    Expanding the square gives ``a cos θ + b sin θ = c`` with the parts of
    ``p1`` and ``p2`` off the axis; see :func:`solve_trig_linear` for slots.

    Args:
        p1: ``(..., 3)`` vector to rotate.
        p2: ``(..., 3)`` fixed point.
        k: ``(..., 3)`` unit axis.
        d: ``(...)`` distance (>= 0).

    Returns:
        ``(theta (..., 2), exact (...))``.
    """
    p1, p2, k, d = _f(p1), _f(p2), _f(k), _f(d)
    k1, k2 = _dot(k, p1), _dot(k, p2)
    u = p1 - k1[..., None] * k
    v = p2 - k2[..., None] * k
    # |R p1 - p2|² = |p1|² + |p2|² - 2 (k1 k2 + uᵀv cos θ + kᵀ(u × v) sin θ)
    rhs = (_dot(p1, p1) + _dot(p2, p2) - d * d) / 2.0 - k1 * k2
    return solve_trig_linear(_dot(u, v), _dot(k, cross(u, v)), rhs)


def subproblem4(
    h: ArrayLike, p: ArrayLike, k: ArrayLike, d: ArrayLike
) -> tuple[FloatArray, BoolArray]:
    """SP4: the angles with ``hᵀ R(k, θ) p = d``.

    ``R p = (kᵀp) k + cos θ u + sin θ (k × u)`` with ``u`` the part of ``p``
    off the axis; see :func:`solve_trig_linear` for slots.

    Args:
        h: ``(..., 3)`` direction (any length).
        p: ``(..., 3)`` vector to rotate.
        k: ``(..., 3)`` unit axis.
        d: ``(...)`` value to reach.

    Returns:
        ``(theta (..., 2), exact (...))``.
    """
    h, p, k, d = _f(h), _f(p), _f(k), _f(d)
    kp = _dot(k, p)
    u = p - kp[..., None] * k
    return solve_trig_linear(_dot(h, u), _dot(h, cross(k, u)), d - kp * _dot(h, k))


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
