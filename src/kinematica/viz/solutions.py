"""Every IK solution of one target, a panel each, titled with its branch and its q.

Two solutions can draw the same picture: a spherical wrist turned by 180° about
its own axes (q4 + π, −q5, q6 + π) moves no link origin, and an arm whose
shoulder has no offset reaches some targets with its links in the same places
on two branches. The figure says so in a caption under the panels, naming the
joints that tell those solutions apart.
"""

from __future__ import annotations

import math
import os
import textwrap
import warnings
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.errors import DimensionError, LimitWarning, UnreachableError
from kinematica.ik.result import IKResult
from kinematica.robot import Robot
from kinematica.viz._mpl import check_picture, equal_limits, figure, new_axes
from kinematica.viz.arm import SAME_PLACE, ArmDrawing, axis_legend, extent_points
from kinematica.viz.geometry import ArmPose, arm_pose, drawing_plane, robot_scale
from kinematica.viz.plot import label_axes, save_figure
from kinematica.viz.ticks import fit_ticks

__all__ = [
    "SOLUTION_COLUMNS",
    "fit_solutions",
    "plot_solutions",
    "q_text",
    "same_links",
    "save_solutions",
]

FloatArray = NDArray[np.float64]

#: Most solution panels side by side in :func:`plot_solutions`.
SOLUTION_COLUMNS = 4
#: Size of a 3-D solution panel's box in its panel (matplotlib's 1 leaves the axis
#: labels of a narrow picture outside it), and the height of a line of the picture's
#: title, of a panel's title and of the caption in pixels.
SOLUTION_ZOOM = 0.8
SUPTITLE_PX = 32
TITLE_PX = 15
CAPTION_PX = 15
NAMES_PX = 20
#: Space (points) between a panel's 3-D axis and its name.
PANEL_NAME_PAD = 8.0
#: Characters of a panel's title on one line (330 pixels at 8 points): its branch, its
#: q (wider characters: digits), and of the caption a panel wide.
TITLE_CHARS = 46
Q_CHARS = 38
CAPTION_CHARS = 55


def q_text(robot: Robot, q: FloatArray, degrees: bool = True) -> str:
    """``q = [10.0, -30.0, ...] (deg)``: revolute joints in degrees (or rad), prismatic in m."""
    prismatic = robot.is_prismatic
    values = [
        f"{v:.3f}" if p else (f"{math.degrees(v):.1f}" if degrees else f"{v:.3f}")
        for v, p in zip(q, prismatic, strict=True)
    ]
    units = [u for u, has in (("deg" if degrees else "rad", not prismatic.all()),) if has]
    units += ["m"] if prismatic.any() else []
    return f"q = [{', '.join(values)}] ({', '.join(units)})"


def same_links(robot: Robot, solutions: FloatArray) -> list[tuple[list[int], list[int]]]:
    """Groups of solutions whose links are in the same places, and the joints they differ in.

    Args:
        robot: The robot.
        solutions: ``(k, n)`` joint values (rad, m).

    Returns:
        For each group of two or more solutions whose frame origins and tool
        point all lie within :data:`~kinematica.viz.arm.SAME_PLACE` of the
        robot's size of the first one's: the 0-based indices of the solutions,
        and the 0-based joints whose values differ in the group (angles compared
        modulo 2π; a difference moving a point at the robot's size by less than
        SAME_PLACE of it is none).
    """
    sols = np.asarray(solutions, dtype=float)
    if sols.shape[0] < 2:
        return []
    scale = robot_scale(robot)
    poses = arm_pose(robot, sols)  # every frame origin and the tool point: (k, m, 3)
    points = np.concatenate([poses.frames[..., :3, 3], poses.tool[:, None, :3, 3]], axis=1)
    prismatic = robot.is_prismatic
    groups: list[list[int]] = []
    for i in range(sols.shape[0]):
        for group in groups:
            gap = np.linalg.norm(points[i] - points[group[0]], axis=-1).max()
            if gap < SAME_PLACE * scale:
                group.append(i)
                break
        else:
            groups.append([i])
    out = []
    for group in (g for g in groups if len(g) > 1):
        diff = sols[group] - sols[group[0]]
        turned = np.angle(np.exp(1j * diff))  # wrapped to (-pi, pi]
        size = np.where(prismatic, np.abs(diff) / scale, np.abs(turned))
        joints = [int(j) for j in np.flatnonzero(size.max(axis=0) >= SAME_PLACE)]
        out.append((group, joints))
    return out


def _caption(groups: list[tuple[list[int], list[int]]]) -> list[str]:
    """One sentence per set of joints: the groups of panels drawn alike that differ in them.

    "Panels (1, 2) and (3, 4) look alike: the links of each pair are in the same
    places; its solutions differ only in q4, q5, q6."
    """
    by_joints: dict[tuple[int, ...], list[list[int]]] = {}
    for group, joints in groups:
        by_joints.setdefault(tuple(joints), []).append(group)
    lines = []
    for key, alike in by_joints.items():
        named = [f"({', '.join(str(i + 1) for i in group)})" for group in alike]
        panels = named[0] if len(named) == 1 else ", ".join(named[:-1]) + " and " + named[-1]
        which = ", ".join(f"q{j + 1}" for j in key) or "no joint (one solution found twice)"
        kind = "pair" if all(len(g) == 2 for g in alike) else "group"
        each = f"of each {kind} " if len(alike) > 1 else ""
        lines.append(
            f"Panels {panels} look alike: the links {each}are in the same places; "
            f"the solutions differ only in {which}."
        )
    return lines


def plot_solutions(
    robot: Robot,
    T: ArrayLike,
    *,
    respect_limits: bool = True,
    frames: bool = False,
    labels: bool = False,
    degrees: bool = True,
    fig: Any = None,
) -> Any:
    """Every IK solution of one target, side by side, each titled with its branch and q.

    Args:
        robot: The robot.
        T: ``(4, 4)`` target pose, or ``(3,)`` position (orientation free),
            world frame, metres.
        respect_limits: Only solutions within the joint limits (as ``robot.ik``).
        frames: Draw the DH frames in every panel (one legend of their colours).
        labels: Name the frames.
        degrees: Give revolute joints in the titles in degrees (else radians).
        fig: A Figure to draw on (empty); a new one through pyplot if ``None``.

    Returns:
        The Figure: one panel per solution, with a common scale, the target
        marked (``gid="target"``), each titled "k: <branch>" over its
        ``q = [...] (deg)``; where solutions draw the same links
        (:func:`same_links`), a caption (``gid="caption"``) under the panels names
        them and the joints that differ.

    Raises:
        UnreachableError: The target has no solution to draw (the message
            gives the IK status and why).
        DimensionError: ``T`` is not one pose or position.
    """
    target = np.asarray(T, dtype=float)
    if target.shape not in ((4, 4), (3,)):
        raise DimensionError(
            f"plot_solutions takes one target: a (4, 4) pose or a (3,) position, "
            f"got shape {target.shape}"
        )
    res = robot.ik(target, respect_limits=respect_limits)
    with warnings.catch_warnings():  # solutions outside the limits were asked for
        warnings.simplefilter("ignore", LimitWarning)
        return _draw_solutions(robot, target, res, frames, labels, degrees, fig)


def _draw_solutions(
    robot: Robot,
    target: FloatArray,
    res: Any,
    frames: bool,
    labels: bool,
    degrees: bool,
    fig: Any,
) -> Any:
    """The panels of :func:`plot_solutions` for the IK result ``res``."""
    assert isinstance(res, IKResult)  # one target gives one result
    sols = res.solutions
    if sols.shape[0] == 0:
        raise UnreachableError(f"{robot.name}: no solution to draw ({res.status}): {res.message}")
    k = sols.shape[0]
    cols = min(k, SOLUTION_COLUMNS)
    rows = math.ceil(k / cols)
    if fig is None:
        fig = figure(330 * cols, 340 * rows + 50, 100, pyplot_managed=True)
    plane = drawing_plane(robot)
    poses = arm_pose(robot, sols)
    point = target[:3, 3] if target.shape == (4, 4) else target
    scale = robot_scale(robot)
    all_pts = np.concatenate([extent_points(poses, scale), point[None]])
    free = ", ".join(f"q{i + 1}" for i in res.free_joints)
    for i in range(k):
        ax = new_axes(fig, plane is None, rows, cols, i + 1)
        one = ArmPose(poses.origins[i], poses.frames[i], poses.tool[i], poses.joints[i])
        ArmDrawing(ax, robot, one, plane=plane, frames=frames, labels=labels, legend=False)
        shown = point if plane is None else point[list(plane)]
        ax.plot(*[[v] for v in shown], marker="*", ms=11, color="#e377c2", ls="", gid="target")
        equal_limits(ax, all_pts, plane, zoom=SOLUTION_ZOOM)
        label_axes(ax, plane)
        branch = res.branches[i] if i < len(res.branches) and res.branches[i] else "solution"
        title = f"{i + 1}: {branch}" + (f" ({free} free)" if free else "")
        q_line = textwrap.fill(q_text(robot, sols[i], degrees), Q_CHARS)
        ax.set_title(f"{textwrap.fill(title, TITLE_CHARS)}\n{q_line}", fontsize=8)
        for axis in (ax.xaxis, ax.yaxis, getattr(ax, "zaxis", None)):
            if axis is not None:  # small panels: names nearer their 7-point tick labels
                axis.label.set_fontsize(8)
                axis.labelpad = PANEL_NAME_PAD
        fit_ticks(ax, 7.0)
    # about 40 characters of the title fit over one panel: a narrow picture wraps it
    head = f"{robot.name}: {k} solution{'s' if k > 1 else ''} ({res.method})"
    fig.suptitle(textwrap.fill(head, 40 * cols), fontsize=11)
    caption = _caption(same_links(robot, sols))
    if caption:
        wrapped = [textwrap.fill(line, CAPTION_CHARS * cols) for line in caption]
        fig.text(0.01, 0.005, "\n".join(wrapped), fontsize=8, ha="left", va="bottom", gid="caption")
    if frames:  # one row in the top-right corner, beside the picture's title
        axis_legend(fig, loc="upper right", ncol=3, title=None, borderaxespad=0.2)
    if plane is not None:  # the layout engine keeps titles and axis labels in the picture
        fig.set_layout_engine("constrained", h_pad=0.06, w_pad=0.06)
    else:  # which it does not do for 3-D axes: room is made for the titles by hand
        fit_solutions(fig)
    return fig


def _caption_lines(fig: Any) -> int:
    text = next((t for t in fig.texts if t.get_gid() == "caption"), None)
    return 0 if text is None else text.get_text().count("\n") + 1


def fit_solutions(fig: Any) -> None:
    """Fit titles and labels in the picture at its size (call again after a resize).

    2-D panels: the layout engine places them, but its first pass beside equal-aspect
    axes leaves the bottom label a pixel out, so one pass is made here before saving.
    3-D panels: room is left for the title lines above them and the caption below.
    """
    if fig.get_layout_engine() is not None:
        fig.draw_without_rendering()
        return
    lines = fig.get_suptitle().count("\n") + 1
    panel = max((ax.get_title().count("\n") + 1 for ax in fig.axes), default=0)
    room = SUPTITLE_PX * lines + TITLE_PX * panel
    height = fig.dpi * fig.get_figheight()
    top = 1.0 - room / height
    lines = _caption_lines(fig)  # the bottom panels' axis names hang below their boxes
    bottom = 0.04 + (CAPTION_PX * lines + (NAMES_PX if lines else 0)) / height
    if top - bottom < 0.4:  # too small for its text (save_solutions resizes it after)
        top, bottom = 0.8, 0.1
    rows = max(ax.get_subplotspec().get_geometry()[0] for ax in fig.axes)
    hspace = 0.25 + TITLE_PX * panel * rows / height  # the titles of the lower rows
    fig.subplots_adjust(left=0.0, right=0.97, bottom=bottom, top=top, wspace=0.1, hspace=hspace)


def save_solutions(
    robot: Robot,
    T: ArrayLike,
    path: str | os.PathLike[str],
    *,
    respect_limits: bool = True,
    frames: bool = False,
    labels: bool = False,
    degrees: bool = True,
    size: tuple[int, int] | None = None,
    dpi: float = 100.0,
) -> tuple[Path, int, tuple[int, int]]:
    """:func:`plot_solutions` into a file, without pyplot.

    Args:
        robot: The robot.
        T: ``(4, 4)`` target pose or ``(3,)`` position (m, world frame).
        path: Output file (PNG, SVG, PDF...).
        respect_limits: Only solutions within the joint limits.
        frames: Draw the DH frames.
        labels: Name the frames.
        degrees: Give revolute joints in the titles in degrees (else radians).
        size: ``(width, height)`` in pixels; about 330 x 340 per panel if ``None``.
        dpi: Dots per inch.

    Returns:
        The path, the number of solutions drawn, and the picture's size in pixels.
    """
    size, dpi = check_picture(size, dpi)  # before the IK is solved
    fig = figure(100, 100, dpi, pyplot_managed=False)
    plot_solutions(
        robot,
        T,
        respect_limits=respect_limits,
        frames=frames,
        labels=labels,
        degrees=degrees,
        fig=fig,
    )
    k = len(fig.axes)
    cols = min(k, SOLUTION_COLUMNS)
    if size is None:
        size = (330 * cols, 340 * math.ceil(k / cols) + 50 + CAPTION_PX * _caption_lines(fig))
    fig.set_size_inches(size[0] / dpi, size[1] / dpi)
    fit_solutions(fig)
    return save_figure(fig, path), k, size
