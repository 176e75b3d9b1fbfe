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

from kinematica.kernels._numba import Array, batch_kernel, inline_kernel, kernel
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
    "fk_rows",
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
        if m > 1 and biggest <= REDUCTION_LIMIT:
            for k in range(m):  # vectorised: no calls, no branches
                Sj[k], Cj[k] = sincos_reduced(Cj[k])
        else:  # one configuration (nothing to vectorise), or angles beyond
            # the reduction's range (or NaN): one at a time
            for k in range(m):
                Sj[k], Cj[k] = sincos(Cj[k])


@inline_kernel
def _store(
    F: Array,
    x0: float,
    x1: float,
    x2: float,
    y0: float,
    y1: float,
    y2: float,
    z0: float,
    z1: float,
    z2: float,
    p0: float,
    p1: float,
    p2: float,
) -> None:
    """Write the frame with columns ``x, y, z, p`` into ``F (4, 4)``."""
    F[0, 0] = x0
    F[1, 0] = x1
    F[2, 0] = x2
    F[0, 1] = y0
    F[1, 1] = y1
    F[2, 1] = y2
    F[0, 2] = z0
    F[1, 2] = z1
    F[2, 2] = z2
    F[0, 3] = p0
    F[1, 3] = p1
    F[2, 3] = p2
    F[3, 0] = 0.0
    F[3, 1] = 0.0
    F[3, 2] = 0.0
    F[3, 3] = 1.0


@inline_kernel
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
        work: Unused (the running frame lives in local variables); kept so
            that the IK kernels calling :func:`walk` need not change.
    """
    # The running frame's columns are the scalars x, y, z, p (three each), not
    # rows of a scratch array: numba cannot tell a scratch array from the
    # outputs (they might alias), so every store to pose/frames/axes would
    # force it to reload the frame from memory; in locals it stays in
    # registers, and a batch runs twice as fast. n and w are the new x and the
    # rotated y of the current joint. Plain statements, no tuple assignments:
    # numba compiles them several times faster.
    n = links.shape[0]
    s0 = ends[START]
    x0 = s0[0, 0]
    x1 = s0[1, 0]
    x2 = s0[2, 0]
    y0 = s0[0, 1]
    y1 = s0[1, 1]
    y2 = s0[2, 1]
    z0 = s0[0, 2]
    z1 = s0[1, 2]
    z2 = s0[2, 2]
    p0 = s0[0, 3]
    p1 = s0[1, 3]
    p2 = s0[2, 3]
    want_frames = frames.shape[0] > 0
    want_axes = axes.shape[0] > 0
    for i in range(n):
        if want_axes:
            axes[i, 0] = z0
            axes[i, 1] = z1
            axes[i, 2] = z2
            axes[i, 3] = p0
            axes[i, 4] = p1
            axes[i, 5] = p2
        c = C[i, k]
        s = S[i, k]
        d = links[i, LINK_D]
        if links[i, LINK_PRISMATIC] != 0.0:
            d += q[i]
        n0 = c * x0 + s * y0
        n1 = c * x1 + s * y1
        n2 = c * x2 + s * y2
        w0 = c * y0 - s * x0
        w1 = c * y1 - s * x1
        w2 = c * y2 - s * x2
        p0 += d * z0
        p1 += d * z1
        p2 += d * z2
        if want_frames and frames_mid and i < n - 1:
            _store(frames[i + 1], n0, n1, n2, w0, w1, w2, z0, z1, z2, p0, p1, p2)
        a = links[i, LINK_A]
        ca = links[i, LINK_CA]
        sa = links[i, LINK_SA]
        p0 += a * n0
        p1 += a * n1
        p2 += a * n2
        x0 = n0
        x1 = n1
        x2 = n2
        y0 = ca * w0 + sa * z0
        y1 = ca * w1 + sa * z1
        y2 = ca * w2 + sa * z2
        z0 = ca * z0 - sa * w0
        z1 = ca * z1 - sa * w1
        z2 = ca * z2 - sa * w2
        if want_frames and not frames_mid and i < n - 1:
            _store(frames[i + 1], x0, x1, x2, y0, y1, y2, z0, z1, z2, p0, p1, p2)
    E = ends[TOOL]
    _store(
        pose,
        x0 * E[0, 0] + y0 * E[1, 0] + z0 * E[2, 0],
        x1 * E[0, 0] + y1 * E[1, 0] + z1 * E[2, 0],
        x2 * E[0, 0] + y2 * E[1, 0] + z2 * E[2, 0],
        x0 * E[0, 1] + y0 * E[1, 1] + z0 * E[2, 1],
        x1 * E[0, 1] + y1 * E[1, 1] + z1 * E[2, 1],
        x2 * E[0, 1] + y2 * E[1, 1] + z2 * E[2, 1],
        x0 * E[0, 2] + y0 * E[1, 2] + z0 * E[2, 2],
        x1 * E[0, 2] + y1 * E[1, 2] + z1 * E[2, 2],
        x2 * E[0, 2] + y2 * E[1, 2] + z2 * E[2, 2],
        p0 + x0 * E[0, 3] + y0 * E[1, 3] + z0 * E[2, 3],
        p1 + x1 * E[0, 3] + y1 * E[1, 3] + z1 * E[2, 3],
        p2 + x2 * E[0, 3] + y2 * E[1, 3] + z2 * E[2, 3],
    )
    if want_frames:
        copy2(frames[0], ends[BASE])
        copy2(frames[n], pose)


@inline_kernel
def finite(q: Array) -> bool:
    """True when every value of ``q`` is finite."""
    ok = True
    for v in q:
        ok &= np.isfinite(v)
    return ok


@inline_kernel
def inside_limits(links: Array, q: Array) -> bool:
    """True when ``q`` is within every joint's own limits."""
    ok = True
    for i in range(links.shape[0]):
        ok &= links[i, LINK_LO] <= q[i] <= links[i, LINK_HI]
    return ok


@kernel
def fk_rows(
    links: Array,
    ends: Array,
    frames_mid: bool,
    Q: Array,
    b0: int,
    b1: int,
    poses: Array,
    frames: Array,
    axes: Array,
) -> tuple[int, int]:
    """Rows ``b0:b1`` of a batch, in one thread: a block of :func:`fk_batch`.

    Args: as :func:`fk_batch`, with the first and the last-plus-one row.

    Returns:
        ``(bad, outside)`` of these rows, as :func:`fk_batch`.
    """
    n = links.shape[0]
    C = np.empty((n, b1 - b0))
    S = np.empty((n, b1 - b0))
    no_frames = np.empty((0, 4, 4))
    no_axes = np.empty((0, 6))
    no_work = np.empty((0, 3))
    bad = 0
    outside = 0
    block_trig(links, Q, b0, b1, C, S)
    for b in range(b0, b1):
        F = frames[b] if frames.shape[0] > 0 else no_frames
        A = axes[b] if axes.shape[0] > 0 else no_axes
        walk(links, ends, frames_mid, C, S, b - b0, Q[b], poses[b], F, A, no_work)
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


@kernel
def fk_one(
    links: Array, ends: Array, frames_mid: bool, q: Array, pose: Array, frames: Array, axes: Array
) -> int:
    """One configuration, as a batch of one (:func:`fk_rows`).

    Args:
        links: ``(n, 10)`` the chain (see :func:`walk`).
        ends: ``(3, 4, 4)`` start, tool, base.
        frames_mid: True for the modified convention.
        q: ``(n,)`` joint values.
        pose: ``(4, 4)`` out.
        frames: ``(n + 1, 4, 4)`` out, or shape ``(0, 4, 4)`` for none.
        axes: ``(n, 6)`` out, or shape ``(0, 6)`` for none.

    Returns:
        ``FK_OK``; ``FK_NOT_FINITE`` (all NaN) when ``q`` holds NaN or inf;
        ``FK_OUTSIDE_LIMITS`` (computed) when a joint is beyond its limits.
    """
    # np.int64, not the literals 0 and 1: numba would compile fk_rows once more
    # for literal arguments (seconds), rather than share the batch's build.
    # A shape-(0, ...) frames/axes array reshaped to a batch of one is a batch
    # of one empty array: fk_rows then records nothing.
    n = links.shape[0]
    bad, outside = fk_rows(
        links,
        ends,
        frames_mid,
        q.reshape((1, n)),
        np.int64(0),
        np.int64(1),
        pose.reshape((1, 4, 4)),
        frames.reshape((1, frames.shape[0], 4, 4)),
        axes.reshape((1, axes.shape[0], 6)),
    )
    if bad:
        return FK_NOT_FINITE
    return FK_OUTSIDE_LIMITS if outside else FK_OK


@kernel
def fk_pose(links: Array, ends: Array, q: Array, pose: Array) -> int:
    """:func:`fk_one` for the tool pose alone (fewer arguments: a cheaper call)."""
    bad, outside = fk_rows(
        links,
        ends,
        np.bool_(False),
        q.reshape((1, links.shape[0])),
        np.int64(0),
        np.int64(1),
        pose.reshape((1, 4, 4)),
        np.empty((0, 0, 4, 4)),
        np.empty((0, 0, 6)),
    )
    if bad:
        return FK_NOT_FINITE
    return FK_OUTSIDE_LIMITS if outside else FK_OK


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
    # The loop body is one call: numba compiles a parallel loop's body
    # slowly, and fk_rows is compiled once for single calls and batches.
    B = Q.shape[0]
    nblocks = (B + BLOCK - 1) // BLOCK
    bad = 0
    outside = 0
    for blk in numba.prange(nblocks):
        b0 = blk * BLOCK
        rows_bad, rows_outside = fk_rows(
            links, ends, frames_mid, Q, b0, min(B, b0 + BLOCK), poses, frames, axes
        )
        bad += rows_bad
        outside += rows_outside
    return bad, outside
