"""Numeric IK of one target: Levenberg-Marquardt with restarts.

Damped least squares on the counted pose errors (the model is
:mod:`kinematica.kernels.lm_model`): each step solves
``(JᵀWJ + λ s I) Δq = JᵀW e`` (in its ``m × m`` form when the arm is
redundant); ``W`` holds the mask weights, ``s`` the mean diagonal of the normal
matrix, so ``λ`` is dimensionless.

* A step that lowers ``½ eᵀWe`` is accepted and ``λ`` shrinks tenfold (the
  last steps are Gauss-Newton steps, quadratically convergent to the 1e-10
  tolerances); a step that does not is rejected and ``λ`` grows fivefold. The
  Jacobian is computed for accepted configurations only.
* Joint limits (:mod:`kinematica.kernels.lm_bounds`): the step is taken in
  variables scaled by the distance to the bound each joint heads for (Coleman
  and Li's affine scaling, as in scipy's ``least_squares(method="trf")``), so
  a joint slows down as it nears that bound and a joint on it is blocked; the
  new configuration is then wrapped and clamped into the bounds.
* An attempt stops when it converges, when ``λ`` exceeds ``LAMBDA_MAX``, when
  the error norm has not halved over ``STALL_WINDOW`` steps (a local minimum),
  or after the step budget.
* An attempt that stops within ``POLISH_LIMIT`` of the target (a near miss)
  gets Gauss-Newton steps taken whatever they do to the error, and keeps the
  best point (:func:`_end_game`). Near a fold or a nearly singular Jacobian
  the damped steps stall a hair from the target: the error left lies along a
  direction of tiny singular value, which any damping above it freezes, and
  the undamped step that crosses the fold may first raise the error before
  the next one lands (a rule of acceptance would refuse it).
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

from kinematica.kernels._numba import Array, IntArray, batch_kernel, kernel
from kinematica.kernels.arrays import copy1
from kinematica.kernels.ik_check import POLISH_DAMPING, POLISH_LIMIT, POLISH_STEPS
from kinematica.kernels.linalg import damped_least_squares
from kinematica.kernels.lm_bounds import active_step, bound_scaling, project
from kinematica.kernels.lm_model import counted, energy, jacobian_rows, norms, pose_errors

__all__ = [
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
def _end_game(
    links: Array,
    ends: Array,
    bounds: Array,
    T: Array,
    rows: IntArray,
    sw: Array,
    scale: Array,
    exact: bool,
    tol_p: float,
    tol_r: float,
    q: Array,
    err: Array,
    J: Array,
    ew: Array,
    Jb: Array,
    dq: Array,
    G: Array,
    b: Array,
    x: Array,
    L: Array,
    C: Array,
    S: Array,
    pose: Array,
    frames: Array,
    axes: Array,
    e6: Array,
    J6: Array,
    A: Array,
    q_best: Array,
) -> int:
    """Gauss-Newton steps from a near miss ``q`` (its ``err`` and rows ``J``), in place.

    ``POLISH_STEPS`` steps of damping ``LAMBDA_MIN``, taken whatever they do
    to the error (across a fold the first one may raise it), then, from the
    best point so far, as many of damping ``POLISH_DAMPING`` (where the
    Jacobian has lost rank, the undamped normal equations blow up). Each step
    holds the joints on a bound that it would carry out (:func:`active_step`).
    Stops at the first point within the tolerances; otherwise leaves ``q``,
    ``err`` and ``J`` at the best point. ``q_best`` is scratch. Returns the number of evaluations.
    """
    n = q.shape[0]
    evaluations = 0
    copy1(q_best, q)
    E_low = energy(sw, err)
    for damping in (LAMBDA_MIN, POLISH_DAMPING):
        for _ in range(POLISH_STEPS):
            for r in range(rows.shape[0]):
                ew[r] = err[r] * sw[r]
            active_step(bounds, q, J, ew, damping, Jb, dq, G, b, x, L)
            for i in range(n):
                q[i] += dq[i]
            project(links, bounds, q)
            pose_errors(links, ends, q, T, rows, C, S, pose, frames, axes, e6, err)
            jacobian_rows(links, axes, pose, e6, rows, sw, exact, J6, A, J)
            evaluations += 1
            pos, rot = norms(rows, scale, err)
            if pos <= tol_p and rot <= tol_r:
                return evaluations
            E_new = energy(sw, err)
            if E_new < E_low:
                copy1(q_best, q)
                E_low = E_new
        copy1(q, q_best)
        pose_errors(links, ends, q, T, rows, C, S, pose, frames, axes, e6, err)
        jacobian_rows(links, axes, pose, e6, rows, sw, exact, J6, A, J)
        evaluations += 1
    return evaluations


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
    exact = counted(w, rows, sw, scale)
    # Scratch space, allocated once per target.
    C = np.empty((n, 1))
    S = np.empty((n, 1))
    pose = np.empty((4, 4))
    frames = np.empty((0, 4, 4))
    axes = np.empty((n, 6))
    J6 = np.empty((6, n))
    A = np.empty((3, 3))
    e6 = np.empty(6)
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
    best_score = math.inf
    evaluations = 0
    attempts = 0
    converged = False
    copy1(q_out, start)
    project(links, bounds, q_out)
    for attempt in range(samples.shape[0] + 1):
        copy1(q, start if attempt == 0 else samples[attempt - 1])
        project(links, bounds, q)
        attempts += 1
        pose_errors(links, ends, q, T, rows, C, S, pose, frames, axes, e6, err)
        jacobian_rows(links, axes, pose, e6, rows, sw, exact, J6, A, J)
        evaluations += 1
        E = energy(sw, err)
        E_ref = E
        lam = LAMBDA_INIT
        k = 0
        while True:
            pos, rot = norms(rows, scale, err)
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
            bound_scaling(bounds, q, J, ew, Jb, d)
            damped_least_squares(Jb, ew, lam, dq, G, b, x, L)
            for i in range(n):
                q_new[i] = q[i] + d[i] * dq[i]
            project(links, bounds, q_new)
            pose_errors(links, ends, q_new, T, rows, C, S, pose, frames, axes, e6, err_new)
            evaluations += 1
            E_new = energy(sw, err_new)
            if E_new < E:
                copy1(q, q_new)
                copy1(err, err_new)
                jacobian_rows(links, axes, pose, e6, rows, sw, exact, J6, A, J)
                E = E_new
                lam = max(lam * LAMBDA_DOWN, LAMBDA_MIN)
            else:
                lam *= LAMBDA_UP
            k += 1
        if not converged and max(pos, rot) < POLISH_LIMIT:
            evaluations += _end_game(
                links, ends, bounds, T, rows, sw, scale, exact, tol_p, tol_r, q, err, J,
                ew, Jb, dq, G, b, x, L, C, S, pose, frames, axes, e6, J6, A,
                q_new,
            )  # fmt: skip
            pos, rot = norms(rows, scale, err)
            converged = pos <= tol_p and rot <= tol_r
        pos, rot = norms(rows, scale, err)
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
