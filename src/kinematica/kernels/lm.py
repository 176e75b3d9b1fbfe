"""Numeric IK of one target: Levenberg-Marquardt with restarts.

Damped least squares on the pose error ``e = (Δp, Δω)`` in the base frame,
``Δp = p_target − p`` (m) and ``Δω`` the rotation vector of ``R_target · Rᵀ``
(rad), with the geometric Jacobian. Each step solves
``(JᵀWJ + λ s I) Δq = JᵀW e`` (in its ``m × m`` form when the arm is
redundant); ``W`` holds the mask weights, ``s`` the mean diagonal of the normal
matrix, so ``λ`` is dimensionless.

* A step that lowers ``½ eᵀWe`` is accepted and ``λ`` shrinks tenfold (the
  last steps are Gauss-Newton steps, quadratically convergent to the 1e-10
  tolerances); a step that does not is rejected and ``λ`` grows fivefold. The
  Jacobian is computed for accepted configurations only.
* With only some rotation components counted, ``Δω`` need not vanish at a
  solution and its rows use the exact derivative ``−J_r⁻¹(Δω) J_ω``.
* Joint limits: the step is taken in variables scaled by the distance to the
  bound each joint heads for (Coleman and Li's affine scaling, as in scipy's
  ``least_squares(method="trf")``): a joint's Jacobian column and its step are
  scaled by ``√min(v / BOUND_SCALE, 1)``, ``v`` its distance (rad or m) to the
  bound the steepest-descent direction pushes it towards, so a joint slows
  down as it nears that bound and a joint on it is blocked. The new
  configuration is then projected: revolute angles are wrapped into a 2π
  window starting at their lower bound and clamped to the nearer bound around
  the circle; prismatic joints are clipped.
* An attempt stops when it converges, when ``λ`` exceeds ``LAMBDA_MAX``, when
  the error norm has not halved over ``STALL_WINDOW`` steps (a local minimum),
  or after the step budget.
* An attempt that stops within ``POLISH_LIMIT`` of the target (a near miss)
  gets ``POLISH_STEPS`` Gauss-Newton steps (damping ``LAMBDA_MIN``), taken
  whatever they do to the error, and keeps the best point. Near a fold or a
  nearly singular Jacobian the damped steps stall a hair from the target: the
  error left lies along a direction of tiny singular value, which any damping
  above it freezes, and the undamped step that crosses the fold may first
  raise the error before the next one lands (a rule of acceptance would
  refuse it).
* A failed attempt restarts from the next of the given ``samples`` (drawn once
  by the caller from a seed: a batch uses the same ones for every target, so
  a target gets the same answer alone or in a batch).
* A target farther from the base than the reach bound is proven out of reach
  and not searched; its distance is computed without overflow (a target
  1e300 m away has a gap of 1e300 m, not a floating-point exception).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from kinematica.kernels._numba import Array, IntArray, batch_kernel, inline_kernel, kernel
from kinematica.kernels.arrays import copy1, copy2
from kinematica.kernels.fk import LINK_PRISMATIC, block_trig, walk
from kinematica.kernels.ik_check import POLISH_DAMPING, POLISH_LIMIT, POLISH_STEPS
from kinematica.kernels.jacobian import columns
from kinematica.kernels.linalg import damped_least_squares
from kinematica.kernels.so3 import inverse_right_jacobian, pose_error

__all__ = [
    "BOUND_HI",
    "BOUND_LO",
    "BOUND_SCALE",
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
    "distance",
    "lm_batch",
    "lm_rows",
    "lm_target",
]

#: Initial damping, relative to the mean diagonal of the normal matrix: about
#: as strong as the Jacobian itself, a safe first step from a distant guess.
LAMBDA_INIT = 1.0
#: Damping factor after an accepted step (towards Gauss-Newton) ...
LAMBDA_DOWN = 0.1
#: ... and after a rejected one (towards short gradient steps).
LAMBDA_UP = 5.0
#: Smallest relative damping, far below the round-off of the normal matrix:
#: the last steps are Gauss-Newton steps, which converge along directions
#: whose singular value is down to 1e-9 of the largest (two prismatic axes
#: 1e-9 rad from parallel; at 1e-18 such an arm is no longer solved). Where
#: round-off leaves a Cholesky pivot at or below zero, the pivot is floored
#: (see :mod:`kinematica.kernels.linalg`): the step is huge, the error grows,
#: and the step is rejected (λ then grows).
LAMBDA_MIN = 1e-21
#: Damping at which an attempt has stalled: even tiny gradient steps no longer
#: reduce the error (a local minimum, or the error is at round-off level).
LAMBDA_MAX = 1e8
#: Progress check: every STALL_WINDOW steps the squared error must have
#: dropped below STALL_FACTOR times its value at the previous check (the error
#: norm must halve), else the attempt has stalled and a restart is better.
STALL_WINDOW = 8
STALL_FACTOR = 0.25
#: Distance to a bound (rad or m) below which a joint heading for it slows
#: down: its column and step are scaled by ``√min(distance / BOUND_SCALE, 1)``.
#: Measured on the Panda within its limits: 10-15 % fewer evaluations than
#: blocking joints only once they sit on a bound, the same on the iiwa14.
BOUND_SCALE = 1.0

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
def distance(T: Array, origin: Array, w: Array) -> float:
    """Distance (m) from ``origin (3,)`` to the position of ``T (4, 4)``, counted axes only.

    The axes whose weight ``w[k]`` is 0 are left out. Computed scaled by the
    largest component, so it never overflows before the distance itself does
    (then it is inf).
    """
    big = 0.0
    for k in range(3):
        if w[k] > 0.0:
            big = max(big, abs(T[k, 3] - origin[k]))
    if big == 0.0 or not math.isfinite(big):
        return big
    s = 0.0
    for k in range(3):
        if w[k] > 0.0:
            s += ((T[k, 3] - origin[k]) / big) ** 2
    return big * math.sqrt(s)


@kernel
def _project(links: Array, bounds: Array, q: Array) -> None:
    """Wrap revolute angles into their window, then clamp into the bounds (in place)."""
    for i in range(links.shape[0]):
        lo = bounds[i, BOUND_LO]
        hi = bounds[i, BOUND_HI]
        v = q[i]
        revolute = links[i, LINK_PRISMATIC] == 0.0
        if revolute:
            base = bounds[i, BOUND_WRAP]
            v = base + (v - base) % _TWO_PI
        if v > hi:
            v = lo if revolute and v - hi > lo + _TWO_PI - v else hi
        q[i] = lo if v < lo else v


@kernel
def _counted(w: Array, rows: IntArray, sw: Array, scale: Array) -> bool:
    """The counted error components of the weights ``w (6,)``.

    Fills ``rows (r,)`` (their indices 0-5), ``sw (r,)`` (the square roots of
    their weights) and ``scale (r,)`` (``max(w, 1)``: the convergence test
    holds the weighted and the plain error to the tolerances). Returns True
    when only some rotation components count (their rows then need the exact
    derivative of the rotation error).
    """
    r = 0
    rotations = 0
    for k in range(6):
        if w[k] > 0.0:
            rows[r] = k
            sw[r] = math.sqrt(w[k])
            scale[r] = max(w[k], 1.0)
            r += 1
            if k >= 3:
                rotations += 1
    return 0 < rotations < 3


@inline_kernel
def _error(
    links: Array,
    ends: Array,
    q: Array,
    T: Array,
    rows: IntArray,
    C: Array,
    S: Array,
    pose: Array,
    frames: Array,
    axes: Array,
    e6: Array,
    err: Array,
    work: Array,
) -> None:
    """Pose at ``q``, its joint axes, the full error ``e6 (6,)`` and the counted ``err (r,)``."""
    n = links.shape[0]
    block_trig(links, q.reshape((1, n)), 0, 1, C, S)
    walk(links, ends, False, C, S, 0, q, pose, frames, axes, work)
    pose_error(pose, T, e6)
    for r in range(rows.shape[0]):
        err[r] = e6[rows[r]]


@inline_kernel
def _jacobian(
    links: Array,
    axes: Array,
    pose: Array,
    e6: Array,
    rows: IntArray,
    sw: Array,
    exact: bool,
    J6: Array,
    A: Array,
    J: Array,
) -> None:
    """Weighted Jacobian rows ``J (r, n)`` of the counted errors, from the last :func:`_error`."""
    n = links.shape[0]
    columns(links, axes, pose, False, J6)
    if exact:  # only some rotation components count: rows J_r⁻¹(Δω) J_ω
        inverse_right_jacobian(e6[3], e6[4], e6[5], A)
        for j in range(n):
            w0 = J6[3, j]
            w1 = J6[4, j]
            w2 = J6[5, j]
            for k in range(3):
                J6[3 + k, j] = A[k, 0] * w0 + A[k, 1] * w1 + A[k, 2] * w2
    for r in range(rows.shape[0]):
        k = rows[r]
        for j in range(n):
            J[r, j] = sw[r] * J6[k, j]


@kernel
def lm_rows(links: Array, ends: Array, w: Array, q: Array, T: Array, err: Array, J: Array) -> int:
    """The search's model at one configuration: counted errors and their Jacobian rows.

    What each LM step linearises, exposed so that it can be checked against
    finite differences of the error.

    Args:
        links: ``(n, 10)`` the chain (see :mod:`kinematica.kernels.fk`).
        ends: ``(3, 4, 4)`` its start, tool and base.
        w: ``(6,)`` weights of the error components (0: not counted).
        q: ``(n,)`` joint values (rad, m).
        T: ``(4, 4)`` target (base frame).
        err: ``(6,)`` out: the first ``r`` entries are the counted errors
            ``e_k`` (unweighted; m, rad), in the order x, y, z, rx, ry, rz.
        J: ``(6, n)`` out: the first ``r`` rows are ``√w_k · ∂(−e_k)/∂q``.

    Returns:
        ``r``, the number of counted components.
    """
    n = links.shape[0]
    r = 0
    for k in range(6):
        if w[k] > 0.0:
            r += 1
    rows = np.empty(r, dtype=np.int64)
    sw = np.empty(r)
    exact = _counted(w, rows, sw, np.empty(r))
    pose = np.empty((4, 4))
    axes = np.empty((n, 6))
    e6 = np.empty(6)
    C = np.empty((n, 1))
    S = np.empty((n, 1))
    frames = np.empty((0, 4, 4))
    _error(links, ends, q, T, rows, C, S, pose, frames, axes, e6, err[:r], np.empty((6, 3)))
    _jacobian(links, axes, pose, e6, rows, sw, exact, np.empty((6, n)), np.empty((3, 3)), J[:r])
    return r


@kernel
def _norms(rows: IntArray, scale: Array, err: Array) -> tuple[float, float]:
    """Position and rotation norms of ``err``, each component scaled by ``scale``."""
    p2 = 0.0
    r2 = 0.0
    for r in range(rows.shape[0]):
        v = (err[r] * scale[r]) ** 2
        if rows[r] < 3:
            p2 += v
        else:
            r2 += v
    return math.sqrt(p2), math.sqrt(r2)


@kernel
def _energy(sw: Array, err: Array) -> float:
    """``½ Σ w_k e_k²`` of the counted errors."""
    t = 0.0
    for r in range(err.shape[0]):
        t += (err[r] * sw[r]) ** 2
    return 0.5 * t


@kernel
def _bound_scaling(bounds: Array, q: Array, J: Array, ew: Array, Jb: Array, d: Array) -> None:
    """Coleman-Li scaling: ``d (n,)`` per joint, and the scaled Jacobian ``Jb = J · diag(d)``.

    ``d_j = √min(v_j / BOUND_SCALE, 1)``, ``v_j`` the distance to the bound
    that the steepest-descent direction ``Jᵀ W e`` pushes joint ``j``
    towards (no such bound: 1).
    """
    count = J.shape[0]
    for j in range(J.shape[1]):
        g = 0.0
        for r in range(count):
            g += J[r, j] * ew[r]
        v = BOUND_SCALE
        if g > 0.0:
            v = min(v, bounds[j, BOUND_HI] - q[j])
        elif g < 0.0:
            v = min(v, q[j] - bounds[j, BOUND_LO])
        d[j] = math.sqrt(max(v, 0.0) / BOUND_SCALE)
        for r in range(count):
            Jb[r, j] = J[r, j] * d[j]


@kernel
def _active_step(
    bounds: Array,
    q: Array,
    J: Array,
    ew: Array,
    damping: float,
    Jb: Array,
    dq: Array,
    G: Array,
    b: Array,
    x: Array,
    L: Array,
) -> None:
    """A Gauss-Newton step ``dq`` holding the joints on a bound that it would carry out.

    Solved again without each such joint until no held joint would leave
    (an active set); ``damping`` is relative, as in :func:`damped_least_squares`.
    """
    n = q.shape[0]
    copy2(Jb, J)
    for _ in range(n + 1):
        damped_least_squares(Jb, ew, damping, dq, G, b, x, L)
        held = False
        for i in range(n):
            if (q[i] <= bounds[i, BOUND_LO] and dq[i] < 0.0) or (
                q[i] >= bounds[i, BOUND_HI] and dq[i] > 0.0
            ):
                for r in range(J.shape[0]):
                    Jb[r, i] = 0.0
                held = True
        if not held:
            return


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
        q_out: ``(n,)`` out: the converged configuration, or the best failed
            one (NaN when the target was not searched).
        stats: ``(STAT_SIZE,)`` out: converged (1.0), evaluations, attempts,
            and the gap (m) when the target is proven out of reach (then it
            is not searched; NaN otherwise).
    """
    n = links.shape[0]
    tol_p = settings[SET_TOL_POSITION]
    tol_r = settings[SET_TOL_ROTATION]
    max_steps = int(settings[SET_MAX_STEPS])
    stats[STAT_CONVERGED] = 0.0
    stats[STAT_ITERATIONS] = 0.0
    stats[STAT_ATTEMPTS] = 0.0
    stats[STAT_GAP] = math.nan
    # A target beyond the reach bound is out of reach (leaving out components
    # that do not count only shortens a distance). A solution may miss by the
    # tolerance in the weighted norm, so the proof needs w_min · gap > tol_p.
    w_min = math.inf
    for k in range(3):
        if w[k] > 0.0:
            w_min = min(w_min, w[k])
    gap = distance(T, settings[SET_BASE : SET_BASE + 3], w) - settings[SET_REACH]
    if w_min < math.inf and gap * w_min > tol_p:
        stats[STAT_GAP] = gap
        q_out[:] = np.nan
        return
    count = 0
    for k in range(6):
        if w[k] > 0.0:
            count += 1
    rows = np.empty(count, dtype=np.int64)
    sw = np.empty(count)
    scale = np.empty(count)
    exact = _counted(w, rows, sw, scale)
    # Scratch space, allocated once per target.
    C = np.empty((n, 1))
    S = np.empty((n, 1))
    pose = np.empty((4, 4))
    frames = np.empty((0, 4, 4))
    axes = np.empty((n, 6))
    J6 = np.empty((6, n))
    A = np.empty((3, 3))
    e6 = np.empty(6)
    work = np.empty((6, 3))
    err = np.empty(count)
    err_new = np.empty(count)
    ew = np.empty(count)
    J = np.empty((count, n))
    Jb = np.empty((count, n))
    big = max(n, count)
    G = np.empty((n, count))
    b = np.empty(big)
    x = np.empty(big)
    L = np.empty((big, big))
    dq = np.empty(n)
    d = np.empty(n)
    q = np.empty(n)
    q_new = np.empty(n)
    q_best = np.empty(n)
    err_best = np.empty(count)
    best_score = math.inf
    evaluations = 0
    attempts = 0
    converged = False
    copy1(q_out, start)
    _project(links, bounds, q_out)
    for attempt in range(samples.shape[0] + 1):
        copy1(q, start if attempt == 0 else samples[attempt - 1])
        _project(links, bounds, q)
        attempts += 1
        _error(links, ends, q, T, rows, C, S, pose, frames, axes, e6, err, work)
        _jacobian(links, axes, pose, e6, rows, sw, exact, J6, A, J)
        evaluations += 1
        E = _energy(sw, err)
        E_ref = E
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
            # One damped step in bound-scaled variables, then back into the bounds.
            for r in range(count):
                ew[r] = err[r] * sw[r]
            _bound_scaling(bounds, q, J, ew, Jb, d)
            damped_least_squares(Jb, ew, lam, dq, G, b, x, L)
            for i in range(n):
                q_new[i] = q[i] + d[i] * dq[i]
            _project(links, bounds, q_new)
            _error(links, ends, q_new, T, rows, C, S, pose, frames, axes, e6, err_new, work)
            evaluations += 1
            E_new = _energy(sw, err_new)
            if E_new < E:
                copy1(q, q_new)
                copy1(err, err_new)
                _jacobian(links, axes, pose, e6, rows, sw, exact, J6, A, J)
                E = E_new
                lam = max(lam * LAMBDA_DOWN, LAMBDA_MIN)
            else:
                lam *= LAMBDA_UP
            k += 1
        if not converged and max(pos, rot) < POLISH_LIMIT:
            # A near miss: Gauss-Newton steps taken whatever they do to the
            # error (across a fold the first one may raise it), then the best;
            # undamped first, then damped as the check's polishing is.
            copy1(q_best, q)
            copy1(err_best, err)
            E_low = E
            for damping in (LAMBDA_MIN, POLISH_DAMPING):
                for _ in range(POLISH_STEPS):
                    for r in range(count):
                        ew[r] = err[r] * sw[r]
                    _active_step(bounds, q, J, ew, damping, Jb, dq, G, b, x, L)
                    for i in range(n):
                        q[i] += dq[i]
                    _project(links, bounds, q)
                    _error(links, ends, q, T, rows, C, S, pose, frames, axes, e6, err, work)
                    _jacobian(links, axes, pose, e6, rows, sw, exact, J6, A, J)
                    evaluations += 1
                    pos, rot = _norms(rows, scale, err)
                    if pos <= tol_p and rot <= tol_r:
                        converged = True
                        break
                    E_new = _energy(sw, err)
                    if E_new < E_low:
                        copy1(q_best, q)
                        copy1(err_best, err)
                        E_low = E_new
                if converged:
                    break
                copy1(q, q_best)
                copy1(err, err_best)
                _error(links, ends, q, T, rows, C, S, pose, frames, axes, e6, err, work)
                _jacobian(links, axes, pose, e6, rows, sw, exact, J6, A, J)
        pos, rot = _norms(rows, scale, err)
        score = max(pos / tol_p, rot / tol_r)
        if converged or score < best_score:
            best_score = score
            copy1(q_out, q)
        if converged:
            break
    stats[STAT_CONVERGED] = 1.0 if converged else 0.0
    stats[STAT_ITERATIONS] = evaluations
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
