"""A trajectory in pictures: joint curves over time beside the tool path in space."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.errors import DimensionError
from kinematica.robot import Robot
from kinematica.viz._mpl import equal_limits, figure, new_axes
from kinematica.viz.arm import ArmDrawing, extent_points
from kinematica.viz.geometry import ArmPose, arm_pose, drawing_plane, robot_scale
from kinematica.viz.plot import EDGE_PX, fit_box, label_axes
from kinematica.viz.ticks import fit_ticks

__all__ = ["check_trajectory", "plot_trajectory"]

FloatArray = NDArray[np.float64]

PATH_COLOR = "#e377c2"


def check_trajectory(
    robot: Robot, t: ArrayLike | None, q: ArrayLike
) -> tuple[FloatArray, FloatArray]:
    """``t`` ``(T,)`` strictly increasing (``0, 1, ...`` if ``None``) and ``q`` ``(T, n)``."""
    qa = robot.check_q(q)
    if qa.ndim != 2 or qa.shape[0] < 1:
        raise DimensionError(
            f"a trajectory is q of shape (T, {robot.dof}), one row per sample; got {qa.shape}"
        )
    if t is None:
        return np.arange(qa.shape[0], dtype=float), qa
    ta = np.asarray(t, dtype=float)
    if ta.shape != (qa.shape[0],):
        raise DimensionError(f"t must have shape ({qa.shape[0]},) like q's rows, got {ta.shape}")
    if not np.all(np.isfinite(ta)) or np.any(np.diff(ta) <= 0):
        raise DimensionError("t must be finite and strictly increasing")
    return ta, qa


def _pose_at(poses: ArmPose, k: int) -> ArmPose:
    return ArmPose(poses.origins[k], poses.frames[k], poses.tool[k], poses.joints[k])


def plot_trajectory(
    robot: Robot,
    t: ArrayLike | None,
    q: ArrayLike,
    *,
    degrees: bool = True,
    frames: bool = False,
    fig: Any = None,
) -> Any:
    """Joint values over time (left) and the tool path in space (right).

    Args:
        robot: The robot.
        t: ``(T,)`` time of each sample, s, strictly increasing; sample
            numbers if ``None``.
        q: ``(T, n)`` joint values (rad, m).
        degrees: Show revolute joints in degrees (else radians); prismatic
            joints are in metres, on their own axes.
        frames: Draw the DH frames on the arm at the start and the end.
        fig: A Figure to draw on (empty); a new one through pyplot if ``None``.

    Returns:
        The Figure. Its joint-curve Axes have one line per joint (label
        ``q1``...); the path Axes holds the tool path (``gid="tool-path"``,
        the origins of ``robot.fk(q)``), the arm at the end and, fainter, at
        the start.
    """
    ta, qa = check_trajectory(robot, t, q)
    if fig is None:
        fig = figure(1100, 480, 100, pyplot_managed=True)
    prismatic = robot.is_prismatic
    groups = [g for g in (np.flatnonzero(~prismatic), np.flatnonzero(prismatic)) if g.size]
    for row, idx in enumerate(groups):
        ax = fig.add_subplot(len(groups), 2, 2 * row + 1)
        is_p = bool(prismatic[idx[0]])
        values = qa[:, idx] if is_p or not degrees else np.rad2deg(qa[:, idx])
        for col, i in enumerate(idx):
            ax.plot(ta, values[:, col], label=f"q{i + 1}", gid=f"q{i + 1}")
        unit = "m" if is_p else ("deg" if degrees else "rad")
        ax.set_ylabel(f"{'prismatic' if is_p else 'revolute'} joints ({unit})")
        ax.set_xlabel("t (s)" if t is not None else "sample")
        ax.grid(True, lw=0.4, alpha=0.5)
        ax.legend(fontsize=7, ncol=min(len(idx), 4), loc="best")
    plane = drawing_plane(robot)
    ax3 = new_axes(fig, plane is None, 1, 2, 2)
    poses = arm_pose(robot, qa)
    path = poses.tool[:, :3, 3]
    shown = path if plane is None else path[:, list(plane)]
    ax3.plot(*shown.T, color=PATH_COLOR, lw=2.0, gid="tool-path")
    ax3.plot(*[[v] for v in shown[0]], marker="o", color=PATH_COLOR, ls="", gid="start")
    ax3.plot(*[[v] for v in shown[-1]], marker="s", color=PATH_COLOR, ls="", gid="end")
    last = len(qa) - 1
    first = _pose_at(poses, 0)
    ArmDrawing(ax3, robot, first, plane=plane, frames=frames, labels=False, alpha=0.3, legend=False)
    ArmDrawing(ax3, robot, _pose_at(poses, last), plane=plane, frames=frames, labels=frames)
    equal_limits(ax3, extent_points(poses, robot_scale(robot)), plane)
    label_axes(ax3, plane)
    fit_ticks(ax3)
    ax3.set_title("tool path", fontsize=10)
    title = fig.suptitle(f"{robot.name}: trajectory of {len(qa)} samples", fontsize=11)
    if plane is None:  # the box as large as the right half below the title allows
        fig.draw_without_rendering()
        width = fig.bbox.width
        curves = max(ax.get_tightbbox().x1 for ax in fig.axes if ax is not ax3)
        top = title.get_window_extent().y0 - EDGE_PX
        fit_box(ax3, (max(curves, width / 2) + EDGE_PX, EDGE_PX, width - EDGE_PX, top))
    return fig
