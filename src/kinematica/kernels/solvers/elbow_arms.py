"""Closed-form IK of 3R elbow arms (anthropomorphic, or with a shoulder offset), one target.

Axis 1 (``h1``) is perpendicular to axes 2 and 3, which are parallel
(direction ``k``). As a product of exponentials on the axes at q = 0,
``T(q) = E1(q1) E2(q2) E3(q3) M``: turns about axes parallel to ``k`` keep
heights along ``k`` and compose into one turn ``φ = d2 + d3`` about ``k``.

* Position targets (the tool origin ``p``): ``k · Rot(h1, −q1)(p − p1)``
  must equal the tool's height ``k · (x − p1)``, an equation
  ``A cos θ + B sin θ = e`` in ``θ = −q1`` (two roots, as in the lecture notes'
  ``q1 = atan2(py, px)`` and ``q1 + π``); then the arm's plane holds a 2R
  triangle (two roots each, the lecture notes' ``cos q3 = (r² − a2² − a3²)/(2 a2 a3)``),
  solved as in :func:`kinematica.kernels.solvers.triangle.two_link`. Up to
  four solutions. A target on axis 1 with the tool's height 0 leaves q1 free
  (``singular``: representatives at q1 = 0 and π); on the shoulder with
  equal links, q2 is free.
* Pose targets: a 3R arm has one solution per reachable pose, and the
  orientation alone fixes it where the position cannot (on axis 1, at the
  fold): ``Rot(h1, q1) k = R Mᵀ k`` gives q1 (``k`` is not on axis 1),
  ``Rot(h1, −q1) R Mᵀ = Rot(k, φ)`` gives ``φ``, and then
  ``Rot(d2) a = t − Rot(φ) b`` in the arm's plane gives ``d2``. The candidate
  takes the slot of its branch; the check judges the whole pose.

Out of reach the candidates are least-squares ones (the height equation's
nearest root, the triangle stretched or folded towards the target) and
``gap`` is a proven lower bound of the distance to the reachable positions:
the height equation's miss, and the tool's distance from the foot of the
common normal of axes 1 and 2 against the range it can take. ``INFO_NEAR``
marks targets where two roots merge (``MERGE_TOL``), or q1 is uncertain
(the target that close to axis 1), and continua of an arm whose axes 2 and 3
are parallel within tolerance only (``P_SLACK``; the gap shrinks by it).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from kinematica.kernels._numba import Array, batch_kernel, kernel
from kinematica.kernels.geometry import rotate, subproblem1, trig_linear
from kinematica.kernels.ik_check import INFO_FREE, INFO_GAP, INFO_NEAR, INFO_SINGULAR
from kinematica.kernels.solvers.triangle import (
    FOLD,
    MERGE_TOL,
    NEAR,
    SINGULAR_TOL,
    turn,
    two_link,
)

__all__ = [
    "P_A",
    "P_B",
    "P_E1",
    "P_E2",
    "P_FOOT",
    "P_H1",
    "P_HEIGHT",
    "P_HK",
    "P_K",
    "P_OFFSET",
    "P_P1",
    "P_P2",
    "P_POSE",
    "P_RE1",
    "P_RK",
    "P_RMAX",
    "P_RMIN",
    "P_S2",
    "P_S3",
    "P_SCALE",
    "P_SIZE",
    "P_SLACK",
    "P_UP",
    "solve",
    "solve_batch",
]

# Parameters (a flat array packed by kinematica.ik.analytic.elbow_arms).
P_POSE = 0  # 1.0: pose targets, 0.0: position targets (tool origin)
P_H1 = 1  # (3,) axis 1 direction (unit, base frame)
P_P1 = 4  # (3,) a point on axis 1 (m)
P_K = 7  # (3,) axes 2 and 3 direction k (unit)
P_E1 = 10  # (3,) basis e1 of the plane normal to k
P_E2 = 13  # (3,) e2 = k × e1
P_HK = 16  # (3,) h1 × k
P_P2 = 19  # (3,) a point on axis 2 (m)
P_A = 22  # (2,) link 2, axis 2 to axis 3 at q = 0, plane coordinates (m)
P_B = 24  # (2,) link 3, axis 3 to the tool origin at q = 0, plane coordinates (m)
P_UP = 26  # (2,) h1 × k in plane coordinates: the side elbow "up" refers to
P_S2 = 28  # k · (axis 2 direction): +1 or -1
P_S3 = 29  # k · (axis 3 direction): +1 or -1
P_HEIGHT = 30  # k · (x − p1): the tool's height along k over axis 1 (m)
P_RK = 31  # (3,) R_Mᵀ k (M = fk(0): the tool pose at q = 0)
P_RE1 = 34  # (3,) R_Mᵀ e1
P_FOOT = 37  # (3,) foot on axis 1 of the common normal of axes 1 and 2 (m)
P_OFFSET = 40  # length of that common normal (m)
P_RMIN = 41  # least distance of the tool origin from the normal's foot on axis 2 (m)
P_RMAX = 42  # largest such distance (m)
P_SCALE = 43  # size of the arm (m): the scale of SINGULAR_TOL
P_SLACK = 44  # how far axis 3's tilt off k may put the tool from the ideal arm's (m)
P_SIZE = 45


@kernel
def _dot(params: Array, at: int, v: Array) -> float:
    """``params[at:at + 3] · v``."""
    return params[at] * v[0] + params[at + 1] * v[1] + params[at + 2] * v[2]


@kernel
def _place(params: Array, theta: float, v: Array, u: Array, t: Array) -> float:
    """Turn ``v = p − p1`` by ``θ = −q1`` about axis 1: ``u (3,)`` out, plane target ``t (2,)``.

    ``t`` is the tool's target in the arm's plane relative to axis 2.

    Returns:
        ``σ = u · (h1 × k)``: which side of axis 1 the target is on (the shoulder branch).
    """
    rotate(params[P_H1 : P_H1 + 3], math.cos(theta), math.sin(theta), v, u)
    t[0] = 0.0
    t[1] = 0.0
    for i in range(3):
        w = u[i] + params[P_P1 + i] - params[P_P2 + i]
        t[0] += params[P_E1 + i] * w
        t[1] += params[P_E2 + i] * w
    return _dot(params, P_HK, u)


@kernel
def _elbow_up_first(params: Array, t: Array) -> bool:
    """True when elbow up is the triangle's branch ψ <= 0 (the target on the h1 side)."""
    return t[0] * params[P_UP] + t[1] * params[P_UP + 1] >= 0.0


@kernel
def _height(params: Array, v: Array, abe: Array) -> None:
    """``A, B, e`` of ``A cos θ + B sin θ = e``: the height of ``Rot(h1, θ) v`` along ``k``."""
    kh = _dot(params, P_K, params[P_H1 : P_H1 + 3])
    hv = _dot(params, P_H1, v)
    abe[0] = _dot(params, P_K, v) - kh * hv
    abe[1] = -_dot(params, P_HK, v)  # k · (h1 × v)
    abe[2] = params[P_HEIGHT] - kh * hv


@kernel
def _position(params: Array, v: Array, abe: Array, Q: Array, info: Array) -> None:
    """The four candidates of the tool origin at ``p = p1 + v`` (``abe``: :func:`_height`)."""
    u = np.empty(3)
    t = np.empty(2)
    roots = np.empty(2)
    br = np.empty((2, 2))
    A = abe[0]
    B = abe[1]
    e = abe[2]
    rho = math.hypot(A, B)
    tol = SINGULAR_TOL * params[P_SCALE]
    if rho <= tol:  # on axis 1: any q1 or none
        roots[0] = 0.0
        roots[1] = math.pi
        if abs(e) <= tol:
            info[INFO_SINGULAR] = 1.0
            info[INFO_FREE] = 1.0
    else:  # least-squares roots when out of reach
        trig_linear(A / rho, B / rho, e / rho, roots)
        c = e / rho  # the roots merge where |c| -> 1; q1 is uncertain where rho -> 0
        if (1.0 - c) * (1.0 + c) < MERGE_TOL * MERGE_TOL or rho < MERGE_TOL * params[P_SCALE]:
            info[INFO_NEAR] = 1.0
    sigma0 = _place(params, roots[0], v, u, t)
    sigma1 = _place(params, roots[1], v, u, t)
    first = 0 if sigma0 >= sigma1 else 1  # the shoulder-right root
    for shoulder in range(2):
        theta = roots[first] if shoulder == 0 else roots[1 - first]
        _place(params, theta, v, u, t)
        code = two_link(params[P_A], params[P_A + 1], params[P_B], params[P_B + 1], t[0], t[1], br)
        if code == FOLD:
            info[INFO_SINGULAR] = 1.0
            info[INFO_FREE + 1] = 1.0
        elif code == NEAR:
            info[INFO_NEAR] = 1.0
        up_first = _elbow_up_first(params, t)
        for row in range(2):
            elbow = row if up_first else 1 - row
            slot = 2 * shoulder + elbow
            Q[slot, 0] = -theta
            Q[slot, 1] = params[P_S2] * br[row, 0]
            Q[slot, 2] = params[P_S3] * br[row, 1]


@kernel
def _pose(params: Array, T: Array, v: Array, Q: Array) -> None:
    """The one candidate of pose ``T``, in the slot of its branch (``v = p − p1``)."""
    kt = np.empty(3)
    f = np.empty(3)
    g = np.empty(3)
    u = np.empty(3)
    t = np.empty(2)
    for i in range(3):
        kt[i] = T[i, 0] * params[P_RK] + T[i, 1] * params[P_RK + 1] + T[i, 2] * params[P_RK + 2]
        f[i] = T[i, 0] * params[P_RE1] + T[i, 1] * params[P_RE1 + 1] + T[i, 2] * params[P_RE1 + 2]
    q1 = subproblem1(params[P_K : P_K + 3], kt, params[P_H1 : P_H1 + 3])
    rotate(params[P_H1 : P_H1 + 3], math.cos(q1), -math.sin(q1), f, g)
    phi = math.atan2(_dot(params, P_E2, g), _dot(params, P_E1, g))
    sigma = _place(params, -q1, v, u, t)
    c = math.cos(phi)
    s = math.sin(phi)
    bx = params[P_B]
    by = params[P_B + 1]
    d2 = turn(params[P_A], params[P_A + 1], t[0] - (c * bx - s * by), t[1] - (s * bx + c * by))
    d3 = phi - d2
    psi = turn(params[P_A], params[P_A + 1], bx, by) + d3  # link 3 relative to link 2
    up = (math.sin(psi) <= 0.0) == _elbow_up_first(params, t)
    slot = (0 if sigma >= 0.0 else 2) + (0 if up else 1)
    Q[slot, 0] = q1
    Q[slot, 1] = params[P_S2] * d2
    Q[slot, 2] = params[P_S3] * d3


@kernel
def solve(params: Array, T: Array, Q: Array, info: Array) -> None:
    """Candidates of one target of a 3R elbow arm (see the module docstring).

    Args:
        params: ``(P_SIZE,)`` the arm (``P_*``).
        T: ``(4, 4)`` target pose of the tool (base frame); for position
            targets only its translation is read.
        Q: ``(4, 3)`` out: slots shoulder right/left x elbow up/down; NaN
            rows where a branch has no candidate.
        info: ``(INFO_FREE + 3,)`` out (zero on entry): ``INFO_SINGULAR`` and
            the free joints on a continuum, ``INFO_NEAR`` where branches merge
            (``MERGE_TOL``), ``INFO_GAP``.
    """
    Q[:, :] = np.nan
    v = np.empty(3)
    for i in range(3):
        v[i] = T[i, 3] - params[P_P1 + i]
    abe = np.empty(3)
    _height(params, v, abe)
    if params[P_POSE] != 0.0:
        _pose(params, T, v, Q)
    else:
        _position(params, v, abe, Q, info)
    miss = abs(abe[2]) - math.hypot(abe[0], abe[1])  # the height equation's, a distance
    dx = T[0, 3] - params[P_FOOT]
    dy = T[1, 3] - params[P_FOOT + 1]
    dz = T[2, 3] - params[P_FOOT + 2]
    r = math.hypot(math.hypot(dx, dy), dz)
    a = params[P_OFFSET]
    gap = max(miss, r - a - params[P_RMAX], params[P_RMIN] - a - r, 0.0)
    if params[P_SLACK] > SINGULAR_TOL * params[P_SCALE]:  # axes 2 and 3 not exactly parallel
        gap -= params[P_SLACK]
        if info[INFO_SINGULAR] != 0.0:  # a continuum of the ideal arm: a miss is no proof
            info[INFO_NEAR] = 1.0
    info[INFO_GAP] = gap if gap > SINGULAR_TOL * params[P_SCALE] else np.nan  # beyond round-off


@batch_kernel
def solve_batch(params: Array, T: Array, Q: Array, info: Array) -> None:
    """:func:`solve` for targets ``T (N, 4, 4)`` in parallel; ``Q``, ``info`` gain an ``N`` axis."""
    for i in numba.prange(T.shape[0]):
        solve(params, T[i], Q[i], info[i])
