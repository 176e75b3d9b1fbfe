"""The workspace as a cloud of points, coloured by manipulability when known."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.errors import DimensionError
from kinematica.robot import Robot
from kinematica.viz._mpl import equal_limits, figure, is_3d, new_axes
from kinematica.viz.arm import ArmDrawing, extent_points
from kinematica.viz.geometry import arm_pose, drawing_plane, robot_scale
from kinematica.viz.plot import axes_plane, label_axes, one_q
from kinematica.viz.ticks import fit_ticks

__all__ = ["plot_workspace", "workspace_arrays"]

FloatArray = NDArray[np.float64]


def workspace_arrays(
    points_or_workspace: Any, values: ArrayLike | None = None
) -> tuple[FloatArray, FloatArray | None]:
    """``(N, 3)`` points and ``(N,)`` colour values from an array or a workspace object.

    Args:
        points_or_workspace: An ``(N, 3)`` array, or any object with a
            ``points`` attribute ``(N, 3)`` and optionally ``manipulability`` ``(N,)``.
        values: ``(N,)`` values to colour by, overriding ``manipulability``.
    """
    source = getattr(points_or_workspace, "points", points_or_workspace)
    pts = np.asarray(source, dtype=float)
    if pts.ndim != 2 or pts.shape[1] != 3:
        raise DimensionError(f"workspace points must have shape (N, 3), got {pts.shape}")
    if values is None:
        values = getattr(points_or_workspace, "manipulability", None)
    if values is None:
        return pts, None
    vals = np.asarray(values, dtype=float)
    if vals.shape != (pts.shape[0],):
        raise DimensionError(
            f"colour values must have shape ({pts.shape[0]},) like the points, got {vals.shape}"
        )
    return pts, vals


def plot_workspace(
    robot: Robot | None,
    points_or_workspace: Any,
    ax: Any = None,
    *,
    q: ArrayLike | None = None,
    values: ArrayLike | None = None,
    label: str = "manipulability",
    size: float = 2.0,
) -> Any:
    """Scatter the reachable points; draw the arm among them when ``robot`` is given.

    Args:
        robot: The robot (drawn at ``q``, and choosing a 2-D view when planar), or ``None``.
        points_or_workspace: ``(N, 3)`` points (m, world frame), or an object
            with ``points`` ``(N, 3)`` and optional ``manipulability`` ``(N,)``.
        ax: An Axes to draw on; a new figure (through pyplot) if ``None``.
        q: ``(n,)`` configuration to draw the arm at; zeros if ``None``.
        values: ``(N,)`` values to colour the points by (overrides ``manipulability``).
        label: Name of the colour values on the colour bar.
        size: Marker size (points²).

    Returns:
        The Axes; the points are the collection with ``gid="workspace"``.
    """
    pts, vals = workspace_arrays(points_or_workspace, values)
    if ax is None:
        plane = drawing_plane(robot) if robot is not None else None
        fig = figure(700, 600, 100, pyplot_managed=True)
        ax = new_axes(fig, plane is None)
    elif is_3d(ax):
        plane = None
    else:
        plane = axes_plane(robot, ax) if robot is not None else (0, 1)
    shown = pts if plane is None else pts[:, list(plane)]
    style: dict[str, Any] = {"s": size, "gid": "workspace", "linewidths": 0}
    if vals is not None:
        style.update(c=vals, cmap="viridis")
    else:
        style.update(color="#1f77b4", alpha=0.35)
    sc = ax.scatter(*shown.T, **style)
    if vals is not None:
        ax.figure.colorbar(sc, ax=ax, shrink=0.7, label=label)
    extent = pts
    if robot is not None:
        qa = np.zeros(robot.dof) if q is None else one_q(robot, q)
        pose = arm_pose(robot, qa)
        ArmDrawing(ax, robot, pose, plane=plane, frames=False, labels=False)
        extent = np.concatenate([pts, extent_points(pose, robot_scale(robot))])
    equal_limits(ax, extent, plane)
    label_axes(ax, plane)
    fit_ticks(ax)
    return ax
