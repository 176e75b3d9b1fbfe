"""Small dense least squares inside kernels (no LAPACK: numba's needs SciPy).

:func:`damped_least_squares` is the step of Levenberg-Marquardt and of the
Gauss-Newton polishing of IK candidates: ``dq`` minimising
``|J dq − e|² + λ s |dq|²``, through the normal equations of the smaller side
solved by Cholesky.
"""

from __future__ import annotations

import math

from kinematica.kernels._numba import Array, kernel

__all__ = ["SCALE_FLOOR", "damped_least_squares"]

#: Mean diagonal below which the normal matrix is treated as zero (every
#: column blocked): its damping is then taken as absolute. A pivot that
#: round-off drives to or below zero is floored to it (the step is then huge
#: and an LM iteration rejects it).
SCALE_FLOOR = 1e-300


@kernel
def _cholesky_solve(G: Array, b: Array, lam: float, x: Array, L: Array) -> None:
    """Solve ``(G Gᵀ + λ s I) x = b`` for ``G (k, m)``; ``L (k, k)`` is work space."""
    k = G.shape[0]
    m = G.shape[1]
    trace = 0.0
    for i in range(k):
        for j in range(i + 1):
            t = 0.0
            for p in range(m):
                t += G[i, p] * G[j, p]
            L[i, j] = t
        trace += L[i, i]
    scale = trace / k
    damping = lam * (scale if scale > SCALE_FLOOR else 1.0)
    for j in range(k):
        t = L[j, j] + damping
        for p in range(j):
            t -= L[j, p] * L[j, p]
        d = math.sqrt(t if t > SCALE_FLOOR else SCALE_FLOOR)
        L[j, j] = d
        for i in range(j + 1, k):
            t = L[i, j]
            for p in range(j):
                t -= L[i, p] * L[j, p]
            L[i, j] = t / d
    for i in range(k):
        t = b[i]
        for p in range(i):
            t -= L[i, p] * x[p]
        x[i] = t / L[i, i]
    for i in range(k - 1, -1, -1):
        t = x[i]
        for p in range(i + 1, k):
            t -= L[p, i] * x[p]
        x[i] = t / L[i, i]


@kernel
def damped_least_squares(
    J: Array, e: Array, lam: float, dq: Array, G: Array, b: Array, x: Array, L: Array
) -> None:
    """``dq (n,)`` minimising ``|J dq − e|² + λ s |dq|²`` for ``J (r, n)``, ``e (r,)``.

    ``s`` is the mean diagonal of the normal matrix, so ``λ`` is relative.
    With ``r <= n`` (a redundant or square problem) ``dq = Jᵀ x`` with
    ``(J Jᵀ + λ s I) x = e``; otherwise ``(JᵀJ + λ s I) dq = Jᵀ e``.

    Args:
        J: ``(r, n)`` the Jacobian (rows already weighted).
        e: ``(r,)`` the error.
        lam: Damping relative to the mean diagonal of the normal matrix.
        dq: ``(n,)`` out.
        G: ``(n, r)`` work space (``Jᵀ``), used when ``r > n``.
        b: ``(max(r, n),)`` work space.
        x: ``(max(r, n),)`` work space.
        L: ``(max(r, n), max(r, n))`` work space.
    """
    r, n = J.shape
    if r <= n:
        _cholesky_solve(J, e, lam, x[:r], L[:r, :r])
        for j in range(n):
            t = 0.0
            for i in range(r):
                t += J[i, j] * x[i]
            dq[j] = t
        return
    for j in range(n):
        t = 0.0
        for i in range(r):
            G[j, i] = J[i, j]
            t += J[i, j] * e[i]
        b[j] = t
    _cholesky_solve(G, b[:n], lam, dq, L[:n, :n])
