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

from kinematica.robot.self_motion import SelfMotion
from kinematica.viz._mpl import figure
from kinematica.viz.plot import save_figure

__all__ = ["save_self_motion"]

#: The width of the picture (pixels) and the height of one joint's panel.
WIDTH, PANEL_HEIGHT = 900, 150


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
    scale = [1.0 if p or not degrees else 180.0 / math.pi for p in slides]
    unit = ["m" if p else ("deg" if degrees else "rad") for p in slides]
    pscale = 180.0 / math.pi if degrees and motion.unit == "rad" else 1.0
    punit = "deg" if degrees and motion.unit == "rad" else motion.unit
    fig = figure(WIDTH, PANEL_HEIGHT * n + 120, dpi, pyplot_managed=False)
    x = motion.values * pscale
    axes = fig.subplots(n, 1, sharex=True)
    colours = [f"C{i % 10}" for i in range(len(motion.families))]
    for j, ax in enumerate(np.atleast_1d(axes)):
        lo, hi = motion.qlim[j] * scale[j]
        top = hi if math.isfinite(hi) else None
        bottom = lo if math.isfinite(lo) else None
        for i, fam in enumerate(motion.families):
            label = f"{i + 1}: {fam.branch}" if j == 0 else None
            ax.plot(x, fam.q[:, j] * scale[j], color=colours[i], lw=1.4, label=label)
        y0, y1 = ax.get_ylim()
        if top is not None:
            y1 = max(y1, top)
            ax.axhspan(top, y1 + 0.05 * (y1 - y0), color="0.85", zorder=0)
        if bottom is not None:
            y0 = min(y0, bottom)
            ax.axhspan(y0 - 0.05 * (y1 - y0), bottom, color="0.85", zorder=0)
        ax.set_ylim(y0 - 0.05 * (y1 - y0), y1 + 0.05 * (y1 - y0))
        ax.set_ylabel(f"{motion.joint_names[j]} ({unit[j]})")
        ax.grid(True, lw=0.3)
    last = np.atleast_1d(axes)[-1]
    last.set_xlabel(f"{motion.parameter} ({punit})")
    fig.suptitle(
        f"self-motion over {motion.parameter}: {len(motion.families)} families "
        f"({motion.method}); grey: beyond the joint limits"
    )
    if motion.families:
        fig.legend(loc="upper right", fontsize="small", ncol=min(4, len(motion.families)))
    return save_figure(fig, path)
