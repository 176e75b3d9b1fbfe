"""Closed-form IK of planar arms and the SCARA, one target: every branch.

Every revolute axis of these arms is parallel to one direction ``k``; the slide
of the PR / PRR arms moves across ``k``, the SCARA's slide along it. In the
plane normal to ``k`` (coordinates on ``e1``, ``e2 = k × e1``; angles
counter-clockwise seen from the side ``k`` points to) a revolute joint turns
everything after it by ± its angle, so the problem is planar. It is written on
the joint axes at q = 0 (product of exponentials), so any base, tool, offset
and DH convention is the same problem: up to three revolute joints, an
optional slide across ``k`` before them, an optional slide along ``k`` (it
commutes with the rest and takes the height).

* Pose targets: the orientation gives the total turn ``φ`` (the sum of the
  revolute turns) and pins the last revolute axis at ``w = p + R w_tool``; the
  joints before it take that axis to ``w``: a 2R triangle (3R, SCARA: two
  branches), a slide and a link (PRR: two), one link (2R: one solution), the
  slide alone (PR: one). The last turn is ``φ`` minus the others.
* Position targets: the joints take the tool origin to the target (2R, PR:
  two branches). An arm with a third joint in the plane (3R, PRR, SCARA) has
  a continuum: its last revolute joint is free (``singular``); its
  representative turn is the first, from the middle of its range outwards,
  that puts a candidate within the joint limits (see :func:`_free_last`).

Candidates are never withheld: out of reach each subproblem gives its
least-squares configuration (the triangle stretched or folded towards the
target, the link across the slide) for the check to judge by forward
kinematics, and ``gap`` is the exact distance from the target position to the
reachable set of the tool origin. Triangles are solved by half-angle formulas
that stay accurate at the folds, ``4 L1 L2 sin²(ψ/2) = (L1 + L2 − r)(L1 + L2 + r)``
and ``4 L1 L2 cos²(ψ/2) = (r − |L1 − L2|)(r + |L1 − L2|)``: a target 1e-9 m
from the first axis of a folded triangle with equal links keeps both
solutions. On that axis itself every first turn solves it (``singular``, that
joint free, and the last one for pose targets: it turns with it). No
quantity that grows with the target is squared: a target at 1e300 m gives
finite candidates and its gap.

An arm is of its class when its axes are parallel (or normal) within the
classification's tolerance; the kernel solves the ideal arm. When the real
one differs from it by more than round-off (``P_SLACK``: its axes' tilts
times the arm's size), the gap shrinks by that much, the ideal arm's
continua (which the real one may not have) get ``INFO_NEAR`` (a miss there
is no proof), and slides put beyond a limit by less than it go onto the
limit. ``INFO_NEAR`` also marks targets where two branches merge
(``MERGE_TOL``).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from kinematica.kernels._numba import Array, batch_kernel, kernel
from kinematica.kernels.ik_check import INFO_FREE, INFO_GAP, INFO_NEAR, INFO_SINGULAR
from kinematica.kernels.solvers.planar_free import free_last
from kinematica.kernels.solvers.planar_params import (
    P_AXIS,
    P_E1,
    P_E2,
    P_K,
    P_LENGTH,
    P_LIFT,
    P_LIFT_TILT,
    P_NREV,
    P_ORIGIN,
    P_POSE,
    P_QLIM,
    P_RE1,
    P_REACH,
    P_REV,
    P_RMAX,
    P_RMIN,
    P_SLACK,
    P_SLIDE,
    P_SLIDE_TILT,
    P_TIP,
    P_TOOL,
    P_U,
    P_WRIST,
)
from kinematica.kernels.solvers.planar_place import emit, place
from kinematica.kernels.solvers.triangle import FOLD, NEAR, SINGULAR_TOL

__all__ = ["solve", "solve_batch"]


@kernel
def _gap(params: Array, x: float, y: float, dz: float) -> float:
    """Distance (m) from the target position to the reachable set of the tool origin.

    ``x, y``: plane coordinates of the target; ``dz``: its height over the plane.
    """
    ax = x - params[P_AXIS]
    ay = y - params[P_AXIS + 1]
    if params[P_SLIDE] >= 0.0:
        across = abs(ay * params[P_U] - ax * params[P_U + 1])
        radial = max(across - params[P_RMAX], 0.0)
    else:
        r = math.hypot(ax, ay)
        radial = max(r - params[P_RMAX], params[P_RMIN] - r, 0.0)
    height = 0.0 if params[P_LIFT] >= 0.0 else dz
    return math.hypot(height, radial)


@kernel
def _dot(params: Array, at: int, x: float, y: float, z: float) -> float:
    """``params[at:at + 3] · (x, y, z)``."""
    return params[at] * x + params[at + 1] * y + params[at + 2] * z


@kernel
def _rotated_dot(params: Array, at: int, T: Array, v: int) -> float:
    """``params[at:at + 3] · (R params[v:v + 3])`` with ``R`` the rotation of ``T``."""
    s = 0.0
    for i in range(3):
        s += params[at + i] * (
            T[i, 0] * params[v] + T[i, 1] * params[v + 1] + T[i, 2] * params[v + 2]
        )
    return s


@kernel
def _snap_slides(params: Array, Q: Array, slack: float) -> None:
    """Slides that the ideal arm puts beyond a limit by less than ``slack`` (m) go onto it.

    The real arm's slide is uncertain by that much; the check judges the result.
    """
    for j in (int(params[P_SLIDE]), int(params[P_LIFT])):
        if j < 0:
            continue
        lo = params[P_QLIM + 2 * j]
        hi = params[P_QLIM + 2 * j + 1]
        for row in range(Q.shape[0]):
            v = Q[row, j]
            if lo - slack <= v < lo:
                Q[row, j] = lo
            elif hi < v <= hi + slack:
                Q[row, j] = hi


@kernel
def solve(params: Array, T: Array, Q: Array, info: Array) -> None:
    """Candidates of one target of a planar arm or a SCARA (see the module docstring).

    Args:
        params: ``(P_SIZE,)`` the arm (``P_*``).
        T: ``(4, 4)`` target pose of the tool (base frame); for position
            targets only its translation is read.
        Q: ``(2, n)`` out: candidates, slot 0 and 1 the two branches (labels
            in the builder); NaN rows where a branch has no candidate.
        info: ``(INFO_FREE + n,)`` out (zero on entry): ``INFO_SINGULAR`` and
            the free joints on a continuum, ``INFO_GAP``.
    """
    Q[:, :] = np.nan
    br = np.zeros((2, 4))  # a subproblem's branches: slide (m), then revolute turns (rad)
    tri = np.empty((2, 2))
    pose = params[P_POSE] != 0.0
    nrev = int(params[P_NREV])
    last = nrev - 1
    ox = T[0, 3] - params[P_ORIGIN]
    oy = T[1, 3] - params[P_ORIGIN + 1]
    oz = T[2, 3] - params[P_ORIGIN + 2]
    x = _dot(params, P_E1, ox, oy, oz)
    y = _dot(params, P_E2, ox, oy, oz)
    dz = _dot(
        params,
        P_K,
        T[0, 3] - params[P_TOOL],
        T[1, 3] - params[P_TOOL + 1],
        T[2, 3] - params[P_TOOL + 2],
    )
    # The arm's axes are parallel (or normal) to k within the classification's
    # tolerance: the ideal arm solved here may put the tool up to `slack` away
    # from the real one. Beyond round-off, a gap shrinks by it.
    slack = params[P_SLACK] + params[P_SLIDE_TILT] * (
        math.hypot(math.hypot(ox, oy), oz) + params[P_LENGTH]
    )
    slack += params[P_LIFT_TILT] * (abs(dz) + params[P_LENGTH])
    gap = _gap(params, x, y, dz)
    approximate = slack > SINGULAR_TOL * params[P_REACH]
    if approximate:
        gap -= slack
    info[INFO_GAP] = gap if gap > SINGULAR_TOL * params[P_REACH] else np.nan  # beyond round-off
    if pose:  # the orientation: the total turn, and where the last revolute axis goes
        phi = math.atan2(_rotated_dot(params, P_E2, T, P_RE1), _rotated_dot(params, P_E1, T, P_RE1))
        for i in range(3):
            w = T[i, 0] * params[P_WRIST] + T[i, 1] * params[P_WRIST + 1]
            w += T[i, 2] * params[P_WRIST + 2]
            if i == 0:
                ox += w
            elif i == 1:
                oy += w
            else:
                oz += w
        code = place(
            params,
            last,
            _dot(params, P_E1, ox, oy, oz),
            _dot(params, P_E2, ox, oy, oz),
            params[P_AXIS + 2 * last],
            params[P_AXIS + 2 * last + 1],
            br,
            tri,
        )
        emit(params, br, last, phi, True, dz, Q)
        if code == FOLD:  # the last joint turns with the first
            info[INFO_FREE + int(params[P_REV + last])] = 1.0
    elif nrev + (1 if params[P_SLIDE] >= 0.0 else 0) == 3:
        code = free_last(params, x, y, dz, br, tri, Q, info)
    else:
        code = place(params, nrev, x, y, params[P_TIP], params[P_TIP + 1], br, tri)
        emit(params, br, nrev, 0.0, False, dz, Q)
    if code == FOLD:
        info[INFO_SINGULAR] = 1.0
        info[INFO_FREE + int(params[P_REV])] = 1.0
    # Merging branches, or a continuum of the ideal arm that the real one may
    # not have (its axes parallel within tolerance only): a miss is no proof.
    if code == NEAR or (approximate and info[INFO_SINGULAR] != 0.0):
        info[INFO_NEAR] = 1.0
    if approximate:
        _snap_slides(params, Q, slack)


@batch_kernel
def solve_batch(params: Array, T: Array, Q: Array, info: Array) -> None:
    """:func:`solve` for targets ``T (N, 4, 4)`` in parallel; ``Q``, ``info`` gain an ``N`` axis."""
    for i in numba.prange(T.shape[0]):
        solve(params, T[i], Q[i], info[i])
