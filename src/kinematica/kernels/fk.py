"""Forward kinematics of a DH chain: one walk along the chain, for every use.

The chain arrives as arrays (see :class:`kinematica.dh.DHChain`): ``links``
``(n, 10)`` with columns ``LINK_*``, and ``ends`` ``(3, 4, 4)`` holding the
transform before the first joint (``START``), the tool (``TOOL``) and the
robot's base (``BASE``, frame 0 of ``all_frames``). Both DH conventions are one
regrouped product (see :mod:`kinematica.dh.chain`)::

    T = start · Π_i [Rot(z, θi) · Tras(z, di) · Tras(x, ai*) · Rot(x, αi*)] · tool

and :func:`walk_row` applies each factor to the running frame's columns ``x,
y, z, p`` directly, with no 4x4 product: ``x' = c x + s y``, ``w = c y - s x``,
``p += d z + a x'``, ``y' = cα w + sα z``, ``z' = cα z - sα w``. It records, on
request, every frame and every joint axis (as a line: direction and point),
which is all the Jacobian and the IK checks need (:func:`walk` is the same
walk for one configuration held in its own arrays).

Joint trigonometry is computed apart (:func:`block_trig`), for one
configuration or for a block of them at once: a loop over a block vectorises.
A batch runs blocks (:func:`fk_rows`) in parallel threads; a single
configuration is a block of one. There is no other FK in kinematica.
"""

from __future__ import annotations

import numba
import numpy as np

from kinematica.kernels._numba import Array, batch_kernel, inline_kernel, kernel
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
    "check_row",
    "fk_batch",
    "fk_one",
    "fk_pose",
    "fk_rows",
    "walk",
    "walk_row",
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

    The angles are first gathered into ``C`` (joint by joint), then one flat
    sine-cosine loop runs over all of them: it vectorises, and even a block
    of 8 candidates of a 6-joint arm is 48 angles, enough for the vector
    loop (8 alone would all fall to its scalar remainder).

    Args:
        links: ``(n, 10)`` the chain.
        Q: ``(B, n)`` joint values.
        b0: The block's first row.
        b1: The row after the block's last.
        C: ``(n, b1 - b0)`` C-contiguous, out: ``C[j, k] = cos θj`` of row
            ``b0 + k`` (the constant θ of a prismatic joint).
        S: ``(n, b1 - b0)`` C-contiguous, out: the sines.
    """
    # Indices, never row views such as C[j] in the loops: a view costs two
    # atomic reference count updates, which took half the time of a single call.
    n = links.shape[0]
    m = b1 - b0
    biggest = 0.0
    for j in range(n):
        th = links[j, LINK_THETA]
        slide = links[j, LINK_PRISMATIC] != 0.0
        for k in range(m):
            v = 0.0 if slide else Q[b0 + k, j] + th
            C[j, k] = v
            if abs(v) > biggest:  # NaN (a branch without a solution) is left to
                biggest = abs(v)  # the polynomial, which keeps it NaN
    if m > 1 and biggest <= REDUCTION_LIMIT:
        flat_c = C.reshape(n * m)
        flat_s = S.reshape(n * m)
        for t in range(n * m):  # vectorised: no calls, no branches
            flat_s[t], flat_c[t] = sincos_reduced(flat_c[t])
    else:  # one configuration (nothing to vectorise, no reshape to pay for),
        # or angles beyond the reduction's range (or inf): one at a time
        for j in range(n):
            for k in range(m):
                S[j, k], C[j, k] = sincos(C[j, k])
    for j in range(n):
        if links[j, LINK_PRISMATIC] != 0.0:
            for k in range(m):
                C[j, k] = links[j, LINK_CT]
                S[j, k] = links[j, LINK_ST]


@inline_kernel
def _store(
    T: Array,
    o: int,
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
    """Write the frame with columns ``x, y, z, p`` into ``T[o]`` (``T (m, 4, 4)``)."""
    T[o, 0, 0] = x0
    T[o, 1, 0] = x1
    T[o, 2, 0] = x2
    T[o, 0, 1] = y0
    T[o, 1, 1] = y1
    T[o, 2, 1] = y2
    T[o, 0, 2] = z0
    T[o, 1, 2] = z1
    T[o, 2, 2] = z2
    T[o, 0, 3] = p0
    T[o, 1, 3] = p1
    T[o, 2, 3] = p2
    T[o, 3, 0] = 0.0
    T[o, 3, 1] = 0.0
    T[o, 3, 2] = 0.0
    T[o, 3, 3] = 1.0


@inline_kernel
def walk_row(
    links: Array,
    ends: Array,
    frames_mid: bool,
    C: Array,
    S: Array,
    k: int,
    Q: Array,
    b: int,
    poses: Array,
    o: int,
    frames: Array,
    axes: Array,
) -> None:
    """Walk the chain at configuration ``Q[b]``; write output slot ``o``.

    Args:
        links: ``(n, 10)`` the chain.
        ends: ``(3, 4, 4)`` start, tool, base.
        frames_mid: True for the modified convention, where frame i sits after
            ``Rot(z)·Tras(z)`` of joint i rather than after the whole factor.
        C: ``(n, m)`` joint cosines (:func:`block_trig`).
        S: ``(n, m)`` joint sines.
        k: The column of ``C`` and ``S`` holding this configuration.
        Q: ``(B, n)`` joint values (the slide of prismatic joints is read here).
        b: The row of ``Q``.
        poses: ``(M, 4, 4)`` out: ``poses[o]`` is the tool pose in the base frame.
        o: The output slot.
        frames: ``(M (n + 1), 4, 4)`` out, or an empty array for none:
            ``frames[o (n + 1) + i]`` is frame i of ``0T0 (base), 0T1, ...,
            0Tn (with tool)``.
        axes: ``(M n, 6)`` out, or an empty array for none: ``axes[o n + i]``
            is joint i's axis as a unit direction and a point on it (base frame).
    """
    # The running frame's columns are the scalars x, y, z, p (three each), not
    # rows of a scratch array: numba cannot tell a scratch array from the
    # outputs (they might alias), so every store to poses/frames/axes would
    # force it to reload the frame from memory; in locals it stays in
    # registers. n and w are the new x and the rotated y of the current joint.
    # Outputs are indexed, never sliced into views (see block_trig), and
    # stacked flat (frames, axes) so that one store routine serves them all.
    # Plain statements, no tuple assignments: numba compiles them several
    # times faster.
    n = links.shape[0]
    x0 = ends[START, 0, 0]
    x1 = ends[START, 1, 0]
    x2 = ends[START, 2, 0]
    y0 = ends[START, 0, 1]
    y1 = ends[START, 1, 1]
    y2 = ends[START, 2, 1]
    z0 = ends[START, 0, 2]
    z1 = ends[START, 1, 2]
    z2 = ends[START, 2, 2]
    p0 = ends[START, 0, 3]
    p1 = ends[START, 1, 3]
    p2 = ends[START, 2, 3]
    want_frames = frames.size > 0
    want_axes = axes.size > 0
    first = o * (n + 1)
    for i in range(n):
        if want_axes:
            axes[o * n + i, 0] = z0
            axes[o * n + i, 1] = z1
            axes[o * n + i, 2] = z2
            axes[o * n + i, 3] = p0
            axes[o * n + i, 4] = p1
            axes[o * n + i, 5] = p2
        c = C[i, k]
        s = S[i, k]
        d = links[i, LINK_D]
        if links[i, LINK_PRISMATIC] != 0.0:
            d += Q[b, i]
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
            _store(frames, first + i + 1, n0, n1, n2, w0, w1, w2, z0, z1, z2, p0, p1, p2)
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
            _store(frames, first + i + 1, x0, x1, x2, y0, y1, y2, z0, z1, z2, p0, p1, p2)
    _store(
        poses,
        o,
        x0 * ends[TOOL, 0, 0] + y0 * ends[TOOL, 1, 0] + z0 * ends[TOOL, 2, 0],
        x1 * ends[TOOL, 0, 0] + y1 * ends[TOOL, 1, 0] + z1 * ends[TOOL, 2, 0],
        x2 * ends[TOOL, 0, 0] + y2 * ends[TOOL, 1, 0] + z2 * ends[TOOL, 2, 0],
        x0 * ends[TOOL, 0, 1] + y0 * ends[TOOL, 1, 1] + z0 * ends[TOOL, 2, 1],
        x1 * ends[TOOL, 0, 1] + y1 * ends[TOOL, 1, 1] + z1 * ends[TOOL, 2, 1],
        x2 * ends[TOOL, 0, 1] + y2 * ends[TOOL, 1, 1] + z2 * ends[TOOL, 2, 1],
        x0 * ends[TOOL, 0, 2] + y0 * ends[TOOL, 1, 2] + z0 * ends[TOOL, 2, 2],
        x1 * ends[TOOL, 0, 2] + y1 * ends[TOOL, 1, 2] + z1 * ends[TOOL, 2, 2],
        x2 * ends[TOOL, 0, 2] + y2 * ends[TOOL, 1, 2] + z2 * ends[TOOL, 2, 2],
        p0 + x0 * ends[TOOL, 0, 3] + y0 * ends[TOOL, 1, 3] + z0 * ends[TOOL, 2, 3],
        p1 + x1 * ends[TOOL, 0, 3] + y1 * ends[TOOL, 1, 3] + z1 * ends[TOOL, 2, 3],
        p2 + x2 * ends[TOOL, 0, 3] + y2 * ends[TOOL, 1, 3] + z2 * ends[TOOL, 2, 3],
    )
    if want_frames:
        for r in range(4):
            for c in range(4):
                frames[first, r, c] = ends[BASE, r, c]
                frames[first + n, r, c] = poses[o, r, c]


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
) -> None:
    """:func:`walk_row` for one configuration ``q (n,)``, its outputs unstacked.

    Args:
        links: ``(n, 10)`` the chain.
        ends: ``(3, 4, 4)`` start, tool, base.
        frames_mid: True for the modified convention.
        C: ``(n, m)`` joint cosines (:func:`block_trig`).
        S: ``(n, m)`` joint sines.
        k: The column of ``C`` and ``S`` holding this configuration.
        q: ``(n,)`` joint values.
        pose: ``(4, 4)`` out: tool pose in the base frame.
        frames: ``(n + 1, 4, 4)`` out, or shape ``(0, 4, 4)`` for none.
        axes: ``(n, 6)`` out, or shape ``(0, 6)`` for none.
    """
    # x[None]: a batch of one as a view numba makes for free (not reshape).
    walk_row(links, ends, frames_mid, C, S, k, q[None], 0, pose[None], 0, frames, axes)


@inline_kernel
def check_row(links: Array, Q: Array, b: int) -> int:
    """``FK_OK``, ``FK_NOT_FINITE`` or ``FK_OUTSIDE_LIMITS`` for configuration ``Q[b]``."""
    finite = True
    inside = True
    for i in range(links.shape[0]):
        v = Q[b, i]
        finite &= np.isfinite(v)
        inside &= links[i, LINK_LO] <= v <= links[i, LINK_HI]
    if not finite:
        return FK_NOT_FINITE
    return FK_OK if inside else FK_OUTSIDE_LIMITS


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

    Args:
        links: ``(n, 10)`` the chain (see :func:`walk_row`).
        ends: ``(3, 4, 4)`` start, tool, base.
        frames_mid: True for the modified convention.
        Q: ``(B, n)`` joint values.
        b0: The first row.
        b1: The row after the last.
        poses: ``(B, 4, 4)`` out.
        frames: ``(B (n + 1), 4, 4)`` out (every frame of row b from
            ``b (n + 1)`` on), or an empty array for none.
        axes: ``(B n, 6)`` out (row b's from ``b n`` on), or an empty array.

    Returns:
        ``(bad, outside)`` of these rows, as :func:`fk_batch`.
    """
    n = links.shape[0]
    C = np.empty((n, b1 - b0))
    S = np.empty((n, b1 - b0))
    bad = 0
    outside = 0
    block_trig(links, Q, b0, b1, C, S)
    for b in range(b0, b1):
        walk_row(links, ends, frames_mid, C, S, b - b0, Q, b, poses, b, frames, axes)
        code = check_row(links, Q, b)
        if code == FK_NOT_FINITE:
            bad += 1
            poses[b, :, :] = np.nan
            if frames.size > 0:
                frames[b * (n + 1) : (b + 1) * (n + 1), :, :] = np.nan
            if axes.size > 0:
                axes[b * n : (b + 1) * n, :] = np.nan
        elif code == FK_OUTSIDE_LIMITS:
            outside += 1
    return bad, outside


@kernel
def fk_one(
    links: Array,
    ends: Array,
    frames_mid: bool,
    q: Array,
    pose: Array,
    frames: Array,
    axes: Array,
) -> int:
    """One configuration, as a batch of one (:func:`fk_rows`).

    Args:
        links: ``(n, 10)`` the chain (see :func:`walk_row`).
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
    # x[None]: a batch of one, as a view numba makes for free (not reshape).
    first: int = np.int64(0)  # type: ignore[assignment]
    last: int = np.int64(1)  # type: ignore[assignment]
    bad, outside = fk_rows(links, ends, frames_mid, q[None], first, last, pose[None], frames, axes)
    if bad:
        return FK_NOT_FINITE
    return FK_OUTSIDE_LIMITS if outside else FK_OK


@kernel
def fk_pose(links: Array, ends: Array, q: Array, pose: Array) -> int:
    """:func:`fk_one` for the tool pose alone (fewer arguments: a cheaper call)."""
    no_frames, no_axes = np.empty((0, 4, 4)), np.empty((0, 6))
    return fk_one(links, ends, np.bool_(False), q, pose, no_frames, no_axes)  # type: ignore[arg-type]


@batch_kernel
def fk_batch(
    links: Array, ends: Array, frames_mid: bool, Q: Array, poses: Array, frames: Array, axes: Array
) -> tuple[int, int]:
    """A batch ``Q (B, n)`` in parallel blocks; rows holding NaN/inf come out NaN.

    Args:
        links: ``(n, 10)`` the chain (see :func:`walk_row`).
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
    B, n = Q.shape
    frame_stack = frames.reshape((frames.shape[0] * (n + 1), 4, 4))
    axis_stack = axes.reshape((axes.shape[0] * n, 6))
    nblocks = (B + BLOCK - 1) // BLOCK
    bad = 0
    outside = 0
    for blk in numba.prange(nblocks):
        b0 = blk * BLOCK
        rows_bad, rows_outside = fk_rows(
            links, ends, frames_mid, Q, b0, min(B, b0 + BLOCK), poses, frame_stack, axis_stack
        )
        bad += rows_bad
        outside += rows_outside
    return bad, outside
