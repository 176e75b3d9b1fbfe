"""Labels placed where they can be read: each beside its own point, none over another.

One rule for every static picture (the arm, its frames, the tool, the world
frame W), the rule of the interactive page made two-dimensional: labels are
placed in order, each in the first of the places around its point, nearest
first, where its box meets no box already placed. A label that had to move
away from its point gets a thin leader line to it.

The places are found when the picture is drawn, from the points projected with
the view of that moment, so a 3-D view that is turned or resized (or an
animation's next frame) places its labels again. :class:`LabelPlacer` is an
invisible artist drawn before the labels (lowest ``zorder``) that moves them.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from kinematica.viz._mpl import is_3d, matplotlib

__all__ = ["LABEL_GAP", "LABEL_RINGS", "LabelPlacer", "place_boxes"]

FloatArray = NDArray[np.float64]

#: Gap (in points, 1/72 in) between a label's box and its point, and around every box.
LABEL_GAP = 2.0
#: Rings of places tried around a point, each a line height further out, before the
#: place whose box overlaps the placed ones least is taken.
LABEL_RINGS = 12
#: The directions tried in each ring: below-right first (the page's place), then the
#: other corners, then the sides; (ha, va) anchor the box's nearest corner or edge.
_DIRECTIONS = (
    ((1.0, -1.0), "left", "top"),
    ((1.0, 1.0), "left", "bottom"),
    ((-1.0, -1.0), "right", "top"),
    ((-1.0, 1.0), "right", "bottom"),
    ((1.0, 0.0), "left", "center"),
    ((-1.0, 0.0), "right", "center"),
    ((0.0, -1.0), "center", "top"),
    ((0.0, 1.0), "center", "bottom"),
)


def _box(anchor: FloatArray, size: FloatArray, offset: FloatArray, ha: str, va: str) -> FloatArray:
    """``(x0, y0, x1, y1)`` of a box of ``size`` placed at ``anchor + offset`` (pixels)."""
    x, y = anchor + offset
    w, h = size
    x0 = x if ha == "left" else (x - w if ha == "right" else x - w / 2)
    y0 = y if va == "bottom" else (y - h if va == "top" else y - h / 2)
    return np.array([x0, y0, x0 + w, y0 + h])


def _overlap(a: FloatArray, b: FloatArray) -> float:
    """Area shared by the boxes ``a`` and ``b`` (``(x0, y0, x1, y1)``)."""
    w = min(a[2], b[2]) - max(a[0], b[0])
    h = min(a[3], b[3]) - max(a[1], b[1])
    return float(w * h) if w > 0 and h > 0 else 0.0


def place_boxes(
    anchors: FloatArray, sizes: FloatArray, gap: float, window: FloatArray | None = None
) -> list[tuple[FloatArray, str, str, int]]:
    """Where each label goes: the placement rule, in pixels, without matplotlib.

    Args:
        anchors: ``(K, 2)`` the labels' points (pixels).
        sizes: ``(K, 2)`` width and height of each label's box (pixels).
        gap: Space kept between a box and its point and around every box (pixels).
        window: ``(x0, y0, x1, y1)`` the boxes should stay inside, or ``None``.

    Returns:
        For each label in order: its offset from its point ``(2,)`` (pixels),
        the alignment ``(ha, va)`` of its box at that offset, and the ring it
        took (0: beside its point).
    """
    placed: list[FloatArray] = []
    out: list[tuple[FloatArray, str, str, int]] = []
    for anchor, size in zip(anchors, sizes, strict=True):
        step = size[1] + gap
        best: tuple[float, FloatArray, str, str, int] | None = None
        for ring in range(LABEL_RINGS):
            for (dx, dy), ha, va in _DIRECTIONS:
                offset = np.array([dx, dy]) * (gap + ring * step)
                box = _box(anchor, size, offset, ha, va)
                padded = box + np.array([-gap, -gap, gap, gap])
                cost = sum(_overlap(padded, other) for other in placed)
                if window is not None:  # area outside the window counts as overlap
                    inside = _overlap(box, window)
                    cost += float((box[2] - box[0]) * (box[3] - box[1])) - inside
                if best is None or cost < best[0]:
                    best = (cost, offset, ha, va, ring)
                if cost == 0.0:
                    break
            if best is not None and best[0] == 0.0:
                break
        assert best is not None
        _, offset, ha, va, ring = best
        placed.append(_box(anchor, size, offset, ha, va))
        out.append((offset, ha, va, ring))
    return out


def _artist_base() -> Any:
    matplotlib()
    from matplotlib.artist import Artist

    return Artist


class LabelPlacer:
    """Labels of points on one Axes (3-D or 2-D), placed again at every draw.

    Args:
        ax: The Axes.
        texts: The labels' texts (empty for a label not shown).
        points: ``(K, 3)`` their points (world frame, m); for a 2-D Axes, the
            two shown coordinates ``(K, 2)``.
        gids: One ``gid`` per label (``"label-S4"``...); its leader line is
            ``"leader-" + gid``.
        style: Keyword arguments of every label's :class:`~matplotlib.text.Annotation`.

    Each label is an Annotation whose ``xy`` is its point (projected into the
    Axes' 2-D data coordinates in 3-D) and whose text is offset from it
    (``textcoords="offset points"``).
    """

    def __init__(
        self,
        ax: Any,
        texts: list[str],
        points: FloatArray,
        gids: list[str],
        style: dict[str, Any],
    ) -> None:
        self.ax = ax
        self.points = np.asarray(points, dtype=float)
        self.labels = [
            ax.annotate(
                text,
                xy=(0.0, 0.0),
                xytext=(0.0, 0.0),
                textcoords="offset points",
                annotation_clip=False,
                gid=gid,
                **style,
            )
            for text, gid in zip(texts, gids, strict=True)
        ]
        from matplotlib.lines import Line2D
        from matplotlib.transforms import IdentityTransform

        alpha = style.get("alpha", 1.0)
        self.leaders = []
        for gid in gids:
            line = Line2D([], [], lw=0.6, color="#555555", alpha=alpha, gid=f"leader-{gid}")
            line.set_transform(IdentityTransform())
            line.set_visible(False)
            ax.add_artist(line)
            self.leaders.append(line)
        self._artist = _placing_artist(self)
        ax.add_artist(self._artist)
        self._project()

    def set_points(self, points: FloatArray) -> None:
        """Move the labels' points (the next draw places them again)."""
        self.points = np.asarray(points, dtype=float)
        self._project()

    def anchors(self) -> FloatArray:
        """``(K, 2)`` the labels' points in the Axes' 2-D data coordinates (projected in 3-D)."""
        if not is_3d(self.ax):
            return self.points[:, :2].copy()
        from mpl_toolkits.mplot3d import proj3d

        M = self.ax.M if getattr(self.ax, "M", None) is not None else self.ax.get_proj()
        x, y, _ = proj3d.proj_transform(*self.points.T, M)
        return np.stack([np.asarray(x, dtype=float), np.asarray(y, dtype=float)], axis=1)

    def _project(self) -> None:
        for label, xy in zip(self.labels, self.anchors(), strict=True):
            label.xy = (float(xy[0]), float(xy[1]))

    def place(self, renderer: Any) -> None:
        """Place every label for the view of this draw (called by the placing artist)."""
        from matplotlib.text import Text

        shown = [k for k, label in enumerate(self.labels) if label.get_text()]
        self._project()
        for line in self.leaders:
            line.set_visible(False)
        if not shown:
            return
        to_px = self.ax.transData
        anchors = to_px.transform(np.array([self.labels[k].xy for k in shown]))
        sizes = []
        for k in shown:
            label = self.labels[k]
            label.set_position((0.0, 0.0))
            label.update_positions(renderer)
            box = Text.get_window_extent(label, renderer)
            sizes.append((box.width, box.height))
        px_per_pt = renderer.points_to_pixels(1.0)
        gap = LABEL_GAP * px_per_pt
        bbox = self.ax.bbox
        window = np.array([bbox.x0, bbox.y0, bbox.x1, bbox.y1])
        places = place_boxes(anchors, np.array(sizes), gap, window)
        for k, anchor, (offset, ha, va, ring) in zip(shown, anchors, places, strict=True):
            label = self.labels[k]
            label.set_horizontalalignment(ha)
            label.set_verticalalignment(va)
            label.set_position(tuple(offset / px_per_pt))
            if ring > 0:  # far from its point: a leader line from the point to the box
                placed = _box(anchor, np.array(sizes[shown.index(k)]), offset, ha, va)
                near = np.clip(anchor, placed[:2], placed[2:])
                self.leaders[k].set_data([anchor[0], near[0]], [anchor[1], near[1]])
                self.leaders[k].set_visible(True)


def _placing_artist(placer: LabelPlacer) -> Any:
    """An invisible artist, drawn first on its Axes, that places ``placer``'s labels."""
    base = _artist_base()

    class _Placing(base):  # type: ignore[misc, valid-type]
        zorder = -1e9

        def draw(self, renderer: Any) -> None:
            placer.place(renderer)
            self.stale = False

        def get_window_extent(self, renderer: Any = None) -> Any:
            from matplotlib.transforms import Bbox

            return Bbox.null()

        def get_tightbbox(self, renderer: Any = None) -> Any:
            return None

    artist = _Placing()
    artist.set_gid("label-placer")
    return artist
