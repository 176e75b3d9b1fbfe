"""A reachability map: per voxel, which share of a set of orientations the arm reaches."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from kinematica.arguments import check_number
from kinematica.errors import ArgumentError

__all__ = ["ReachabilityMap", "ReachabilitySlice"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int32]
BoolArray = NDArray[np.bool_]

_AXES = {"x": 0, "y": 1, "z": 2}


@dataclass(frozen=True)
class ReachabilitySlice:
    """One layer of a map's voxels, for pictures.

    Attributes:
        plane: ``"xy"``, ``"xz"`` or ``"yz"`` (axes u, v of the arrays).
        at: Coordinate (m) of the layer's centres along the third axis.
        origin: ``(2,)`` (u, v) of the lower corner of pixel ``[0, 0]`` (m).
        pixel: Side of a pixel (m).
        index: ``(nu, nv)`` reachability index.
        manipulability: ``(nu, nv)`` best manipulability (NaN where none).
    """

    plane: str
    at: float
    origin: FloatArray
    pixel: float
    index: FloatArray
    manipulability: FloatArray

    @property
    def extent(self) -> tuple[float, float, float, float]:
        """``(u_min, u_max, v_min, v_max)`` in metres (for ``imshow``)."""
        nu, nv = self.index.shape
        u0, v0 = (float(v) for v in self.origin)
        return (u0, u0 + nu * self.pixel, v0, v0 + nv * self.pixel)


@dataclass(frozen=True)
class ReachabilityMap:
    """Where an arm reaches which tool orientations, voxel by voxel.

    Every voxel centre was asked every orientation of :attr:`orientations` (or,
    with ``orientations=None``, the position alone) by the closed-form IK
    within the joint limits. Voxels whose centre lies outside the reach ball
    (:attr:`radius` about :attr:`centre`) are unreachable and were not asked.

    Attributes:
        robot: The robot's name.
        origin: ``(3,)`` lower corner of voxel ``[0, 0, 0]`` (m, base frame).
        resolution: Side of a voxel (m).
        orientations: ``(N, 3, 3)`` the tool orientations asked (base frame),
            or ``(0, 3, 3)`` when positions alone were asked (then ``N = 1``).
        reached: ``(nx, ny, nz)`` orientations reached, per voxel (0..N).
        solutions: ``(nx, ny, nz)`` IK solutions within the limits, summed over
            the orientations.
        manipulability: ``(nx, ny, nz)`` the best manipulability (Yoshikawa's,
            of the task rows, :func:`kinematica.motion.manipulability` with
            ``axes="task"``) over every solution in the voxel; NaN where none
            (all NaN if not computed).
        centre: ``(3,)`` centre of the reach ball (m).
        radius: Its radius (m).
        approach: ``(direction (3,), half-angle rad)`` of a cone of tool z
            axes, or None (all of SO(3), or a planar arm's plane).
        plane: For a planar arm, the base axis (0, 1, 2) normal to its plane; else None.
        complete: Every pose was solved in closed form, every solution found;
            False when some were solved numerically (the map is then a lower bound).
        held: For a redundant arm, the parameter its IK held (``"arm angle"``,
            a joint's name) at its default value: the map is that arm's at that
            value, a lower bound of the whole self-motion's; None otherwise.
    """

    robot: str
    origin: FloatArray
    resolution: float
    orientations: FloatArray
    reached: IntArray
    solutions: IntArray
    manipulability: FloatArray
    centre: FloatArray
    radius: float
    approach: tuple[FloatArray, float] | None = None
    plane: int | None = None
    complete: bool = True
    held: str | None = None

    @property
    def shape(self) -> tuple[int, int, int]:
        """``(nx, ny, nz)``."""
        nx, ny, nz = self.reached.shape
        return (nx, ny, nz)

    @property
    def count(self) -> int:
        """N, the orientations asked per voxel (1 for positions alone)."""
        return max(1, int(self.orientations.shape[0]))

    @property
    def queries(self) -> int:
        """Poses a map of this grid asks at most: voxels × N."""
        return int(self.reached.size) * self.count

    @property
    def index(self) -> FloatArray:
        """``(nx, ny, nz)`` the reachability index: the share of orientations reached."""
        out: FloatArray = self.reached / float(self.count)
        return out

    @property
    def reachable(self) -> BoolArray:
        """``(nx, ny, nz)`` True where at least one orientation is reached."""
        out: BoolArray = self.reached > 0
        return out

    @property
    def dexterous(self) -> BoolArray:
        """``(nx, ny, nz)`` True where every orientation is reached."""
        out: BoolArray = self.reached == self.count
        return out

    @property
    def voxel_volume(self) -> float:
        """Volume (m³) of a voxel; for a planar arm the area (m²) of its pixel."""
        return self.resolution ** (2 if self.plane is not None else 3)

    @property
    def reachable_volume(self) -> float:
        """Volume (m³, area m² for a planar arm) of the reachable voxels."""
        return float(np.count_nonzero(self.reachable)) * self.voxel_volume

    @property
    def dexterous_volume(self) -> float:
        """Volume (m³, area m² for a planar arm) of the dexterous voxels."""
        return float(np.count_nonzero(self.dexterous)) * self.voxel_volume

    def centres(self) -> FloatArray:
        """``(nx, ny, nz, 3)`` the voxel centres (m, base frame)."""
        axes = [
            self.origin[k] + (np.arange(self.shape[k]) + 0.5) * self.resolution for k in range(3)
        ]
        grid = np.meshgrid(*axes, indexing="ij")
        return np.stack(grid, axis=-1)

    def slice(self, plane: str = "xz", at: float | None = None) -> ReachabilitySlice:
        """The layer of voxels a coordinate plane cuts.

        Args:
            plane: ``"xy"``, ``"xz"`` or ``"yz"`` (either order); a planar arm's
                own plane whatever is given.
            at: Coordinate (m) along the third axis; the reach ball's centre if None.

        Raises:
            ArgumentError: Unknown plane, or ``at`` outside the grid.
        """
        if self.plane is not None:
            plane = "".join(a for k, a in enumerate("xyz") if k != self.plane)
        key = "".join(sorted(plane.lower())) if isinstance(plane, str) else ""
        if key not in ("xy", "xz", "yz"):
            raise ArgumentError(f"plane must be 'xy', 'xz' or 'yz', got {plane!r}", arg="plane")
        u, v = _AXES[key[0]], _AXES[key[1]]
        w = 3 - u - v
        coord = (
            float(self.centre[w])
            if at is None
            else check_number(at, "at", unit="m", what="a coordinate")
        )
        k = float(np.floor((coord - self.origin[w]) / self.resolution))
        if self.shape[w] == 1 and self.plane == w:
            k = 0.0
        if not 0 <= k < self.shape[w]:
            lo = float(self.origin[w])
            hi = lo + self.shape[w] * self.resolution
            raise ArgumentError(
                f"at={coord:g} m is outside the map along {'xyz'[w]} ([{lo:.4g}, {hi:.4g}] m)",
                arg="at",
            )
        layer = int(k)
        return ReachabilitySlice(
            plane=key,
            at=float(self.origin[w] + (layer + 0.5) * self.resolution),
            origin=self.origin[[u, v]].copy(),
            pixel=self.resolution,
            index=np.take(self.index, layer, axis=w),
            manipulability=np.take(self.manipulability, layer, axis=w),
        )

    def index_at(self, points: FloatArray) -> FloatArray:
        """``(...)`` the index of the voxels holding ``points`` ``(..., 3)`` (m); 0 outside."""
        p = np.asarray(points, dtype=np.float64)
        ijk = np.floor((p - self.origin) / self.resolution).astype(np.int64)
        if self.plane is not None:  # the plane's one layer answers for every point of it
            ijk[..., self.plane] = 0
        inside = np.all((ijk >= 0) & (ijk < np.array(self.shape)), axis=-1)
        out = np.zeros(p.shape[:-1])
        if np.any(inside):
            hit = ijk[inside]
            out[inside] = self.index[hit[:, 0], hit[:, 1], hit[:, 2]]
        return out
