"""Static pictures of the arm: one configuration, or every IK solution of a pose."""

from __future__ import annotations

import math
import os
import textwrap
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.errors import DimensionError, UnreachableError
from kinematica.ik.result import IKResult
from kinematica.io.atomic import atomic_path, write_failed
from kinematica.robot import Robot
from kinematica.robot.ellipsoid import EllipsoidKind
from kinematica.viz._mpl import VizError, check_picture, equal_limits, figure, is_3d, new_axes
from kinematica.viz.arm import ArmDrawing, extent_points
from kinematica.viz.ellipsoid import draw_ellipsoid
from kinematica.viz.geometry import ArmPose, arm_pose, drawing_plane, robot_scale

__all__ = [
    "IMAGE_SUFFIXES",
    "check_image_path",
    "fit_solutions",
    "plot",
    "plot_solutions",
    "save_figure",
    "save_plot",
    "save_solutions",
]

FloatArray = NDArray[np.float64]

#: File types a static picture can be written as (matplotlib's Agg, SVG and PDF writers).
IMAGE_SUFFIXES = (".png", ".svg", ".pdf", ".jpg", ".jpeg")
#: Most solution panels side by side in :func:`plot_solutions`.
SOLUTION_COLUMNS = 4
#: Size of a 3-D solution panel's cube in its panel (matplotlib's 1 leaves the axis
#: labels of a narrow picture outside it), and the height of a line of the picture's
#: title and of a panel's title in pixels.
SOLUTION_ZOOM = 0.8
SUPTITLE_PX = 32
TITLE_PX = 16


def one_q(robot: Robot, q: ArrayLike) -> FloatArray:
    """``q`` checked as one configuration ``(n,)``."""
    qa = robot.check_q(q)
    if qa.ndim != 1:
        raise DimensionError(
            f"a picture shows one configuration: q must have shape ({robot.dof},), "
            f"got shape {qa.shape}"
        )
    return qa


def axes_plane(robot: Robot, ax: Any) -> tuple[int, int] | None:
    """The plane a 2-D Axes shows ``robot`` in; ``None`` for a 3-D Axes."""
    if is_3d(ax):
        return None
    plane = drawing_plane(robot)
    if plane is None:
        raise VizError(
            f"{robot.name} is not a planar arm (its joint axes are not all parallel to one "
            "world axis): draw it on a 3-D Axes (projection='3d') or pass ax=None"
        )
    return plane


def label_axes(ax: Any, plane: tuple[int, int] | None) -> None:
    """Name the world coordinates on the axes (metres)."""
    names = ("x (m)", "y (m)", "z (m)")
    if plane is None:
        ax.set_xlabel(names[0])
        ax.set_ylabel(names[1])
        ax.set_zlabel(names[2])
    else:
        ax.set_xlabel(names[plane[0]])
        ax.set_ylabel(names[plane[1]])
        ax.grid(True, lw=0.4, alpha=0.5)


def plot(
    robot: Robot,
    q: ArrayLike,
    ax: Any = None,
    frames: bool = True,
    labels: bool = True,
) -> Any:
    """Draw the arm at ``q``: links, joints, the DH frames S0..Sn, tool and base.

    The links are one line (``gid="links"``) through the frame origins of
    ``robot.fk(q, all_frames=True)``: S0 (the base), S1, ..., S(n-1) and the
    tool. Revolute joints are cylinders along their axis (discs in 2-D),
    prismatic joints boxes; each frame has x, y, z arrows in red, green, blue
    labelled S0..Sn as on the slides, the tool frame is drawn apart when the
    robot has a tool transform, and a grey plate marks the base (with the
    world frame W when the base transform is not the identity). A planar arm
    (every joint axis parallel to, or for prismatic joints normal to, one
    world axis) is drawn in 2-D in that plane; the axes are always equally
    scaled.

    Args:
        robot: The robot.
        q: ``(n,)`` joint values (rad, m).
        ax: An Axes to draw on: 3-D, or 2-D for a planar arm. A new figure
            (through pyplot) when ``None``.
        frames: Draw the frames.
        labels: Name the frames.

    Returns:
        The Axes.

    Raises:
        DimensionError: ``q`` is not one configuration of ``robot``.
        VizError: A 2-D ``ax`` for an arm that is not planar; matplotlib missing.
    """
    qa = one_q(robot, q)
    if ax is None:
        plane = drawing_plane(robot)
        fig = figure(640, 560, 100, pyplot_managed=True)
        ax = new_axes(fig, plane is None)
    else:
        plane = axes_plane(robot, ax)
    draw_arm(ax, robot, arm_pose(robot, qa), plane, frames=frames, labels=labels)
    return ax


def draw_arm(
    ax: Any,
    robot: Robot,
    pose: ArmPose,
    plane: tuple[int, int] | None,
    *,
    frames: bool,
    labels: bool,
    extra: FloatArray | None = None,
) -> ArmDrawing:
    """Draw one arm, then scale the axes equally around it (and ``extra`` points)."""
    drawing = ArmDrawing(ax, robot, pose, plane=plane, frames=frames, labels=labels)
    pts = extent_points(pose, drawing.scale)
    if extra is not None:
        pts = np.concatenate([pts, np.asarray(extra, dtype=float).reshape(-1, 3)])
    equal_limits(ax, pts, plane)
    label_axes(ax, plane)
    return drawing


def plot_solutions(
    robot: Robot,
    T: ArrayLike,
    *,
    respect_limits: bool = True,
    frames: bool = False,
    labels: bool = False,
    fig: Any = None,
) -> Any:
    """Every IK solution of one target, side by side, each titled with its branch.

    Args:
        robot: The robot.
        T: ``(4, 4)`` target pose, or ``(3,)`` position (orientation free),
            world frame, metres.
        respect_limits: Only solutions within the joint limits (as ``robot.ik``).
        frames: Draw the DH frames in every panel.
        labels: Name the frames.
        fig: A Figure to draw on (empty); a new one through pyplot if ``None``.

    Returns:
        The Figure: one panel per solution, with a common scale, the target
        marked (``gid="target"``), each titled "k: <branch>".

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
    assert isinstance(res, IKResult)  # one target gives one result
    sols = res.solutions
    if sols.shape[0] == 0:
        raise UnreachableError(f"{robot.name}: no solution to draw ({res.status}): {res.message}")
    k = sols.shape[0]
    cols = min(k, SOLUTION_COLUMNS)
    rows = math.ceil(k / cols)
    if fig is None:
        fig = figure(330 * cols, 320 * rows + 50, 100, pyplot_managed=True)
    plane = drawing_plane(robot)
    poses = arm_pose(robot, sols)
    point = target[:3, 3] if target.shape == (4, 4) else target
    scale = robot_scale(robot)
    all_pts = np.concatenate([extent_points(poses, scale), point[None]])
    free = ", ".join(f"q{i + 1}" for i in res.free_joints)
    for i in range(k):
        ax = new_axes(fig, plane is None, rows, cols, i + 1)
        one = ArmPose(poses.origins[i], poses.frames[i], poses.tool[i], poses.joints[i])
        ArmDrawing(ax, robot, one, plane=plane, frames=frames, labels=labels)
        shown = point if plane is None else point[list(plane)]
        ax.plot(*[[v] for v in shown], marker="*", ms=11, color="#e377c2", ls="", gid="target")
        equal_limits(ax, all_pts, plane)
        label_axes(ax, plane)
        branch = res.branches[i] if i < len(res.branches) and res.branches[i] else "solution"
        title = f"{i + 1}: {branch}" + (f" ({free} free)" if free else "")
        ax.set_title(textwrap.fill(title, 34), fontsize=9)
        ax.tick_params(labelsize=7)
    # about 40 characters of the title fit over one panel: a narrow picture wraps it
    head = f"{robot.name}: {k} solution{'s' if k > 1 else ''} ({res.method})"
    fig.suptitle(textwrap.fill(head, 40 * cols), fontsize=11)
    if plane is not None:  # the layout engine keeps titles and axis labels in the picture
        fig.set_layout_engine("constrained", h_pad=0.06, w_pad=0.06)
    else:  # which it does not do for 3-D axes: each cube is drawn smaller in its panel
        for ax in fig.axes:
            ax.set_box_aspect((1.0, 1.0, 1.0), zoom=SOLUTION_ZOOM)
        fit_solutions(fig)
    return fig


def fit_solutions(fig: Any) -> None:
    """Fit titles and labels in the picture at its size (call again after a resize).

    2-D panels: the layout engine places them, but its first pass beside equal-aspect
    axes leaves the bottom label a pixel out, so one pass is made here before saving.
    3-D panels: room is left for the title lines above them.
    """
    if fig.get_layout_engine() is not None:
        fig.draw_without_rendering()
        return
    lines = fig.get_suptitle().count("\n") + 1
    panel = max((ax.get_title().count("\n") + 1 for ax in fig.axes), default=0)
    room = SUPTITLE_PX * lines + TITLE_PX * panel
    top = 1.0 - room / (fig.dpi * fig.get_figheight())
    fig.subplots_adjust(left=0.0, right=0.97, bottom=0.04, top=top, wspace=0.1, hspace=0.25)


def save_figure(fig: Any, path: str | os.PathLike[str]) -> Path:
    """Write ``fig`` at its own pixel size; the file type follows the suffix."""
    out = check_image_path(path)
    try:
        with atomic_path(out) as tmp:
            fig.savefig(tmp, dpi=fig.dpi)
    except OSError as exc:
        raise VizError(write_failed(out, exc, "the picture")) from exc
    return out


def check_image_path(path: str | os.PathLike[str]) -> Path:
    """``path`` as a Path a picture can be written to: a known suffix, an existing folder.

    Raises:
        VizError: Another suffix, or a folder that does not exist.
    """
    out = Path(path)
    if out.suffix.lower() not in IMAGE_SUFFIXES:
        raise VizError(
            f"{out}: cannot write a picture of type {out.suffix or '(none)'!r}; "
            f"use one of {', '.join(IMAGE_SUFFIXES)}"
        )
    if not out.parent.is_dir():
        raise VizError(f"{out}: the folder {out.parent} does not exist")
    return out


def save_plot(
    robot: Robot,
    q: ArrayLike,
    path: str | os.PathLike[str],
    *,
    frames: bool = True,
    labels: bool = True,
    size: tuple[int, int] = (800, 700),
    dpi: float = 100.0,
    title: str | None = None,
    ellipsoid: EllipsoidKind | None = None,
) -> Path:
    """:func:`plot` into a file of ``size`` pixels (PNG, SVG, PDF...), without pyplot.

    ``ellipsoid="velocity"`` or ``"force"`` also draws that ellipsoid of the tool
    point (scaled to the arm: :func:`kinematica.viz.ellipsoid.draw_ellipsoid`);
    the title then states the scale.
    """
    qa = one_q(robot, q)
    fig = figure(*size, dpi, pyplot_managed=False)
    plane = drawing_plane(robot)
    ax = new_axes(fig, plane is None)
    extra = None
    text = title if title is not None else robot.name
    if ellipsoid is not None:
        extra, scale = draw_ellipsoid(ax, robot, qa, ellipsoid, plane)
        unit = "m/s per rad/s" if ellipsoid == "velocity" else "N per N·m"
        text += f"\n{ellipsoid} ellipsoid of the tool point, drawn at {scale:.3g} m per ({unit})"
    draw_arm(ax, robot, arm_pose(robot, qa), plane, frames=frames, labels=labels, extra=extra)
    ax.set_title(text, fontsize=10)
    tight_single(fig, plane is None)
    return save_figure(fig, path)


def tight_single(fig: Any, three_d: bool) -> None:
    """Let one Axes fill its figure (3-D axes carry wide margins by default)."""
    if three_d:
        fig.subplots_adjust(left=0.0, right=0.96, bottom=0.03, top=0.92)
    else:
        fig.subplots_adjust(left=0.1, right=0.97, bottom=0.08, top=0.94)


def save_solutions(
    robot: Robot,
    T: ArrayLike,
    path: str | os.PathLike[str],
    *,
    respect_limits: bool = True,
    frames: bool = False,
    labels: bool = False,
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
        size: ``(width, height)`` in pixels; about 330 x 320 per panel if ``None``.
        dpi: Dots per inch.

    Returns:
        The path, the number of solutions drawn, and the picture's size in pixels.
    """
    size, dpi = check_picture(size, dpi)  # before the IK is solved
    fig = figure(100, 100, dpi, pyplot_managed=False)
    plot_solutions(robot, T, respect_limits=respect_limits, frames=frames, labels=labels, fig=fig)
    k = len(fig.axes)
    cols = min(k, SOLUTION_COLUMNS)
    if size is None:
        size = (330 * cols, 320 * math.ceil(k / cols) + 50)
    fig.set_size_inches(size[0] / dpi, size[1] / dpi)
    fit_solutions(fig)
    return save_figure(fig, path), k, size
