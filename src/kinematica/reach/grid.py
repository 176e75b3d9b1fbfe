"""The voxel grid a reachability map fills, and what the arm can be asked there.

The grid covers a box of the base frame with cubic voxels of side ``h``; the
map asks its questions at voxel *centres*. By default the box is the cube of
half-side R about the origin of the arm's first joint frame, R a bound on the
arm's reach (:func:`kinematica.ik.numeric.reach_bound`: the sum of the chain's
translations): no tool position lies outside that ball, so voxels whose centre
lies outside it are unreachable without asking the IK.

A planar arm (every joint axis parallel: the structure classes ``planar-*``)
moves its tool in one plane. When that plane's normal is a base axis, the grid
is one voxel thick along it, at the plane, and the orientations asked are
turns about the normal (:func:`~kinematica.reach.orientations.planar_set`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.arguments import check_number
from kinematica.errors import ArgumentError, KinematicaError
from kinematica.ik.numeric import reach_bound
from kinematica.robot.sampling import sampling_box
from kinematica.robot.structure import classify

if TYPE_CHECKING:
    from kinematica.robot import Robot

__all__ = ["AXIS_TOL", "MAX_VOXELS", "Grid", "Plane", "arm_plane", "make_grid"]

FloatArray = NDArray[np.float64]

#: Most voxels in a map's grid (each holds 24 bytes of results).
MAX_VOXELS = 1 << 24
#: A planar arm's normal counts as a base axis when its other components are below this.
AXIS_TOL = 1e-9


@dataclass(frozen=True)
class Plane:
    """The plane a planar arm moves its tool in.

    Attributes:
        normal: ``(3,)`` unit normal (the joints' common axis), base frame.
        axis: 0, 1 or 2: the base axis the normal lies along.
        at: The plane's coordinate (m) along that axis.
        start: ``(3, 3)`` the tool's rotation at q = 0.
        dof: The arm's number of joints (2: the orientation follows the position).
    """

    normal: FloatArray
    axis: int
    at: float
    start: FloatArray
    dof: int


@dataclass(frozen=True)
class Grid:
    """Cubic voxels over a box of the base frame.

    Attributes:
        origin: ``(3,)`` lower corner of voxel ``[0, 0, 0]`` (m, base frame).
        resolution: Side of a voxel (m).
        shape: ``(nx, ny, nz)`` voxels along x, y, z.
        centre: ``(3,)`` centre of the reach ball (m).
        radius: Radius of the reach ball (m): no tool position lies outside it.
    """

    origin: FloatArray
    resolution: float
    shape: tuple[int, int, int]
    centre: FloatArray
    radius: float

    @property
    def size(self) -> int:
        """Number of voxels."""
        return math.prod(self.shape)

    def centres(self, flat: NDArray[np.intp]) -> FloatArray:
        """``(m, 3)`` centres (m) of the voxels of C-order flat indices ``flat``."""
        ijk = np.stack(np.unravel_index(flat, self.shape), axis=-1)
        out: FloatArray = self.origin + (ijk + 0.5) * self.resolution
        return out

    def inside_reach(self) -> NDArray[np.intp]:
        """Flat indices (ascending) of the voxels whose centre lies in the reach ball."""
        h, o = self.resolution, self.origin
        axes = [o[k] + (np.arange(self.shape[k]) + 0.5) * h - self.centre[k] for k in range(3)]
        d2 = axes[0][:, None, None] ** 2 + axes[1][None, :, None] ** 2
        d2 = d2 + axes[2][None, None, :] ** 2
        out: NDArray[np.intp] = np.flatnonzero(d2 <= self.radius**2)
        return out


def arm_plane(robot: Robot) -> Plane | None:
    """The plane of a planar arm whose normal is a base axis; None for other arms.

    Raises:
        KinematicaError: A planar arm whose plane is not normal to a base axis
            (its map would need a tilted grid).
    """
    structure = classify(robot)
    if not structure.kind.startswith("planar-"):
        return None
    feats = structure.features
    revolute = [i for i, t in enumerate(feats.joint_types) if t == "R"]
    normal = feats.directions[revolute[0]]
    axis = int(np.argmax(np.abs(normal)))
    off = np.delete(np.abs(normal), axis)
    if np.any(off > AXIS_TOL):
        raise KinematicaError(
            f"{robot.name} is planar in a plane whose normal {np.round(normal, 6).tolist()} is "
            "not a base axis: turn its base so that its joint axes lie along x, y or z"
        )
    T0 = robot.fk(np.zeros(robot.dof))
    return Plane(
        normal=normal.copy(),
        axis=axis,
        at=float(T0[axis, 3]),
        start=T0[:3, :3].copy(),
        dof=robot.dof,
    )


def _region(region: ArrayLike, plane: Plane | None) -> FloatArray:
    try:
        box = np.asarray(region, dtype=np.float64)
    except (TypeError, ValueError):
        raise ArgumentError(
            f"region must be [[xmin, ymin, zmin], [xmax, ymax, zmax]] (m), got {region!r}",
            arg="region",
        ) from None
    if box.shape != (2, 3) or not np.all(np.isfinite(box)):
        raise ArgumentError(
            "region must be 2 rows of 3 finite numbers, [[xmin, ymin, zmin], "
            f"[xmax, ymax, zmax]] (m), got shape {box.shape}",
            arg="region",
        )
    live = [k for k in range(3) if plane is None or k != plane.axis]
    if np.any(box[1, live] <= box[0, live]):
        raise ArgumentError(
            f"region: each maximum must exceed its minimum, got {box.tolist()}", arg="region"
        )
    return box


def make_grid(
    robot: Robot, region: ArrayLike | None, resolution: float
) -> tuple[Grid, Plane | None]:
    """The grid of a map of ``robot`` over ``region`` (default: its reach cube).

    Args:
        robot: The robot; a prismatic joint needs limits.
        region: ``(2, 3)`` lower and upper corners of the box (m, base frame),
            or None for the cube about the reach ball. The box is covered by
            whole voxels from its lower corner (the last may stick out).
        resolution: Voxel side (m).

    Returns:
        The grid and, for a planar arm, its plane.

    Raises:
        ArgumentError: A bad region or resolution, or more than MAX_VOXELS voxels.
        KinematicaError: A prismatic joint without limits; a tilted planar arm.
    """
    h = check_number(resolution, "resolution", positive=True, unit="m", what="a length")
    plane = arm_plane(robot)
    chain = robot.chain
    box_q = sampling_box(robot)
    radius = reach_bound(chain, box_q[:, 0], box_q[:, 1])
    centre = chain.start[:3, 3].astype(np.float64)
    box = np.stack([centre - radius, centre + radius]) if region is None else _region(region, plane)
    span = box[1] - box[0]
    with np.errstate(over="ignore"):
        counts = np.maximum(1.0, np.ceil(span / h - 1e-9))
    origin = box[0].copy()
    if plane is not None:
        counts[plane.axis] = 1.0
        origin[plane.axis] = plane.at - h / 2.0
    total = float(np.prod(counts))
    if not math.isfinite(total) or total > MAX_VOXELS:
        raise ArgumentError(
            f"resolution {h:g} m gives {total:.3g} voxels over a region "
            f"{np.round(span, 4).tolist()} m wide; at most {MAX_VOXELS} "
            "(a coarser resolution or a smaller region)",
            arg="resolution",
        )
    shape = (int(counts[0]), int(counts[1]), int(counts[2]))
    return Grid(origin, h, shape, centre, radius), plane
