"""The arm on a matplotlib Axes: links, joints, DH frames S0..Sn, tool, base.

:class:`ArmDrawing` creates the artists once and moves them with
:meth:`ArmDrawing.update`, so an animation redraws only what changes. Every
artist has a ``gid`` (``"links"``, ``"joints"``, ``"frames"``, ``"tool-frame"``,
``"base"``, ``"label-S0"``...) so tests and users can find it.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from kinematica.robot import Robot
from kinematica.viz.geometry import (
    ARROW,
    HEAD_LENGTH,
    HEAD_WIDTH,
    JOINT_RADIUS,
    ArmPose,
    arrow_segments,
    box,
    cylinder,
    plane_normal_sign,
    robot_scale,
)
from kinematica.viz.labels import LabelPlacer

__all__ = [
    "AXIS_COLORS",
    "ArmDrawing",
    "arrow_lengths",
    "axis_legend",
    "coincident_names",
    "extent_points",
]

FloatArray = NDArray[np.float64]

#: Colours of the x, y and z arrows of a frame (red, green, blue, as on the slides).
AXIS_COLORS = ("#d62728", "#2ca02c", "#1f77b4")
LINK_COLOR = "#333333"
REVOLUTE_COLOR = "#f0a030"
PRISMATIC_COLOR = "#4a90d9"
BASE_COLOR = "#9a9a9a"
#: Frame origins closer than this fraction of the robot's size share one label ("S4, S5"):
#: no picture can show them apart. Frames further apart each have their own label at
#: their own origin, placed by :mod:`kinematica.viz.labels` so that none covers another.
SAME_PLACE = 1e-6
#: A frame whose origin is that of k earlier ones (S5 at S4's) is drawn with arrows
#: SHRINK**k as long, so that the arrows of frames in one place can be told apart.
SHRINK = 0.6
#: Below this fraction of the arrow length, a frame axis seen in a 2-D view is
#: drawn as a dot (pointing at the viewer) or a cross (away from the viewer).
OUT_OF_PLANE = 0.3


def extent_points(pose: ArmPose, scale: float) -> FloatArray:
    """``(N, 3)`` points a view must contain to show the arm(s) of ``pose`` whole."""
    tips = pose.frames[..., :3, 3][..., None, :] + ARROW * scale * np.swapaxes(
        pose.frames[..., :3, :3], -1, -2
    )
    parts = [
        pose.origins.reshape(-1, 3),
        tips.reshape(-1, 3),
        pose.tool[..., :3, 3].reshape(-1, 3),
        np.zeros((1, 3)),
    ]
    return np.concatenate(parts)


def coincident_names(points: FloatArray, scale: float) -> list[str]:
    """Each frame's label: "S4, S5" for the first of frames in one place, "" for the others.

    Frames whose origins are within :data:`SAME_PLACE` of the robot's size of
    the first one of a group share its label (as on the interactive page).
    """
    names = [""] * len(points)
    first: list[int] = []
    for i, p in enumerate(points):
        for j in first:
            if np.linalg.norm(points[j] - p) < SAME_PLACE * scale:
                names[j] += f", S{i}"
                break
        else:
            first.append(i)
            names[i] = f"S{i}"
    return names


def axis_legend(ax: Any, **where: Any) -> Any:
    """A legend of the frame arrows' colours: x red, y green, z blue (``gid="axis-legend"``).

    Args:
        ax: The Axes, or a Figure for one legend over all its panels.
        where: Keyword arguments of ``legend`` (``loc``...).
    """
    from matplotlib.lines import Line2D

    handles = [
        Line2D([], [], color=color, lw=2.0, label=f"{name} axis")
        for name, color in zip("xyz", AXIS_COLORS, strict=True)
    ]
    style = {"loc": "upper left", "fontsize": 7, "title": "frame arrows", "title_fontsize": 7}
    style.update(where)
    legend = ax.legend(handles=handles, **style)
    legend.set_gid("axis-legend")
    return legend


def arrow_lengths(frames: FloatArray, scale: float) -> FloatArray:
    """``(F,)`` arrow length of each frame: ARROW * scale, times SHRINK per earlier frame there.

    Frames in one place (within :data:`SAME_PLACE` of ``scale``), such as S4 and
    S5 at a spherical wrist's centre, would draw their arrows over each other.
    """
    origins = frames[:, :3, 3]
    gaps = np.linalg.norm(origins[:, None] - origins[None], axis=-1)
    earlier = np.tril(gaps < SAME_PLACE * scale, k=-1).sum(axis=1)
    lengths: FloatArray = ARROW * scale * SHRINK**earlier
    return lengths


def _arrow_2d(start: FloatArray, tip: FloatArray, length: float) -> list[FloatArray]:
    """Shaft and two head strokes of a 2-D arrow, the head sized by ``length``."""
    d = tip - start
    d = d / np.linalg.norm(d)
    side = np.array([-d[1], d[0]])
    back = tip - HEAD_LENGTH * length * d
    return [
        np.array([start, tip]),
        np.array([tip, back + HEAD_WIDTH * length * side]),
        np.array([tip, back - HEAD_WIDTH * length * side]),
    ]


class ArmDrawing:
    """The artists of one arm on one Axes, 3-D or 2-D (a planar arm's plane).

    Args:
        ax: A matplotlib Axes (2-D) or Axes3D.
        robot: The robot.
        pose: Its :class:`ArmPose` at one configuration.
        plane: The two world coordinates of a 2-D Axes, ``None`` for 3-D.
        frames: Draw the DH frames S0..Sn and the tool frame.
        labels: Name the frames (S0..Sn, tool, W for the world frame).
        alpha: Opacity of everything drawn (fainter ghosts of other poses).
        legend: With ``frames``, a legend of the arrows' colours (x, y, z) on the Axes.
    """

    def __init__(
        self,
        ax: Any,
        robot: Robot,
        pose: ArmPose,
        *,
        plane: tuple[int, int] | None = None,
        frames: bool = True,
        labels: bool = True,
        alpha: float = 1.0,
        legend: bool = True,
    ) -> None:
        self.ax, self.robot, self.plane = ax, robot, plane
        self.show_frames, self.show_labels, self.alpha = frames, labels, alpha
        self.scale = robot_scale(robot)
        self.prismatic = robot.is_prismatic
        self.has_tool = not np.array_equal(robot.tool, np.eye(4))
        self._draw_base()
        xy = self._project(pose.origins)
        self.links = ax.plot(*xy.T, color=LINK_COLOR, lw=3.0, alpha=alpha, gid="links")[0]
        self.joints = self._collection(self._joint_faces(pose), "joints")
        self.frames = self.tool_frame = self.tool_link = None
        if frames:
            segs, colors = self._frame_lines(pose.frames)
            self.frames = self._lines(segs, colors, 1.4, "frames")
            if self.has_tool:
                segs, colors = self._frame_lines(pose.tool[None])
                self.tool_frame = self._lines(segs, colors, 2.4, "tool-frame")
        if self.has_tool:
            ends = self._project(np.stack([pose.frames[-1, :3, 3], pose.tool[:3, 3]]))
            self.tool_link = ax.plot(
                *ends.T, color=LINK_COLOR, lw=1.2, ls="--", alpha=alpha, gid="tool"
            )[0]
        self.placer: LabelPlacer | None = None
        if labels:
            gids = [f"label-S{i}" for i in range(len(pose.frames))]
            if self.has_tool and frames:
                gids.append("label-tool")
            if self._shows_world():
                gids.append("label-W")
            style = {"fontsize": 8, "alpha": alpha, "zorder": 5}
            texts, points = self._label_texts(pose, len(gids))
            self.placer = LabelPlacer(ax, texts, self._project(points), gids, style)
        self.texts: list[Any] = [] if self.placer is None else self.placer.labels
        self.legend = None
        if frames and legend:  # 3-D: a corner the box leaves free; 2-D: where it is empty
            self.legend = axis_legend(ax, loc="upper left" if plane is None else "best")

    # ----------------------------------------------------------------- public
    def update(self, pose: ArmPose) -> None:
        """Move every artist to the configuration of ``pose``."""
        self._set_line(self.links, pose.origins)
        self.joints.set_verts(self._joint_faces(pose))
        if self.frames is not None:
            self.frames.set_segments(self._frame_lines(pose.frames)[0])
        if self.tool_frame is not None:
            self.tool_frame.set_segments(self._frame_lines(pose.tool[None])[0])
        if self.tool_link is not None:
            self._set_line(self.tool_link, np.stack([pose.frames[-1, :3, 3], pose.tool[:3, 3]]))
        self._write_labels(pose)

    # -------------------------------------------------------------- internals
    def _label_texts(self, pose: ArmPose, count: int) -> tuple[list[str], FloatArray]:
        """The labels' texts and points: frames (in one place: one label), tool, W."""
        origins = pose.frames[:, :3, 3]
        texts = coincident_names(origins, self.scale)
        points = [origins]
        if len(texts) < count and self.has_tool and self.show_frames:
            texts.append("tool")
            points.append(pose.tool[None, :3, 3])
        if len(texts) < count:
            texts.append("W")
            points.append(np.zeros((1, 3)))
        return texts, np.concatenate(points)

    def _write_labels(self, pose: ArmPose) -> None:
        """Name the frames at this pose (the next draw places the labels)."""
        if self.placer is None:
            return
        texts, points = self._label_texts(pose, len(self.placer.labels))
        for label, text in zip(self.placer.labels, texts, strict=True):
            label.set_text(text)
        self.placer.set_points(self._project(points))

    def _shows_world(self) -> bool:
        """True when the world frame W is drawn (and named): a base transform moves S0."""
        return self.show_frames and not np.array_equal(self.robot.base, np.eye(4))

    def _project(self, pts: FloatArray) -> FloatArray:
        return pts if self.plane is None else pts[..., list(self.plane)]

    def _set_line(self, line: Any, pts: FloatArray) -> None:
        if self.plane is None:
            line.set_data_3d(pts[:, 0], pts[:, 1], pts[:, 2])
        else:
            xy = self._project(pts)
            line.set_data(xy[:, 0], xy[:, 1])

    def _collection(self, faces: list[FloatArray] | FloatArray, gid: str) -> Any:
        colors = [PRISMATIC_COLOR if p else REVOLUTE_COLOR for p in self.prismatic]
        per_face = [c for c, f in zip(colors, self._face_counts(), strict=True) for _ in range(f)]
        if self.plane is None:
            from mpl_toolkits.mplot3d.art3d import Poly3DCollection

            coll = Poly3DCollection(
                faces, facecolors=per_face, edgecolors="#00000040", linewidths=0.3, alpha=self.alpha
            )
            self.ax.add_collection3d(coll)
        else:
            from matplotlib.collections import PolyCollection

            coll = PolyCollection(
                list(faces),
                facecolors=per_face,
                edgecolors="#222222",
                linewidths=0.8,
                alpha=self.alpha,
            )
            coll.set_zorder(3)
            self.ax.add_collection(coll)
        coll.set_gid(gid)
        return coll

    def _face_counts(self) -> list[int]:
        if self.plane is not None:
            return [1] * self.robot.dof
        return [6 if p else 14 for p in self.prismatic]

    def _joint_faces(self, pose: ArmPose) -> list[FloatArray] | FloatArray:
        r = JOINT_RADIUS * self.scale
        faces: list[FloatArray] = []
        for frame, prismatic in zip(pose.joints, self.prismatic, strict=True):
            if self.plane is None:
                if prismatic:
                    faces.extend(box(frame, (r, r, 2.0 * r)))
                else:
                    faces.extend(cylinder(frame, r, 2.5 * r))
            elif prismatic:  # a rectangle along the (in-plane) axis
                o, z = frame[:3, 3], frame[:3, 2]
                u = self._project(z)
                w = np.array([-u[1], u[0]])
                c = self._project(o)
                faces.append(
                    np.array(
                        [
                            c + 2 * r * u + r * w,
                            c - 2 * r * u + r * w,
                            c - 2 * r * u - r * w,
                            c + 2 * r * u - r * w,
                        ]
                    )
                )
            else:  # the axis is normal to the plane: a disc
                ang = np.linspace(0.0, 2.0 * np.pi, 24, endpoint=False)
                c = self._project(frame[:3, 3])
                faces.append(c + 1.2 * r * np.stack([np.cos(ang), np.sin(ang)], axis=1))
        return faces if self.plane is not None else _padded(faces)

    def _frame_lines(self, frames: FloatArray) -> tuple[list[FloatArray], list[str]]:
        segs: list[FloatArray] = []
        colors: list[str] = []
        for frame, length in zip(frames, arrow_lengths(frames, self.scale), strict=True):
            arrows = arrow_segments(frame, length)
            for j in range(3):
                if self.plane is None:
                    segs.extend(arrows[j])
                    colors.extend([AXIS_COLORS[j]] * 3)
                    continue
                flat = self._project(arrows[j, 0])
                if np.linalg.norm(flat[1] - flat[0]) >= OUT_OF_PLANE * length:
                    segs.extend(_arrow_2d(flat[0], flat[1], length))
                    colors.extend([AXIS_COLORS[j]] * 3)
                    continue
                glyph = self._out_of_plane(frame, j, length)
                segs.extend(glyph)
                colors.extend([AXIS_COLORS[j]] * len(glyph))
        return segs, colors

    def _out_of_plane(self, frame: FloatArray, j: int, length: float) -> list[FloatArray]:
        """A circle with a dot (axis towards the viewer) or a cross (away), 2-D."""
        assert self.plane is not None
        c = self._project(frame[:3, 3])
        normal = 3 - sum(self.plane)
        toward = frame[normal, j] * plane_normal_sign(self.plane) > 0
        r = 0.22 * length
        ang = np.linspace(0.0, 2.0 * np.pi, 17)
        ring = c + r * np.stack([np.cos(ang), np.sin(ang)], axis=1)
        glyph = [ring[k : k + 2] for k in range(16)]
        if toward:
            dot = c + 0.25 * r * np.stack([np.cos(ang), np.sin(ang)], axis=1)
            glyph.extend(dot[k : k + 2] for k in range(16))
        else:
            d = 0.7 * r / np.sqrt(2.0)
            glyph.append(c + np.array([[-d, -d], [d, d]]))
            glyph.append(c + np.array([[-d, d], [d, -d]]))
        return glyph

    def _lines(self, segs: list[FloatArray], colors: list[str], lw: float, gid: str) -> Any:
        if self.plane is None:
            from mpl_toolkits.mplot3d.art3d import Line3DCollection

            coll = Line3DCollection(segs, colors=colors, linewidths=lw, alpha=self.alpha)
            self.ax.add_collection3d(coll)
        else:
            from matplotlib.collections import LineCollection

            coll = LineCollection(segs, colors=colors, linewidths=lw, alpha=self.alpha)
            coll.set_zorder(4)
            self.ax.add_collection(coll)
        coll.set_gid(gid)
        return coll

    def _draw_base(self) -> None:
        """A grey plate under S0 (in the world's horizontal plane), and the world frame W."""
        base = self.robot.base
        s = 0.08 * self.scale
        o = base[:3, 3]
        if self.plane is None:
            from mpl_toolkits.mplot3d.art3d import Poly3DCollection

            plate = o + np.array([[-s, -s, 0.0], [s, -s, 0.0], [s, s, 0.0], [-s, s, 0.0]])
            coll = Poly3DCollection([plate], facecolors=BASE_COLOR, alpha=0.6 * self.alpha)
            self.ax.add_collection3d(coll)
        else:
            from matplotlib.patches import Rectangle

            c = self._project(o)
            coll = Rectangle(
                (c[0] - s, c[1] - s / 2),
                2 * s,
                s / 2,
                facecolor=BASE_COLOR,
                edgecolor="#555555",
                hatch="///",
                alpha=self.alpha,
            )
            self.ax.add_patch(coll)
        coll.set_gid("base")
        if not self._shows_world():
            return
        segs, colors = self._frame_lines(np.eye(4)[None])
        self._lines(segs, colors, 1.0, "world-frame")
        ends = self._project(np.stack([np.zeros(3), o]))
        self.ax.plot(*ends.T, color=BASE_COLOR, lw=1.0, ls=":", alpha=self.alpha, gid="base-link")


def _padded(faces: list[FloatArray]) -> FloatArray:
    """3-D polygons ``(F, V, 3)`` of one vertex count: shorter ones repeat their last corner.

    matplotlib's ``Poly3DCollection`` pads polygons of unequal length with
    uninitialised memory and its autoscaling reads the padding (matplotlib
    3.11): a box (4 corners) beside a cylinder's faces (12) then put random
    numbers, sometimes ±1e308, into the axis limits. A repeated corner draws
    nothing.
    """
    size = max(len(f) for f in faces)
    out = np.empty((len(faces), size, 3))
    for i, f in enumerate(faces):
        out[i, : len(f)] = f
        out[i, len(f) :] = f[-1]
    return out
