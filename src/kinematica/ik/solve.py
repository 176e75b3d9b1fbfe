"""``robot.ik``: choose a solver, run its kernel on the targets, check the answers.

One path for one target and for a batch of any shape: a closed-form solver's
kernel (or the numeric search) proposes candidates, the check kernel of
:mod:`kinematica.kernels.ik_check` judges them by forward kinematics, and the
outcome is wrapped in an :class:`IKResult` (one target) or an
:class:`IKBatchResult` (a batch).
"""

from __future__ import annotations

import math
import weakref
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.dh import DHChain
from kinematica.errors import ArgumentError, DimensionError, KinematicaError
from kinematica.ik.analytic import SOLVERS
from kinematica.ik.numeric import LABEL, check_seed, numeric_setup
from kinematica.ik.registry import ClosedForm, TargetKind, describe
from kinematica.ik.result import IKBatchResult, IKResult
from kinematica.ik.status import STATUS_NAMES, IKStatus
from kinematica.ik.structure import features
from kinematica.ik.targets import Targets, Tolerance, parse_mask, parse_targets, parse_tolerance
from kinematica.kernels import resolve_workers, set_workers
from kinematica.kernels.ik_check import (
    INFO_FREE,
    INFO_GAP,
    META_COUNT,
    META_GAP,
    META_NEAREST_POSITION,
    META_NEAREST_ROTATION,
    META_OUT_COUNT,
    META_SIZE,
    META_STATUS,
    OPT_COMPLETE,
    OPT_HAS_Q0,
    OPT_RESPECT_LIMITS,
    OPT_SIZE,
    OPT_TOL_POSITION,
    OPT_TOL_ROTATION,
    STATUS_INVALID,
    STATUS_NOT_FOUND,
    STATUS_OUT_OF_LIMITS,
    check_batch,
    check_target,
    info_size,
)
from kinematica.kernels.lm import STAT_GAP, STAT_SIZE, lm_batch, lm_target

__all__ = ["Method", "closed_form", "solve_ik", "structure_of"]

FloatArray = NDArray[np.float64]
Method = Literal["auto", "analytic", "numeric"]

_POSE = np.ones(6)
_POSITION = np.array([1.0, 1.0, 1.0, 0.0, 0.0, 0.0])

# Closed-form solvers are built once per chain (a chain is immutable, so the
# solver is a pure function of it); the cache forgets a chain when it dies.
_SOLVERS: weakref.WeakKeyDictionary[DHChain, dict[str, ClosedForm | None]] = (
    weakref.WeakKeyDictionary()
)


def structure_of(chain: DHChain) -> tuple[str, str]:
    """``(kind, summary)`` of a chain's structure (see :func:`describe`)."""
    return describe(features(chain), SOLVERS)


def closed_form(chain: DHChain, target: TargetKind) -> ClosedForm | None:
    """The closed-form solver of a chain for pose or position targets, if there is one.

    A reduced arm (fewer than 6 joints) without a pose solver takes its
    position solver for poses: the whole pose is then checked.
    """
    per_chain = _SOLVERS.setdefault(chain, {})
    if target not in per_chain:
        found = None
        f = features(chain)
        for spec in SOLVERS:
            if spec.handles(f):
                found = spec.build(chain, f, target)
                if found is not None:
                    break
        if found is None and target == "pose" and chain.dof < 6:
            found = closed_form(chain, "position")
        per_chain[target] = found
    return per_chain[target]


def _check_workers(workers: int | None) -> None:
    """``workers`` validated up front, whether or not a batch will use it."""
    try:
        resolve_workers(workers)
    except ValueError as exc:
        raise ArgumentError(str(exc)) from None


def _q0(chain: DHChain, q0: ArrayLike | None, targets: Targets) -> FloatArray | None:
    """``(N, n)`` q0 per target, or None."""
    if q0 is None:
        return None
    try:
        q = np.asarray(q0, dtype=float)
    except (TypeError, ValueError) as exc:
        raise DimensionError(f"q0 must be numbers, got {q0!r}") from exc
    n = chain.dof
    if q.ndim == 0 or q.shape[-1] != n:
        raise DimensionError(f"q0 must hold {n} joint values, got shape {q.shape}")
    if not np.all(np.isfinite(q)):
        raise DimensionError("q0 holds NaN or inf")
    try:
        full = np.broadcast_to(q, (*targets.shape, n))
    except ValueError:
        raise DimensionError(
            f"q0 of shape {q.shape} does not match targets of batch shape {targets.shape}"
        ) from None
    return np.ascontiguousarray(full.reshape(-1, n))


def solve_ik(
    chain: DHChain,
    target: ArrayLike,
    *,
    method: Method = "auto",
    respect_limits: bool = True,
    q0: ArrayLike | None = None,
    mask: ArrayLike | None = None,
    seed: int | np.random.Generator | None = None,
    tol: float | tuple[float, float] | Tolerance | None = None,
    workers: int | None = None,
) -> IKResult | IKBatchResult:
    """Every inverse-kinematics solution of a target, or an honest status.

    See :meth:`kinematica.Robot.ik` for the arguments and what comes back.
    """
    if method not in ("auto", "analytic", "numeric"):
        raise KinematicaError(f"method must be 'auto', 'analytic' or 'numeric', got {method!r}")
    targets = parse_targets(target)
    m = parse_mask(mask)
    tolerance = parse_tolerance(tol)
    seed = check_seed(seed)
    _check_workers(workers)
    q0s = _q0(chain, q0, targets)
    kind: TargetKind = "position" if targets.position else "pose"
    w = _POSITION if targets.position else _POSE
    if m is not None:
        w = m * w
    closed = None if method == "numeric" or m is not None else closed_form(chain, kind)
    if method == "analytic" and closed is None:
        why = "a mask was given" if m is not None else f"structure: {structure_of(chain)[1]}"
        raise KinematicaError(f"no closed-form solver for this arm ({why}); use method='numeric'")
    N = targets.poses.shape[0]
    if closed is not None:
        Q, info = _closed_candidates(closed, targets, chain.dof, workers)
        labels, name = closed.labels, f"analytic:{closed.name}"
    else:
        Q, info = _numeric_candidates(
            chain, targets, w, tolerance, respect_limits, seed, q0s, workers
        )
        labels, name = (LABEL,), "numeric:lm"
    opts = np.empty(OPT_SIZE)
    opts[OPT_TOL_POSITION] = tolerance.position
    opts[OPT_TOL_ROTATION] = tolerance.rotation
    opts[OPT_RESPECT_LIMITS] = float(respect_limits)
    opts[OPT_COMPLETE] = float(closed is not None)
    opts[OPT_HAS_Q0] = float(q0s is not None)
    slots = Q.shape[1]
    q0_rows = q0s if q0s is not None else np.zeros((N, chain.dof))
    out_q = np.empty((N, slots, chain.dof))
    out_slot = np.empty((N, slots), dtype=np.int64)
    out_res = np.empty((N, slots, 2))
    meta = np.zeros((N, META_SIZE))
    if targets.single:
        check_target(
            chain.links, chain.ends, chain.qlim, targets.poses[0], Q[0], info[0], w,
            q0_rows[0], opts, out_q[0], out_slot[0], out_res[0], meta[0],
        )  # fmt: skip
        if closed is None:
            _unproven(meta)
        return _one(
            out_q[0], out_slot[0], out_res[0], meta[0], info[0], labels, name, closed, targets
        )
    for i in targets.invalid:
        meta[i, META_STATUS] = STATUS_INVALID
    set_workers(workers)
    check_batch(
        chain.links, chain.ends, chain.qlim, targets.poses, Q, info, w, q0_rows, opts,
        out_q, out_slot, out_res, meta,
    )  # fmt: skip
    if closed is None:
        _unproven(meta)
    return _many(out_q, out_slot, out_res, meta, info, labels, name, closed, targets)


def _closed_candidates(
    closed: ClosedForm, targets: Targets, n: int, workers: int | None
) -> tuple[FloatArray, FloatArray]:
    """Candidates ``(N, m, n)`` and solver info ``(N, k)`` of a closed form."""
    if closed.legacy is not None:
        return closed.legacy(targets.poses)
    N = targets.poses.shape[0]
    Q = np.empty((N, closed.slots, n))
    info = np.zeros((N, info_size(n)))
    if N == 1:
        closed.solve_one(closed.params, targets.poses[0], Q[0], info[0])
    else:
        set_workers(workers)
        closed.solve_batch(closed.params, targets.poses, Q, info)
    return Q, info


def _numeric_candidates(
    chain: DHChain,
    targets: Targets,
    w: FloatArray,
    tolerance: Tolerance,
    respect_limits: bool,
    seed: int | np.random.Generator | None,
    q0s: FloatArray | None,
    workers: int | None,
) -> tuple[FloatArray, FloatArray]:
    """The numeric search's one candidate per target ``(N, 1, n)``, and its info."""
    setup = numeric_setup(
        chain,
        respect_limits=respect_limits,
        tol_position=tolerance.position,
        tol_rotation=tolerance.rotation,
        seed=seed,
    )
    N, n = targets.poses.shape[0], chain.dof
    Q = np.empty((N, 1, n))
    stats = np.empty((N, STAT_SIZE))
    args = (chain.links, chain.ends, setup.bounds, w, setup.settings)
    if N == 1:
        start = setup.middle if q0s is None else q0s[0]
        lm_target(*args, targets.poses[0], start, setup.samples, Q[0, 0], stats[0])
    else:
        starts = np.broadcast_to(setup.middle, (N, n)) if q0s is None else q0s
        set_workers(workers)
        lm_batch(*args, targets.poses, np.ascontiguousarray(starts), setup.samples, Q[:, 0], stats)
    info = np.zeros((N, info_size(n)))
    info[:, INFO_GAP] = stats[:, STAT_GAP]
    return Q, info


def _unproven(meta: FloatArray) -> None:
    """A search's statuses: ``out_of_limits`` is a proof it cannot give.

    The search stays within the limits; a candidate the check's polishing
    carried just past one does not show that no solution lies within them:
    such a target is ``not_found`` (the candidate is still listed).
    """
    status = meta[..., META_STATUS]
    status[status == STATUS_OUT_OF_LIMITS] = STATUS_NOT_FOUND


def _one(
    out_q: FloatArray,
    out_slot: NDArray[np.int64],
    out_res: FloatArray,
    meta: FloatArray,
    info: FloatArray,
    labels: tuple[str, ...],
    method: str,
    closed: ClosedForm | None,
    targets: Targets,
) -> IKResult:
    count, out_count = int(meta[META_COUNT]), int(meta[META_OUT_COUNT])
    status = STATUS_NAMES[int(meta[META_STATUS])]
    gap = float(meta[META_GAP])
    end = count + out_count
    return IKResult(
        solutions=out_q[:count].copy(),
        status=status,
        method=method,
        residuals=out_res[:count].copy(),
        branches=tuple(labels[j] for j in out_slot[:count]),
        out_of_limits=out_q[count:end].copy(),
        out_of_limits_branches=tuple(labels[j] for j in out_slot[count:end]),
        free_joints=_free(info) if status == IKStatus.SINGULAR else (),
        gap=None if math.isnan(gap) else gap,
        nearest_error=(float(meta[META_NEAREST_POSITION]), float(meta[META_NEAREST_ROTATION])),
        notes=targets.notes.get(0, ()),
        complete=closed is not None,
    )


def _free(info: FloatArray) -> tuple[int, ...]:
    return tuple(int(i) for i in np.flatnonzero(info[INFO_FREE:]))


def _many(
    out_q: FloatArray,
    out_slot: NDArray[np.int64],
    out_res: FloatArray,
    meta: FloatArray,
    info: FloatArray,
    labels: tuple[str, ...],
    method: str,
    closed: ClosedForm | None,
    targets: Targets,
) -> IKBatchResult:
    _N, m, n = out_q.shape
    shape = targets.shape
    count = meta[:, META_COUNT].astype(np.int64)
    out_count = meta[:, META_OUT_COUNT].astype(np.int64)
    k = int(count.max(initial=0))
    j = int(out_count.max(initial=0))
    rows = np.arange(m)
    names = np.array([*labels, ""], dtype=str)  # slot -1 -> ""
    inside = rows[None, :k] < count[:, None]
    solutions = np.where(inside[..., None], out_q[:, :k], np.nan)
    residuals = np.where(inside[..., None], out_res[:, :k], np.nan)
    branches = np.where(inside, names[out_slot[:, :k]], "")
    idx = np.minimum(count[:, None] + rows[None, :j], m - 1)
    outside = rows[None, :j] < out_count[:, None]
    o_q = np.where(outside[..., None], np.take_along_axis(out_q, idx[..., None], axis=1), np.nan)
    o_slot = np.take_along_axis(out_slot, idx, axis=1)
    o_branches = np.where(outside, names[o_slot], "")
    codes = meta[:, META_STATUS].astype(np.int64)
    status = np.array([str(STATUS_NAMES[c]) for c in range(6)], dtype=str)[codes]
    free = (info[:, INFO_FREE:] != 0.0) & (status == str(IKStatus.SINGULAR))[:, None]
    unravel = (
        (lambda i: tuple(int(v) for v in np.unravel_index(i, shape))) if shape else (lambda i: ())
    )
    return IKBatchResult(
        solutions=solutions.reshape(*shape, k, n),
        count=count.reshape(shape),
        status=status.reshape(shape),
        method=method,
        residuals=residuals.reshape(*shape, k, 2),
        branches=branches.reshape(*shape, k),
        out_of_limits=o_q.reshape(*shape, j, n),
        out_of_limits_count=out_count.reshape(shape),
        out_of_limits_branches=o_branches.reshape(*shape, j),
        free=free.reshape(*shape, n),
        gap=meta[:, META_GAP].reshape(shape),
        nearest_error=meta[:, [META_NEAREST_POSITION, META_NEAREST_ROTATION]].reshape(*shape, 2),
        errors={unravel(i): msg for i, msg in targets.invalid.items()},
        notes={unravel(i): note for i, note in targets.notes.items()},
        complete=closed is not None,
    )
