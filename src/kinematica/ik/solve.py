"""``robot.ik``: choose a solver, run its kernel on the targets, check the answers.

One path for one target and for a batch of any shape: a closed-form solver's
kernel (or the numeric search) proposes candidates, the check kernel of
:mod:`kinematica.kernels.ik_check` judges them by forward kinematics, and the
outcome is wrapped in an :class:`IKResult` (one target) or an
:class:`IKBatchResult` (a batch).
"""

from __future__ import annotations

import weakref
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.dh import DHChain
from kinematica.errors import ArgumentError, DimensionError, KinematicaError
from kinematica.ik.analytic import SOLVERS
from kinematica.ik.numeric import LABEL, check_seed, numeric_setup
from kinematica.ik.registry import ClosedForm, TargetKind, describe
from kinematica.ik.result import CheckOutput, IKBatchResult, IKResult, result_of
from kinematica.ik.structure import features
from kinematica.ik.targets import Targets, Tolerance, parse_mask, parse_targets, parse_tolerance
from kinematica.kernels import resolve_workers, set_workers
from kinematica.kernels.ik_check import (
    INFO_FREE,
    INFO_GAP,
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
            position = closed_form(chain, "position")
            found = position if position is not None and not position.partial else None
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
    if workers is not None or not targets.single:  # one target starts no thread
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
    complete = closed is not None
    opts = _options(tolerance, respect_limits, complete, q0s is not None)
    if targets.single and closed is not None:
        return _one_closed(chain, closed, targets, w, opts, q0s)
    N = targets.poses.shape[0]
    if closed is not None:
        Q, info = _closed_candidates(closed, targets, chain.dof, workers)
        labels, name = closed.labels, f"analytic:{closed.name}"
    else:
        Q, info = _numeric_candidates(
            chain, targets, w, tolerance, respect_limits, seed, q0s, workers
        )
        labels, name = (LABEL,), "numeric:lm"
    slots, n = Q.shape[1], chain.dof
    q0_rows = q0s if q0s is not None else np.zeros((N, n))
    out_q = np.empty((N, slots, n))
    out_slot = np.empty((N, slots), dtype=np.int64)
    out_res = np.empty((N, slots, 2))
    meta = np.zeros((N, META_SIZE))
    raw = CheckOutput(out_q, out_slot, out_res, meta, info[:, INFO_FREE:])
    if targets.single:
        check_target(
            chain.links, chain.ends, chain.qlim, targets.poses[0], Q[0], info[0], w,
            q0_rows[0], opts, out_q[0], out_slot[0], out_res[0], meta[0],
        )  # fmt: skip
        if closed is None:
            _unproven(meta)
        return result_of(
            out_q[0], out_slot[0], out_res[0], meta[0], info[0, INFO_FREE:],
            labels, name, complete, targets.notes.get(0, ()),
        )  # fmt: skip
    for i in targets.invalid:
        meta[i, META_STATUS] = STATUS_INVALID
    set_workers(workers)
    check_batch(
        chain.links, chain.ends, chain.qlim, targets.poses, Q, info, w, q0_rows, opts,
        out_q, out_slot, out_res, meta,
    )  # fmt: skip
    if closed is None:
        _unproven(meta)
    shape = targets.shape

    def where(i: int) -> tuple[int, ...]:
        return tuple(int(v) for v in np.unravel_index(i, shape))

    return IKBatchResult(
        raw=raw,
        method=name,
        labels=labels,
        shape=shape,
        errors={where(i): msg for i, msg in targets.invalid.items()},
        notes={where(i): note for i, note in targets.notes.items()},
        complete=complete,
    )


# The option arrays of the check kernel, one per combination of settings seen.
_OPTIONS: dict[tuple[float, float, bool, bool, bool], FloatArray] = {}


def _options(
    tolerance: Tolerance, respect_limits: bool, complete: bool, has_q0: bool
) -> FloatArray:
    """The check kernel's ``opts`` for these settings (built once, then reused)."""
    key = (tolerance.position, tolerance.rotation, bool(respect_limits), complete, has_q0)
    opts = _OPTIONS.get(key)
    if opts is None:
        opts = np.empty(OPT_SIZE)
        opts[OPT_TOL_POSITION] = tolerance.position
        opts[OPT_TOL_ROTATION] = tolerance.rotation
        opts[OPT_RESPECT_LIMITS] = float(respect_limits)
        opts[OPT_COMPLETE] = float(complete)
        opts[OPT_HAS_Q0] = float(has_q0)
        if len(_OPTIONS) < 64:
            _OPTIONS[key] = opts
    return opts


_ZEROS: dict[int, FloatArray] = {}


def _zeros(n: int) -> FloatArray:
    """A ``(n,)`` zero vector made once per size: the check kernel never writes ``q0``.

    (Not flagged read-only: numba would compile the check kernel once more for it.)
    """
    z = _ZEROS.get(n)
    if z is None:
        z = _ZEROS[n] = np.zeros(n)
    return z


def _one_closed(
    chain: DHChain,
    closed: ClosedForm,
    targets: Targets,
    w: FloatArray,
    opts: FloatArray,
    q0s: FloatArray | None,
) -> IKResult:
    """One target, one closed form: the solver kernel, the check kernel, the result."""
    n, m = chain.dof, closed.slots
    T = targets.poses[0]
    Q = np.empty((m, n))
    info = np.zeros(INFO_FREE + n)
    closed.solve_one(closed.params, T, Q, info)
    out_q = np.empty((m, n))
    out_slot = np.empty(m, dtype=np.int64)
    out_res = np.empty((m, 2))
    meta = np.empty(META_SIZE)
    q0 = _zeros(n) if q0s is None else q0s[0]
    check_target(
        chain.links, chain.ends, chain.qlim, T, Q, info, w, q0, opts, out_q, out_slot, out_res, meta
    )
    notes = targets.notes.get(0, ()) if targets.notes else ()
    return result_of(
        out_q, out_slot, out_res, meta, info[INFO_FREE:],
        closed.labels, closed.method, True, notes,
    )  # fmt: skip


def _closed_candidates(
    closed: ClosedForm, targets: Targets, n: int, workers: int | None
) -> tuple[FloatArray, FloatArray]:
    """Candidates ``(N, m, n)`` and solver info ``(N, k)`` of a closed form."""
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
