"""Measurement CSV files: joint readings, then the measured pose or point, one row each.

The format ``kinematica calibrate`` reads::

    # comment lines and blank lines are skipped; a first line of names is a header
    q1,q2,q3,q4,q5,q6,x,y,z,a,b,c
    0,-45,30,0,60,0,0.41213,0.10022,0.5321,12.1,44.9,-3.2

Each row holds the robot's n joint readings, then either the measured tool point
``x, y, z`` (n + 3 columns: position measurements) or the measured tool pose ``x, y, z``
and three Euler angles (n + 6 columns: pose measurements). Units are the command
line's: angles in degrees (radians with ``--rad``), lengths in the robot file's unit
(``--units`` to choose), Euler angles in the sequence ``--euler`` (default ZYZ).
Reading returns the numbers as written; the caller converts units.
"""

from __future__ import annotations

import csv
import io
import os
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from kinematica.errors import KinematicaError
from kinematica.io.reading import read_limited

__all__ = ["MAX_BYTES", "MeasurementFileError", "read_measurements"]

FloatArray = NDArray[np.float64]

#: Largest measurement file read (16 MiB): far beyond any tracker session.
MAX_BYTES = 16 * 2**20


class MeasurementFileError(KinematicaError, ValueError):
    """A measurement CSV file is missing or malformed (the message says where)."""


def read_measurements(path: str | os.PathLike[str], dof: int) -> tuple[FloatArray, FloatArray, str]:
    """Read a measurement CSV file (module docstring).

    Args:
        path: The file.
        dof: The robot's joints n.

    Returns:
        ``(q (m, n), measured (m, 3 or 6), kind)`` as written (no unit converted),
        ``kind`` ``"position"`` (n + 3 columns) or ``"pose"`` (n + 6 columns).

    Raises:
        MeasurementFileError: no such file, a row of another width, a value that
            is not a finite number (line and column named), no rows.
    """
    p = Path(path)
    raw = read_limited(
        p, MAX_BYTES, "measurement CSV file", lambda m: MeasurementFileError(f"{p}: {m}")
    )
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError:
        raise MeasurementFileError(f"{p}: not UTF-8 text") from None
    widths = {dof + 3: "position", dof + 6: "pose"}
    rows: list[list[float]] = []
    width = 0
    for line_no, row in enumerate(csv.reader(io.StringIO(text)), start=1):
        cells = [c.strip() for c in row]
        if not cells or all(not c for c in cells) or cells[0].startswith("#"):
            continue
        values: list[float] = []
        for col, cell in enumerate(cells, start=1):
            v: float | None
            try:
                v = float(cell)
            except ValueError:
                v = None
            if v is None or not np.isfinite(v):
                if not rows and v is None and col == 1:
                    values = []  # a header line of names
                    break
                raise MeasurementFileError(
                    f"{p}: line {line_no}, column {col}: expected a finite number, got {cell!r}"
                )
            values.append(v)
        if not values:
            if rows or width:
                raise MeasurementFileError(f"{p}: line {line_no}: a second header line")
            width = -1
            continue
        if len(values) not in widths:
            raise MeasurementFileError(
                f"{p}: line {line_no}: {len(values)} columns; expected {dof + 3} ({dof} joint "
                f"readings, then x, y, z of a point) or {dof + 6} (then x, y, z and three "
                "Euler angles of a pose)"
            )
        if rows and len(values) != len(rows[0]):
            raise MeasurementFileError(
                f"{p}: line {line_no}: {len(values)} columns, the rows before have {len(rows[0])}"
            )
        rows.append(values)
    if not rows:
        raise MeasurementFileError(f"{p}: no measurements (rows of numbers)")
    data = np.array(rows, dtype=float)
    return data[:, :dof], data[:, dof:], widths[data.shape[1]]
