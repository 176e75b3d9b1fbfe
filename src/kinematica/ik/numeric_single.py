"""The Levenberg-Marquardt search of numeric IK for one target, on Python floats.

The same algorithm, step for step, as a row of
:func:`kinematica.ik.numeric_batch.search_batch` (the same constants and tests
in the same order; restarts run one after another), all on Python floats:
for one target numpy's per-call cost (about a microsecond per operation on
tiny arrays) would dominate, down to the 6x6 damped normal equations.
"""

from __future__ import annotations

import math
import weakref
from collections.abc import Sequence
from operator import mul

import numpy as np
from numpy.typing import NDArray

from kinematica.ik.numeric_model import SERIES_ANGLE
from kinematica.ik.numeric_problem import (
    LAMBDA_DOWN,
    LAMBDA_INIT,
    LAMBDA_MAX,
    LAMBDA_MIN,
    LAMBDA_UP,
    SCALE_FLOOR,
    STALL_FACTOR,
    STALL_WINDOW,
    TWO_PI,
    LMProblem,
    Sampler,
    SearchResult,
)

__all__ = ["kernel_of", "residuals_single", "search_single"]

FloatArray = NDArray[np.float64]

# The Python-float copy of a problem, built once per problem (problems are
# immutable and cached per robot by ``kinematica.ik.numeric``).
_KERNELS: weakref.WeakKeyDictionary[LMProblem, _Kernel] = weakref.WeakKeyDictionary()


class _Kernel:
    """One problem's data as Python floats, and the scalar steps on it."""

    def __init__(self, problem: LMProblem) -> None:
        chain = problem.chain
        self.chain = chain
        self.n = chain.dof
        self.revolute = (~problem.prismatic).tolist()
        self.rows = problem.rows.tolist()
        self.weight = problem.weight.tolist()
        self.weighted = problem.weighted
        self.all_rows = self.rows == [0, 1, 2, 3, 4, 5]
        self.check = problem.check.tolist()
        self.is_position = problem.is_position.tolist()
        self.orientation = problem.orientation
        self.exact = problem.exact
        self.wrap_base = problem.wrap_base.tolist()
        self.lower = problem.lower.tolist()
        self.upper = problem.upper.tolist()
        self.clamped = problem.clamped
        self.tol_position = problem.tol_position
        self.tol_angle = problem.tol_angle
        self.max_steps = problem.max_iterations
        self.wide = len(self.rows) <= self.n

    def project(self, q: list[float]) -> list[float]:
        """Wrap revolute angles into their window and clamp (see ``LMProblem.project``)."""
        out = []
        for qi, rev, base, lo, hi in zip(
            q, self.revolute, self.wrap_base, self.lower, self.upper, strict=True
        ):
            if rev:
                qi = base + (qi - base) % TWO_PI
            if qi > hi:
                qi = lo if rev and qi - hi > lo + TWO_PI - qi else hi
            out.append(lo if qi < lo else qi)
        return out

    def error6(
        self, T: list[list[float]], p_t: list[float], R_t: list[list[float]] | None
    ) -> list[float]:
        """All six error components ``(Δp, Δω)`` of a tool pose ``T`` (rows of 4x4)."""
        (x0, y0, z0, p0), (x1, y1, z1, p1), (x2, y2, z2, p2) = T[0], T[1], T[2]
        e = [p_t[0] - p0, p_t[1] - p1, p_t[2] - p2, 0.0, 0.0, 0.0]
        if R_t is not None and self.orientation:
            # M = R_t · Rᵀ, R's rows being (x_i, y_i, z_i).
            rows_c = ((x0, y0, z0), (x1, y1, z1), (x2, y2, z2))
            M = [[ti[0] * c[0] + ti[1] * c[1] + ti[2] * c[2] for c in rows_c] for ti in R_t]
            e[3:] = _rotvec(M)
        return e

    def error(
        self, T: list[list[float]], p_t: list[float], R_t: list[list[float]] | None
    ) -> list[float]:
        """Counted error components (unweighted) of a tool pose ``T`` (rows of 4x4)."""
        e = self.error6(T, p_t, R_t)
        return e if self.all_rows else [e[r] for r in self.rows]

    def evaluate(
        self, q: list[float], p_t: list[float], R_t: list[list[float]] | None
    ) -> tuple[list[float], list[Sequence[float]]]:
        """Counted errors ``(m,)`` (unweighted) and weighted Jacobian rows ``(m, n)``."""
        axes: list[tuple[float, ...]] = []
        T = self.chain.pose_rows(q, axes)
        p0, p1, p2 = T[0][3], T[1][3], T[2][3]

        # Geometric Jacobian columns: [z × (p − o); z] (revolute), [z; 0] (prismatic).
        cols: list[tuple[float, float, float, float, float, float]] = []
        for rev, (a0, a1, a2, o0, o1, o2) in zip(self.revolute, axes, strict=True):
            if rev:
                d0, d1, d2 = p0 - o0, p1 - o1, p2 - o2
                cols.append((a1 * d2 - a2 * d1, a2 * d0 - a0 * d2, a0 * d1 - a1 * d0, a0, a1, a2))
            else:
                cols.append((a0, a1, a2, 0.0, 0.0, 0.0))
        e = self.error6(T, p_t, R_t)
        if self.exact and R_t is not None:
            # Only some rotation components count: their rows are J_r⁻¹(Δω) J_ω.
            (a00, a01, a02), (a10, a11, a12), (a20, a21, a22) = _inverse_right_jacobian(e[3:])
            cols = [
                (
                    c0,
                    c1,
                    c2,
                    a00 * w0 + a01 * w1 + a02 * w2,
                    a10 * w0 + a11 * w1 + a12 * w2,
                    a20 * w0 + a21 * w1 + a22 * w2,
                )
                for c0, c1, c2, w0, w1, w2 in cols
            ]
        J: list[Sequence[float]] = list(zip(*cols, strict=True))
        if not self.all_rows:
            J = [J[r] for r in self.rows]
            e = [e[r] for r in self.rows]
        if self.weighted:
            J = [[w * v for v in row] for row, w in zip(J, self.weight, strict=True)]
        return e, J

    def residuals(self, err: list[float]) -> tuple[float, float]:
        """Position and rotation norms of ``err``, each component scaled by ``check``."""
        pos = rot = 0.0
        for v, c, is_pos in zip(err, self.check, self.is_position, strict=True):
            if is_pos:
                pos += (v * c) ** 2
            else:
                rot += (v * c) ** 2
        return math.sqrt(pos), math.sqrt(rot)

    def score(self, err: list[float]) -> float:
        """Worst scaled error norm relative to its tolerance (≤ 1: converged)."""
        pos, rot = self.residuals(err)
        return max(pos / self.tol_position, rot / self.tol_angle)

    def attempt(
        self, q0: list[float], p_t: list[float], R_t: list[list[float]] | None
    ) -> tuple[list[float], bool, int, list[float]]:
        """One LM attempt from ``q0``, exactly as a row of ``search_batch`` runs.

        Returns:
            ``(q, converged, evaluations, error)``.
        """
        tol_p, tol_a, weight = self.tol_position, self.tol_angle, self.weight
        q = self.project(q0)
        err, J = self.evaluate(q, p_t, R_t)
        E = E_ref = 0.5 * sum((v * w) ** 2 for v, w in zip(err, weight, strict=True))
        lam = LAMBDA_INIT
        k = 0
        while True:
            pos, rot = self.residuals(err)
            if pos <= tol_p and rot <= tol_a:
                return q, True, k + 1, err
            window = k > 0 and k % STALL_WINDOW == 0
            if (window and STALL_FACTOR * E_ref < E) or lam > LAMBDA_MAX or k >= self.max_steps:
                return q, False, k + 1, err
            if window:
                E_ref = E
            dq = self.step(J, err, lam, q)
            q_new = self.project([qi + di for qi, di in zip(q, dq, strict=True)])
            err_new, J_new = self.evaluate(q_new, p_t, R_t)
            E_new = 0.5 * sum((v * w) ** 2 for v, w in zip(err_new, weight, strict=True))
            if E_new < E:
                q, err, J, E = q_new, err_new, J_new, E_new
                lam = max(lam * LAMBDA_DOWN, LAMBDA_MIN)
            else:
                lam *= LAMBDA_UP
            k += 1

    def step(
        self, J: list[Sequence[float]], err: list[float], lam: float, q: list[float]
    ) -> list[float]:
        """One damped least-squares step, with the binding joints blocked.

        Joints held at a limit they would leave outwards are blocked, as in
        ``numeric_batch._step``; the normal equations are those of
        ``numeric_batch._damped_solve``, solved by Cholesky on Python floats
        (for a 6x6 system this beats a numpy call's overhead).
        """
        ew = [v * w for v, w in zip(err, self.weight, strict=True)]
        if self.clamped:
            blocked = set()
            for i, (qi, lo, hi) in enumerate(zip(q, self.lower, self.upper, strict=True)):
                if qi <= lo or qi >= hi:
                    g = sum(row[i] * e for row, e in zip(J, ew, strict=True))
                    if (qi <= lo and g < 0.0) or (qi >= hi and g > 0.0):
                        blocked.add(i)
            if blocked:
                J = [[0.0 if i in blocked else v for i, v in enumerate(row)] for row in J]
        if self.wide:  # (J Jᵀ + λ s I) x = e, dq = Jᵀ x
            x = _damped_cholesky(J, ew, lam)
            return [sum(map(mul, col, x)) for col in zip(*J, strict=True)]
        cols = list(zip(*J, strict=True))  # (JᵀJ + λ s I) dq = Jᵀ e
        return _damped_cholesky(cols, [sum(map(mul, col, ew)) for col in cols], lam)


def _damped_cholesky(G: Sequence[Sequence[float]], b: list[float], lam: float) -> list[float]:
    """Solve ``(G Gᵀ + λ s I) x = b`` by Cholesky, ``s`` the mean diagonal of ``G Gᵀ``.

    A pivot that round-off drives to zero or below is floored as in
    ``numeric_batch._cholesky_solve``: the step is then huge and rejected.
    """
    k = len(G)
    L = [[0.0] * k for _ in range(k)]
    trace = 0.0
    for i, gi in enumerate(G):
        Li = L[i]
        for j in range(i):
            Li[j] = sum(map(mul, gi, G[j]))
        Li[i] = d = sum(map(mul, gi, gi))
        trace += d
    scale = trace / k
    damping = lam * (scale if scale > SCALE_FLOOR else 1.0)
    for j in range(k):
        Lj = L[j]
        t = Lj[j] + damping
        for p in range(j):
            t -= Lj[p] * Lj[p]
        Lj[j] = d = math.sqrt(t if t > SCALE_FLOOR else SCALE_FLOOR)
        for i in range(j + 1, k):
            Li = L[i]
            t = Li[j]
            for p in range(j):
                t -= Li[p] * Lj[p]
            Li[j] = t / d
    y = [0.0] * k
    for i in range(k):
        Li = L[i]
        t = b[i]
        for p in range(i):
            t -= Li[p] * y[p]
        y[i] = t / Li[i]
    x = [0.0] * k
    for i in range(k - 1, -1, -1):
        t = y[i]
        for p in range(i + 1, k):
            t -= L[p][i] * x[p]
        x[i] = t / L[i][i]
    return x


def _inverse_right_jacobian(phi: list[float]) -> list[list[float]]:
    """``J_r⁻¹(φ)`` of SO(3) (see ``numeric_batch._inverse_right_jacobian``)."""
    x, y, z = phi
    th2 = x * x + y * y + z * z
    half = 0.5 * math.sqrt(th2)
    if half < 0.5 * SERIES_ANGLE:
        alpha = 1.0 - th2 / 12.0 - th2 * th2 / 720.0
        c = 1.0 / 12.0 + th2 / 720.0 + th2 * th2 / 30240.0
    else:
        alpha = half / math.tan(half)
        c = (1.0 - alpha) / th2
    hx, hy, hz = 0.5 * x, 0.5 * y, 0.5 * z
    return [
        [alpha + c * x * x, c * x * y - hz, c * x * z + hy],
        [c * y * x + hz, alpha + c * y * y, c * y * z - hx],
        [c * z * x - hy, c * z * y + hx, alpha + c * z * z],
    ]


def _rotvec(M: list[list[float]]) -> list[float]:
    """Rotation vector of a rotation matrix (see ``numeric_batch._rotvec``)."""
    v0 = 0.5 * (M[2][1] - M[1][2])
    v1 = 0.5 * (M[0][2] - M[2][0])
    v2 = 0.5 * (M[1][0] - M[0][1])
    sin = math.sqrt(v0 * v0 + v1 * v1 + v2 * v2)
    cos = 0.5 * (M[0][0] + M[1][1] + M[2][2] - 1.0)
    angle = math.atan2(sin, cos)
    if cos >= 0.0:
        ratio = angle / sin if sin > 0.0 else 1.0
        return [v0 * ratio, v1 * ratio, v2 * ratio]
    # Near π: the axis from the column of the symmetric part with the largest
    # diagonal, (M + Mᵀ)/2 − cos θ I = (1 − cos θ) n nᵀ; its sign follows v.
    S = [[0.5 * (M[i][j] + M[j][i]) - (cos if i == j else 0.0) for j in range(3)] for i in range(3)]
    col = max(range(3), key=lambda i: S[i][i])
    n = [S[0][col], S[1][col], S[2][col]]
    norm = math.sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2])
    if n[0] * v0 + n[1] * v1 + n[2] * v2 < 0.0:
        norm = -norm
    return [n[0] / norm * angle, n[1] / norm * angle, n[2] / norm * angle]


def search_single(
    problem: LMProblem,
    p_target: FloatArray,
    R_target: FloatArray | None,
    start: FloatArray,
    restarts: int,
    sample: Sampler,
) -> SearchResult:
    """Search one target: attempts one after another, restarting failed ones.

    Args:
        problem: The problem.
        p_target: ``(3,)`` target position (base frame, m).
        R_target: ``(3, 3)`` target rotation, or None for a position target.
        start: ``(n,)`` first guess.
        restarts: Random restarts allowed.
        sample: Draws restart configurations.

    Returns:
        The result, as a batch of one.
    """
    kernel = kernel_of(problem)
    p_t = p_target.tolist()
    R_t = None if R_target is None else R_target.tolist()
    best_q = kernel.project(start.tolist())
    best_score = math.inf
    iterations = attempts = 0
    ok = False
    guess = best_q
    for attempt in range(restarts + 1):
        if attempt:
            guess = sample(1)[0].tolist()
        attempts += 1
        q, ok, steps, err = kernel.attempt(guess, p_t, R_t)
        iterations += steps
        s = kernel.score(err)
        if ok or s < best_score:
            best_q, best_score = q, s
        if ok:
            break
    return SearchResult(
        q=np.array([best_q]),
        converged=np.array([ok]),
        iterations=np.array([iterations], dtype=np.int64),
        attempts=np.array([attempts], dtype=np.int64),
    )


def kernel_of(problem: LMProblem) -> _Kernel:
    """The problem's Python-float kernel, built once."""
    kernel = _KERNELS.get(problem)
    if kernel is None:
        kernel = _KERNELS[problem] = _Kernel(problem)
    return kernel


def residuals_single(
    problem: LMProblem, T: FloatArray, p_target: FloatArray, R_target: FloatArray | None
) -> tuple[float, float]:
    """Scaled position and rotation residuals of one tool pose ``T (4, 4)``."""
    kernel = kernel_of(problem)
    R_t = None if R_target is None else R_target.tolist()
    return kernel.residuals(kernel.error(T[:3].tolist(), p_target.tolist(), R_t))
