"""The motion layer's pictures: a workspace slice as a map, a time-optimal timing.

matplotlib is an optional dependency (extra ``viz``), imported only here,
when a picture is asked for.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from kinematica.errors import ArgumentError, KinematicaError, MissingDependencyError
from kinematica.io.atomic import atomic_path, write_failed
from kinematica.motion.volume import sampling_holes
from kinematica.motion.workspace import WorkspaceSlice

if TYPE_CHECKING:
    from kinematica.motion.optimal import TimeOptimal

__all__ = [
    "MissingDependencyError",
    "check_map_path",
    "plot_time_optimal",
    "plot_workspace_slice",
    "require_matplotlib",
    "slice_figure",
]


def require_matplotlib() -> Any:
    """``matplotlib.pyplot`` on the non-interactive Agg backend.

    Raises:
        MissingDependencyError: matplotlib is not installed.
    """
    try:
        import matplotlib
    except ImportError as exc:
        raise MissingDependencyError(
            "drawing a picture needs matplotlib: pip install 'kinematica[viz]'"
        ) from exc
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def check_map_path(path: str | Path) -> Path:
    """``path`` as a Path a map can be written to: a file type matplotlib writes.

    Checked before anything is drawn (the command line: before sampling), since the
    type follows the name's suffix.

    Raises:
        ArgumentError: A suffix matplotlib writes no picture for (``.txt``), or none.
        MissingDependencyError: matplotlib is not installed.
    """
    require_matplotlib()
    from matplotlib.backend_bases import FigureCanvasBase

    out = Path(path)
    kinds = sorted(FigureCanvasBase.get_supported_filetypes())
    if out.suffix[1:].lower() not in kinds:
        raise ArgumentError(
            f"{out}: cannot draw a map as a file of type {out.suffix or '(none)'!r}; "
            f"name it with one of {', '.join('.' + k for k in kinds)}",
            arg="path",
        )
    return out


def plot_workspace_slice(sl: WorkspaceSlice, path: str | Path, title: str = "") -> Path:
    """Save a workspace slice as a picture: reachable pixels coloured by manipulability.

    Pixels no sample fell in that the slice's area counts as inside
    (:func:`kinematica.motion.volume.sampling_holes`: enclosed by sampled
    pixels, never a cell of a cavity three pixels wide) are filled with their
    neighbours' value, marked with a dot and named in the legend; nothing
    outside the closed region is painted.

    Args:
        sl: The slice (:meth:`kinematica.motion.Workspace.slice`).
        path: Output file; the format follows the extension (``.png``, ``.svg``, ...).
        title: Title line (the plane and the area are added).

    Returns:
        The path written.

    Raises:
        ArgumentError: ``path`` names a file type matplotlib does not write.
    """
    out = check_map_path(path)
    plt = require_matplotlib()
    return _save(plt, slice_figure(sl, title), out)


def slice_figure(sl: WorkspaceSlice, title: str = "") -> Any:
    """The Figure :func:`plot_workspace_slice` saves (a bare Figure, not pyplot's).

    Its Axes holds the reach image (the first ``AxesImage``: 1 where reachable,
    NaN elsewhere), the manipulability image when computed, and the filled
    sampling holes as dots (``gid="sampling-holes"``).
    """
    require_matplotlib()
    from matplotlib.figure import Figure

    u, v = sl.plane[0], sl.plane[1]
    w = ({"x", "y", "z"} - {u, v}).pop()
    fig = Figure(figsize=(6.4, 5.9), dpi=110)
    ax = fig.add_subplot()
    holes = sampling_holes(sl.occupancy)
    reach = np.where(sl.occupancy | holes, 1.0, np.nan)
    ax.imshow(reach.T, origin="lower", extent=sl.extent, cmap="Greys", vmin=0.0, vmax=3.0)
    if np.isfinite(sl.manipulability).any():
        shown = _fill_from_neighbours(sl.manipulability, holes)
        im = ax.imshow(shown.T, origin="lower", extent=sl.extent, cmap="viridis")
        fig.colorbar(im, ax=ax, label="manipulability (largest in each pixel)")
    if holes.any():
        i, j = np.nonzero(holes)
        centres = np.asarray(sl.origin) + (np.stack([i, j], axis=1) + 0.5) * sl.pixel
        ax.scatter(
            centres[:, 0],
            centres[:, 1],
            s=4,
            marker="o",
            color="white",
            edgecolors="#333333",
            linewidths=0.3,
            gid="sampling-holes",
            label=f"{int(holes.sum())} pixels inside the region that no sample hit: "
            "filled\n(value of their neighbours), as the area counts them",
        )
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.11), fontsize=7, frameon=False)
    ax.set_xlabel(f"{u} (m)")
    ax.set_ylabel(f"{v} (m)")
    ax.set_aspect("equal")
    head = f"{title}\n" if title else ""
    ax.set_title(f"{head}{u}{v} slice at {w} = {sl.at:.3f} m, area {sl.area:.4g} m²")
    return fig


def _fill_from_neighbours(values: np.ndarray, holes: np.ndarray) -> np.ndarray:
    """``values`` with each hole given the mean of its face neighbours' finite values."""
    out = values.copy()
    padded = np.pad(values, 1, constant_values=np.nan)
    around = np.stack(
        [padded[:-2, 1:-1], padded[2:, 1:-1], padded[1:-1, :-2], padded[1:-1, 2:]], axis=0
    )
    finite = np.isfinite(around)
    total = np.where(finite, around, 0.0).sum(axis=0)
    count = finite.sum(axis=0)
    mean = np.divide(total, count, out=np.full(values.shape, np.nan), where=count > 0)
    out[holes] = mean[holes]
    return out


def _save(plt: Any, fig: Any, path: str | Path) -> Path:
    """Write ``fig`` to ``path`` (atomically) and close it."""
    out = Path(path)
    try:
        with atomic_path(out) as tmp:
            fig.savefig(tmp, bbox_inches="tight")
    except OSError as exc:
        raise KinematicaError(write_failed(out, exc, "the picture")) from exc
    finally:
        plt.close(fig)
    return out


def plot_time_optimal(res: TimeOptimal, path: str | Path, title: str = "") -> Path:
    """Save a time-optimal timing: q, q̇, q̈ against time with their limits, and the phase plane.

    The phase plane shows the path speed ``ṡ`` against ``s``, the limit curve (the
    largest ``ṡ`` each grid interval's own limits allow) and the controllable sets.

    Args:
        res: The :func:`~kinematica.motion.optimal.time_optimal` result.
        path: Output file; the format follows the extension (``.png``, ``.svg``, ...).
        title: Title line (the duration and status are added).

    Returns:
        The path written.
    """
    plt = require_matplotlib()
    tr = res.trajectory
    fig, axes = plt.subplots(2, 2, figsize=(11, 7.5), dpi=100)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    panels: list[tuple[Any, Any, str]] = [
        (tr.q, None, "q (rad, m)"),
        (tr.qd, res.vel, "q̇ (rad/s, m/s)"),
        (tr.qdd, res.acc, "q̈ (rad/s², m/s²)"),
    ]
    for ax, (values, lim, label) in zip(axes.ravel()[:3], panels, strict=True):
        for j in range(values.shape[1]):
            c = colours[j % len(colours)]
            ax.plot(tr.t, values[:, j], color=c, lw=1.2, label=f"q{j + 1}")
            if lim is not None:
                for bound in lim[j]:
                    if np.isfinite(bound):
                        ax.axhline(bound, color=c, lw=0.8, ls="--", alpha=0.6)
        ax.set_xlabel("t (s)")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    axes[0, 0].legend(fontsize=7, ncol=2)
    ax = axes[1, 1]
    k = res.controllable
    ax.fill_between(res.s, k[:, 0], k[:, 1], color="0.85", label="controllable sets")
    ax.plot(res.s, res.sd_max, color="tab:red", lw=1.0, label="limit curve")
    ax.plot(res.s, res.sd, color="tab:blue", lw=1.6, label="ṡ (time-optimal)")
    if res.s_stop is not None:
        ax.axvline(res.s_stop, color="k", ls=":", label=f"stops: {res.limit}")
    top = np.nanmax(res.sd) if np.isfinite(res.sd).any() else 1.0
    ax.set_ylim(0.0, 1.6 * top if top > 0 else 1.0)
    ax.set_xlabel("s")
    ax.set_ylabel("ṡ (1/s)")
    ax.set_title("phase plane")
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    head = f"{title}: " if title else ""
    fig.suptitle(f"{head}{res.status}, {res.duration:.4g} s")
    fig.tight_layout()
    return _save(plt, fig, path)
