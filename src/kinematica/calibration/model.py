"""The error model of a calibration: a small rigid transform in every link, base and tool.

The robot's compiled chain (:class:`kinematica.core.Chain`, whatever it was read from)
is written ``T(q) = S · Π_i [M_i(q_i) · Rz(θ_i) Tz(d_i) · Trans(a_i, y_i, 0) Rx(α_i)] · U``
(``S`` its start, ``U`` its tool; for a DH table ``y_i = 0`` and ``θ_i, d_i, a_i, α_i`` are
row i's in the standard convention, Craig's ``a_i, α_i`` in the modified one). The
calibrated chain puts a rigid error transform in each link, between ``Tz(d_i)`` and
``Trans(a_i, y_i, 0)``, and one on each side of the chain::

    T(q; δ) = E_base · S · Π_i [M_i(q_i) Rz(θ_i) Tz(d_i) · E_i · Trans(a_i, y_i, 0) Rx(α_i)]
              · U · E_tool

with ``E(x, y, z, rx, ry, rz) = Trans(x, y, z) · Rz(rz) · Ry(ry) · Rx(rx)``. In a link the
six components are named after the DH values they change: ``z`` is ``d_i`` (exactly:
``Tz`` commutes with ``Tz``), ``rz`` is ``θ_i`` (``Rz(θ) Tz(d) Rz(ε) = Rz(θ + ε) Tz(d)``),
``x`` is ``a_i``, ``rx`` is ``α_i`` (``Rx`` commutes with ``Tx``), ``ry`` is Hayati's twist
``β_i`` about y and ``y`` the offset ``y_i`` along it. Every parameter moves its link by a
rigid motion of its own size, wherever the axes are: consecutive parallel axes, where a
DH table needs a huge ``d`` for a small tilt, cost this model nothing (``β_i`` takes the
tilt). The model has ``6 n + 12`` parameters, more than the data can tell apart; which
subset it can is found from the Jacobian (:mod:`kinematica.calibration.identify`).

The identification Jacobian is analytic: each parameter moves everything after it by
a twist (a rotation about, or a translation along, an axis of the frame it acts in),
read off the chain's frames, which the core computes (one batch call per evaluation).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

import kinematica._core as _core
from kinematica.core import Chain

__all__ = [
    "COMPONENTS",
    "ErrorModel",
    "error_transform",
    "inv_left_coefficient",
    "inv_left_jacobian",
    "log_rotation",
]

FloatArray = NDArray[np.float64]

#: The six components of an error transform, in the order of the parameter vector.
COMPONENTS = ("x", "y", "z", "rx", "ry", "rz")
#: What each component of a link's error transform is called (its DH value, Hayati's β).
LINK_NAMES = {"x": "a", "y": "y", "z": "d", "rx": "alpha", "ry": "beta", "rz": "theta"}
#: Below this rotation angle (rad), the SO(3) logarithm and its Jacobian use their series
#: to θ⁶ (the next terms are below 1e-19 here); above it, their closed forms, whose
#: cancellation (1/θ² against a term near it) costs 1e-11 relative at this angle.
SMALL_ANGLE = 1e-2


def _rz(c: float) -> FloatArray:
    return np.array([[math.cos(c), -math.sin(c), 0.0], [math.sin(c), math.cos(c), 0.0], [0, 0, 1]])


def _ry(b: float) -> FloatArray:
    return np.array([[math.cos(b), 0.0, math.sin(b)], [0, 1, 0], [-math.sin(b), 0.0, math.cos(b)]])


def _rx(a: float) -> FloatArray:
    return np.array([[1, 0, 0], [0.0, math.cos(a), -math.sin(a)], [0.0, math.sin(a), math.cos(a)]])


def error_transform(e: FloatArray) -> FloatArray:
    """``(4, 4)`` ``E = Trans(x, y, z) Rz(rz) Ry(ry) Rx(rx)`` of ``e = (x, y, z, rx, ry, rz)``."""
    E = np.eye(4)
    E[:3, :3] = _rz(e[5]) @ _ry(e[4]) @ _rx(e[3])
    E[:3, 3] = e[:3]
    return E


def _local_axes(e: FloatArray) -> tuple[FloatArray, FloatArray]:
    """The axes of E's six components in the frame E acts in, and the point the rotations hold.

    ``∂E/∂x_k · E⁻¹`` is a twist: a translation along x, y, z for the first three, a
    rotation about ``Rz Ry x``, ``Rz y``, ``z`` through ``(x, y, z)`` for the last three.
    """
    Rz, Ry = _rz(e[5]), _ry(e[4])
    axes = np.array([[1.0, 0, 0], [0, 1.0, 0], [0, 0, 1.0], Rz @ Ry[:, 0], Rz[:, 1], [0, 0, 1.0]])
    return axes, np.asarray(e[:3], dtype=float)


def _hat(v: FloatArray) -> FloatArray:
    """``(..., 3, 3)`` the cross-product matrices of ``v (..., 3)``."""
    H = np.zeros((*v.shape[:-1], 3, 3))
    H[..., 0, 1], H[..., 0, 2] = -v[..., 2], v[..., 1]
    H[..., 1, 0], H[..., 1, 2] = v[..., 2], -v[..., 0]
    H[..., 2, 0], H[..., 2, 1] = -v[..., 1], v[..., 0]
    return H


def log_rotation(R: FloatArray) -> FloatArray:
    """``(..., 3)`` the rotation vectors of rotations ``R (..., 3, 3)`` (angle below π)."""
    cos = np.clip((np.trace(R, axis1=-2, axis2=-1) - 1.0) / 2.0, -1.0, 1.0)
    theta = np.arccos(cos)
    w = np.stack(
        [R[..., 2, 1] - R[..., 1, 2], R[..., 0, 2] - R[..., 2, 0], R[..., 1, 0] - R[..., 0, 1]], -1
    )
    small = theta < SMALL_ANGLE
    sin = np.sin(np.where(small, 1.0, theta))
    t2 = theta**2
    series = 0.5 + t2 * (1.0 / 12.0 + t2 * (7.0 / 720.0 + t2 * 31.0 / 30240.0))
    factor = np.where(small, series, theta / (2.0 * sin))
    return w * factor[..., None]


def inv_left_coefficient(theta: FloatArray) -> FloatArray:
    """``1/θ² − (1 + cos θ) / (2 θ sin θ)``, the coefficient of ``φ̂²`` in ``J_l⁻¹(φ)``.

    Its series ``1/12 + θ²/720 + θ⁴/30240 + θ⁶/1209600`` below :data:`SMALL_ANGLE` (the
    closed form cancels there: both of its terms are near 1/θ²).
    """
    small = theta < SMALL_ANGLE
    t = np.where(small, 1.0, theta)
    closed = 1.0 / t**2 - (1.0 + np.cos(t)) / (2.0 * t * np.sin(t))
    t2 = theta**2
    series = 1.0 / 12.0 + t2 * (1.0 / 720.0 + t2 * (1.0 / 30240.0 + t2 / 1209600.0))
    return np.where(small, series, closed)


def inv_left_jacobian(phi: FloatArray) -> FloatArray:
    """``(..., 3, 3)`` the inverse left Jacobian of SO(3) at rotation vectors ``phi (..., 3)``.

    ``log(exp(ε ω) exp(φ)) = φ + ε J_l⁻¹(φ) ω + O(ε²)``: how a rotation residual
    ``log(R Rₘᵀ)`` moves when the model's ``R`` turns by ``ε ω`` (world frame).
    """
    coef = inv_left_coefficient(np.linalg.norm(phi, axis=-1))
    H = _hat(phi)
    return np.eye(3) - 0.5 * H + coef[..., None, None] * (H @ H)


@dataclass(frozen=True, eq=False)
class ErrorModel:
    """A chain's error model: the nominal transforms and the parameters' names.

    Parameters are ordered: base (6), each link's (6), tool (6), each block in
    :data:`COMPONENTS` order; ``δ = 0`` is the nominal chain.

    Attributes:
        chain: The nominal chain (the robot's compiled chain).
        start: ``(4, 4)`` the transform before joint 1's motion (world frame).
        heads: ``(n, 4, 4)`` each link's ``Rz(θ_i) Tz(d_i)``.
        tails: ``(n, 4, 4)`` each link's ``Trans(a_i, y_i, 0) Rx(α_i)``.
        tool: ``(4, 4)`` the transform after the last link.
        nominal: ``(6 n + 12,)`` the nominal value each parameter's name stands for
            (θ, d, a, α, y of the links; 0 for β, base and tool).
    """

    chain: Chain
    start: FloatArray
    heads: FloatArray
    tails: FloatArray
    tool: FloatArray
    nominal: FloatArray

    @classmethod
    def of(cls, chain: Chain) -> ErrorModel:
        """The error model of a compiled chain."""
        F = np.asarray(chain.fixed_parts)
        t = np.asarray(chain.translations)
        n = chain.dof
        theta = np.arctan2(F[:, 1, 0], F[:, 0, 0])
        alpha = np.arctan2(F[:, 2, 1], F[:, 2, 2])
        heads = np.tile(np.eye(4), (n, 1, 1))
        tails = np.tile(np.eye(4), (n, 1, 1))
        for i in range(n):
            heads[i, :3, :3] = _rz(theta[i])
            heads[i, :3, 3] = heads[i, :3, :3] @ np.array([0.0, 0.0, t[i, 2]])
            tails[i, :3, :3] = _rx(alpha[i])
            tails[i, :3, 3] = (t[i, 0], t[i, 1], 0.0)
        nominal = np.zeros(6 * n + 12)
        links = nominal[6:-6].reshape(n, 6)
        links[:, 0], links[:, 1], links[:, 2] = t[:, 0], t[:, 1], t[:, 2]
        links[:, 3], links[:, 5] = alpha, theta
        return cls(chain, np.asarray(chain.start), heads, tails, np.asarray(chain.tool), nominal)

    @property
    def dof(self) -> int:
        """Joints n."""
        return self.chain.dof

    @property
    def size(self) -> int:
        """Parameters: ``6 n + 12``."""
        return 6 * self.dof + 12

    @cached_property
    def names(self) -> tuple[str, ...]:
        """Each parameter's name, in the order of the parameter vector.

        ``base_x``..., then ``a1``, ``y1``, ``d1``, ``alpha1``, ``beta1``, ``theta1``...,
        then ``tool_x``... (``_rx, _ry, _rz``: rotations about x, y, z).
        """
        base = [f"base_{c}" for c in COMPONENTS]
        links = [f"{LINK_NAMES[c]}{i}" for i in range(1, self.dof + 1) for c in COMPONENTS]
        return (*base, *links, *(f"tool_{c}" for c in COMPONENTS))

    @cached_property
    def is_angle(self) -> NDArray[np.bool_]:
        """``(6 n + 12,)`` True for the angles (rad), False for the lengths (m)."""
        return np.tile(np.array([False, False, False, True, True, True]), self.dof + 2)

    def blocks(self, delta: FloatArray) -> FloatArray:
        """``(n + 2, 6)`` the parameter vector as base, links, tool blocks."""
        return np.asarray(delta, dtype=float).reshape(self.dof + 2, 6)

    def transforms(self, delta: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        """``(start, between (n - 1, 4, 4), end)`` of the chain at ``δ``.

        ``T(q) = start · M_1(q_1) between_1 ··· M_n(q_n) · end``: the fixed transforms of
        the calibrated chain (what a URDF of it writes).
        """
        e = self.blocks(delta)
        links = self.heads @ np.array([error_transform(x) for x in e[1:-1]]) @ self.tails
        start = error_transform(e[0]) @ self.start
        end = links[-1] @ self.tool @ error_transform(e[-1])
        return start, links[:-1], end

    def frames(self, delta: FloatArray, q: FloatArray) -> tuple[FloatArray, FloatArray]:
        """The frames each error transform acts in, and the tool poses, at ``δ``, ``q (m, n)``.

        One core call computes every frame (the chain at ``δ``, its frame i placed
        right before ``E_i``).

        Returns:
            ``(W (m, n + 2, 4, 4), T (m, 4, 4))``: ``W[:, 0]`` the world frame
            (before ``E_base``), ``W[:, i]`` link i's frame before ``E_i``,
            ``W[:, -1]`` the tool's frame before ``E_tool``; ``T`` the tool poses.
        """
        n, m = self.dof, q.shape[0]
        e = self.blocks(delta)
        start, between, _ = self.transforms(delta)
        free = np.full(n, np.inf)
        # the core's last frame is its tool pose: with Rz(θ_n) Tz(d_n) as the tool, the
        # frame right before E_n, as the offsets place the others
        core = _core.Chain.from_transforms(
            start, np.ascontiguousarray(between), self.heads[-1], np.ascontiguousarray(self.heads),
            np.ascontiguousarray(self.chain.prismatic), -free, free, start,
        )  # fmt: skip
        frames, _, _, _ = core.fk_batch(np.ascontiguousarray(q, dtype=float), True, 1)
        W = np.empty((m, n + 2, 4, 4))
        W[:, 0] = np.eye(4)
        W[:, 1:-1] = frames[:, 1:]
        last = error_transform(e[-2]) @ self.tails[-1] @ self.tool
        W[:, -1] = frames[:, -1] @ last
        T = W[:, -1] @ error_transform(e[-1])
        return W, T

    def twists(self, delta: FloatArray, W: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        """What each parameter does to everything after it, as a world-frame twist.

        Args:
            delta: ``(6 n + 12,)`` the parameters.
            W: ``(m, n + 2, 4, 4)`` the frames of :meth:`frames`.

        Returns:
            ``(axis (m, p, 3), point (m, p, 3), rotation (p,))``: each parameter's
            unit axis and a point on it (world frame, m); ``rotation`` True where
            the parameter turns about the axis, False where it slides along it.
        """
        e = self.blocks(delta)
        axes = np.empty((self.dof + 2, 6, 3))
        points = np.empty((self.dof + 2, 3))
        for b in range(self.dof + 2):
            axes[b], points[b] = _local_axes(e[b])
        R, p = W[..., :3, :3], W[..., :3, 3]  # (m, n+2, 3, 3), (m, n+2, 3)
        world_axes = np.swapaxes(R @ np.swapaxes(axes, 1, 2), -1, -2)  # (m, n+2, 6, 3)
        world_points = (R @ points[:, :, None])[..., 0] + p
        m = W.shape[0]
        point = np.broadcast_to(world_points[:, :, None, :], (m, self.dof + 2, 6, 3))
        rotation = np.tile(np.array([False, False, False, True, True, True]), self.dof + 2)
        return world_axes.reshape(m, -1, 3), point.reshape(m, -1, 3), rotation

    def fk(self, delta: FloatArray, q: FloatArray) -> FloatArray:
        """``(m, 4, 4)`` the tool poses of the chain at ``δ`` for ``q (m, n)``."""
        return self.frames(delta, q)[1]
