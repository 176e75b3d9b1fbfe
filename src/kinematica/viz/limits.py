"""A timed joint trajectory against its limits: q, q̇, q̈ (and the jerk) over time.

One row per derivative, one colour per joint; each limit is drawn as a
dashed line at ``±limit`` in its joint's colour, so a curve that touches its
dashes is at its limit (as a time-optimal or jerk-limited move is in each of
its phases) and one that crosses them breaks it.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.errors import DimensionError
from kinematica.motion.trajectory import JointTrajectory
from kinematica.viz._mpl import figure
from kinematica.viz.plot import save_figure

__all__ = ["plot_limits", "save_limits"]

FloatArray = NDArray[np.float64]

_ROWS = (
    ("position", "q (rad, m)"),
    ("velocity", "q̇ (rad/s, m/s)"),
    ("acceleration", "q̈ (rad/s², m/s²)"),
    ("jerk", "q⃛ (rad/s³, m/s³)"),
)


def _limit(x: ArrayLike | None, n: int, name: str) -> FloatArray | None:
    if x is None:
        return None
    a = np.broadcast_to(np.asarray(x, dtype=float), (n,))
    if not np.all(a > 0):
        raise DimensionError(f"{name} must be {n} positive limits (or one for all)")
    return np.asarray(a)


def plot_limits(
    traj: JointTrajectory,
    *,
    vmax: ArrayLike | None = None,
    amax: ArrayLike | None = None,
    jmax: ArrayLike | None = None,
    fig: Any = None,
    title: str = "",
) -> Any:
    """Joint values, velocities, accelerations and (if known) jerks over time.

    Args:
        traj: The trajectory; a :class:`~kinematica.motion.scurve.JerkTrajectory`
            adds its jerk row and brings its own limits.
        vmax: ``(n,)`` speed limits (or one number) drawn as dashed ``±vmax``
            lines; the trajectory's own when ``None`` and it has them.
        amax: Acceleration limits, likewise.
        jmax: Jerk limits, likewise (drawn when the trajectory has a jerk).
        fig: A Figure to draw on (empty); a new 1000 x 900 pixel one if ``None``.
        title: The figure's title.

    Returns:
        The Figure; its Axes are ``position``, ``velocity``, ``acceleration``
        (and ``jerk``) by label, each joint's curve with ``gid`` ``q1``... and
        its limit lines with ``gid`` ``q1-limit``...; through waypoints a
        dotted line (``gid="waypoint"``) at each waypoint's time. The jerk
        of a jerk-limited move is drawn from its exact pieces.
    """
    t, q = traj.t, traj.q
    if q.ndim != 2 or t.shape != (q.shape[0],):
        raise DimensionError(f"a trajectory has t (m,) and q (m, n), got {t.shape}, {q.shape}")
    n = q.shape[1]
    jerk = getattr(traj, "qddd", None)
    own = (getattr(traj, name, None) for name in ("vmax", "amax", "jmax"))
    given = (vmax, amax, jmax)
    lims = [
        _limit(g if g is not None else o, n, nm)
        for g, o, nm in zip(given, own, ("vmax", "amax", "jmax"), strict=True)
    ]
    series: list[tuple[FloatArray, FloatArray | None]] = [
        (q, None),
        (traj.qd, lims[0]),
        (traj.qdd, lims[1]),
    ]
    if jerk is not None:
        series.append((jerk, lims[2]))
    if fig is None:
        fig = figure(1000, 220 * len(series) + 120, 100, pyplot_managed=False)
    axes = fig.subplots(len(series), 1, sharex=True, squeeze=False)[:, 0]
    colours = [f"C{j % 10}" for j in range(n)]
    waypoints = getattr(traj, "waypoint_times", None)
    pieces = getattr(traj, "pieces", None)
    for ax, (values, lim), (label, ylabel) in zip(axes, series, _ROWS, strict=False):
        ax.set_label(label)
        x = t
        if label == "jerk" and pieces is not None:
            # piecewise constant: steps at the exact switch times, not ramps between samples
            x = pieces.breaks
            values = np.vstack([pieces(x[:-1], 3), pieces(x[-1:], 3, left=True)])
        for j in range(n):
            style = {"color": colours[j], "lw": 1.3, "label": f"q{j + 1}", "gid": f"q{j + 1}"}
            if label == "jerk":
                ax.step(x, values[:, j], where="post", **style)
            else:
                ax.plot(x, values[:, j], **style)
            if lim is not None:
                for sign in (1.0, -1.0):
                    ax.axhline(
                        sign * lim[j],
                        color=colours[j],
                        ls="--",
                        lw=0.8,
                        alpha=0.7,
                        gid=f"q{j + 1}-limit",
                    )
        for tw in () if waypoints is None else waypoints:
            ax.axvline(tw, color="0.5", lw=0.8, ls=":", gid="waypoint")
        ax.set_ylabel(ylabel, fontsize=9)
        ax.grid(True, lw=0.4, alpha=0.5)
    axes[0].legend(fontsize=7, ncol=min(n, 7), loc="upper left", bbox_to_anchor=(0.0, 1.28))
    axes[-1].set_xlabel("t (s)")
    kind = "jerk-limited" if jerk is not None else "timed"
    head = f"{title}: " if title else ""
    dotted = "" if waypoints is None else "; dotted: waypoints"
    fig.suptitle(
        f"{head}{kind} trajectory, {float(t[-1]):.4g} s; dashed: ±limits{dotted}", fontsize=11
    )
    fig.subplots_adjust(left=0.09, right=0.98, bottom=0.07, top=0.9, hspace=0.12)
    return fig


def save_limits(traj: JointTrajectory, path: str | os.PathLike[str], **kwargs: Any) -> Path:
    """:func:`plot_limits` into a file (PNG, SVG, PDF...); ``kwargs`` as there."""
    return save_figure(plot_limits(traj, **kwargs), path)
