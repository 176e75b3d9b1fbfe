"""From raw IK candidates to checked, distinct, limit-aware solutions: one target.

Every candidate a solver proposes is judged here by forward kinematics against
the target, never by the solver's own word. Candidates a little off (round-off
near a double root) get a few Gauss-Newton steps first and count only if they
then meet the tolerances. Solutions are wrapped to (-π, π] (or moved by 2π
into their limit window), duplicates modulo 2π dropped, split by the joint
limits, sorted (by distance to ``q0`` when given, else in the solver's slot
order), and the target gets an honest status.

Solvers hand over, per target: candidates ``Q (m, n)`` (NaN rows: no real
solution on that branch) and ``info`` (``INFO_*`` slots): whether the solutions
form a continuum (``singular``, with the free joints), whether the target is
near a singular set where a closed form loses solutions to round-off
(``near``), and a lower bound of the distance to the reachable set (``gap``).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from kinematica.kernels._numba import Array, IntArray, batch_kernel, inline_kernel, kernel
from kinematica.kernels.fk import LINK_PRISMATIC, block_trig, fk_one, walk_row
from kinematica.kernels.jacobian import columns
from kinematica.kernels.linalg import damped_least_squares
from kinematica.kernels.so3 import angle_between, pose_error, wrap

__all__ = [
    "DEDUP_TOL",
    "INFO_FREE",
    "INFO_GAP",
    "INFO_NEAR",
    "INFO_SINGULAR",
    "LIMIT_TOL",
    "META_COUNT",
    "META_GAP",
    "META_NEAR",
    "META_NEAREST_POSITION",
    "META_NEAREST_ROTATION",
    "META_OUT_COUNT",
    "META_SIZE",
    "META_STATUS",
    "OPT_COMPLETE",
    "OPT_HAS_Q0",
    "OPT_RESPECT_LIMITS",
    "OPT_SIZE",
    "OPT_TOL_POSITION",
    "OPT_TOL_ROTATION",
    "POLISH_DAMPING",
    "POLISH_LIMIT",
    "POLISH_STEPS",
    "STATUS_INVALID",
    "STATUS_NOT_FOUND",
    "STATUS_OK",
    "STATUS_OUT_OF_LIMITS",
    "STATUS_SINGULAR",
    "STATUS_UNREACHABLE",
    "TARGET_BLOCK",
    "check_batch",
    "check_target",
    "info_size",
]

#: Candidates whose residual is below this (m or rad) but above the tolerance
#: are polished by Gauss-Newton steps before being judged.
POLISH_LIMIT = 1e-5
#: Gauss-Newton steps for polishing: quadratic convergence from 1e-5 needs 2-3.
POLISH_STEPS = 4
#: Relative damping of the polishing steps (as the numeric solver's smallest):
#: negligible next to any singular value that matters, it keeps the normal
#: equations solvable at a double root, where the Jacobian loses rank.
POLISH_DAMPING = 1e-12
#: Two solutions closer than this in every joint (rad or m, angles modulo 2π)
#: are the same solution.
DEDUP_TOL = 1e-7
#: Slack on joint limits for values computed by floating point (rad or m).
LIMIT_TOL = 1e-12

# What a solver reports per target, besides its candidates (``info``).
INFO_SINGULAR = 0  # 1.0: infinitely many solutions; candidates are representatives
INFO_NEAR = 1  # 1.0: near a singular set, solutions may be lost to round-off
INFO_GAP = 2  # lower bound of the distance to the reachable set (m), NaN: unknown
INFO_FREE = 3  # n slots from here: 1.0 for the joints left free (singular)

# Options of a check (``opts``).
OPT_TOL_POSITION, OPT_TOL_ROTATION, OPT_RESPECT_LIMITS, OPT_COMPLETE, OPT_HAS_Q0 = range(5)
OPT_SIZE = 5

# What a check reports per target (``meta``).
META_STATUS, META_COUNT, META_OUT_COUNT, META_GAP = range(4)
META_NEAREST_POSITION, META_NEAREST_ROTATION, META_NEAR = 4, 5, 6
META_SIZE = 7

# Status codes (the ik layer names them).
STATUS_OK, STATUS_SINGULAR, STATUS_OUT_OF_LIMITS = 0, 1, 2
STATUS_UNREACHABLE, STATUS_NOT_FOUND, STATUS_INVALID = 3, 4, 5

_TWO_PI = 2.0 * math.pi
#: Targets per block of a batch (the check's, and the solvers' that make work
#: arrays): each block makes its work arrays once.
TARGET_BLOCK = 64


def info_size(n: int) -> int:
    """Length of a solver's ``info`` row for an arm of ``n`` joints."""
    return INFO_FREE + n


@inline_kernel
def _residual(
    links: Array,
    ends: Array,
    Q: Array,
    b: int,
    T: Array,
    w: Array,
    C: Array,
    S: Array,
    k: int,
    poses: Array,
    pose: Array,
    e: Array,
    no_frames: Array,
    no_axes: Array,
) -> tuple[float, float]:
    """Position (m) and rotation (rad) error of ``Q[b]`` against ``T``, weighted by ``w (6,)``.

    ``C[:, k]`` and ``S[:, k]`` hold the cosines and sines of ``Q[b]``'s joint
    angles (:func:`~kinematica.kernels.fk.block_trig`). Unweighted, the
    rotation error is the angle of ``Rtᵀ R`` (exact near 0); with weights, the
    norms of the weighted error components. ``poses (1, 4, 4)`` receives the
    pose and ``pose`` is ``poses[0]``; ``no_frames`` ``(0, 4, 4)`` and
    ``no_axes`` ``(0, 6)`` are empty. All are made once by the caller (an
    allocation per candidate cost a tenth of the check).
    """
    walk_row(links, ends, False, C, S, k, Q, b, poses, 0, no_frames, no_axes)
    plain = w[0] == 1.0 and w[1] == 1.0 and w[2] == 1.0
    if plain and w[3] == 1.0 and w[4] == 1.0 and w[5] == 1.0:
        dx, dy, dz = T[0, 3] - pose[0, 3], T[1, 3] - pose[1, 3], T[2, 3] - pose[2, 3]
        return math.sqrt(dx * dx + dy * dy + dz * dz), angle_between(pose, T)
    pose_error(pose, T, e)
    p2 = r2 = 0.0
    for i in range(3):
        p2 += (w[i] * e[i]) ** 2
        r2 += (w[i + 3] * e[i + 3]) ** 2
    return math.sqrt(p2), math.sqrt(r2)


@kernel
def _polish(
    links: Array,
    ends: Array,
    q: Array,
    T: Array,
    w: Array,
    pose: Array,
    e: Array,
    no_frames: Array,
) -> None:
    """``POLISH_STEPS`` Gauss-Newton steps on ``q`` towards ``T`` (weighted rows only).

    Its buffers are allocated here: few candidates are polished, and
    allocating them for every target cost a tenth of the check.
    """
    n = links.shape[0]
    axes = np.empty((n, 6))
    J6 = np.empty((6, n))
    Jr = np.empty((6, n))
    er = np.empty(6)
    dq = np.empty(n)
    big = max(n, 6)
    G = np.empty((n, 6))
    b = np.empty(big)
    x = np.empty(big)
    L = np.empty((big, big))
    r = 0
    for k in range(6):
        if w[k] > 0.0:
            r += 1
    for _ in range(POLISH_STEPS):
        # the FK kernel of robot.fk, called, not the walk inlined: the polish
        # is rare, and inlining the walk here cost seconds of compilation
        fk_one(links, ends, np.bool_(False), q, pose, no_frames, axes)  # type: ignore[arg-type]
        columns(links, axes, pose, False, J6)
        pose_error(pose, T, e)
        row = 0
        for k in range(6):
            if w[k] > 0.0:
                er[row] = w[k] * e[k]
                for j in range(n):
                    Jr[row, j] = w[k] * J6[k, j]
                row += 1
        damped_least_squares(Jr[:r], er[:r], POLISH_DAMPING, dq, G[:, :r], b, x, L)
        for j in range(n):
            q[j] += dq[j]
            if links[j, LINK_PRISMATIC] == 0.0:
                q[j] = wrap(q[j])


@kernel
def _same(links: Array, qs: Array, a: int, b: int) -> bool:
    """True when rows ``a`` and ``b`` of ``qs`` agree within ``DEDUP_TOL`` in every joint.

    Angles compare modulo 2π. (Rows by index, not as views: a view per pair
    costs two atomic reference-count updates.)
    """
    for j in range(links.shape[0]):
        d = qs[a, j] - qs[b, j]
        if links[j, LINK_PRISMATIC] == 0.0:
            d = abs(d)
            d = min(d, _TWO_PI - d) if d <= _TWO_PI else abs(wrap(d))
        if abs(d) >= DEDUP_TOL:
            return False
    return True


@kernel
def check_target(
    links: Array,
    ends: Array,
    qlim: Array,
    T: Array,
    Q: Array,
    info: Array,
    w: Array,
    q0: Array,
    opts: Array,
    out_q: Array,
    out_slot: IntArray,
    out_res: Array,
    meta: Array,
) -> None:
    """Check the candidates ``Q (m, n)`` of one target ``T (4, 4)``.

    Args:
        links: ``(n, 10)`` the chain (see :mod:`kinematica.kernels.fk`).
        ends: ``(3, 4, 4)`` its start, tool and base.
        qlim: ``(n, 2)`` joint limits.
        T: ``(4, 4)`` target pose (base frame); for a position target, its
            rotation is ignored through ``w``.
        Q: ``(m, n)`` candidates, NaN rows for branches without a solution.
        info: ``(INFO_FREE + n,)`` what the solver knows (``INFO_*``).
        w: ``(6,)`` weights of the error components x, y, z, rx, ry, rz
            (all 1: the whole pose; ``1, 1, 1, 0, 0, 0``: the position).
        q0: ``(n,)`` configuration to sort by (when ``OPT_HAS_Q0``).
        opts: ``(OPT_SIZE,)`` tolerances (m, rad) and flags (``OPT_*``).
        out_q: ``(m, n)`` out: solutions within the limits, sorted, then those
            outside, sorted; NaN after.
        out_slot: ``(m,)`` out: the candidate slot of each row (for its branch
            label), -1 after.
        out_res: ``(m, 2)`` out: position (m) and rotation (rad) residuals.
        meta: ``(META_SIZE,)`` out: status code, counts, gap, nearest miss.
    """
    meta[META_STATUS] = STATUS_OK  # not STATUS_INVALID: a target to check
    m, n = Q.shape
    # A batch of one, with the types check_batch passes (else numba compiles
    # the block a second time, seconds): reshape keeps arrays C-contiguous
    # (x[None] would not), and np.int64 bounds are not the literals 0 and 1.
    first: int = np.int64(0)  # type: ignore[assignment]
    last: int = np.int64(1)  # type: ignore[assignment]
    _check_block(
        links, ends, qlim, T.reshape((1, 4, 4)), Q.reshape((1, m, n)),
        info.reshape((1, info.size)), w, q0.reshape((1, n)), opts,
        out_q.reshape((1, m, n)), out_slot.reshape((1, m)), out_res.reshape((1, m, 2)),
        meta.reshape((1, META_SIZE)), first, last,
    )  # fmt: skip


@kernel
def _scratch(
    m: int, n: int
) -> tuple[Array, Array, Array, Array, Array, Array, Array, Array, Array, Array, IntArray, Array]:
    """The work arrays of :func:`_check` for ``m`` candidates of ``n`` joints."""
    return (
        np.empty((n, m)),  # C, S: every candidate's cosines and sines, in one vectorised pass
        np.empty((n, m)),
        np.empty((n, 1)),  # C1, S1: a polished candidate's
        np.empty((n, 1)),
        np.empty((1, 4, 4)),  # poses: the pose of a candidate
        np.empty(6),  # e
        np.empty((0, 4, 4)),  # no_frames
        np.empty((0, 6)),  # no_axes
        np.empty((m, n)),  # qs: the wrapped candidates
        np.empty((m, 2)),  # res: their residuals
        np.empty(m, dtype=np.int64),  # state: 0 no, 1 solution within limits, 2 outside
        np.empty(m),  # key: sort key
    )


@inline_kernel
def _check(
    links: Array,
    ends: Array,
    qlim: Array,
    T: Array,
    Q: Array,
    info: Array,
    w: Array,
    q0: Array,
    opts: Array,
    out_q: Array,
    out_slot: IntArray,
    out_res: Array,
    meta: Array,
    C: Array,
    S: Array,
    C1: Array,
    S1: Array,
    poses: Array,
    pose: Array,
    e: Array,
    no_frames: Array,
    no_axes: Array,
    qs: Array,
    res: Array,
    state: IntArray,
    key: Array,
) -> None:
    """:func:`check_target` with its work arrays given (:func:`_scratch`).

    ``pose`` is ``poses[0]`` (a view made once, with the work arrays).
    Inlined into :func:`_check_block`, its one caller: a call passing these
    26 arrays cost 0.17 µs per target, a seventh of the check.
    """
    m, n = Q.shape
    tol_p, tol_r = opts[OPT_TOL_POSITION], opts[OPT_TOL_ROTATION]
    respect = opts[OPT_RESPECT_LIMITS] != 0.0
    for j in range(m):
        state[j] = 0
    close = False
    near_p = near_r = math.nan
    near_score = math.inf
    for j in range(m):
        for k in range(n):
            v = Q[j, k]
            qs[j, k] = wrap(v) if links[k, LINK_PRISMATIC] == 0.0 else v
    block_trig(links, qs, 0, m, C, S)
    for j in range(m):
        valid = True
        for k in range(n):
            valid &= np.isfinite(qs[j, k])
        if not valid:
            continue
        # The residual, and again after polishing a near miss: one call site
        # (each site inlines the whole FK walk, seconds of compilation).
        Cj, Sj, col = C, S, j
        p_err = r_err = math.inf
        ok = False
        for attempt in range(2):
            p_err, r_err = _residual(
                links, ends, qs, j, T, w, Cj, Sj, col, poses, pose, e, no_frames, no_axes
            )
            ok = p_err <= tol_p and r_err <= tol_r
            if ok or attempt == 1 or not max(p_err, r_err) < POLISH_LIMIT:
                break
            _polish(links, ends, qs[j], T, w, pose, e, no_frames)
            block_trig(links, qs, j, j + 1, C1, S1)
            Cj, Sj, col = C1, S1, 0
        close |= max(p_err, r_err) < POLISH_LIMIT
        if not ok:
            score = max(p_err / tol_p, r_err / tol_r)
            if score < near_score:
                near_score, near_p, near_r = score, p_err, r_err
            continue
        # An angle outside its limits whose turn ±2π is inside is taken there;
        # then within its limits or not (one pass over the joints).
        inside = True
        if respect:
            for k in range(n):
                lo = qlim[k, 0] - LIMIT_TOL
                hi = qlim[k, 1] + LIMIT_TOL
                v = qs[j, k]
                if links[k, LINK_PRISMATIC] == 0.0:
                    if v < lo and v + _TWO_PI <= hi:
                        v += _TWO_PI
                        qs[j, k] = v
                    elif v > hi and v - _TWO_PI >= lo:
                        v -= _TWO_PI
                        qs[j, k] = v
                inside &= lo <= v <= hi
        duplicate = False  # (modulo 2π: the turn above changes nothing here)
        for i in range(j):
            if state[i] != 0 and _same(links, qs, j, i):
                duplicate = True
                break
        if duplicate:
            continue
        state[j] = 1 if inside else 2
        res[j, 0], res[j, 1] = p_err, r_err
        if opts[OPT_HAS_Q0] != 0.0:
            d2 = 0.0
            for k in range(n):
                d = qs[j, k] - q0[k]
                if links[k, LINK_PRISMATIC] == 0.0:
                    d = wrap(d)
                d2 += d * d
            key[j] = math.sqrt(d2)
        else:
            key[j] = j
    # Within the limits first, then outside; each sorted by key (insertion sort: m is small).
    row = 0
    count = 0
    for group in (1, 2):
        first = row
        for j in range(m):
            if state[j] != group:
                continue
            pos = row
            while pos > first and key[out_slot[pos - 1]] > key[j]:
                out_slot[pos] = out_slot[pos - 1]
                pos -= 1
            out_slot[pos] = j
            row += 1
        if group == 1:
            count = row
    for r in range(m):
        if r < row:
            j = out_slot[r]
            for k in range(n):
                out_q[r, k] = qs[j, k]
            out_res[r, 0], out_res[r, 1] = res[j, 0], res[j, 1]
        else:
            out_slot[r] = -1
            out_q[r, :] = np.nan
            out_res[r, :] = np.nan
    out_count = row - count
    gap = info[INFO_GAP]
    if count > 0:
        status = STATUS_SINGULAR if info[INFO_SINGULAR] != 0.0 else STATUS_OK
    elif out_count > 0:
        status = STATUS_OUT_OF_LIMITS
    elif gap > tol_p or (opts[OPT_COMPLETE] != 0.0 and not close and info[INFO_NEAR] == 0.0):
        status = STATUS_UNREACHABLE
    else:
        status = STATUS_NOT_FOUND
    meta[META_STATUS] = status
    meta[META_COUNT] = count
    meta[META_OUT_COUNT] = out_count
    meta[META_GAP] = gap if status == STATUS_UNREACHABLE else math.nan
    meta[META_NEAREST_POSITION] = near_p
    meta[META_NEAREST_ROTATION] = near_r
    meta[META_NEAR] = info[INFO_NEAR]


@batch_kernel
def check_batch(
    links: Array,
    ends: Array,
    qlim: Array,
    T: Array,
    Q: Array,
    info: Array,
    w: Array,
    q0: Array,
    opts: Array,
    out_q: Array,
    out_slot: IntArray,
    out_res: Array,
    meta: Array,
) -> None:
    """:func:`check_target` for targets ``T (N, 4, 4)`` in parallel (arrays gain an ``N`` axis).

    ``q0`` is ``(N, n)``; a row of ``meta`` whose status is already
    ``STATUS_INVALID`` (a malformed target) stays invalid, its numbers NaN.
    """
    N = T.shape[0]
    for blk in numba.prange((N + TARGET_BLOCK - 1) // TARGET_BLOCK):
        _check_block(
            links, ends, qlim, T, Q, info, w, q0, opts, out_q, out_slot, out_res, meta,
            blk * TARGET_BLOCK, min(N, (blk + 1) * TARGET_BLOCK),
        )  # fmt: skip


@kernel
def _check_block(
    links: Array,
    ends: Array,
    qlim: Array,
    T: Array,
    Q: Array,
    info: Array,
    w: Array,
    q0: Array,
    opts: Array,
    out_q: Array,
    out_slot: IntArray,
    out_res: Array,
    meta: Array,
    b0: int,
    b1: int,
) -> None:
    """:func:`check_target` for targets ``b0 <= i < b1`` of a batch, one after another.

    The arrays are :func:`check_batch`'s; the work arrays are made once for
    the block. A row of ``meta`` whose status is ``STATUS_INVALID`` (a
    malformed target) stays invalid, its numbers NaN.
    """
    m, n = Q.shape[1], Q.shape[2]
    C, S, C1, S1, poses, e, no_frames, no_axes, qs, res, state, key = _scratch(m, n)
    pose = poses[0]
    for i in range(b0, b1):
        if meta[i, META_STATUS] == STATUS_INVALID:  # no numbers for a malformed target
            out_q[i, :, :] = np.nan
            out_slot[i, :] = -1
            out_res[i, :, :] = np.nan
            meta[i, META_COUNT] = 0.0
            meta[i, META_OUT_COUNT] = 0.0
            meta[i, META_GAP] = math.nan
            meta[i, META_NEAREST_POSITION] = math.nan
            meta[i, META_NEAREST_ROTATION] = math.nan
            meta[i, META_NEAR] = 0.0
            continue
        _check(
            links, ends, qlim, T[i], Q[i], info[i], w, q0[i], opts,
            out_q[i], out_slot[i], out_res[i], meta[i],
            C, S, C1, S1, poses, pose, e, no_frames, no_axes, qs, res, state, key,
        )  # fmt: skip
