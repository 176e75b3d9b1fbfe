"""Tick marks thinned to what fits: no two tick labels of an axis run together.

A small 3-D panel's axes are a hundred pixels long and drawn aslant, where
matplotlib's default of up to nine ticks prints "-0.2-0.10.00.1" as one word.
:class:`FittingLocator` chooses, when the axis is drawn, the most ticks whose
labels keep apart on the screen: two neighbouring labels, a step ``s`` of
data apart along an axis whose screen direction per unit of data is
``(ux, uy)``, do not meet when ``s·|ux|`` exceeds a label's width or
``s·|uy|`` its height.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from kinematica.viz._mpl import is_3d, matplotlib

__all__ = ["TICK_ROOM", "fit_ticks"]

FloatArray = NDArray[np.float64]

#: Room kept around a tick label, as a factor of its estimated size: the estimate
#: (0.62 of the font size a character) is a little wide for digits and short for "-".
TICK_ROOM = 1.35
#: Most ticks on an axis (matplotlib's own default).
MAX_TICKS = 9


def _label_size(ax: Any, axis: Any, ticks: Any, size: float) -> tuple[float, float]:
    """Estimated ``(width, height)`` in pixels of the widest of ``ticks``' labels (``size`` pt)."""
    px = size * ax.figure.dpi / 72.0
    formatter = axis.get_major_formatter()
    formatter.set_locs(ticks)
    chars = max((len(formatter(v)) for v in ticks), default=1)
    return 0.62 * px * chars * TICK_ROOM, 1.2 * px * TICK_ROOM


def _screen_step(ax: Any, index: int, lo: float, hi: float) -> tuple[float, float]:
    """``(|ux|, |uy|)``: pixels on the screen per unit of data along axis ``index``."""
    if not is_3d(ax):
        box = ax.get_window_extent()
        span = box.width if index == 0 else box.height
        d = span / (hi - lo)
        return (d, 0.0) if index == 0 else (0.0, d)
    from mpl_toolkits.mplot3d import proj3d

    M = ax.M if getattr(ax, "M", None) is not None else ax.get_proj()
    limits = [ax.get_xlim3d(), ax.get_ylim3d(), ax.get_zlim3d()]
    mid = np.array([sum(v) / 2.0 for v in limits])
    a, b = mid.copy(), mid.copy()
    a[index], b[index] = lo, hi
    x, y, _ = proj3d.proj_transform(*np.stack([a, b]).T, M)
    px = ax.transData.transform(np.stack([x, y], axis=1))
    d = np.abs(px[1] - px[0]) / (hi - lo)
    return float(d[0]), float(d[1])


def _fitting_locator_class() -> Any:
    matplotlib()
    from matplotlib.ticker import MaxNLocator

    class FittingLocator(MaxNLocator):
        """MaxNLocator with the most bins whose labels keep apart on the screen."""

        def __init__(self, ax: Any, index: int, size: float) -> None:
            super().__init__(nbins=MAX_TICKS, steps=[1, 2, 2.5, 5, 10])
            self._ax, self._index, self._size = ax, index, size

        def tick_values(self, vmin: float, vmax: float) -> Any:
            lo, hi = sorted((float(vmin), float(vmax)))
            ticks: FloatArray
            if not hi > lo:
                return super().tick_values(vmin, vmax)
            ux, uy = _screen_step(self._ax, self._index, lo, hi)
            axis = (self._ax.xaxis, self._ax.yaxis, getattr(self._ax, "zaxis", None))[self._index]
            for bins in range(MAX_TICKS, 1, -1):
                self.set_params(nbins=bins)
                ticks = np.asarray(super().tick_values(vmin, vmax), dtype=float)
                inside = ticks[(ticks >= lo - 1e-9 * (hi - lo)) & (ticks <= hi + 1e-9 * (hi - lo))]
                if len(inside) < 2:
                    return ticks
                w, h = _label_size(self._ax, axis, inside, self._size)
                step = float(np.min(np.diff(np.sort(inside))))
                if step * ux > w or step * uy > h:
                    break
            else:  # not even two labels fit: the one nearest the middle
                return inside[[int(np.argmin(np.abs(inside - (lo + hi) / 2)))]]
            if not is_3d(self._ax):
                return ticks
            # a 3-D axis meets the next one at a corner of the box, where their end
            # labels would touch: none within half a label of either end
            room = 0.5 * min(w / ux if ux > 0 else np.inf, h / uy if uy > 0 else np.inf)
            keep = (ticks >= lo + room) & (ticks <= hi - room)
            return ticks[keep] if keep.sum() >= 2 else ticks

    return FittingLocator


def fit_ticks(ax: Any, size: float = 8.0) -> None:
    """Tick labels of ``size`` points on every axis of ``ax`` (2-D or 3-D), thinned to fit."""
    locator = _fitting_locator_class()
    ax.tick_params(labelsize=size)
    axes = [ax.xaxis, ax.yaxis] + ([ax.zaxis] if is_3d(ax) else [])
    for index, axis in enumerate(axes):
        axis.set_major_locator(locator(ax, index, size))
