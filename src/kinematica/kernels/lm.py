"""Numeric IK of one target: Levenberg-Marquardt with restarts.

Damped least squares on the pose error ``e = (Δp, Δω)`` in the base frame,
``Δp = p_target − p`` (m) and ``Δω`` the rotation vector of ``R_target · Rᵀ``
(rad), with the geometric Jacobian. Each step solves
``(JᵀWJ + λ s I) Δq = JᵀW e`` (in its ``m × m`` form when the arm is
redundant); ``W`` holds the mask weights, ``s`` the mean diagonal of the normal
matrix, so ``λ`` is dimensionless.

* A step that lowers ``½ eᵀWe`` is accepted and ``λ`` shrinks tenfold (the
  last steps are Gauss-Newton steps, quadratically convergent to the 1e-10
  tolerances); a step that does not is rejected and ``λ`` grows fivefold.
* With only some rotation components counted, ``Δω`` need not vanish at a
  solution and its rows use the exact derivative ``−J_r⁻¹(Δω) J_ω``.
* Joint limits by projection: revolute angles are wrapped into a 2π window
  starting at their lower bound and clamped to the nearer bound around the
  circle; prismatic joints are clipped. A joint on a bound that the
  steepest-descent direction pushes outwards is blocked before the step.
* An attempt stops when it converges, when ``λ`` exceeds ``LAMBDA_MAX``, when
  the error norm has not halved over ``STALL_WINDOW`` steps (a local minimum),
  or after the step budget.
* A failed attempt restarts from the next of the given ``samples`` (drawn once
  by the caller from a seed: a batch uses the same ones for every target, so
  a target gets the same answer alone or in a batch).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from kinematica.kernels._numba import Array, IntArray, batch_kernel, kernel
from kinematica.kernels.arrays import copy1, copy2
from kinematica.kernels.fk import LINK_PRISMATIC, block_trig, walk
from kinematica.kernels.jacobian import columns
from kinematica.kernels.linalg import damped_least_squares
from kinematica.kernels.so3 import inverse_right_jacobian, pose_error

__all__ = [
    "BOUND_HI",
    "BOUND_LO",
    "BOUND_WRAP",
    "LAMBDA_DOWN",
    "LAMBDA_INIT",
    "LAMBDA_MAX",
    "LAMBDA_MIN",
    "LAMBDA_UP",
    "SET_BASE",
    "SET_MAX_STEPS",
    "SET_REACH",
    "SET_SIZE",
    "SET_TOL_POSITION",
    "SET_TOL_ROTATION",
    "STALL_FACTOR",
    "STALL_WINDOW",
    "STAT_ATTEMPTS",
    "STAT_CONVERGED",
    "STAT_GAP",
    "STAT_ITERATIONS",
    "STAT_SIZE",
    "lm_batch",
    "lm_target",
]

#: Initial damping, relative to the mean diagonal of the normal matrix: about
#: as strong as the Jacobian itself, a safe first step from a distant guess.
LAMBDA_INIT = 1.0
#: Damping factor after an accepted step (towards Gauss-Newton) ...
LAMBDA_DOWN = 0.1
#: ... and after a rejected one (towards short gradient steps).
LAMBDA_UP = 5.0
#: Smallest relative damping: negligible next to any singular value that
#: matters (so the last steps converge quadratically), yet it keeps the normal
#: matrix positive definite in floating point, rank-deficient Jacobian or not.
LAMBDA_MIN = 1e-12
#: Damping at which an attempt has stalled: even tiny gradient steps no longer
#: reduce the error (a local minimum, or the error is at round-off level).
LAMBDA_MAX = 1e8
#: Progress check: every STALL_WINDOW steps the squared error must have
#: dropped below STALL_FACTOR times its value at the previous check (the error
#: norm must halve), else the attempt has stalled and a restart is better.
STALL_WINDOW = 8
STALL_FACTOR = 0.25

_TWO_PI = 2.0 * math.pi

# Columns of ``bounds`` (n, 3): start of each revolute joint's 2π window, clamps.
BOUND_WRAP, BOUND_LO, BOUND_HI = range(3)
# Settings (``settings``): tolerances, steps per attempt, reach bound and base origin.
SET_TOL_POSITION, SET_TOL_ROTATION, SET_MAX_STEPS, SET_REACH, SET_BASE = 0, 1, 2, 3, 4
SET_SIZE = 7
# What a search reports (``stats``).
STAT_CONVERGED, STAT_ITERATIONS, STAT_ATTEMPTS, STAT_GAP = range(4)
STAT_SIZE = 4


@kernel
def _project(links: Array, bounds: Array, q: Array) -> None:
    """Wrap revolute angles into their window, then clamp into the bounds (in place)."""
    for i in range(links.shape[0]):
        lo, hi = bounds[i, BOUND_LO], bounds[i, BOUND_HI]
        v = q[i]
        revolute = links[i, LINK_PRISMATIC] == 0.0
        if revolute:
            base = bounds[i, BOUND_WRAP]
            v = base + (v - base) % _TWO_PI
        if v > hi:
            v = lo if revolute and v - hi > lo + _TWO_PI - v else hi
        q[i] = lo if v < lo else v


@kernel
def _evaluate(
    links: Array,
    ends: Array,
    q: Array,
    T: Array,
    rows: IntArray,
    sw: Array,
    exact: bool,
    C: Array,
    S: Array,
    pose: Array,
    axes: Array,
    J6: Array,
    A: Array,
    e6: Array,
    err: Array,
    J: Array,
    work: Array,
) -> None:
    """Counted errors ``err (r,)`` (unweighted) and weighted Jacobian rows ``J (r, n)``."""
    n = links.shape[0]
    block_trig(links, q.reshape((1, n)), 0, 1, C, S)
    walk(links, ends, False, C, S, 0, q, pose, np.empty((0, 4, 4)), axes, work)
    columns(links, axes, pose, False, J6)
    pose_error(pose, T, e6)
    if exact:  # only some rotation components count: rows J_r⁻¹(Δω) J_ω
        inverse_right_jacobian(e6[3], e6[4], e6[5], A)
        for j in range(n):
            w0, w1, w2 = J6[3, j], J6[4, j], J6[5, j]
            for k in range(3):
                J6[3 + k, j] = A[k, 0] * w0 + A[k, 1] * w1 + A[k, 2] * w2
    for r in range(rows.shape[0]):
        k = rows[r]
        err[r] = e6[k]
        for j in range(n):
            J[r, j] = sw[r] * J6[k, j]


@kernel
def _norms(rows: IntArray, scale: Array, err: Array) -> tuple[float, float]:
    """Position and rotation norms of ``err``, each component scaled by ``scale``."""
    p2 = r2 = 0.0
    for r in range(rows.shape[0]):
        v = (err[r] * scale[r]) ** 2
        if rows[r] < 3:
            p2 += v
        else:
            r2 += v
    return math.sqrt(p2), math.sqrt(r2)


@kernel
def _energy(sw: Array, err: Array) -> float:
    t = 0.0
    for r in range(err.shape[0]):
        t += (err[r] * sw[r]) ** 2
    return 0.5 * t


@kernel
def lm_target(
    links: Array,
    ends: Array,
    bounds: Array,
    w: Array,
    settings: Array,
    T: Array,
    start: Array,
    samples: Array,
    q_out: Array,
    stats: Array,
) -> None:
    """Search one target: attempts one after another, restarting failed ones.

    Args:
        links: ``(n, 10)`` the chain (see :mod:`kinematica.kernels.fk`).
        ends: ``(3, 4, 4)`` its start, tool and base.
        bounds: ``(n, 3)`` per joint: start of the 2π window, lower and upper clamp.
        w: ``(6,)`` weights of the error components (0: not counted).
        settings: ``(SET_SIZE,)`` tolerances (m, rad), steps per attempt, the
            reach bound (m) and the base origin ``(3,)``.
        T: ``(4, 4)`` target (base frame).
        start: ``(n,)`` first guess.
        samples: ``(R, n)`` restart configurations, used in order.
        q_out: ``(n,)`` out: the converged configuration, or the best failed one.
        stats: ``(STAT_SIZE,)`` out: converged (1.0), evaluations, attempts,
            and the gap (m) when the target lies beyond the reach bound (then
            it is not searched; NaN otherwise).
    """
    n = links.shape[0]
    tol_p, tol_r = settings[SET_TOL_POSITION], settings[SET_TOL_ROTATION]
    max_steps = int(settings[SET_MAX_STEPS])
    # A target beyond the reach bound (leaving out components that do not count
    # only shortens a distance) is provably out of reach: not searched.
    d2 = 0.0
    for k in range(3):
        if w[k] > 0.0:
            d2 += (T[k, 3] - settings[SET_BASE + k]) ** 2
    gap = math.sqrt(d2) - settings[SET_REACH]
    stats[STAT_GAP] = gap if gap > tol_p else math.nan
    if gap > tol_p:
        stats[STAT_CONVERGED] = 0.0
        stats[STAT_ITERATIONS] = 0.0
        stats[STAT_ATTEMPTS] = 0.0
        q_out[:] = np.nan
        return
    count = 0
    for k in range(6):
        if w[k] > 0.0:
            count += 1
    rows = np.empty(count, dtype=np.int64)
    sw = np.empty(count)
    scale = np.empty(count)
    count = 0
    rotations = 0
    for k in range(6):
        if w[k] > 0.0:
            rows[count] = k
            sw[count] = math.sqrt(w[k])
            scale[count] = max(w[k], 1.0)
            count += 1
            rotations += k >= 3
    exact = 0 < rotations < 3
    clamped = False
    for i in range(n):
        clamped |= np.isfinite(bounds[i, BOUND_LO]) or np.isfinite(bounds[i, BOUND_HI])
    C = np.empty((n, 1))
    S = np.empty((n, 1))
    pose = np.empty((4, 4))
    axes = np.empty((n, 6))
    J6 = np.empty((6, n))
    A = np.empty((3, 3))
    e6 = np.empty(6)
    err = np.empty(count)
    J = np.empty((count, n))
    err_new = np.empty(count)
    J_new = np.empty((count, n))
    Jb = np.empty((count, n))
    ew = np.empty(count)
    big = max(n, count)
    G = np.empty((n, count))
    b = np.empty(big)
    x = np.empty(big)
    L = np.empty((big, big))
    dq = np.empty(n)
    work = np.empty((6, 3))
    q = np.empty(n)
    q_new = np.empty(n)
    best_score = math.inf
    iterations = 0
    attempts = 0
    converged = False
    copy1(q_out, start)
    _project(links, bounds, q_out)
    for attempt in range(samples.shape[0] + 1):
        copy1(q, start if attempt == 0 else samples[attempt - 1])
        _project(links, bounds, q)
        attempts += 1
        _evaluate(links, ends, q, T, rows, sw, exact, C, S, pose, axes, J6, A, e6, err, J, work)
        E = E_ref = _energy(sw, err)
        lam = LAMBDA_INIT
        k = 0
        while True:
            pos, rot = _norms(rows, scale, err)
            if pos <= tol_p and rot <= tol_r:
                converged = True
                break
            window = k > 0 and k % STALL_WINDOW == 0
            if (window and STALL_FACTOR * E_ref < E) or lam > LAMBDA_MAX or k >= max_steps:
                break
            if window:
                E_ref = E
            # One damped step, with the joints held at a bound they would leave blocked.
            for r in range(count):
                ew[r] = err[r] * sw[r]
            copy2(Jb, J)
            if clamped:
                for i in range(n):
                    if q[i] <= bounds[i, BOUND_LO] or q[i] >= bounds[i, BOUND_HI]:
                        g = 0.0
                        for r in range(count):
                            g += J[r, i] * ew[r]
                        if (q[i] <= bounds[i, BOUND_LO] and g < 0.0) or (
                            q[i] >= bounds[i, BOUND_HI] and g > 0.0
                        ):
                            Jb[:, i] = 0.0
            damped_least_squares(Jb, ew, lam, dq, G, b, x, L)
            for i in range(n):
                q_new[i] = q[i] + dq[i]
            _project(links, bounds, q_new)
            _evaluate(
                links,
                ends,
                q_new,
                T,
                rows,
                sw,
                exact,
                C,
                S,
                pose,
                axes,
                J6,
                A,
                e6,
                err_new,
                J_new,
                work,
            )
            E_new = _energy(sw, err_new)
            if E_new < E:
                copy1(q, q_new)
                copy1(err, err_new)
                copy2(J, J_new)
                E = E_new
                lam = max(lam * LAMBDA_DOWN, LAMBDA_MIN)
            else:
                lam *= LAMBDA_UP
            k += 1
        iterations += k + 1
        pos, rot = _norms(rows, scale, err)
        score = max(pos / tol_p, rot / tol_r)
        if converged or score < best_score:
            best_score = score
            copy1(q_out, q)
        if converged:
            break
    stats[STAT_CONVERGED] = 1.0 if converged else 0.0
    stats[STAT_ITERATIONS] = iterations
    stats[STAT_ATTEMPTS] = attempts


@batch_kernel
def lm_batch(
    links: Array,
    ends: Array,
    bounds: Array,
    w: Array,
    settings: Array,
    T: Array,
    start: Array,
    samples: Array,
    q_out: Array,
    stats: Array,
) -> None:
    """:func:`lm_target` for targets ``T (N, 4, 4)``, ``start (N, n)`` in parallel."""
    for i in numba.prange(T.shape[0]):
        lm_target(links, ends, bounds, w, settings, T[i], start[i], samples, q_out[i], stats[i])
