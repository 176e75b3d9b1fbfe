"""Forward kinematics of a DH chain, exploiting the DH structure.

Both conventions are one product once the factors are regrouped (``Tras(x)``
and ``Rot(x)`` commute, as do ``Rot(z)`` and ``Tras(z)``)::

    T = S · Π_i [Rot(z, θi) · Tras(z, di) · Tras(x, ai*) · Rot(x, αi*)] · E

* standard: ``S = base``, ``(ai*, αi*) = (ai, αi)``, ``E = tool``;
* modified: ``S = base · Rot(x, α0) · Tras(x, a0)`` (row 1's ``a``/``alpha``),
  ``(ai*, αi*)`` are row ``i+1``'s ``a``/``alpha`` (zero after the last joint),
  ``E = tool``.

Each factor then updates the running frame's columns ``x, y, z, p`` directly,
with no 4x4 product: ``x' = c x + s y``, ``w = c y - s x``, ``p += d z + a x'``,
``y' = cα w + sα z``, ``z' = cα z - sα w``. Twists of 0, ±90° and 180° cost no
multiplication at all. Batches run in cache-sized blocks, a few numpy calls
per link; one configuration runs on Python floats, where numpy's per-call cost
would dominate.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from kinematica.dh.convert import rx_tx
from kinematica.dh.joints import Convention, Joint, Prismatic, check_convention

__all__ = ["DHChain"]

FloatArray = NDArray[np.float64]

#: |cos| or |sin| of a constant angle below this is taken as exactly 0 (and the
#: other as exactly ±1): cos(pi/2) evaluates to 6.1e-17, not 0, and the exact
#: value lets twists of 0/±90/180 degrees skip their multiplications.
SNAP_TOL = 1e-15

#: Configurations per block in the batched kernel: 3 x 1024 doubles per column
#: array keep a dozen temporaries inside a 1 MiB L2 cache.
BLOCK = 1024


def _snap(v: float) -> float:
    if abs(v) < SNAP_TOL:
        return 0.0
    if abs(abs(v) - 1.0) < SNAP_TOL:
        return math.copysign(1.0, v)
    return v


@dataclass(frozen=True, eq=False)
class DHChain:
    """A DH table compiled for forward kinematics.

    Attributes:
        prismatic: ``(n,)`` bool, True for prismatic joints.
        theta: ``(n,)`` constant part of θ (the offset, for revolute joints), rad.
        d: ``(n,)`` constant part of d (the offset, for prismatic joints), m.
        a: ``(n,)`` regrouped ``ai*`` (see module docstring), m.
        ca: ``(n,)`` cos of the regrouped twist ``αi*`` (snapped).
        sa: ``(n,)`` sin of the regrouped twist ``αi*`` (snapped).
        start: ``(4, 4)`` constant transform before the first joint.
        end: ``(4, 4)`` constant transform after the last link (the tool).
        frames_mid: True for the modified convention, where frame i sits after
            ``Rot(z)·Tras(z)`` of joint i rather than after the whole factor.
        base: ``(4, 4)`` the robot's base, frame 0 of ``all_frames``.
    """

    prismatic: NDArray[np.bool_]
    theta: FloatArray
    d: FloatArray
    a: FloatArray
    ca: FloatArray
    sa: FloatArray
    start: FloatArray
    end: FloatArray
    frames_mid: bool
    base: FloatArray
    _end_identity: bool = field(init=False, repr=False)
    _start_rows: list[list[float]] = field(init=False, repr=False)
    _end_rows: list[list[float]] = field(init=False, repr=False)
    _links: list[tuple[bool, float, float, float, float, float]] = field(init=False, repr=False)

    def __post_init__(self) -> None:
        # Python-float copies for the single-configuration path.
        object.__setattr__(self, "_end_identity", bool(np.array_equal(self.end, np.eye(4))))
        object.__setattr__(self, "_start_rows", self.start[:3].tolist())
        object.__setattr__(self, "_end_rows", self.end[:3].tolist())
        links = zip(
            self.prismatic.tolist(),
            self.theta.tolist(),
            self.d.tolist(),
            self.a.tolist(),
            self.ca.tolist(),
            self.sa.tolist(),
            strict=True,
        )
        object.__setattr__(self, "_links", list(links))

    @classmethod
    def from_joints(
        cls,
        joints: Sequence[Joint],
        convention: Convention,
        base: FloatArray,
        tool: FloatArray,
    ) -> DHChain:
        """Compile a DH table with its base and tool transforms.

        Args:
            joints: The rows, base to tip.
            convention: ``"standard"`` or ``"modified"``.
            base: ``(4, 4)`` pose of frame 0 in the world (base) frame.
            tool: ``(4, 4)`` pose of the tool in frame n.
        """
        conv = check_convention(convention)
        n = len(joints)
        prismatic = np.array([isinstance(j, Prismatic) for j in joints], dtype=bool)
        theta = np.array([j.theta for j in joints], dtype=float)
        d = np.array([j.d for j in joints], dtype=float)
        a_row = np.array([j.a for j in joints], dtype=float)
        alpha_row = np.array([j.alpha for j in joints], dtype=float)
        if conv == "standard":
            a, alpha, start = a_row, alpha_row, np.array(base, dtype=float)
        else:
            a = np.append(a_row[1:], 0.0)
            alpha = np.append(alpha_row[1:], 0.0)
            start = np.asarray(base, dtype=float) @ rx_tx(float(alpha_row[0]), float(a_row[0]))
        ca = np.array([_snap(math.cos(v)) for v in alpha], dtype=float).reshape(n)
        sa = np.array([_snap(math.sin(v)) for v in alpha], dtype=float).reshape(n)
        return cls(
            prismatic=prismatic,
            theta=theta,
            d=d,
            a=a,
            ca=ca,
            sa=sa,
            start=start,
            end=np.array(tool, dtype=float),
            frames_mid=conv == "modified",
            base=np.array(base, dtype=float),
        )

    @property
    def dof(self) -> int:
        """Number of joints."""
        return int(self.prismatic.shape[0])

    # ------------------------------------------------------------------ batch
    def fk_batch(self, q: FloatArray, all_frames: bool = False) -> FloatArray:
        """Forward kinematics of a flat batch.

        Args:
            q: ``(B, n)`` joint values (rad for revolute, m for prismatic).
            all_frames: Return every frame rather than the end pose only.

        Returns:
            ``(B, 4, 4)`` tool pose in the base frame, or ``(B, n+1, 4, 4)``
            frames ``0T0 (base), 0T1, ..., 0Tn (with tool)``.
        """
        B = q.shape[0]
        n = self.dof
        out = np.empty((B, n + 1, 4, 4) if all_frames else (B, 4, 4))
        for b0 in range(0, B, BLOCK):
            b1 = min(B, b0 + BLOCK)
            self._block(q[b0:b1], out[b0:b1], all_frames)
        if all_frames:
            out[:, 0] = self.base
        return out

    def joint_frames(self, q: FloatArray) -> FloatArray:
        """Frames whose z axis is each joint's axis, and the tool pose.

        Args:
            q: ``(B, n)`` joint values.

        Returns:
            ``(B, n+1, 4, 4)``: entry ``i < n`` is a frame whose z axis lies on
            joint ``i+1``'s axis (standard: DH frame i; modified: frame i+1 before
            its joint moves it); entry ``n`` is the tool pose. Used for Jacobians.
        """
        B = q.shape[0]
        out = np.empty((B, self.dof + 1, 4, 4))
        for b0 in range(0, B, BLOCK):
            b1 = min(B, b0 + BLOCK)
            self._block(q[b0:b1], out[b0:b1], False, joints=True)
        return out

    def _block(
        self, q: FloatArray, out: FloatArray, all_frames: bool, joints: bool = False
    ) -> None:
        n = self.dof
        qt = q.T  # (n, b): one contiguous row per joint after the arithmetic below
        theta = np.where(self.prismatic[:, None], self.theta[:, None], qt + self.theta[:, None])
        ct, st = np.cos(theta), np.sin(theta)
        S = self.start
        X, Y, Z, P = S[:3, 0:1], S[:3, 1:2], S[:3, 2:3], S[:3, 3:4]  # (3, 1) broadcast
        for i in range(n):
            if joints:
                _store(out[:, i], X, Y, Z, P)
            if self.prismatic[i]:
                c, s = _snap(float(ct[i, 0])), _snap(float(st[i, 0]))
                X1, W = _rotate_const(X, Y, c, s)
                P = P + (qt[i] + self.d[i]) * Z
            else:
                c_i, s_i = ct[i], st[i]
                X1 = c_i * X + s_i * Y
                W = c_i * Y - s_i * X
                if self.d[i] != 0.0:
                    P = P + self.d[i] * Z
            if all_frames and self.frames_mid and i < n - 1:
                _store(out[:, i + 1], X1, W, Z, P)
            if self.a[i] != 0.0:
                P = P + self.a[i] * X1
            X = X1
            Y, Z = _twist(W, Z, float(self.ca[i]), float(self.sa[i]))
            if all_frames and not self.frames_mid and i < n - 1:
                _store(out[:, i + 1], X, Y, Z, P)
        target = out[:, n] if all_frames or joints else out
        if not self._end_identity:
            E = self.end
            X, Y, Z, P = (
                E[0, 0] * X + E[1, 0] * Y + E[2, 0] * Z,
                E[0, 1] * X + E[1, 1] * Y + E[2, 1] * Z,
                E[0, 2] * X + E[1, 2] * Y + E[2, 2] * Z,
                P + E[0, 3] * X + E[1, 3] * Y + E[2, 3] * Z,
            )
        _store(target, X, Y, Z, P)

    # ----------------------------------------------------------------- single
    def fk_single(self, q: Sequence[float]) -> FloatArray:
        """Forward kinematics of one configuration, on Python floats.

        Args:
            q: ``(n,)`` joint values.

        Returns:
            ``(4, 4)`` tool pose in the base frame.
        """
        rows = self.pose_rows(q)
        rows.append([0.0, 0.0, 0.0, 1.0])
        return np.array(rows)

    def pose_rows(
        self, q: Sequence[float], axes: list[tuple[float, ...]] | None = None
    ) -> list[list[float]]:
        """The tool pose of one configuration as three rows of Python floats.

        Args:
            q: ``(n,)`` joint values.
            axes: If a list, each joint's axis is appended to it as
                ``(zx, zy, zz, ox, oy, oz)``: direction and a point on it (base
                frame), for Jacobians.

        Returns:
            The top three rows ``[[r00, r01, r02, px], ...]`` of ``T``.
        """
        (x0, y0, z0, p0), (x1, y1, z1, p1), (x2, y2, z2, p2) = self._start_rows
        cos, sin = math.cos, math.sin
        for qi, (prismatic, th, di, ai, ca, sa) in zip(q, self._links, strict=True):
            if axes is not None:
                axes.append((z0, z1, z2, p0, p1, p2))
            if prismatic:
                di = di + qi
            else:
                th = th + qi
            c, s = cos(th), sin(th)
            x0, x1, x2, w0, w1, w2 = (
                c * x0 + s * y0,
                c * x1 + s * y1,
                c * x2 + s * y2,
                c * y0 - s * x0,
                c * y1 - s * x1,
                c * y2 - s * x2,
            )
            p0 += di * z0 + ai * x0
            p1 += di * z1 + ai * x1
            p2 += di * z2 + ai * x2
            y0, y1, y2, z0, z1, z2 = (
                ca * w0 + sa * z0,
                ca * w1 + sa * z1,
                ca * w2 + sa * z2,
                ca * z0 - sa * w0,
                ca * z1 - sa * w1,
                ca * z2 - sa * w2,
            )
        T = [[x0, y0, z0, p0], [x1, y1, z1, p1], [x2, y2, z2, p2]]
        if self._end_identity:
            return T
        E = self._end_rows
        return [
            [
                r[0] * E[0][j] + r[1] * E[1][j] + r[2] * E[2][j] + (r[3] if j == 3 else 0.0)
                for j in range(4)
            ]
            for r in T
        ]


def _rotate_const(
    X: FloatArray, Y: FloatArray, c: float, s: float
) -> tuple[FloatArray, FloatArray]:
    """``(c X + s Y, c Y - s X)`` for a constant angle, skipping exact zeros."""
    if s == 0.0:
        return (X, Y) if c == 1.0 else (-X, -Y)
    if c == 0.0:
        return (Y, -X) if s == 1.0 else (-Y, X)
    return c * X + s * Y, c * Y - s * X


def _twist(W: FloatArray, Z: FloatArray, ca: float, sa: float) -> tuple[FloatArray, FloatArray]:
    """New ``(y, z)`` columns after ``Rot(x, α)``: ``(cα W + sα Z, cα Z - sα W)``."""
    if sa == 0.0:
        return (W, Z) if ca == 1.0 else (-W, -Z)
    if ca == 0.0:
        return (Z, -W) if sa == 1.0 else (-Z, W)
    return ca * W + sa * Z, ca * Z - sa * W


def _store(T: FloatArray, X: FloatArray, Y: FloatArray, Z: FloatArray, P: FloatArray) -> None:
    """Write columns ``(3, b)`` (or ``(3, 1)``) into transforms ``T (b, 4, 4)``."""
    T[:, :3, 0] = X.T
    T[:, :3, 1] = Y.T
    T[:, :3, 2] = Z.T
    T[:, :3, 3] = P.T
    T[:, 3, :3] = 0.0
    T[:, 3, 3] = 1.0
