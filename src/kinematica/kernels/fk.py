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

from kinematica.kernels._numba import batch_kernel, inline_kernel, kernel
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
    "inside_limits",
    "fk_pose",
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
def block_trig(links, Q, b0, b1, C, S):  # type: ignore[no-untyped-def]
    """Cosine and sine of every joint angle of configurations ``Q[b0:b1]``.

    Each joint's angles are first gathered into a contiguous row (``C[j]``
    serves as that buffer), so that the sine-cosine loop over them vectorises.

    Args:
        links: ``(n, 10)`` the chain.
        Q: ``(B, n)`` joint values.
        b0, b1: The block's rows.
        C, S: ``(n, >= b1 - b0)`` out: ``C[j, k] = cos θj`` of row ``b0 + k``
            (the constant θ of a prismatic joint).
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


@inline_kernel
def _store(F, xx, xy, xz, yx, yy, yz, zx, zy, zz, px, py, pz):  # type: ignore[no-untyped-def]
    F[0, 0], F[1, 0], F[2, 0], F[3, 0] = xx, xy, xz, 0.0
    F[0, 1], F[1, 1], F[2, 1], F[3, 1] = yx, yy, yz, 0.0
    F[0, 2], F[1, 2], F[2, 2], F[3, 2] = zx, zy, zz, 0.0
    F[0, 3], F[1, 3], F[2, 3], F[3, 3] = px, py, pz, 1.0


@kernel
def walk(links, ends, frames_mid, C, S, k, q, pose, frames, axes):  # type: ignore[no-untyped-def]
    """Walk the chain at one configuration.

    Args:
        links: ``(n, 8)`` the chain; ``ends``: ``(3, 4, 4)`` start, tool, base.
        frames_mid: True for the modified convention, where frame i sits after
            ``Rot(z)·Tras(z)`` of joint i rather than after the whole factor.
        C, S: ``(n, m)`` joint cosines and sines (:func:`block_trig`); column ``k``.
        q: ``(n,)`` joint values (the slide of prismatic joints is read here).
        pose: ``(4, 4)`` out: tool pose in the base frame.
        frames: ``(n + 1, 4, 4)`` out, or shape ``(0, 4, 4)`` for none: every
            frame ``0T0 (base), 0T1, ..., 0Tn (with tool)``.
        axes: ``(n, 6)`` out, or shape ``(0, 6)`` for none: each joint's axis
            as a unit direction and a point on it (base frame).
    """
    n = links.shape[0]
    s0 = ends[START]
    xx, xy, xz = s0[0, 0], s0[1, 0], s0[2, 0]
    yx, yy, yz = s0[0, 1], s0[1, 1], s0[2, 1]
    zx, zy, zz = s0[0, 2], s0[1, 2], s0[2, 2]
    px, py, pz = s0[0, 3], s0[1, 3], s0[2, 3]
    want_frames = frames.shape[0] > 0
    want_axes = axes.shape[0] > 0
    for i in range(n):
        if want_axes:
            axes[i, 0], axes[i, 1], axes[i, 2] = zx, zy, zz
            axes[i, 3], axes[i, 4], axes[i, 5] = px, py, pz
        c, s = C[i, k], S[i, k]
        d = links[i, LINK_D]
        if links[i, LINK_PRISMATIC] != 0.0:
            d += q[i]
        nx, ny, nz = c * xx + s * yx, c * xy + s * yy, c * xz + s * yz
        wx, wy, wz = c * yx - s * xx, c * yy - s * xy, c * yz - s * xz
        px, py, pz = px + d * zx, py + d * zy, pz + d * zz
        if want_frames and frames_mid and i < n - 1:
            _store(frames[i + 1], nx, ny, nz, wx, wy, wz, zx, zy, zz, px, py, pz)
        a, ca, sa = links[i, LINK_A], links[i, LINK_CA], links[i, LINK_SA]
        px, py, pz = px + a * nx, py + a * ny, pz + a * nz
        xx, xy, xz = nx, ny, nz
        yx, yy, yz, zx, zy, zz = (
            ca * wx + sa * zx,
            ca * wy + sa * zy,
            ca * wz + sa * zz,
            ca * zx - sa * wx,
            ca * zy - sa * wy,
            ca * zz - sa * wz,
        )
        if want_frames and not frames_mid and i < n - 1:
            _store(frames[i + 1], xx, xy, xz, yx, yy, yz, zx, zy, zz, px, py, pz)
    E = ends[TOOL]
    _store(
        pose,
        xx * E[0, 0] + yx * E[1, 0] + zx * E[2, 0],
        xy * E[0, 0] + yy * E[1, 0] + zy * E[2, 0],
        xz * E[0, 0] + yz * E[1, 0] + zz * E[2, 0],
        xx * E[0, 1] + yx * E[1, 1] + zx * E[2, 1],
        xy * E[0, 1] + yy * E[1, 1] + zy * E[2, 1],
        xz * E[0, 1] + yz * E[1, 1] + zz * E[2, 1],
        xx * E[0, 2] + yx * E[1, 2] + zx * E[2, 2],
        xy * E[0, 2] + yy * E[1, 2] + zy * E[2, 2],
        xz * E[0, 2] + yz * E[1, 2] + zz * E[2, 2],
        px + xx * E[0, 3] + yx * E[1, 3] + zx * E[2, 3],
        py + xy * E[0, 3] + yy * E[1, 3] + zy * E[2, 3],
        pz + xz * E[0, 3] + yz * E[1, 3] + zz * E[2, 3],
    )
    if want_frames:
        frames[0, :, :] = ends[BASE]
        frames[n, :, :] = pose


@kernel
def finite(q):  # type: ignore[no-untyped-def]
    """True when every value of ``q`` is finite."""
    ok = True
    for v in q:
        ok &= np.isfinite(v)
    return ok


@kernel
def inside_limits(links, q):  # type: ignore[no-untyped-def]
    """True when ``q`` is within every joint's own limits."""
    ok = True
    for i in range(links.shape[0]):
        ok &= links[i, LINK_LO] <= q[i] <= links[i, LINK_HI]
    return ok


@kernel
def fk_one(links, ends, frames_mid, q, pose, frames, axes):  # type: ignore[no-untyped-def]
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
    walk(links, ends, frames_mid, C, S, 0, q, pose, frames, axes)
    return FK_OK if inside_limits(links, q) else FK_OUTSIDE_LIMITS


@kernel
def fk_pose(links, ends, q, pose):  # type: ignore[no-untyped-def]
    """:func:`fk_one` for the tool pose alone (fewer arguments: a cheaper call)."""
    return fk_one(links, ends, False, q, pose, np.empty((0, 4, 4)), np.empty((0, 6)))


@batch_kernel
def fk_batch(links, ends, frames_mid, Q, poses, frames, axes):  # type: ignore[no-untyped-def]
    """A batch ``Q (B, n)`` in parallel blocks; rows holding NaN/inf come out NaN.

    Args:
        links, ends, frames_mid: The chain (see :func:`walk`).
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
        block_trig(links, Q, b0, b1, C, S)
        for b in range(b0, b1):
            F = frames[b] if frames.shape[0] > 0 else no_frames
            A = axes[b] if axes.shape[0] > 0 else no_axes
            walk(links, ends, frames_mid, C, S, b - b0, Q[b], poses[b], F, A)
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
