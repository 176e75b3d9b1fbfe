"""Spherical-wrist arms (6R, and RRP of the Stanford type): the builder of their kernel.

The kernel (:mod:`kinematica.kernels.solvers.spherical_wrist`) places the wrist
centre by joints 1-3 (any first three axes: meeting, parallel or skew
shoulders; the last needs Pieper's quartic) and solves the wrist for the
rotation left over; this module reads the geometry from the joint axes once
per arm and packs it.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from kinematica.dh import DHChain
from kinematica.ik.analytic.arm_point import (
    GEOMETRY_TOL,
    arm_geometry,
    places_point,
    unit_normal,
)
from kinematica.ik.registry import ClosedForm, SolverSpec, TargetKind
from kinematica.ik.structure import Features
from kinematica.kernels import fk
from kinematica.kernels.solvers import decoupled
from kinematica.kernels.solvers import spherical_wrist as wrist_kernel

__all__ = ["SPECS", "build", "wrist_params"]

FloatArray = NDArray[np.float64]


def wrist_params(
    params: FloatArray, h4: FloatArray, h5: FloatArray, h6: FloatArray, R_home: FloatArray
) -> bool:
    """Write the wrist's parameters into ``params (W_SIZE,)``; False for no 3-DOF wrist.

    Args:
        params: The solver's parameters, written from ``W_LH`` on.
        h4: ``(3,)`` unit axis 4 at q = 0 (base frame); ``h5``, ``h6`` likewise.
        h5: See ``h4``.
        h6: See ``h4``.
        R_home: ``(3, 3)`` the tool's rotation at q = 0.
    """
    k45 = float(h4 @ h5)
    ea = h5 - k45 * h4
    s45 = float(np.linalg.norm(ea))
    if s45 < GEOMETRY_TOL or np.linalg.norm(np.cross(h5, h6)) < GEOMETRY_TOL:
        return False  # consecutive wrist axes coincide: no 3-DOF wrist
    ea = ea / s45
    eb = np.cross(h4, ea)
    F = np.stack([h4, ea, eb])  # rows: the frame (h4, ea, eb)
    x6 = unit_normal(h6)
    k56 = float(h5 @ h6)
    # "no-flip" bends the wrist as at q = 0 (the sign of γ there), or as q5 > 0
    # bends it from there when γ = 0 at q = 0 (h6 in the plane of h4 and h5,
    # e.g. aligned with h4): (h4 × h5)ᵀ R5(ε) h6 ≈ ε (k45 k56 - h4ᵀh6)
    home = float(np.cross(h4, h5) @ h6)
    bend = k45 * k56 - float(h4 @ h6)
    vectors = {
        wrist_kernel.W_LH: R_home.T @ h6,
        wrist_kernel.W_LX: R_home.T @ x6,
        wrist_kernel.W_H4: h4,
        wrist_kernel.W_H5: h5,
        wrist_kernel.W_H6: h6,
        wrist_kernel.W_X6: x6,
        wrist_kernel.W_Y6: np.cross(h6, x6),
        wrist_kernel.W_EA: ea,
        wrist_kernel.W_EB: eb,
        wrist_kernel.W_N56: F @ np.cross(h5, h6),
        wrist_kernel.W_H6F: F @ h6,
    }
    for o, v in vectors.items():
        params[o : o + 3] = v
    params[wrist_kernel.W_K45] = k45
    params[wrist_kernel.W_S45] = s45
    params[wrist_kernel.W_K56] = k56
    params[wrist_kernel.W_FLIP] = math.copysign(1.0, home if abs(home) > GEOMETRY_TOL else bend)
    twin = max(abs(k45), abs(k56), float(np.linalg.norm(np.cross(h4, h6))))
    params[wrist_kernel.W_TWIN] = 1.0 if twin <= wrist_kernel.TWIN_TOL else 0.0
    return True


def build(chain: DHChain, f: Features, target: TargetKind) -> ClosedForm | None:
    """The closed form of a 6R or RRP arm whose last three axes meet, or None.

    None for position targets (see :mod:`kinematica.ik.analytic.arm_position`),
    when joints 1-3 cannot move the wrist centre in three directions, or when
    two consecutive wrist axes coincide.
    """
    if target != "pose" or f.wrist_center is None or f.dof != 6:
        return None
    h, p = f.directions, f.points
    M, _, _ = fk(chain, np.zeros(6))
    c = np.asarray(f.wrist_center, dtype=float)
    c_tool = M[:3, :3].T @ (c - M[:3, 3])
    prismatic = f.joint_types[2] == "P"
    if not places_point(chain, c_tool):
        return None
    arm = arm_geometry(h[:3], p[:3], prismatic, c)
    if arm is None:
        return None
    params = np.zeros(wrist_kernel.W_SIZE)
    params[: arm.params.size] = arm.params
    params[decoupled.P_MODE] = decoupled.MODE_POSE
    params[wrist_kernel.W_CTOOL : wrist_kernel.W_CTOOL + 3] = c_tool
    if not wrist_params(params, h[3], h[4], h[5], M[:3, :3]):
        return None
    lim = wrist_kernel.W_LIMITS
    params[lim : lim + 4] = [*chain.qlim[3], *chain.qlim[5]]
    params.flags.writeable = False
    labels = tuple(f"{pos}, wrist {w}" for pos in arm.labels for w in ("no-flip", "flip"))
    return ClosedForm(
        name="rrp-spherical-wrist" if prismatic else "spherical-wrist",
        labels=labels,
        params=params,
        solve_one=decoupled.solve,
        solve_batch=decoupled.solve_batch,
    )


def _wrist_arm(types: str) -> SolverSpec:
    return SolverSpec(
        kind="spherical-wrist-6R" if types == "RRRRRR" else "rrp-spherical-wrist",
        summary="6R, spherical wrist"
        if types == "RRRRRR"
        else "RRP + spherical wrist (Stanford type)",
        handles=lambda f: f.joint_types == types and f.wrist_center is not None,
        build=build,
    )


#: The two structures: 6R, and RRP (Stanford type), each with a spherical wrist.
SPECS: tuple[SolverSpec, ...] = (_wrist_arm("RRRRRR"), _wrist_arm("RRPRRR"))
