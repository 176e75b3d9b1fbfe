"""Cartesian paths through several poses, their corners blended.

The tool runs along straight lines between the poses' positions while its
orientation turns along each segment's geodesic (slerp, a constant rotation
rate in the tool frame). The path parameter ``s`` in [0, 1] is shared among
the segments in proportion to their length ``|Δp| + ROTATION_LENGTH·θ`` (θ the
segment's rotation angle), so a pure reorientation takes its share too and a
path through collinear positions with one orientation is the straight line at
uniform speed in ``s``, with no corner.

A corner ``i`` is blended over ``s`` in ``[s_i - δ, s_i + δ]`` by constant
"acceleration" in ``s`` (a parabola joining the incoming and outgoing lines
tangentially: Craig's linear-parabolic blend, in space), and the orientation
likewise in the tangent space at the corner's orientation: ``R_i·exp(ω_in·x +
(ω_out − ω_in)·(x + δ)²/(4δ))`` with ``x = s - s_i``. Position and orientation
are continuous with continuous rates ``d/ds``. ``δ`` is chosen so that the
blend leaves each segment at most ``blend`` metres before the corner (exactly
``blend`` where the two segments move at the same rate in ``s``), and never
more than half of either segment; a corner between two pure rotations is not
blended (the blend is a length).
The corner poses themselves are then not reached; with ``blend = 0`` every
pose is passed exactly.

The path is followed on one IK branch exactly as :func:`cartesian_path`
follows its line: singular crossings, unreachable poses, joint limits and
branch changes are events.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.errors import DimensionError, KinematicaError
from kinematica.motion.cartesian import CartesianPath, follow, path_samples
from kinematica.motion.cartesian_timed import time_cartesian
from kinematica.motion.trajectory import DEFAULT_DT
from kinematica.spatial import (
    check_transform,
    make_transform,
    matrix_from_rotvec,
    rotvec_from_matrix,
)

if TYPE_CHECKING:
    from kinematica.robot import Robot

__all__ = ["ROTATION_LENGTH", "BlendedPolyline", "cartesian_via_path"]

FloatArray = NDArray[np.float64]

#: Path length (m) a tool rotation of one radian counts for when ``s`` is shared among segments.
ROTATION_LENGTH = 0.1


class BlendedPolyline:
    """Poses at path parameters ``s``: lines, slerps and blended corners.

    Attributes:
        knots: ``(k,)`` path parameter of each given pose (0 and 1 at the ends).
        delta: ``(k,)`` half-width in ``s`` of each corner's blend (0 at the ends).
    """

    def __init__(self, poses: FloatArray, blend: float) -> None:
        self.p = poses[:, :3, 3]
        self.R = poses[:, :3, :3]
        dp = np.diff(self.p, axis=0)
        rot = rotvec_from_matrix(np.swapaxes(self.R[:-1], -1, -2) @ self.R[1:])
        length = np.linalg.norm(dp, axis=1) + ROTATION_LENGTH * np.linalg.norm(rot, axis=1)
        if np.any(length == 0.0):
            i = int(np.flatnonzero(length == 0.0)[0])
            raise KinematicaError(f"poses {i + 1} and {i + 2} are equal")
        share = length / length.sum()
        self.knots = np.concatenate([[0.0], np.cumsum(share)])
        self.knots[-1] = 1.0
        self.vel = dp / share[:, None]  # dp/ds of each segment
        self.omega = rot / share[:, None]  # tool-frame rotation rate per unit s
        k = poses.shape[0]
        self.delta = np.zeros(k)
        for i in range(1, k - 1):
            rate = max(np.linalg.norm(self.vel[i - 1]), np.linalg.norm(self.vel[i]))
            wide = blend / rate if rate > 0 else 0.0
            self.delta[i] = min(wide, 0.5 * share[i - 1], 0.5 * share[i])

    def __call__(self, s: ArrayLike) -> FloatArray:
        """Poses ``(..., 4, 4)`` (base frame) at path parameters ``s`` ``(...)`` in [0, 1]."""
        sa = np.asarray(s, dtype=float)
        flat = np.atleast_1d(sa).ravel()
        k = self.knots.size
        j = np.clip(np.searchsorted(self.knots, flat, side="right") - 1, 0, k - 2)
        # The corner whose blend holds s, if any: j's (just after it) or j+1's (just before).
        after = flat - self.knots[j] < self.delta[j]
        before = self.knots[j + 1] - flat < self.delta[j + 1]
        corner = np.where(after, j, np.where(before, j + 1, -1))
        blended = corner >= 0
        c = np.where(blended, corner, j)  # the pose the expansion is about
        x = flat - self.knots[c]
        seg_in = np.where(blended, c - 1, j)  # line in use (the incoming one in a blend)
        lin = x[:, None]
        pos = self.p[c] + self.vel[seg_in] * lin
        phi = self.omega[seg_in] * lin
        if blended.any():
            b = np.flatnonzero(blended)
            d = self.delta[c[b]][:, None]
            w = (x[b][:, None] + d) ** 2 / (4.0 * d)
            pos[b] += (self.vel[c[b]] - self.vel[c[b] - 1]) * w
            phi[b] += (self.omega[c[b]] - self.omega[c[b] - 1]) * w
        R = self.R[c] @ matrix_from_rotvec(phi)
        T = make_transform(R, pos)
        end = flat >= 1.0  # the last pose exactly
        T[end] = make_transform(self.R[-1], self.p[-1])
        out: FloatArray = T.reshape(*sa.shape, 4, 4)
        return out


def cartesian_via_path(
    robot: Robot,
    poses: ArrayLike,
    blend: float = 0.0,
    steps: int = 100,
    q0: ArrayLike | None = None,
    s: ArrayLike | None = None,
    position_only: bool | None = None,
    *,
    vmax: ArrayLike | None = None,
    amax: ArrayLike | None = None,
    tcp_speed: float | None = None,
    tcp_angular_speed: float | None = None,
    dt: float = DEFAULT_DT,
) -> CartesianPath:
    """Follow straight lines through ``poses``, the corners blended over ``blend`` metres.

    Given any of ``vmax``, ``amax``, ``tcp_speed``, ``tcp_angular_speed``, the
    path is timed by the robot, as :func:`~kinematica.motion.cartesian.cartesian_path`'s.

    Args:
        robot: The robot.
        poses: ``(k, 4, 4)`` tool poses (base frame), k >= 2, consecutive
            ones distinct.
        blend: Blend radius (m) >= 0: how far before and after each corner
            the path leaves the lines (at most half of a segment); 0 passes
            every pose with a corner.
        steps: Number of samples, both ends included (>= 2).
        q0: ``(n,)`` configuration whose branch the path starts on.
        s: ``(m,)`` non-decreasing path parameters in [0, 1] instead of
            ``steps`` uniform ones (e.g. a time scaling ``s(t)``).
        position_only: As for :func:`cartesian_path`.
        vmax: Joint velocity limits (rad/s, m/s), as for :func:`cartesian_path`.
        amax: Joint acceleration limits (rad/s², m/s²).
        tcp_speed: Largest linear speed of the tool (m/s).
        tcp_angular_speed: Largest angular speed of the tool (rad/s).
        dt: Largest sample spacing (s) of a timed path.

    Returns:
        The :class:`CartesianPath`, with its ``events``; timed when limits are given.

    Raises:
        DimensionError: Poses that are not rigid transforms, bad shapes.
        KinematicaError: Two consecutive poses equal, ``blend < 0``, ``steps < 2``
            or ``s`` not increasing within [0, 1].
    """
    P = check_transform(np.asarray(poses, dtype=float), name="poses")
    if P.ndim != 3 or P.shape[0] < 2:
        raise DimensionError(f"poses must be (k, 4, 4) with k >= 2, got shape {P.shape}")
    if not (np.isfinite(blend) and blend >= 0):
        raise KinematicaError(f"blend must be a length >= 0 (m), got {blend!r}", arg="blend")
    ss = path_samples(steps, s)
    geo = BlendedPolyline(P, float(blend))
    path = follow(robot, geo, ss, q0, position_only)
    timing = (vmax, amax, tcp_speed, tcp_angular_speed, dt)
    if any(v is not None for v in timing[:4]):
        return time_cartesian(robot, geo, path, timing)
    return path
