"""Static pictures of the arm at one configuration (every IK solution: :mod:`.solutions`)."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.errors import DimensionError
from kinematica.io.atomic import atomic_path, write_failed
from kinematica.robot import Robot
from kinematica.robot.ellipsoid import EllipsoidKind
from kinematica.viz._mpl import VizError, equal_limits, figure, is_3d, new_axes
from kinematica.viz.arm import ArmDrawing, extent_points
from kinematica.viz.ellipsoid import draw_ellipsoid
from kinematica.viz.geometry import ArmPose, arm_pose, drawing_plane
from kinematica.viz.ticks import fit_ticks

__all__ = [
    "IMAGE_SUFFIXES",
    "arm_figure",
    "check_image_path",
    "plot",
    "save_figure",
    "save_plot",
]

FloatArray = NDArray[np.float64]

#: File types a static picture can be written as (matplotlib's Agg, SVG and PDF writers).
IMAGE_SUFFIXES = (".png", ".svg", ".pdf", ".jpg", ".jpeg")
#: Space (points) between a 3-D axis and its name, beyond its tick labels.
AXIS_NAME_PAD = 14.0
#: Free room (pixels) at a single picture's edges, and the draws made to fit it.
EDGE_PX = 4
FIT_STEPS = 3


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
    if plane is None:  # clear of the tick labels (matplotlib's pad of 4 points is not)
        ax.set_xlabel(names[0], labelpad=AXIS_NAME_PAD)
        ax.set_ylabel(names[1], labelpad=AXIS_NAME_PAD)
        ax.set_zlabel(names[2], labelpad=AXIS_NAME_PAD)
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
    fit_ticks(ax)
    return drawing


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
    the title then states the scale. The arm fills the picture (:func:`tight_single`).
    """
    fig = arm_figure(
        robot,
        q,
        frames=frames,
        labels=labels,
        size=size,
        dpi=dpi,
        title=title,
        ellipsoid=ellipsoid,
    )
    return save_figure(fig, path)


def arm_figure(
    robot: Robot,
    q: ArrayLike,
    *,
    frames: bool = True,
    labels: bool = True,
    size: tuple[int, int] = (800, 700),
    dpi: float = 100.0,
    title: str | None = None,
    ellipsoid: EllipsoidKind | None = None,
) -> Any:
    """The Figure :func:`save_plot` writes (a bare Figure, without pyplot)."""
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
    return fig


def drawn_box(ax: Any) -> Any:
    """The Bbox (pixels) of a drawn 3-D Axes' box, its axes' ticks and names, its texts.

    ``Axes3D.get_tightbbox`` also holds the Axes' whole rectangle, most of it empty.
    """
    from matplotlib.transforms import Bbox
    from mpl_toolkits.mplot3d import proj3d

    renderer = ax.figure._get_renderer()
    limits = (ax.get_xlim3d(), ax.get_ylim3d(), ax.get_zlim3d())
    corners = np.array(np.meshgrid(*limits, indexing="ij")).reshape(3, -1)
    x, y, _ = proj3d.proj_transform(*corners, ax.M)
    boxes = [
        Bbox.from_extents(
            *ax.transData.transform(np.stack([x, y], 1)).min(0),
            *ax.transData.transform(np.stack([x, y], 1)).max(0),
        )
    ]
    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        boxes.append(axis.get_tightbbox(renderer))
    texts = [ax.title, *ax.texts]
    boxes += [t.get_window_extent(renderer) for t in texts if t.get_visible() and t.get_text()]
    return Bbox.union([b for b in boxes if b is not None and b.width > 0])


def tight_single(fig: Any, three_d: bool) -> None:
    """Let one Axes fill its figure: the 3-D box as large as its title and labels allow.

    The Axes' title becomes the figure's (at its top) and the legend of the frame
    arrows goes to the figure's top-left corner. A 3-D box is sized by
    matplotlib's ``zoom`` and its tick labels stick out of its Axes by amounts
    that depend on the view: the picture is drawn (without rendering) and the
    zoom and the Axes' place corrected until the box, its ticks and axis names
    fill the figure below the title within :data:`EDGE_PX`.
    """
    if not three_d:  # the layout engine keeps the axes' names and title inside
        fig.set_layout_engine("constrained", h_pad=0.04, w_pad=0.04)
        return
    ax = fig.axes[0]
    width, height = fig.bbox.width, fig.bbox.height
    top = height - EDGE_PX
    if ax.get_title():
        title = fig.suptitle(ax.get_title(), fontsize=10, y=top / height, va="top")
        ax.set_title("")
        fig.draw_without_rendering()
        top = title.get_window_extent().y0 - EDGE_PX
    legend = ax.get_legend()
    if legend is not None:
        legend.set_bbox_to_anchor((0.0, 1.0), transform=fig.transFigure)
    fig.subplots_adjust(left=0.0, right=1.0, bottom=0.0, top=top / height)
    fit_box(ax, (EDGE_PX, EDGE_PX, width - EDGE_PX, top))


def fit_box(ax: Any, region: tuple[float, float, float, float]) -> None:
    """Zoom and move a 3-D Axes until its box, ticks, axis names and title fill ``region``.

    Args:
        ax: An Axes3D of a figure that can be drawn.
        region: ``(x0, y0, x1, y1)`` in pixels of the figure.
    """
    fig = ax.figure
    x0, y0, x1, y1 = region
    aspect, zoom = np.array(ax.get_box_aspect()), 1.0
    for _ in range(FIT_STEPS):
        fig.draw_without_rendering()
        box = drawn_box(ax)
        factor = min((x1 - x0) / box.width, (y1 - y0) / box.height)
        zoom = float(np.clip(zoom * factor, 0.2, 5.0))
        ax.set_box_aspect(aspect, zoom=zoom)
        fig.draw_without_rendering()
        box = drawn_box(ax)  # then centred: the zoom grows the box about the Axes' centre
        pos = ax.get_position()
        dx = ((x0 + x1) / 2 - (box.x0 + box.x1) / 2) / fig.bbox.width
        dy = ((y0 + y1) / 2 - (box.y0 + box.y1) / 2) / fig.bbox.height
        ax.set_position([pos.x0 + dx, pos.y0 + dy, pos.width, pos.height])
