"""Trajectory CSV files: a header ``t,q1,...,qn``, then time (s) and joint values (rad, m).

The format :mod:`kinematica.motion` writes too. Reading checks everything a
picture relies on and says where a file is wrong: line, column, what was found.
"""

from __future__ import annotations

import csv
import math
import os
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.errors import KinematicaError
from kinematica.io.atomic import atomic_path, write_failed
from kinematica.io.reading import read_limited

__all__ = ["MAX_BYTES", "TrajectoryFileError", "read_trajectory", "write_trajectory"]

FloatArray = NDArray[np.float64]

#: Largest trajectory file read (64 MiB): about a million samples of six joints.
MAX_BYTES = 64 * 2**20


class TrajectoryFileError(KinematicaError, ValueError):
    """A trajectory CSV file is missing or malformed (the message says where)."""


def read_trajectory(
    path: str | os.PathLike[str], dof: int | None = None
) -> tuple[FloatArray, FloatArray]:
    """Read a trajectory CSV file.

    Args:
        path: The file: a header row ``t,q1,...,qn``, then one row per sample
            with the time (s, strictly increasing) and the joint values in SI
            units (rad for revolute, m for prismatic joints). Blank lines and
            lines starting with ``#`` are skipped.
        dof: The number of joints expected (the robot's), or ``None``.

    Returns:
        ``t`` of shape ``(T,)`` and ``q`` of shape ``(T, n)``.

    Raises:
        TrajectoryFileError: No such file, not a regular file (a FIFO, a
            device), larger than MAX_BYTES, not UTF-8, no header, a wrong number of
            columns, a value that is not a finite number, time not increasing.
    """
    p = Path(path)
    data = read_limited(
        p, MAX_BYTES, "trajectory file", lambda reason: TrajectoryFileError(f"{p}: {reason}")
    )
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise TrajectoryFileError(
            f"{p}: not UTF-8 text (bad byte at position {exc.start})"
        ) from exc
    rows = [
        (number, row)
        for number, row in enumerate(csv.reader(text.splitlines()), start=1)
        if row and any(cell.strip() for cell in row) and not row[0].lstrip().startswith("#")
    ]
    if not rows:
        raise TrajectoryFileError(f"{p}: empty trajectory file (expected a header t,q1,...,qn)")
    line, header = rows[0]
    names = [cell.strip() for cell in header]
    if names[0].lower() != "t" or len(names) < 2:
        raise TrajectoryFileError(
            f"{p}, line {line}: the header must be t,q1,...,qn (time first), "
            f"found {','.join(names)}"
        )
    n = len(names) - 1
    if dof is not None and n != dof:
        raise TrajectoryFileError(
            f"{p}, line {line}: {n} joint column(s) ({','.join(names[1:])}), the robot has {dof}"
        )
    if len(rows) < 2:
        raise TrajectoryFileError(f"{p}: the header is not followed by any sample")
    values = np.empty((len(rows) - 1, n + 1))
    for k, (number, row) in enumerate(rows[1:]):
        if len(row) != n + 1:
            raise TrajectoryFileError(
                f"{p}, line {number}: expected {n + 1} values (t and {n} joints), found {len(row)}"
            )
        for j, cell in enumerate(row):
            try:
                v = float(cell)
            except ValueError:
                v = math.nan
            if not math.isfinite(v):
                raise TrajectoryFileError(
                    f"{p}, line {number}, column {names[j]}: expected a finite number, "
                    f"found {cell.strip()!r}"
                ) from None
            values[k, j] = v
    t = values[:, 0]
    bad = np.flatnonzero(np.diff(t) <= 0)
    if bad.size:
        number = rows[int(bad[0]) + 2][0]
        raise TrajectoryFileError(
            f"{p}, line {number}: time must increase, found t = {t[bad[0] + 1]:g} after "
            f"{t[bad[0]]:g}"
        )
    return t.copy(), values[:, 1:].copy()


def write_trajectory(path: str | os.PathLike[str], t: ArrayLike, q: ArrayLike) -> Path:
    """Write ``t`` ``(T,)`` (s) and ``q`` ``(T, n)`` (rad, m) as a trajectory CSV file."""
    tt = np.asarray(t, dtype=float)
    qq = np.asarray(q, dtype=float)
    if tt.ndim != 1 or qq.ndim != 2 or qq.shape[0] != tt.shape[0]:
        raise TrajectoryFileError(
            f"a trajectory needs t of shape (T,) and q of shape (T, n), got {tt.shape} and "
            f"{qq.shape}"
        )
    p = Path(path)
    try:
        with atomic_path(p) as tmp, tmp.open("w", newline="", encoding="utf-8") as fh:
            writer = csv.writer(fh)
            writer.writerow(["t", *(f"q{i}" for i in range(1, qq.shape[1] + 1))])
            for ti, qi in zip(tt, qq, strict=True):
                writer.writerow([repr(float(ti)), *(repr(float(v)) for v in qi)])
    except OSError as exc:
        raise TrajectoryFileError(write_failed(p, exc, "the trajectory")) from exc
    return p
