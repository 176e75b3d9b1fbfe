"""``reachability(robot, ...)``: the orientation-aware reachability map by exact IK.

At each voxel centre of a grid over the workspace, a fixed set of tool
orientations (:mod:`kinematica.reach.orientations`) is solved by the arm's
batched closed-form IK within its joint limits. A voxel's *reachability index*
is the share of the orientations reached; it is *dexterous* when all are.
Unlike a cloud of forward-kinematics samples, nothing is estimated: the index
of a voxel is the exact answer for its centre and its orientations (for the
arm's closed form; an arm without one is solved numerically, and its map says
so through :attr:`ReachabilityMap.complete`). A redundant arm is answered as
its IK answers a pose by default, with a parameter held (an SRS arm's arm
angle 0, or a joint at the middle of its limits): its map is then that of the
arm at that value, a lower bound of what the whole self-motion reaches, and
:attr:`ReachabilityMap.held` names the parameter.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from kinematica.arguments import check_flag
from kinematica.errors import ArgumentError, KinematicaError
from kinematica.reach.cluster import Scheduler, check_workers, dask_client, default_workers
from kinematica.reach.compute import solve_blocks
from kinematica.reach.grid import make_grid
from kinematica.reach.orientations import MAX_ORIENTATIONS, cone_set, planar_set, so3_set
from kinematica.reach.reachmap import ReachabilityMap

if TYPE_CHECKING:
    from kinematica.robot import Robot

__all__ = ["MAX_QUERIES", "reachability"]

#: Most poses one map asks (voxels inside the reach ball × orientations).
MAX_QUERIES = 10**10


def _approach(approach: object) -> tuple[object, object]:
    if (
        not isinstance(approach, tuple | list)
        or len(approach) != 2
        or isinstance(approach[1], tuple | list | np.ndarray)
    ):
        raise ArgumentError(
            "approach must be (direction, half_angle): a tool z axis (3 numbers, base "
            f"frame) and the cone's half-angle in rad, got {approach!r}",
            arg="approach",
        )
    direction, half = approach
    return direction, half  # cone_set checks both


def reachability(
    robot: Robot,
    region: ArrayLike | None = None,
    resolution: float = 0.05,
    orientations: int | ArrayLike | None = 64,
    approach: tuple[ArrayLike, float] | None = None,
    *,
    manipulability: bool = True,
    scheduler: Scheduler = None,
    workers: int | None = None,
    threads: int | None = None,
    progress: Callable[[int], None] | None = None,
) -> ReachabilityMap:
    """The reachability map of ``robot``: which tool orientations it reaches where.

    Args:
        robot: The robot (a prismatic joint needs limits).
        region: ``(2, 3)`` lower and upper corners of a box (m, base frame);
            None: the cube about the arm's reach ball.
        resolution: Voxel side (m).
        orientations: How many orientations to ask at each voxel centre, spread
            evenly over SO(3) (:func:`~kinematica.reach.orientations.so3_set`);
            or ``(N, 3, 3)`` rotations of your own; or None for the tool
            position alone (any orientation: a positioning arm, or a planar 2R).
            A planar arm is asked turns about its joint axis
            (:func:`~kinematica.reach.orientations.planar_set`).
        approach: ``(direction, half_angle)``: ask orientations whose tool z
            axis lies within ``half_angle`` (rad) of ``direction`` (3,) instead
            (:func:`~kinematica.reach.orientations.cone_set`); e.g.
            ``((0, 0, -1), 0.3)`` for a tool pointing down within 0.3 rad.
        manipulability: Also the best manipulability per voxel (about half the
            time of the map: every solution's Jacobian and its singular values).
        scheduler: ``None`` (this process), ``"local"`` (a Dask LocalCluster),
            ``"tcp://host:port"`` (a running scheduler) or a ``distributed.Client``.
            The map is the same bit for bit on any of them.
        workers: Processes of a ``"local"`` cluster; given alone, implies it.
        threads: Core threads of each IK batch in this process (None: the
            library default, ``KINEMATICA_WORKERS`` or every core).
        progress: Called with the number of poses done after each block.

    Returns:
        The :class:`~kinematica.reach.reachmap.ReachabilityMap`.

    Raises:
        ArgumentError: A bad region, resolution, orientation count or set,
            approach, or too many voxels or poses.
        KinematicaError: A prismatic joint without limits, a tilted planar arm,
            or a Dask cluster that cannot be used.
    """
    grid, plane = make_grid(robot, region, resolution)
    manipulability = check_flag(manipulability, "manipulability")
    scheduler, workers = check_workers(workers, scheduler)
    if progress is not None and not callable(progress):
        raise ArgumentError(f"progress must be a function or None, got {progress!r}")
    cone = None
    if orientations is None:
        if approach is not None:
            raise ArgumentError(
                "approach asks orientations: give orientations=N with it", arg="approach"
            )
        rotations = None
    elif isinstance(orientations, int | np.integer) and not isinstance(orientations, bool):
        if approach is not None:
            direction, half = _approach(approach)
            rotations = cone_set(int(orientations), direction, half)  # type: ignore[arg-type]
            axis = np.asarray(direction, dtype=np.float64)
            cone = (axis / np.linalg.norm(axis), float(half))  # type: ignore[arg-type]
        elif plane is not None:
            rotations = planar_set(int(orientations), plane.normal, plane.start)
        else:
            rotations = so3_set(int(orientations))
    else:
        rotations = _rotations(orientations)
    n_orient = 1 if rotations is None else rotations.shape[0]
    voxels = grid.inside_reach()
    if voxels.size * n_orient > MAX_QUERIES:
        raise ArgumentError(
            f"the map asks {voxels.size * n_orient:.3g} poses ({voxels.size} voxels × "
            f"{n_orient} orientations); at most {MAX_QUERIES:.0e}",
            arg="resolution",
        )
    with dask_client(scheduler, workers) as client:
        n_workers = workers or default_workers()
        if client is not None and workers is None:
            n_workers = max(1, len(client.scheduler_info().get("workers", {})))
        reached, solutions, best, how = solve_blocks(
            robot,
            grid.centres,
            voxels,
            rotations,
            manipulability=manipulability,
            threads=threads,
            client=client,
            workers=n_workers,
            progress=progress,
        )
    shape = grid.shape
    full_r = np.zeros(math.prod(shape), dtype=np.int32)
    full_s = np.zeros(math.prod(shape), dtype=np.int32)
    full_m = np.full(math.prod(shape), np.nan)
    full_r[voxels], full_s[voxels], full_m[voxels] = reached, solutions, best
    return ReachabilityMap(
        robot=robot.name,
        origin=grid.origin,
        resolution=grid.resolution,
        orientations=np.zeros((0, 3, 3)) if rotations is None else rotations,
        reached=full_r.reshape(shape),
        solutions=full_s.reshape(shape),
        manipulability=full_m.reshape(shape),
        centre=grid.centre,
        radius=grid.radius,
        approach=cone,
        plane=None if plane is None else plane.axis,
        complete=how.complete,
        held=how.held,
    )


def _rotations(orientations: ArrayLike) -> np.ndarray:
    """A user's ``(N, 3, 3)`` rotations, checked."""
    from kinematica.spatial import check_rotation

    try:
        R = np.asarray(orientations, dtype=np.float64)
    except (TypeError, ValueError):
        raise ArgumentError(
            f"orientations must be a count, (N, 3, 3) rotations or None, got {orientations!r}",
            arg="orientations",
        ) from None
    if R.ndim != 3 or R.shape[1:] != (3, 3) or R.shape[0] == 0:
        raise ArgumentError(
            f"orientations must be a count, (N, 3, 3) rotations or None, got shape {R.shape}",
            arg="orientations",
        )
    if R.shape[0] > MAX_ORIENTATIONS:
        raise ArgumentError(
            f"orientations holds {R.shape[0]} rotations; at most {MAX_ORIENTATIONS}",
            arg="orientations",
        )
    try:
        return check_rotation(R, "orientations")
    except KinematicaError as exc:
        raise ArgumentError(str(exc), arg="orientations") from None
