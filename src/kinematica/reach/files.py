"""Reachability maps on disk: a VTK image for ParaView, ``.npz`` for numpy.

Why a VTK XML image (``.vti``) rather than NetCDF or Zarr through xarray: a
reachability map is a regular grid of cubic voxels with a few values each,
which is exactly what VTK's ImageData holds (origin, spacing, cell data);
ParaView, VisIt, PyVista and VTK itself open it with no conversion, and it is
written here with the standard library alone (xarray, netCDF4 or zarr would be
heavy dependencies for four arrays). The ``.npz`` file keeps everything the
map object holds (the orientations too) and reads back into a
:class:`~kinematica.reach.reachmap.ReachabilityMap` with :func:`load_map`.

The ``.vti`` file holds, per voxel (VTK cell data, x fastest as VTK orders it):
``reachability_index`` (Float64), ``reached`` (Int32, orientations reached),
``solutions`` (Int32), ``manipulability`` (Float64, NaN where none) and
``dexterous`` (UInt8). Arrays are base64 "binary" with a UInt64 byte-count
header encoded apart from the data, as VTK's own writer does.
"""

from __future__ import annotations

import base64
import os
from pathlib import Path
from typing import Any
from xml.sax.saxutils import quoteattr

import numpy as np
from numpy.typing import NDArray

from kinematica.errors import ArgumentError, KinematicaError
from kinematica.reach.reachmap import ReachabilityMap

__all__ = ["load_map", "save_map", "vti_text"]

_VTK_TYPES = {
    np.dtype(np.float64): "Float64",
    np.dtype(np.int32): "Int32",
    np.dtype(np.uint8): "UInt8",
}
_FIELDS = ("origin", "resolution", "orientations", "reached", "solutions", "manipulability")
_FORMAT_VERSION = 1


def _binary(a: NDArray[np.generic]) -> str:
    """VTK inline binary: the byte count (UInt64) and the data, each base64 on its own."""
    data = np.ascontiguousarray(a).astype(a.dtype.newbyteorder("<"), copy=False).tobytes()
    header = np.array([len(data)], dtype="<u8").tobytes()
    return (base64.b64encode(header) + base64.b64encode(data)).decode("ascii")


def vti_text(m: ReachabilityMap) -> str:
    """The map as the text of a VTK XML ImageData file (cell data per voxel)."""
    nx, ny, nz = m.shape
    h = float(m.resolution)
    ox, oy, oz = (float(v) for v in m.origin)
    arrays: dict[str, NDArray[np.generic]] = {
        "reachability_index": m.index,
        "reached": m.reached.astype(np.int32),
        "solutions": m.solutions.astype(np.int32),
        "manipulability": m.manipulability.astype(np.float64),
        "dexterous": m.dexterous.astype(np.uint8),
    }
    lines = [
        '<?xml version="1.0"?>',
        '<VTKFile type="ImageData" version="1.0" byte_order="LittleEndian" header_type="UInt64">',
        f"  <!-- kinematica reachability map of {m.robot.replace('--', '- -')}: "
        f"{m.count} orientations per voxel -->",
        f'  <ImageData WholeExtent="0 {nx} 0 {ny} 0 {nz}" '
        f'Origin="{ox!r} {oy!r} {oz!r}" '
        f'Spacing="{h!r} {h!r} {h!r}" Direction="1 0 0 0 1 0 0 0 1">',
        f'    <Piece Extent="0 {nx} 0 {ny} 0 {nz}">',
        '      <CellData Scalars="reachability_index">',
    ]
    for name, a in arrays.items():
        flat = np.transpose(a).reshape(-1)  # VTK: x varies fastest
        vtk_type = _VTK_TYPES[flat.dtype]
        lines.append(
            f'        <DataArray type="{vtk_type}" Name={quoteattr(name)} format="binary">'
            f"{_binary(flat)}</DataArray>"
        )
    lines += ["      </CellData>", "    </Piece>", "  </ImageData>", "</VTKFile>", ""]
    return "\n".join(lines)


def save_map(m: ReachabilityMap, path: str | os.PathLike[str]) -> Path:
    """Write the map to ``path``: ``.vti`` (VTK image) or ``.npz`` (numpy).

    Raises:
        ArgumentError: Another suffix.
        KinematicaError: The file cannot be written.
    """
    p = Path(path)
    suffix = p.suffix.lower()
    if suffix not in (".vti", ".npz"):
        raise ArgumentError(
            f"{p}: a reachability map is written as .vti (VTK, ParaView) or .npz (numpy)",
            arg="path",
        )
    try:
        if suffix == ".vti":
            p.write_text(vti_text(m), encoding="ascii")
        else:
            approach = (
                np.full(4, np.nan)
                if m.approach is None
                else np.append(m.approach[0], m.approach[1])
            )
            with p.open("wb") as f:
                arrays: dict[str, Any] = {name: np.asarray(getattr(m, name)) for name in _FIELDS}
                arrays.update(
                    version=np.int64(_FORMAT_VERSION),
                    robot=np.str_(m.robot),
                    centre=m.centre,
                    radius=np.float64(m.radius),
                    approach=approach,
                    plane=np.int64(-1 if m.plane is None else m.plane),
                    complete=np.bool_(m.complete),
                    held=np.str_("" if m.held is None else m.held),
                )
                np.savez_compressed(f, **arrays)
    except OSError as exc:
        raise KinematicaError(f"cannot write {p}: {exc.strerror or exc}") from exc
    return p


def load_map(path: str | os.PathLike[str]) -> ReachabilityMap:
    """Read a map written by :func:`save_map` as ``.npz``.

    Raises:
        KinematicaError: The file is missing, unreadable, or not such a map.
    """
    p = Path(path)
    try:
        with np.load(p, allow_pickle=False) as data:
            if int(data["version"]) != _FORMAT_VERSION:
                raise KinematicaError(
                    f"{p}: a reachability map of format {int(data['version'])}, "
                    f"this kinematica reads {_FORMAT_VERSION}"
                )
            approach = data["approach"]
            plane = int(data["plane"])
            return ReachabilityMap(
                robot=str(data["robot"]),
                origin=data["origin"],
                resolution=float(data["resolution"]),
                orientations=data["orientations"],
                reached=data["reached"],
                solutions=data["solutions"],
                manipulability=data["manipulability"],
                centre=data["centre"],
                radius=float(data["radius"]),
                approach=None
                if np.isnan(approach[0])
                else (approach[:3].copy(), float(approach[3])),
                plane=None if plane < 0 else plane,
                complete=bool(data["complete"]),
                held=str(data["held"]) or None,
            )
    except (OSError, KeyError, ValueError) as exc:
        raise KinematicaError(f"{p}: not a reachability map written by kinematica ({exc})") from exc
