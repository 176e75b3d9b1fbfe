"""The model the numeric search linearises: counted pose errors and their Jacobian rows.

The error of a configuration ``q`` against a target ``T`` is ``e = (Δp, Δω)``
in the base frame (:func:`kinematica.kernels.so3.pose_error`). Of its six
components the search counts those of positive weight ``w_k`` (a mask); it
minimises ``½ Σ w_k e_k²`` with the rows ``√w_k · ∂(−e_k)/∂q``: the geometric
Jacobian's, except that when only some rotation components count, ``Δω`` need
not vanish at a solution and its rows are the exact derivative
``−J_r⁻¹(Δω) J_ω``.
"""

from __future__ import annotations

import math

import numpy as np

from kinematica.kernels._numba import Array, IntArray, inline_kernel, kernel
from kinematica.kernels.fk import block_trig, walk
from kinematica.kernels.jacobian import columns
from kinematica.kernels.so3 import inverse_right_jacobian, pose_error

__all__ = ["counted", "energy", "jacobian_rows", "lm_rows", "norms", "pose_errors"]


@kernel
def counted(w: Array, rows: IntArray, sw: Array, scale: Array) -> bool:
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
def pose_errors(
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
) -> None:
    """Pose at ``q``, its joint axes, the full error ``e6 (6,)`` and the counted ``err (r,)``."""
    n = links.shape[0]
    block_trig(links, q.reshape((1, n)), 0, 1, C, S)
    walk(links, ends, False, C, S, 0, q, pose, frames, axes)
    pose_error(pose, T, e6)
    for r in range(rows.shape[0]):
        err[r] = e6[rows[r]]


@inline_kernel
def jacobian_rows(
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
    """Weighted rows ``J (r, n)`` of the counted errors, from the last :func:`pose_errors`."""
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
def norms(rows: IntArray, scale: Array, err: Array) -> tuple[float, float]:
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
def energy(sw: Array, err: Array) -> float:
    """``½ Σ w_k e_k²`` of the counted errors."""
    t = 0.0
    for r in range(err.shape[0]):
        t += (err[r] * sw[r]) ** 2
    return 0.5 * t


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
    exact = counted(w, rows, sw, np.empty(r))
    pose = np.empty((4, 4))
    axes = np.empty((n, 6))
    e6 = np.empty(6)
    C = np.empty((n, 1))
    S = np.empty((n, 1))
    frames = np.empty((0, 4, 4))
    pose_errors(links, ends, q, T, rows, C, S, pose, frames, axes, e6, err[:r])
    jacobian_rows(links, axes, pose, e6, rows, sw, exact, np.empty((6, n)), np.empty((3, 3)), J[:r])
    return r
