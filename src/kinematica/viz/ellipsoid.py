"""The tool's velocity or force ellipsoid drawn on a picture of the arm.

The ellipsoid (:func:`kinematica.motion.ellipsoid`, translational rows) is drawn
around the tool point, scaled so that its longest semi-axis is
:data:`ELLIPSOID_SIZE` of the arm's size: its radii are a speed per unit joint
rate (or a force per unit joint effort), not a length, so only its shape and
orientation are read off the picture; the scale is returned to be stated.
A planar arm gets the ellipse in its drawing plane (the rows of those axes).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.robot import Robot
from kinematica.robot.ellipsoid import EllipsoidKind, ellipsoid
from kinematica.viz._mpl import VizError
from kinematica.viz.geometry import robot_scale

__all__ = ["ELLIPSOID_SIZE", "draw_ellipsoid", "ellipsoid_points"]

FloatArray = NDArray[np.float64]

#: Longest drawn semi-axis, as a fraction of the arm's size (:func:`robot_scale`).
ELLIPSOID_SIZE = 0.25


def ellipsoid_points(
    robot: Robot,
    q: ArrayLike,
    kind: EllipsoidKind = "velocity",
    plane: tuple[int, int] | None = None,
    resolution: int = 24,
) -> tuple[FloatArray, float, FloatArray]:
    """Points to draw the ellipsoid (or, in ``plane``, the ellipse) around the tool.

    Args:
        robot: The robot.
        q: ``(n,)`` joint values (rad, m).
        kind: ``"velocity"`` or ``"force"``.
        plane: The two world axes of a planar arm's drawing, or None (3-D).
        resolution: Points along each angle.

    Returns:
        ``(points, scale, radii)``: ``(resolution, resolution, 3)`` (3-D) or
        ``(resolution, 3)`` (the plane) world points (m), the factor from the
        radii to drawn metres, and the radii themselves.

    Raises:
        VizError: A radius is infinite (a force ellipsoid at a singularity) or 0
            everywhere.
    """
    axes = [0, 1, 2] if plane is None else list(plane)
    e = ellipsoid(robot, q, kind, axes=axes)
    if not np.all(np.isfinite(e.radii)) or not e.radii.max() > 0.0:
        raise VizError(
            f"the {kind} ellipsoid at this q has an infinite or zero radius (a singular "
            "configuration): nothing to draw"
        )
    scale = ELLIPSOID_SIZE * robot_scale(robot) / float(e.radii.max())
    if plane is None:
        pts = e.center + (e.surface(resolution) - e.center) * scale
        return pts, scale, e.radii
    u = np.linspace(0.0, 2.0 * np.pi, resolution)
    circle = np.stack([np.cos(u), np.sin(u)], axis=-1)
    offsets = circle @ (e.directions * e.radii * scale).T  # (resolution, 2) in the plane
    pts = np.tile(e.center, (resolution, 1))
    pts[:, plane[0]] += offsets[:, 0]
    pts[:, plane[1]] += offsets[:, 1]
    return pts, scale, e.radii


def draw_ellipsoid(
    ax: Any, robot: Robot, q: ArrayLike, kind: EllipsoidKind, plane: tuple[int, int] | None
) -> tuple[FloatArray, float]:
    """Draw the ellipsoid on ``ax`` (``gid="ellipsoid"``); returns its points and scale."""
    pts, scale, _ = ellipsoid_points(robot, q, kind, plane)
    colour = "tab:purple" if kind == "velocity" else "tab:orange"
    if plane is None:
        ax.plot_wireframe(
            pts[..., 0], pts[..., 1], pts[..., 2], color=colour, lw=0.4, alpha=0.6, gid="ellipsoid"
        )
    else:
        ax.plot(pts[:, plane[0]], pts[:, plane[1]], color=colour, lw=1.2, gid="ellipsoid")
    return pts.reshape(-1, 3), scale
