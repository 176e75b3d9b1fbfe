"""A picture of a redundant arm's self-motion: each joint against the parameter.

One panel per joint; each family is one line (its colour and branch in the
legend), the values beyond the joint's own limits shaded. matplotlib is imported
only when a picture is drawn (the ``viz`` extra).
"""

from __future__ import annotations

import math
import os
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from kinematica.robot.self_motion import SelfMotion
from kinematica.viz._mpl import figure, matplotlib
from kinematica.viz.plot import save_figure

__all__ = ["save_self_motion"]

#: The width of the picture (pixels) and the height of one joint's panel.
WIDTH, PANEL_HEIGHT = 1000, 150
#: The legend's columns, and the height of one of its rows (pixels).
LEGEND_COLUMNS, LEGEND_ROW = 2, 17
#: Line styles, one per round of the 20 colours (families beyond 20 repeat a colour).
STYLES = ("-", "--", ":", "-.")

FloatArray = NDArray[np.float64]


def save_self_motion(
    motion: SelfMotion,
    path: str | os.PathLike[str],
    *,
    degrees: bool = True,
    prismatic: tuple[bool, ...] | None = None,
    dpi: float = 100.0,
) -> Path:
    """Each joint against the parameter, one line per family, into ``path`` (PNG, SVG...).

    Args:
        motion: The self-motion.
        path: The file; its suffix says the type.
        degrees: Angles in degrees (else radians), the parameter's too when it is one.
        prismatic: ``(n,)`` True for the joints drawn in metres (all angles if None).
        dpi: Dots per inch.
    """
    n = motion.qlim.shape[0]
    slides = prismatic or (False,) * n
    # the parameter's own joint is a straight line against itself: not drawn
    joints = [j for j in range(n) if motion.joint_names[j] != motion.parameter]
    scale = [1.0 if p or not degrees else 180.0 / math.pi for p in slides]
    unit = ["m" if p else ("deg" if degrees else "rad") for p in slides]
    pscale = 180.0 / math.pi if degrees and motion.unit == "rad" else 1.0
    punit = "deg" if degrees and motion.unit == "rad" else motion.unit
    count = len(motion.families)
    legend_rows = math.ceil(count / LEGEND_COLUMNS)
    legend_px = LEGEND_ROW * legend_rows + 30
    height = PANEL_HEIGHT * len(joints) + 90 + legend_px
    fig = figure(WIDTH, height, dpi, pyplot_managed=False)
    fig.subplots_adjust(top=1.0 - 50 / height, bottom=(legend_px + 45) / height, hspace=0.15)
    x = motion.values * pscale
    colours = matplotlib().colormaps["tab20"]
    axes = np.atleast_1d(fig.subplots(len(joints), 1, sharex=True))
    for ax, j in zip(axes, joints, strict=True):
        for i, fam in enumerate(motion.families):
            xs, y = x, fam.q[:, j] * scale[j]
            if not slides[j]:  # a turn wrapped across ±π: a break in the line, not a jump
                xs, y = _broken(x, y, math.pi * scale[j])
            label = f"{i + 1}: {fam.branch}" if ax is axes[0] else None
            style = STYLES[(i // 20) % len(STYLES)]
            ax.plot(xs, y, color=colours(i % 20), ls=style, lw=1.4, label=label)
        lo, hi = motion.qlim[j] * scale[j]
        y0, y1 = ax.get_ylim()
        y0 = min(y0, lo) if math.isfinite(lo) else y0
        y1 = max(y1, hi) if math.isfinite(hi) else y1
        pad = 0.05 * (y1 - y0)
        if math.isfinite(hi):
            ax.axhspan(hi, y1 + pad, color="0.85", zorder=0)
        if math.isfinite(lo):
            ax.axhspan(y0 - pad, lo, color="0.85", zorder=0)
        ax.set_ylim(y0 - pad, y1 + pad)
        ax.set_ylabel(f"{motion.joint_names[j]} ({unit[j]})")
        ax.grid(True, lw=0.3)
    axes[-1].set_xlim(x[0], x[-1])  # the whole sweep, where families are or are not
    axes[-1].set_xlabel(f"{motion.parameter} ({punit})")
    fig.suptitle(
        f"self-motion over {motion.parameter}: {count} families ({motion.method}); "
        "grey: beyond the joint limits",
        y=1.0 - 12 / height,
    )
    if count:
        fig.legend(loc="lower center", fontsize="small", ncol=LEGEND_COLUMNS, frameon=False)
    return save_figure(fig, path)


def _broken(x: FloatArray, y: FloatArray, half_turn: float) -> tuple[FloatArray, FloatArray]:
    """``(x, y)`` with a NaN point put between adjacent ``y`` more than half a turn apart."""
    with np.errstate(invalid="ignore"):
        jump = np.flatnonzero(np.abs(np.diff(y)) > half_turn) + 1
    if not jump.size:
        return x, y
    return np.insert(x, jump, x[jump]), np.insert(y, jump, np.nan)
