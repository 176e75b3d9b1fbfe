"""The one picture the motion layer draws: a workspace slice as a map.

matplotlib is an optional dependency (extra ``viz``), imported only here,
when a picture is asked for.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from kinematica.errors import ArgumentError, KinematicaError
from kinematica.io.atomic import atomic_path, write_failed
from kinematica.motion.workspace import WorkspaceSlice

__all__ = [
    "MissingDependencyError",
    "check_map_path",
    "plot_workspace_slice",
    "require_matplotlib",
]


class MissingDependencyError(KinematicaError, ImportError):
    """An optional dependency needed for this feature is not installed."""


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
    u, v = sl.plane[0], sl.plane[1]
    w = ({"x", "y", "z"} - {u, v}).pop()
    fig, ax = plt.subplots(figsize=(6.4, 5.6), dpi=110)
    reach = np.where(sl.occupancy, 1.0, np.nan)
    ax.imshow(reach.T, origin="lower", extent=sl.extent, cmap="Greys", vmin=0.0, vmax=3.0)
    if np.isfinite(sl.manipulability).any():
        im = ax.imshow(sl.manipulability.T, origin="lower", extent=sl.extent, cmap="viridis")
        fig.colorbar(im, ax=ax, label="manipulability (largest in each pixel)")
    ax.set_xlabel(f"{u} (m)")
    ax.set_ylabel(f"{v} (m)")
    ax.set_aspect("equal")
    head = f"{title}\n" if title else ""
    ax.set_title(f"{head}{u}{v} slice at {w} = {sl.at:.3f} m, area {sl.area:.4g} m²")
    try:
        with atomic_path(out) as tmp:
            fig.savefig(tmp, bbox_inches="tight")
    except OSError as exc:
        raise KinematicaError(write_failed(out, exc, "the picture")) from exc
    finally:
        plt.close(fig)
    return out
