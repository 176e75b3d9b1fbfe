"""The reachability map in the interactive page: what the page embeds of a map.

A map (:func:`kinematica.reach.reachability`, or one saved as ``.npz`` by
:func:`kinematica.reach.save_map`) goes into the page as numbers only: the
grid (origin, voxel side, shape), the orientations asked per voxel, and, for
each reachable voxel, its flat index and how many orientations it reaches. The
page (``web/reach.js``) draws those voxels as squares coloured by the
reachability index (viridis, the colours of :func:`kinematica.viz.plot_reachability`),
with a switch and a slice control; nothing of the map is ever markup or code.
:func:`coarse_map` is the map the page computes when asked for one without a
file: :data:`COARSE_VOXELS` voxels across the reach ball, :data:`COARSE_ORIENTATIONS`
orientations each (a fraction of a second for a 6R arm).
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any, Final

import numpy as np

from kinematica.errors import KinematicaError
from kinematica.reach import ReachabilityMap, load_map, reachability
from kinematica.reach.grid import make_grid
from kinematica.robot import Robot
from kinematica.viz._mpl import VizError

__all__ = [
    "COARSE_ORIENTATIONS",
    "COARSE_VOXELS",
    "MAX_PAGE_VOXELS",
    "coarse_map",
    "page_map",
    "reach_data",
]

#: Most reachable voxels a page draws (each a square, every frame redrawn).
MAX_PAGE_VOXELS: Final = 100_000
#: Voxels across the reach ball's diameter in :func:`coarse_map`.
COARSE_VOXELS: Final = 24
#: Orientations per voxel in :func:`coarse_map`.
COARSE_ORIENTATIONS: Final = 16


def coarse_map(robot: Robot) -> ReachabilityMap:
    """A quick map for the page: :data:`COARSE_VOXELS` across, :data:`COARSE_ORIENTATIONS` each.

    An arm of fewer than six joints (a planar arm: over its plane) is asked
    positions alone; a redundant arm too, with half as many voxels across (its
    map is searched numerically in part, see :attr:`ReachabilityMap.complete`).
    """
    grid, plane = make_grid(robot, None, 1.0)  # the reach ball, whatever the voxel side
    # a redundant arm's map is searched numerically where its closed form holds a
    # parameter: an eighth of the voxels, positions alone
    across = COARSE_VOXELS if robot.dof <= 6 else COARSE_VOXELS // 2
    side = 2.0 * grid.radius / across if grid.radius > 0 else 1.0
    # an arm of fewer than six joints reaches few of a set over SO(3): its positions alone
    orientations = None if plane is not None or robot.dof != 6 else COARSE_ORIENTATIONS
    return reachability(robot, resolution=side, orientations=orientations, manipulability=False)


def page_map(robot: Robot, reach: ReachabilityMap | str | os.PathLike[str]) -> ReachabilityMap:
    """The map a page shows: ``reach`` itself, or the map saved in that ``.npz`` file.

    Raises:
        VizError: The file is not a map kinematica wrote, or is another robot's.
    """
    if isinstance(reach, ReachabilityMap):
        return reach
    if not isinstance(reach, str | os.PathLike):
        raise VizError(
            f"reach must be a ReachabilityMap or the path of a map saved as .npz, got {reach!r}"
        )
    path = Path(reach)
    try:
        m = load_map(path)
    except KinematicaError as exc:
        raise VizError(str(exc)) from exc
    if m.robot != robot.name:
        raise VizError(
            f"{path}: the map of {m.robot!r}, not of {robot.name!r}; "
            "compute it for this robot (kinematica reach ROBOT -o map.npz)"
        )
    return m


def reach_data(m: ReachabilityMap) -> dict[str, Any]:
    """What the page embeds of the map ``m``: numbers only (see the module docs).

    Raises:
        VizError: More than :data:`MAX_PAGE_VOXELS` reachable voxels.
    """
    flat = m.reached.reshape(-1)
    voxels = np.flatnonzero(flat > 0)
    if voxels.size > MAX_PAGE_VOXELS:
        raise VizError(
            f"the map has {voxels.size} reachable voxels; a page draws at most "
            f"{MAX_PAGE_VOXELS}: compute it with a coarser resolution"
        )
    return {
        "origin": [float(v) for v in m.origin],
        "resolution": float(m.resolution),
        "shape": list(m.shape),
        "count": m.count,
        "positions": m.orientations.shape[0] == 0,
        "plane": m.plane,
        "voxels": voxels.tolist(),
        "reached": flat[voxels].tolist(),
        "dexterous": int(np.count_nonzero(m.dexterous)),
    }
