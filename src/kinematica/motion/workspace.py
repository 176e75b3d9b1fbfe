"""The workspace: where the tool point can go, sampled in joint space.

``workspace(robot, samples=N)`` draws ``N`` configurations uniformly within the
joint limits, computes the tool positions in chunks (memory stays bounded:
32 bytes per sample for the points and the manipulability, plus one chunk and
one voxel grid of at most :data:`MAX_CELLS` cells), and bins them into cubic
voxels.

Volume. Uniform joint samples are dense near the workspace boundary and
sparse in its middle, so a raw count of hit voxels has holes inside and a
ragged surface. :func:`kinematica.motion.volume.grid_measure` closes the
holes and weighs each boundary voxel by the fraction of it the samples in it
say is covered (see there). With the default voxel (about six samples per
voxel) a Cartesian arm's box comes out within 1 % at 10⁵ samples, and a 3R
arm's spherical shell and a planar 3R arm's disc area too
(``tests/motion/test_workspace.py``).

A workspace whose points all lie in one coordinate plane (planar arms) is
measured in that plane: ``area`` (m²), ``volume = 0``, and ``plane`` names it
(``"xz"`` for an arm moving in the base's xz plane); its slices default to it.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from kinematica.arguments import check_count, check_flag, check_number
from kinematica.errors import KinematicaError
from kinematica.ik.numeric import check_seed, reach_bound
from kinematica.motion.volume import CHUNK, grid_measure
from kinematica.robot.sampling import Seed, random_q, sampling_box
from kinematica.robot.velocity import manipulability as _manipulability

if TYPE_CHECKING:
    from kinematica.robot import Robot

__all__ = [
    "CHUNK",
    "MAX_CELLS",
    "MAX_SAMPLES",
    "PLANAR_TOL",
    "Workspace",
    "WorkspaceSlice",
    "voxel_range",
    "workspace",
]

FloatArray = NDArray[np.float64]
BoolArray = NDArray[np.bool_]

#: Largest voxel grid; a finer ``voxel`` is coarsened to fit.
MAX_CELLS = 1 << 22
#: Most configurations sampled (32 bytes each: 640 MB).
MAX_SAMPLES = 20_000_000
#: A workspace thinner than this (m) along an axis is planar (or lower-dimensional).
PLANAR_TOL = 1e-9
#: Default voxel: about this many samples per occupied voxel.
SAMPLES_PER_VOXEL = 6.0

_AXES = {"x": 0, "y": 1, "z": 2}


@dataclass(frozen=True)
class WorkspaceSlice:
    """A planar slice of a workspace: one layer of voxels.

    Attributes:
        plane: ``"xy"``, ``"xz"`` or ``"yz"`` (base frame axes u, v).
        at: Coordinate (m) of the slice along the third axis.
        pixel: Side of a pixel (m), the voxel side.
        origin: ``(2,)`` (u, v) of the lower corner of pixel ``[0, 0]`` (m).
        occupancy: ``(nu, nv)`` True where a sample fell in the layer.
        manipulability: ``(nu, nv)`` largest manipulability of those samples
            (NaN where empty, or all NaN if not computed).
        area: Area (m²) of the slice, measured like the volume.
    """

    plane: str
    at: float
    pixel: float
    origin: FloatArray
    occupancy: BoolArray
    manipulability: FloatArray
    area: float

    @property
    def extent(self) -> tuple[float, float, float, float]:
        """``(u_min, u_max, v_min, v_max)`` in metres (for ``imshow``)."""
        nu, nv = self.occupancy.shape
        u0, v0 = (float(v) for v in self.origin)
        return (u0, u0 + nu * self.pixel, v0, v0 + nv * self.pixel)


@dataclass(frozen=True)
class Workspace:
    """A sampled workspace.

    Attributes:
        robot: The robot's name.
        points: ``(N, 3)`` tool positions (m, base frame).
        manipulability: ``(N,)`` manipulability of each sample, or ``None``.
        voxel: Side of a voxel (m).
        origin: ``(3,)`` lower corner of voxel ``[0, 0, 0]`` (m).
        occupancy: ``(nx, ny, nz)`` True where a sample fell.
        manipulability_map: ``(nx, ny, nz)`` largest manipulability in each
            voxel, NaN where empty (all NaN when not computed).
        bounds: ``(2, 3)`` smallest and largest x, y, z of the points (m).
        volume: Volume (m³) from the voxels (see the module docstring); 0 for
            a planar workspace.
        area: For a planar workspace, its area (m²); ``None`` otherwise.
    """

    robot: str
    points: FloatArray
    manipulability: FloatArray | None
    voxel: float
    origin: FloatArray
    occupancy: BoolArray
    manipulability_map: FloatArray
    bounds: FloatArray
    volume: float
    area: float | None

    @property
    def planar(self) -> bool:
        """True when every point lies in one coordinate plane (within PLANAR_TOL)."""
        return self.area is not None

    @property
    def plane(self) -> str | None:
        """The coordinate plane a planar workspace lies in (``"xy"``, ``"xz"``, ``"yz"``), or None.

        The axis along which the points are flattest is left out: for a planar
        arm, the plane it moves in (the plane :func:`kinematica.viz.plot` draws it in).
        """
        if not self.planar:
            return None
        flat = int(np.argmin(self.bounds[1] - self.bounds[0]))
        return "".join(axis for k, axis in enumerate("xyz") if k != flat)

    @property
    def reach(self) -> float:
        """Largest distance (m) of a sampled point from the base origin."""
        return float(np.sqrt(np.max(np.sum(self.points**2, axis=1))))

    def slice(self, plane: str | None = None, at: float | None = None) -> WorkspaceSlice:
        """The layer of voxels cut by a coordinate plane.

        Args:
            plane: Two base axes, ``"xy"``, ``"xz"`` or ``"yz"`` (either order);
                if ``None``, the workspace's own :attr:`plane` when it is
                planar, else ``"xz"``.
            at: Coordinate (m) along the third axis; the middle of the bounds
                if ``None`` (the plane of a planar workspace).

        Returns:
            The :class:`WorkspaceSlice`.

        Raises:
            KinematicaError: Unknown plane, or ``at`` outside the grid.
        """
        if plane is None:
            plane = self.plane or "xz"
        key = "".join(sorted(plane.lower())) if isinstance(plane, str) else ""
        if key not in ("xy", "xz", "yz"):
            raise KinematicaError(f"plane must be 'xy', 'xz' or 'yz', got {plane!r}")
        u, v = _AXES[key[0]], _AXES[key[1]]
        w = 3 - u - v
        coord = (
            float(self.bounds[:, w].mean())
            if at is None
            else check_number(at, "at", unit="m", what="a coordinate")
        )
        k = float(np.floor((coord - self.origin[w]) / self.voxel))  # inf for at=1e308
        if not 0 <= k < self.occupancy.shape[w]:
            lo, hi = self.bounds[:, w]
            raise KinematicaError(
                f"at={coord:g} m is outside the workspace along {'xyz'[w]} ([{lo:.4g}, {hi:.4g}] m)"
            )
        occ = np.take(self.occupancy, int(k), axis=w)
        man = np.take(self.manipulability_map, int(k), axis=w)
        layer = np.clip(np.floor((self.points[:, w] - self.origin[w]) / self.voxel), 0, None) == k
        uv = self.points[layer][:, [u, v]]
        return WorkspaceSlice(
            plane=key,
            at=coord,
            pixel=self.voxel,
            origin=self.origin[[u, v]].copy(),
            occupancy=occ,
            manipulability=man,
            area=grid_measure(occ, uv, self.origin[[u, v]], self.voxel),
        )


def _default_voxel(points: FloatArray, extent: FloatArray, samples: int) -> float:
    """About SAMPLES_PER_VOXEL samples per occupied voxel, from a coarse first count."""
    dims = extent > PLANAR_TOL
    d = int(dims.sum())
    if d == 0:
        return 1e-3
    coarse = float(extent[dims].max()) / 24.0
    origin = points.min(axis=0) - coarse
    occ = _occupancy(points, origin, coarse, extent)
    size = grid_measure(occ, points, origin, coarse)
    return float((SAMPLES_PER_VOXEL * size / samples) ** (1.0 / d))


def _grid_shape(extent: FloatArray, voxel: float) -> tuple[int, int, int]:
    flat = extent <= PLANAR_TOL
    n = np.where(flat, 1, np.floor(extent / voxel).astype(np.int64) + 3)
    return (int(n[0]), int(n[1]), int(n[2]))


def _occupancy(
    points: FloatArray, origin: FloatArray, voxel: float, extent: FloatArray
) -> BoolArray:
    shape = _grid_shape(extent, voxel)
    occ = np.zeros(shape, dtype=bool)
    for start in range(0, points.shape[0], CHUNK):
        idx = _cells(points[start : start + CHUNK], origin, voxel, shape)
        occ.reshape(-1)[idx] = True
    return occ


def _cells(
    points: FloatArray, origin: FloatArray, voxel: float, shape: tuple[int, int, int]
) -> NDArray[np.intp]:
    ijk = np.floor((points - origin) / voxel).astype(np.intp)
    ijk = np.clip(ijk, 0, np.array(shape) - 1)
    out: NDArray[np.intp] = np.ravel_multi_index(tuple(ijk.T), shape)
    return out


def voxel_range(robot: Robot) -> tuple[float, float]:
    """The voxel sides (m) :func:`workspace` accepts for ``robot``: ``(smallest, largest)``.

    Every tool position lies within a ball of radius R about the base (R, a
    bound on the reach: the sum of the chain's translations), so the
    workspace is at most 2R wide along any axis. A voxel wider than 2R holds
    the whole workspace; one narrower than 2R / MAX_CELLS would need more
    cells along a single axis than the whole grid may have.
    """
    box = sampling_box(robot)
    span = 2.0 * reach_bound(robot.chain, box[:, 0], box[:, 1])
    return span / MAX_CELLS, span


def workspace(
    robot: Robot,
    samples: int = 100_000,
    seed: Seed = None,
    voxel: float | None = None,
    manipulability: bool = True,
    progress: Callable[[int], None] | None = None,
) -> Workspace:
    """Sample the workspace of the tool point.

    Args:
        robot: The robot; every prismatic joint needs limits.
        samples: Number of configurations N, drawn uniformly within the limits.
        seed: Seed or ``numpy.random.Generator`` (reproducible).
        voxel: Voxel side (m); by default about six samples per voxel.
        manipulability: Also compute each sample's manipulability
            (:func:`kinematica.motion.manipulability` with ``axes="task"``:
            position rows for 3R/2R positioning arms, all six otherwise) and its map.
        progress: Called with the number of samples done after each chunk
            (the command line hangs a progress bar on it).

    Returns:
        The :class:`Workspace`.

    Raises:
        ArgumentError: ``samples`` not a whole number from 1 to MAX_SAMPLES, a
            bad ``seed``, or ``voxel`` outside :func:`voxel_range`.
        KinematicaError: A prismatic joint without limits.
    """
    n = check_count(samples, "samples", lo=1, hi=MAX_SAMPLES)
    rng = np.random.default_rng(check_seed(seed))
    if voxel is not None:
        smallest, largest = voxel_range(robot)
        voxel = check_number(
            voxel,
            "voxel",
            positive=True,
            lo=smallest or None,  # 0 for an arm that does not move its tool point
            hi=largest or None,
            unit=f"m for {robot.name}",
            what="a length",
        )
    manipulability = check_flag(manipulability, "manipulability")
    if progress is not None and not callable(progress):
        raise KinematicaError(f"progress must be a function or None, got {progress!r}")
    points = np.empty((n, 3))
    w = np.empty(n) if manipulability else None
    for start in range(0, n, CHUNK):
        stop = min(n, start + CHUNK)
        q = random_q(robot, stop - start, seed=rng)
        points[start:stop] = robot.fk(q)[:, :3, 3]
        if w is not None:
            w[start:stop] = _manipulability(robot, q, axes="task")
        if progress is not None:
            progress(stop - start)

    lo, hi = points.min(axis=0), points.max(axis=0)
    extent = hi - lo
    h = _default_voxel(points, extent, n) if voxel is None else float(voxel)
    cells = math.prod(_grid_shape(extent, h))  # Python integers: no overflow
    if cells > MAX_CELLS:  # coarsen to fit the grid in memory
        dims = int(np.sum(extent > PLANAR_TOL))
        h *= (cells / MAX_CELLS) ** (1.0 / dims) * 1.01
    origin = np.where(extent > PLANAR_TOL, lo - h, lo - h / 2)
    shape = _grid_shape(extent, h)
    occ = np.zeros(shape, dtype=bool)
    wmap = np.full(shape, np.nan)
    for start in range(0, n, CHUNK):
        idx = _cells(points[start : start + CHUNK], origin, h, shape)
        occ.reshape(-1)[idx] = True
        if w is not None:
            flat = wmap.reshape(-1)
            chunk_w = w[start : start + CHUNK]
            flat[idx] = np.fmax(flat[idx], -np.inf)  # NaN -> -inf before the max
            np.maximum.at(flat, idx, chunk_w)
    planar = bool(np.any(extent <= PLANAR_TOL))
    size = grid_measure(occ, points, origin, h)
    return Workspace(
        robot=robot.name,
        points=points,
        manipulability=w,
        voxel=h,
        origin=origin,
        occupancy=occ,
        manipulability_map=wmap,
        bounds=np.stack([lo, hi]),
        volume=0.0 if planar else size,
        area=size if planar else None,
    )
