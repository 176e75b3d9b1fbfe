"""matplotlib, imported when a picture is drawn: backend choice, figures, equal axes.

Nothing here runs at import time. :func:`pyplot` picks the headless ``Agg``
backend when there is no display (and no backend was chosen by the user), so
pictures can be written on a server or in CI.
"""

from __future__ import annotations

import os
import sys
from typing import Any

import numpy as np
from numpy.typing import NDArray

from kinematica.arguments import check_count, check_number, check_size
from kinematica.errors import ArgumentError, KinematicaError

__all__ = [
    "MAX_DPI",
    "MAX_PIXELS",
    "MAX_SIDE",
    "MIN_DPI",
    "MIN_SIDE",
    "VizError",
    "check_picture",
    "equal_limits",
    "figure",
    "is_3d",
    "matplotlib",
    "new_axes",
    "pyplot",
]

FloatArray = NDArray[np.float64]

#: Extra room around the drawn points, as a fraction of the largest extent.
MARGIN = 0.08
#: Narrowest side of a picture's box, as a fraction of its widest.
MIN_BOX_SIDE = 0.35
#: Smallest and largest side of a picture (pixels; Agg refuses 2^16 and more).
MIN_SIDE, MAX_SIDE = 16, 20_000
#: Most pixels in a picture: 40 megapixels are 160 MB of RGBA while it is drawn.
MAX_PIXELS = 40_000_000
#: Dots per inch, which scale text and lines against the picture's pixels: at 10
#: a 10-point label is 1.4 pixels high, at 2400 it is wider than a 330-pixel panel.
MIN_DPI, MAX_DPI = 10.0, 2400.0


class VizError(KinematicaError):
    """A picture cannot be drawn or written as asked (missing extra, bad format...)."""


def matplotlib() -> Any:
    """The ``matplotlib`` module, or a :class:`VizError` saying how to install it."""
    try:
        import matplotlib as mpl
    except ImportError as exc:  # pragma: no cover - the test extra installs it
        raise VizError("pictures need matplotlib: pip install 'kinematica[viz]'") from exc
    return mpl


def _headless() -> bool:
    if sys.platform in ("darwin", "win32"):
        return False
    return not (os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


def pyplot() -> Any:
    """``matplotlib.pyplot``, on the Agg backend when there is no display."""
    mpl = matplotlib()
    if "matplotlib.pyplot" not in sys.modules and not os.environ.get("MPLBACKEND") and _headless():
        mpl.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def check_picture(size: object, dpi: object) -> tuple[tuple[int, int] | None, float]:
    """``size`` (``(width, height)`` pixels, or ``None``) and ``dpi``, checked.

    Raises:
        ArgumentError: A side outside MIN_SIDE..MAX_SIDE, more than MAX_PIXELS
            in all, or ``dpi`` outside MIN_DPI..MAX_DPI (``arg`` says which).
    """
    checked = None
    if size is not None:
        if not isinstance(size, tuple | list | np.ndarray) or len(size) != 2:
            raise ArgumentError(f"size must be (width, height) in pixels, got {size!r}", arg="size")
        w, h = (check_count(v, "size", lo=MIN_SIDE, hi=MAX_SIDE) for v in size)
        check_size(w * h, MAX_PIXELS, "size", "pixels")
        checked = (w, h)
    dots = check_number(dpi, "dpi", lo=MIN_DPI, hi=MAX_DPI, what="a number of dots per inch")
    return checked, dots


def figure(width_px: int, height_px: int, dpi: float, *, pyplot_managed: bool) -> Any:
    """A new Figure of ``width_px`` x ``height_px`` pixels.

    Args:
        width_px: Width in pixels (``figsize * dpi``).
        height_px: Height in pixels.
        dpi: Dots per inch.
        pyplot_managed: Create it through pyplot (so ``plt.show()`` displays
            it), or as a bare Figure that is only saved (command line, files).
    """
    check_picture((width_px, height_px), dpi)
    size = (width_px / dpi, height_px / dpi)
    if pyplot_managed:
        return pyplot().figure(figsize=size, dpi=dpi)
    matplotlib()
    from matplotlib.figure import Figure

    return Figure(figsize=size, dpi=dpi)


def new_axes(fig: Any, three_d: bool, *args: Any) -> Any:
    """Add an Axes (3-D or 2-D) to ``fig``; ``args`` as ``add_subplot`` takes them."""
    if three_d:
        import mpl_toolkits.mplot3d  # noqa: F401  (registers the 3d projection)

        return fig.add_subplot(*(args or (1, 1, 1)), projection="3d")
    return fig.add_subplot(*(args or (1, 1, 1)))


def is_3d(ax: Any) -> bool:
    """True for an ``Axes3D``."""
    return getattr(ax, "name", "") == "3d"


def equal_limits(
    ax: Any, points: FloatArray, plane: tuple[int, int] | None = None, zoom: float = 1.0
) -> None:
    """Equal scaling on every axis, the box shaped like the points' extent.

    Each axis spans the points' extent with a :data:`MARGIN` (at least
    :data:`MIN_BOX_SIDE` of the widest, so an arm standing straight up is not
    drawn in a sliver); the box's sides (3-D ``box_aspect``, 2-D ``aspect``
    ``"equal"``) are in proportion to the spans, so a metre has one length on
    every axis and the arm fills the panel instead of a cube around it.

    Args:
        ax: The Axes.
        points: ``(N, 3)`` points that must be visible (metres, world frame).
        plane: For a 2-D Axes, the two world coordinates shown (e.g. ``(0, 1)``).
        zoom: Size of a 3-D box in its panel (matplotlib's ``zoom``).
    """
    pts = np.asarray(points, dtype=float).reshape(-1, 3)
    pts = pts[np.all(np.isfinite(pts), axis=1)]
    if pts.size == 0:
        pts = np.zeros((1, 3))
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    centre = (lo + hi) / 2.0
    cols = list(plane) if plane is not None else [0, 1, 2]
    half = (hi[cols] - lo[cols]) / 2.0
    widest = float(np.max(half))
    if widest <= 0:
        half = np.full(len(cols), 0.5)
    else:
        half = np.maximum(half + MARGIN * widest, MIN_BOX_SIDE * widest)
    setters = (ax.set_xlim, ax.set_ylim, getattr(ax, "set_zlim", None))
    for setter, col, h in zip(setters, cols, half, strict=False):
        setter(centre[col] - h, centre[col] + h)
    if is_3d(ax):
        ax.set_box_aspect(tuple(float(h) for h in half), zoom=zoom)
    else:
        ax.set_aspect("equal", adjustable="box")
