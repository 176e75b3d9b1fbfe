"""Pictures of reachability maps and base placements (matplotlib, the ``viz`` extra).

:func:`plot_reachability` draws a map as three slices through the reach ball's
centre, coloured by the reachability index (the dexterous voxels at 1), beside
a 3-D view of the reachable voxels; a planar arm's map is its one plane.
:func:`plot_placement` draws a base-placement search from above: the feasible
base positions coloured by the worst manipulability over the task (the best
yaw at each), the best base, and the task's positions.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from kinematica.reach import BasePlacement, ReachabilityMap
from kinematica.viz._mpl import figure, new_axes
from kinematica.viz.plot import save_figure
from kinematica.viz.ticks import fit_ticks

__all__ = ["plot_placement", "plot_reachability", "save_placement_plot", "save_reachability_plot"]

#: Most voxels the 3-D view draws (a random, seeded choice above it).
MAX_DRAWN_VOXELS = 40_000
#: Picture size (pixels) and dots per inch.
WIDTH, HEIGHT, DPI = 1500, 1100, 110


def _slice_panel(ax: Any, m: ReachabilityMap, plane: str, fig: Any) -> Any:
    sl = m.slice(plane)
    shown = np.where(sl.index > 0, sl.index, np.nan)
    im = ax.imshow(
        shown.T, origin="lower", extent=sl.extent, cmap="viridis", vmin=0.0, vmax=1.0,
        interpolation="nearest",
    )  # fmt: skip
    ax.set_xlabel(f"{sl.plane[0]} (m)")
    ax.set_ylabel(f"{sl.plane[1]} (m)")
    third = ({"x", "y", "z"} - set(sl.plane)).pop()
    ax.set_title(f"{sl.plane} slice, {third} = {sl.at:.3f} m", fontsize=10)
    ax.set_aspect("equal")
    return im


def plot_reachability(m: ReachabilityMap, title: str = "") -> Any:
    """A figure of the map: slices through the reach centre and a 3-D view.

    Args:
        m: The map.
        title: A title line (the robot, the orientations and the volumes are added).

    Returns:
        The matplotlib Figure (not managed by pyplot).
    """
    fig = figure(WIDTH, HEIGHT, DPI, pyplot_managed=False)
    what = (
        "positions only"
        if m.orientations.shape[0] == 0
        else f"{m.count} orientations"
        + (
            ""
            if m.approach is None
            else f" within {np.degrees(m.approach[1]):.0f}° of the approach"
        )
    )
    unit = "m²" if m.plane is not None else "m³"
    head = f"{title}\n" if title else ""
    fig.suptitle(
        f"{head}{m.robot}: reachability index, {what} per voxel of {m.resolution:g} m\n"
        f"reachable {m.reachable_volume:.4g} {unit}, dexterous {m.dexterous_volume:.4g} {unit}",
        fontsize=11,
    )
    if m.plane is not None:
        ax = new_axes(fig, False)
        im = _slice_panel(ax, m, "xy", fig)
        fig.colorbar(im, ax=ax, label="reachability index (1: dexterous)")
        return fig
    fig.subplots_adjust(right=0.86, wspace=0.3, hspace=0.3)
    im = None
    for k, plane in enumerate(("xy", "xz", "yz")):
        im = _slice_panel(new_axes(fig, False, 2, 2, k + 1), m, plane, fig)
    ax3 = new_axes(fig, True, 2, 2, 4)
    # cut away the half y > centre: the inside of the reachable set shows
    cut = m.reachable & (m.centres()[..., 1] <= m.centre[1])
    centres = m.centres()[cut]
    index = m.index[cut]
    if centres.shape[0] > MAX_DRAWN_VOXELS:
        pick = np.random.default_rng(0).choice(centres.shape[0], MAX_DRAWN_VOXELS, replace=False)
        centres, index = centres[pick], index[pick]
    if centres.size:
        ax3.scatter(
            centres[:, 0], centres[:, 1], centres[:, 2], c=index, cmap="viridis",
            vmin=0.0, vmax=1.0, s=6, alpha=0.6, linewidths=0,
        )  # fmt: skip
        lo, hi = centres.min(axis=0), centres.max(axis=0)
        half = float(np.max(hi - lo)) / 2 + m.resolution
        mid = (lo + hi) / 2
        ax3.set_xlim(mid[0] - half, mid[0] + half)
        ax3.set_ylim(mid[1] - half, mid[1] + half)
        ax3.set_zlim(mid[2] - half, mid[2] + half)
        ax3.view_init(elev=20, azim=-60)
    ax3.set_xlabel("x (m)")
    ax3.set_ylabel("y (m)")
    ax3.set_zlabel("z (m)")
    fit_ticks(ax3)
    ax3.set_title(f"reachable voxels, y ≤ {m.centre[1]:.3g} m (the rest cut away)", fontsize=10)
    if im is not None:
        cax = fig.add_axes((0.89, 0.15, 0.015, 0.7))
        fig.colorbar(im, cax=cax, label="reachability index (1: dexterous)")
    return fig


def save_reachability_plot(
    m: ReachabilityMap, path: str | os.PathLike[str], title: str = ""
) -> Path:
    """Write :func:`plot_reachability`'s figure to ``path`` (``.png``, ``.svg``, ...)."""
    return save_figure(plot_reachability(m, title), path)


def plot_placement(
    found: BasePlacement, task_poses: ArrayLike | None = None, title: str = ""
) -> Any:
    """A figure of a base-placement search seen from above (world x, y).

    Args:
        found: The search's result.
        task_poses: ``(m, 4, 4)`` the task, to mark its positions; optional.
        title: A title line.

    Returns:
        The matplotlib Figure (not managed by pyplot).
    """
    fig = figure(1000, 850, DPI, pyplot_managed=False)
    ax = new_axes(fig, False)
    xy = np.round(found.positions[:, :2] / found.resolution).astype(np.int64)
    keys, inverse = np.unique(xy, axis=0, return_inverse=True)
    inverse = inverse.reshape(-1)
    best = np.full(keys.shape[0], -np.inf)
    np.maximum.at(best, inverse, np.where(found.feasible, found.worst_manipulability, -np.inf))
    pts = keys * found.resolution
    feasible = np.isfinite(best)
    ax.scatter(pts[~feasible, 0], pts[~feasible, 1], s=10, c="lightgrey", label="infeasible")
    if feasible.any():
        sc = ax.scatter(
            pts[feasible, 0], pts[feasible, 1], s=28, c=best[feasible], cmap="viridis",
            marker="s", label="feasible (best yaw)",
        )  # fmt: skip
        fig.colorbar(sc, ax=ax, label="worst manipulability over the task")
    if found.best is not None:
        b = found.best
        ax.plot(b[0, 3], b[1, 3], marker="*", markersize=18, color="crimson", linestyle="",
                label="best base")  # fmt: skip
        ax.annotate("", xy=(b[0, 3] + 2 * found.resolution * b[0, 0],
                            b[1, 3] + 2 * found.resolution * b[1, 0]),
                    xytext=(b[0, 3], b[1, 3]),
                    arrowprops={"arrowstyle": "->", "color": "crimson"})  # fmt: skip
    if task_poses is not None:
        t = np.asarray(task_poses, dtype=float).reshape(-1, 4, 4)
        ax.scatter(t[:, 0, 3], t[:, 1, 3], marker="x", c="k", s=30, label="task positions")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_aspect("equal")
    ax.legend(loc="best", fontsize=8)
    head = f"{title}\n" if title else ""
    ax.set_title(
        f"{head}base placement: {found.count} of {found.positions.shape[0]} candidate bases "
        "reach every task pose",
        fontsize=10,
    )
    return fig


def save_placement_plot(
    found: BasePlacement,
    path: str | os.PathLike[str],
    task_poses: ArrayLike | None = None,
    title: str = "",
) -> Path:
    """Write :func:`plot_placement`'s figure to ``path``."""
    return save_figure(plot_placement(found, task_poses, title), path)
