"""The pose error of numeric IK and its Jacobian, batched across rows.

Rows (one attempt at one target each) lie along the *last* axis, "structure
of arrays": frames as ``(3, R)`` columns, the Jacobian as ``(m, n, R)``, so
every operation is one numpy call on ``R`` contiguous numbers. The forward
kinematics is the regrouped DH product of :class:`kinematica.dh.DHChain`, on
the same compiled rows, keeping the joint axes the Jacobian needs.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from kinematica.dh import DHChain
from kinematica.ik.numeric_problem import LMProblem

__all__ = ["SERIES_ANGLE", "evaluate", "pose_error"]

FloatArray = NDArray[np.float64]

#: Below this rotation angle (rad) J_r⁻¹'s coefficients are taken from their
#: series (to θ⁴, exact to round-off there); above it the closed forms lose
#: under 1e-11 relative.
SERIES_ANGLE = 1e-2


def _rotate(X: FloatArray, Y: FloatArray, c: float, s: float) -> tuple[FloatArray, FloatArray]:
    """``(c X + s Y, c Y − s X)`` for constants, skipping exact zeros."""
    if s == 0.0:
        return (X, Y) if c == 1.0 else (-X, -Y)
    if c == 0.0:
        return (Y, -X) if s == 1.0 else (-Y, X)
    return c * X + s * Y, c * Y - s * X


def _frames(
    chain: DHChain, q: FloatArray
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray, FloatArray, FloatArray]:
    """Tool frame and joint axes, by the same regrouped product as ``DHChain``.

    Args:
        chain: The compiled chain.
        q: ``(n, R)`` joint values.

    Returns:
        ``(X, Y, Z, P, axes, points)``: the tool's rotation columns and origin,
        each ``(3, R)``; each joint's axis direction and a point on it, each
        ``(3, n, R)``. All in the base frame.
    """
    n, R = q.shape
    prismatic = chain.prismatic
    theta = np.where(prismatic[:, None], chain.theta[:, None], q + chain.theta[:, None])
    ct, st = np.cos(theta), np.sin(theta)
    S = chain.start
    X, Y, Z, P = (np.repeat(S[:3, j : j + 1], R, axis=1) for j in range(4))
    axes = np.empty((3, n, R))
    points = np.empty((3, n, R))
    for i in range(n):
        axes[:, i] = Z
        points[:, i] = P
        if prismatic[i]:
            th = float(chain.theta[i])
            X1, W = _rotate(X, Y, math.cos(th), math.sin(th))
            P = P + (q[i] + chain.d[i]) * Z
        else:
            c, s = ct[i], st[i]
            X1 = c * X
            X1 += s * Y
            W = c * Y
            W -= s * X
            if chain.d[i] != 0.0:
                P = P + chain.d[i] * Z
        if chain.a[i] != 0.0:
            P = P + chain.a[i] * X1
        X = X1
        Y, Z = _rotate(W, Z, float(chain.ca[i]), float(chain.sa[i]))
    E = chain.end
    if not np.array_equal(E, np.eye(4)):
        X, Y, Z, P = (
            E[0, 0] * X + E[1, 0] * Y + E[2, 0] * Z,
            E[0, 1] * X + E[1, 1] * Y + E[2, 1] * Z,
            E[0, 2] * X + E[1, 2] * Y + E[2, 2] * Z,
            P + E[0, 3] * X + E[1, 3] * Y + E[2, 3] * Z,
        )
    return X, Y, Z, P, axes, points


def _rotvec(M: FloatArray) -> FloatArray:
    """Rotation vectors ``(3, R)`` of rotations ``M (3, 3, R)``, exact at 0 and near π.

    ``θ = atan2(|v|, (tr M − 1)/2)`` with ``v`` the skew part's vector; the axis
    comes from ``v`` up to π/2 and from the symmetric part beyond, where ``v``
    loses accuracy: the branches of :func:`kinematica.spatial.rotvec_from_matrix`,
    in this module's layout and without its validation.
    """
    v = np.stack([M[2, 1] - M[1, 2], M[0, 2] - M[2, 0], M[1, 0] - M[0, 1]])  # 2 sin θ n
    sin2 = np.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
    cos2 = M[0, 0] + M[1, 1] + M[2, 2] - 1.0
    angle = np.arctan2(sin2, cos2)
    rotvec = v * np.divide(angle, sin2, out=np.full_like(angle, 0.5), where=sin2 > 0.0)
    near_pi = np.flatnonzero(cos2 < 0.0)
    if near_pi.size:
        # (M + Mᵀ)/2 − cos θ I = (1 − cos θ) n nᵀ: the column with the largest
        # diagonal is the best-conditioned multiple of n; its sign follows v.
        Mn = M[:, :, near_pi]
        S = 0.5 * (Mn + Mn.transpose(1, 0, 2)) - 0.5 * cos2[near_pi] * np.eye(3)[:, :, None]
        col = np.argmax(np.stack([S[0, 0], S[1, 1], S[2, 2]]), axis=0)
        axis = S[:, col, np.arange(near_pi.size)]
        axis /= np.sqrt(np.sum(axis * axis, axis=0))
        sign = np.where(np.sum(axis * v[:, near_pi], axis=0) < 0.0, -1.0, 1.0)
        rotvec[:, near_pi] = axis * (sign * angle[near_pi])
    return rotvec


def _errors(
    X: FloatArray,
    Y: FloatArray,
    Z: FloatArray,
    P: FloatArray,
    p_target: FloatArray,
    R_target: FloatArray | None,
) -> tuple[FloatArray, FloatArray | None]:
    """``(Δp, Δω)``, each ``(3, R)``; ``Δω`` None for position targets."""
    dp = p_target - P
    if R_target is None:
        return dp, None
    # (R_target Rᵀ)[i, j] = Σ_k R_target[i, k] R[j, k], R's columns being X, Y, Z.
    M = np.einsum("ikr,jkr->ijr", R_target, np.stack([X, Y, Z], axis=1))
    return dp, _rotvec(M)


def pose_error(
    problem: LMProblem,
    X: FloatArray,
    Y: FloatArray,
    Z: FloatArray,
    P: FloatArray,
    p_target: FloatArray,
    R_target: FloatArray | None,
) -> FloatArray:
    """The counted error components, unweighted.

    Args:
        problem: The problem.
        X: ``(3, R)`` the tool's x axis (base frame).
        Y: ``(3, R)`` its y axis.
        Z: ``(3, R)`` its z axis.
        P: ``(3, R)`` the tool origin (m).
        p_target: ``(3, R)`` target positions.
        R_target: ``(3, 3, R)`` target rotations, or None for position targets.

    Returns:
        ``(m, R)``: the components ``problem.rows`` of ``(Δp, Δω)``, with
        ``Δp = p_target − p`` (m) and ``Δω`` the rotation vector of
        ``R_target · Rᵀ`` (rad), both in the base frame.
    """
    dp, dw = _errors(X, Y, Z, P, p_target, R_target if problem.orientation else None)
    return dp[problem.rows] if dw is None else np.concatenate([dp, dw])[problem.rows]


def _inverse_right_jacobian(phi: FloatArray) -> FloatArray:
    """``J_r⁻¹(φ) = α I + ½[φ]× + c φφᵀ`` of SO(3), ``(3, 3, R)`` for ``φ (3, R)``.

    With ``θ = |φ|``: ``α = (θ/2) cot(θ/2)`` and ``c = (1 − α)/θ²``, by their
    series below :data:`SERIES_ANGLE` (where ``1 − α`` cancels).
    """
    th2 = np.sum(phi * phi, axis=0)
    half = 0.5 * np.sqrt(th2)
    small = half < 0.5 * SERIES_ANGLE
    safe = np.where(small, 1.0, half)
    alpha = np.where(small, 1.0 - th2 / 12.0 - th2 * th2 / 720.0, safe / np.tan(safe))
    c = np.where(
        small,
        1.0 / 12.0 + th2 / 720.0 + th2 * th2 / 30240.0,
        (1.0 - alpha) / np.where(small, 1.0, th2),
    )
    x, y, z = 0.5 * phi
    out = c * phi[:, None] * phi[None]
    out[0, 0] += alpha
    out[1, 1] += alpha
    out[2, 2] += alpha
    out[0, 1] -= z
    out[1, 0] += z
    out[0, 2] += y
    out[2, 0] -= y
    out[1, 2] -= x
    out[2, 1] += x
    return out


def evaluate(
    problem: LMProblem, q: FloatArray, p_target: FloatArray, R_target: FloatArray | None
) -> tuple[FloatArray, FloatArray]:
    """Counted errors ``(m, R)`` (unweighted) and weighted Jacobian rows ``(m, n, R)``.

    Column i of the geometric Jacobian is ``[z × (p − o); z]`` for a revolute
    joint with axis ``z`` through ``o``, ``[z; 0]`` for a prismatic one. The
    error Jacobian is ``−J``, except that with only some rotation components
    counted its rotation rows are ``−J_r⁻¹(Δω) J_ω`` (see ``LMProblem.exact``).
    """
    X, Y, Z, P, axes, points = _frames(problem.chain, q)
    dp, dw = _errors(X, Y, Z, P, p_target, R_target if problem.orientation else None)
    rows = problem.rows.tolist()
    err = dp[rows] if dw is None else np.concatenate([dp, dw])[rows]
    z0, z1, z2 = axes
    d0, d1, d2 = P[:, None, :] - points
    prismatic = problem.prismatic[:, None]
    has_prismatic = bool(problem.prismatic.any())
    angular = axes * ~prismatic if has_prismatic else axes
    if problem.exact and dw is not None:
        angular = np.einsum("ijr,jnr->inr", _inverse_right_jacobian(dw), angular)
    J = np.empty((len(rows), *q.shape))
    for i, r in enumerate(rows):
        if r == 0:
            np.multiply(z1, d2, out=J[i])
            J[i] -= z2 * d1
        elif r == 1:
            np.multiply(z2, d0, out=J[i])
            J[i] -= z0 * d2
        elif r == 2:
            np.multiply(z0, d1, out=J[i])
            J[i] -= z1 * d0
        else:
            J[i] = angular[r - 3]
        if has_prismatic and r < 3:
            J[i] = np.where(prismatic, axes[r], J[i])
    if problem.weighted:
        J *= problem.weight[:, None, None]
    return err, J
