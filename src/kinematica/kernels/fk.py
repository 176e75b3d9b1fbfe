"""Forward kinematics of a DH chain: one walk along the chain, for every use.

The chain arrives as arrays (see :class:`kinematica.dh.DHChain`): ``links``
``(n, 10)`` with columns ``LINK_*``, and ``ends`` ``(3, 4, 4)`` holding the
transform before the first joint (``START``), the tool (``TOOL``) and the
robot's base (``BASE``, frame 0 of ``all_frames``). Both DH conventions are one
regrouped product (see :mod:`kinematica.dh.chain`)::

    T = start · Π_i [Rot(z, θi) · Tras(z, di) · Tras(x, ai*) · Rot(x, αi*)] · tool

and :func:`walk` applies each factor to the running frame's columns ``x, y, z,
p`` directly, with no 4x4 product: ``x' = c x + s y``, ``w = c y - s x``,
``p += d z + a x'``, ``y' = cα w + sα z``, ``z' = cα z - sα w``. It records, on
request, every frame and every joint axis (as a line: direction and point),
which is all the Jacobian and the IK checks need.

Joint trigonometry is computed apart (:func:`block_trig`), for one
configuration or for a block of them at once: a loop over a block vectorises.
A batch runs blocks in parallel threads; a single configuration is a block of
one. There is no other FK in kinematica.
"""

from __future__ import annotations

import numba
import numpy as np

from kinematica.kernels._numba import Array, batch_kernel, kernel
from kinematica.kernels.arrays import copy2
from kinematica.kernels.trig import REDUCTION_LIMIT, sincos, sincos_reduced

__all__ = [
    "BASE",
    "BLOCK",
    "FK_NOT_FINITE",
    "FK_OK",
    "FK_OUTSIDE_LIMITS",
    "LINK_A",
    "LINK_CA",
    "LINK_CT",
    "LINK_D",
    "LINK_HI",
    "LINK_LO",
    "LINK_PRISMATIC",
    "LINK_SA",
    "LINK_ST",
    "LINK_THETA",
    "START",
    "TOOL",
    "block_trig",
    "finite",
    "fk_batch",
    "fk_one",
    "fk_pose",
    "inside_limits",
    "walk",
]

# Columns of ``links``: joint type (1.0 prismatic), constant θ and d, the
# regrouped a* and (cos, sin) of α*, (cos, sin) of the constant θ (prismatic),
# and the joint's own limits (±inf where it has none).
(
    LINK_PRISMATIC,
    LINK_THETA,
    LINK_D,
    LINK_A,
    LINK_CA,
    LINK_SA,
    LINK_CT,
    LINK_ST,
    LINK_LO,
    LINK_HI,
) = range(10)
#: What :func:`fk_one` returns, and :func:`fk_batch` counts.
FK_OK, FK_NOT_FINITE, FK_OUTSIDE_LIMITS = 0, 1, 2
# Rows of ``ends``.
START, TOOL, BASE = range(3)

#: Configurations per block of a batch: the joint trigonometry of a block
#: (2 x 8 x 256 doubles) stays in the L1 cache.
BLOCK = 256


@kernel
def block_trig(links: Array, Q: Array, b0: int, b1: int, C: Array, S: Array) -> None:
    """Cosine and sine of every joint angle of configurations ``Q[b0:b1]``.

    Each joint's angles are first gathered into a contiguous row (``C[j]``
    serves as that buffer), so that the sine-cosine loop over them vectorises.

    Args:
        links: ``(n, 10)`` the chain.
        Q: ``(B, n)`` joint values.
        b0: The block's first row.
        b1: The row after the block's last.
        C: ``(n, >= b1 - b0)`` out: ``C[j, k] = cos θj`` of row ``b0 + k``
            (the constant θ of a prismatic joint).
        S: ``(n, >= b1 - b0)`` out: the sines.
    """
    n = links.shape[0]
    m = b1 - b0
    for j in range(n):
        Cj, Sj = C[j], S[j]
        if links[j, LINK_PRISMATIC] != 0.0:
            Cj[:m] = links[j, LINK_CT]
            Sj[:m] = links[j, LINK_ST]
            continue
        th = links[j, LINK_THETA]
        biggest = 0.0
        for k in range(m):
            Cj[k] = Q[b0 + k, j] + th
            biggest = max(biggest, abs(Cj[k]))
        if biggest <= REDUCTION_LIMIT:
            for k in range(m):  # vectorised: no calls, no branches
                Sj[k], Cj[k] = sincos_reduced(Cj[k])
        else:  # rare: angles beyond the reduction's range (or NaN)
            for k in range(m):
                Sj[k], Cj[k] = sincos(Cj[k])


@kernel
def _store(F: Array, X: Array, Y: Array, Z: Array, P: Array) -> None:
    """Write the frame with columns ``X, Y, Z, P`` (each ``(3,)``) into ``F (4, 4)``."""
    for r in range(3):
        F[r, 0] = X[r]
        F[r, 1] = Y[r]
        F[r, 2] = Z[r]
        F[r, 3] = P[r]
        F[3, r] = 0.0
    F[3, 3] = 1.0


@kernel
def walk(
    links: Array,
    ends: Array,
    frames_mid: bool,
    C: Array,
    S: Array,
    k: int,
    q: Array,
    pose: Array,
    frames: Array,
    axes: Array,
    work: Array,
) -> None:
    """Walk the chain at one configuration.

    Args:
        links: ``(n, 10)`` the chain.
        ends: ``(3, 4, 4)`` start, tool, base.
        frames_mid: True for the modified convention, where frame i sits after
            ``Rot(z)·Tras(z)`` of joint i rather than after the whole factor.
        C: ``(n, m)`` joint cosines (:func:`block_trig`).
        S: ``(n, m)`` joint sines.
        k: The column of ``C`` and ``S`` holding this configuration.
        q: ``(n,)`` joint values (the slide of prismatic joints is read here).
        pose: ``(4, 4)`` out: tool pose in the base frame.
        frames: ``(n + 1, 4, 4)`` out, or shape ``(0, 4, 4)`` for none: every
            frame ``0T0 (base), 0T1, ..., 0Tn (with tool)``.
        axes: ``(n, 6)`` out, or shape ``(0, 6)`` for none: each joint's axis
            as a unit direction and a point on it (base frame).
        work: ``(6, 3)`` scratch space.
    """
    # Plain statements, no tuple assignments: numba compiles them several
    # times faster. The running frame's columns are X, Y, Z, P; N and W the
    # new x and the rotated y of the current joint.
    n = links.shape[0]
    X = work[0]
    Y = work[1]
    Z = work[2]
    P = work[3]
    N = work[4]
    W = work[5]
    s0 = ends[START]
    for r in range(3):
        X[r] = s0[r, 0]
        Y[r] = s0[r, 1]
        Z[r] = s0[r, 2]
        P[r] = s0[r, 3]
    want_frames = frames.shape[0] > 0
    want_axes = axes.shape[0] > 0
    for i in range(n):
        if want_axes:
            for r in range(3):
                axes[i, r] = Z[r]
                axes[i, 3 + r] = P[r]
        c = C[i, k]
        s = S[i, k]
        d = links[i, LINK_D]
        if links[i, LINK_PRISMATIC] != 0.0:
            d += q[i]
        for r in range(3):
            N[r] = c * X[r] + s * Y[r]
            W[r] = c * Y[r] - s * X[r]
            P[r] += d * Z[r]
        if want_frames and frames_mid and i < n - 1:
            _store(frames[i + 1], N, W, Z, P)
        a = links[i, LINK_A]
        ca = links[i, LINK_CA]
        sa = links[i, LINK_SA]
        for r in range(3):
            P[r] += a * N[r]
            X[r] = N[r]
            Y[r] = ca * W[r] + sa * Z[r]
            Z[r] = ca * Z[r] - sa * W[r]
        if want_frames and not frames_mid and i < n - 1:
            _store(frames[i + 1], X, Y, Z, P)
    E = ends[TOOL]
    for r in range(3):
        pose[r, 0] = X[r] * E[0, 0] + Y[r] * E[1, 0] + Z[r] * E[2, 0]
        pose[r, 1] = X[r] * E[0, 1] + Y[r] * E[1, 1] + Z[r] * E[2, 1]
        pose[r, 2] = X[r] * E[0, 2] + Y[r] * E[1, 2] + Z[r] * E[2, 2]
        pose[r, 3] = P[r] + X[r] * E[0, 3] + Y[r] * E[1, 3] + Z[r] * E[2, 3]
        pose[3, r] = 0.0
    pose[3, 3] = 1.0
    if want_frames:
        copy2(frames[0], ends[BASE])
        copy2(frames[n], pose)


@kernel
def finite(q: Array) -> bool:
    """True when every value of ``q`` is finite."""
    ok = True
    for v in q:
        ok &= np.isfinite(v)
    return ok


@kernel
def inside_limits(links: Array, q: Array) -> bool:
    """True when ``q`` is within every joint's own limits."""
    ok = True
    for i in range(links.shape[0]):
        ok &= links[i, LINK_LO] <= q[i] <= links[i, LINK_HI]
    return ok


@kernel
def fk_one(
    links: Array, ends: Array, frames_mid: bool, q: Array, pose: Array, frames: Array, axes: Array
) -> int:
    """One configuration: see :func:`walk`.

    Returns:
        ``FK_OK``; ``FK_NOT_FINITE`` (nothing computed) when ``q`` holds NaN or
        inf; ``FK_OUTSIDE_LIMITS`` (computed) when a joint is beyond its limits.
    """
    if not finite(q):
        return FK_NOT_FINITE
    n = links.shape[0]
    C = np.empty((n, 1))
    S = np.empty((n, 1))
    block_trig(links, q.reshape((1, n)), 0, 1, C, S)
    walk(links, ends, frames_mid, C, S, 0, q, pose, frames, axes, np.empty((6, 3)))
    return FK_OK if inside_limits(links, q) else FK_OUTSIDE_LIMITS


@kernel
def fk_pose(links: Array, ends: Array, q: Array, pose: Array) -> int:
    """:func:`fk_one` for the tool pose alone (fewer arguments: a cheaper call)."""
    return fk_one(links, ends, False, q, pose, np.empty((0, 4, 4)), np.empty((0, 6)))


@batch_kernel
def fk_batch(
    links: Array, ends: Array, frames_mid: bool, Q: Array, poses: Array, frames: Array, axes: Array
) -> tuple[int, int]:
    """A batch ``Q (B, n)`` in parallel blocks; rows holding NaN/inf come out NaN.

    Args:
        links: ``(n, 10)`` the chain (see :func:`walk`).
        ends: ``(3, 4, 4)`` start, tool, base.
        frames_mid: True for the modified convention.
        Q: ``(B, n)`` joint values.
        poses: ``(B, 4, 4)`` out.
        frames: ``(B, n + 1, 4, 4)`` out, or shape ``(0, 0, 4, 4)`` for none.
        axes: ``(B, n, 6)`` out, or shape ``(0, 0, 6)`` for none.

    Returns:
        ``(bad, outside)``: the numbers of rows of ``Q`` holding NaN or inf,
        and of rows beyond some joint's limits.
    """
    B, n = Q.shape
    nblocks = (B + BLOCK - 1) // BLOCK
    bad = 0
    outside = 0
    no_frames = np.empty((0, 4, 4))
    no_axes = np.empty((0, 6))
    for blk in numba.prange(nblocks):
        b0 = blk * BLOCK
        b1 = min(B, b0 + BLOCK)
        C = np.empty((n, BLOCK))
        S = np.empty((n, BLOCK))
        work = np.empty((6, 3))
        block_trig(links, Q, b0, b1, C, S)
        for b in range(b0, b1):
            F = frames[b] if frames.shape[0] > 0 else no_frames
            A = axes[b] if axes.shape[0] > 0 else no_axes
            walk(links, ends, frames_mid, C, S, b - b0, Q[b], poses[b], F, A, work)
            if not finite(Q[b]):
                bad += 1
                poses[b, :, :] = np.nan
                if frames.shape[0] > 0:
                    frames[b, :, :, :] = np.nan
                if axes.shape[0] > 0:
                    axes[b, :, :] = np.nan
            elif not inside_limits(links, Q[b]):
                outside += 1
    return bad, outside
