"""Where a planar arm's parameters sit in the flat array its kernel reads.

Packed once per arm by :mod:`kinematica.ik.analytic.planar_arms`, read by
:mod:`kinematica.kernels.solvers.planar_arms` and its helpers. Plane
coordinates are on ``e1``, ``e2 = k × e1`` relative to ``P_ORIGIN``.
"""

from __future__ import annotations

__all__ = [
    "P_AXIS",
    "P_E1",
    "P_E2",
    "P_K",
    "P_LENGTH",
    "P_LIFT",
    "P_LIFT_SIGN",
    "P_LIFT_TILT",
    "P_NREV",
    "P_ORIGIN",
    "P_POSE",
    "P_QLIM",
    "P_RE1",
    "P_REACH",
    "P_REV",
    "P_RMAX",
    "P_RMIN",
    "P_SIGN",
    "P_SIZE",
    "P_SLACK",
    "P_SLIDE",
    "P_SLIDE_TILT",
    "P_SWAP",
    "P_TIP",
    "P_TOOL",
    "P_U",
    "P_WRIST",
]

P_POSE = 0  # 1.0: pose targets, 0.0: position targets (tool origin)
P_SWAP = 1  # 1.0: the triangle's branch ψ >= 0 takes slot 0 (SCARA), else ψ <= 0 does
P_SLIDE = 2  # joint index of the slide across k, or -1
P_LIFT = 3  # joint index of the slide along k (SCARA), or -1
P_LIFT_SIGN = 4  # k · (that slide's direction): +1 or -1
P_NREV = 5  # number of revolute joints, 1 to 3
P_REV = 6  # (3,) their joint indices, base to tip
P_SIGN = 9  # (3,) k · (their axis direction): +1 or -1
P_K = 12  # (3,) the common axis direction k (unit, base frame)
P_E1 = 15  # (3,) plane basis e1 (unit, normal to k)
P_E2 = 18  # (3,) plane basis e2 = k × e1
P_ORIGIN = 21  # (3,) origin of the plane coordinates: on the first revolute axis (base frame, m)
P_TOOL = 24  # (3,) tool origin at q = 0 (base frame, m)
P_RE1 = 27  # (3,) R_Mᵀ e1 (M = fk(0): the tool pose at q = 0)
P_WRIST = 30  # (3,) the last revolute axis point in the tool frame at q = 0 (m)
P_AXIS = 33  # (3, 2) the revolute axis points at q = 0, plane coordinates (m)
P_TIP = 39  # (2,) the tool origin at q = 0, plane coordinates (m)
P_U = 41  # (2,) the slide direction across k, plane coordinates (unit)
P_REACH = 43  # sum of the in-plane link lengths (m): the scale of SINGULAR_TOL
P_RMIN = 44  # least distance of the tool origin from the first revolute axis (m)
P_RMAX = 45  # largest distance from that axis (or across the slide's line) (m)
P_QLIM = 46  # (4, 2) joint limits (rad or m; ±inf where there are none)
P_SLACK = 54  # how far the arm's revolute axes may put the tool from the ideal arm's (m)
P_SLIDE_TILT = 55  # |k · slide direction|: the slide's tilt out of the plane (sine)
P_LIFT_TILT = 56  # |k × lift direction|: the SCARA slide's tilt off k (sine)
P_LENGTH = 57  # sum of the distances between consecutive axes and to the tool (m)
P_SIZE = 58
