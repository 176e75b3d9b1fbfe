"""Trajectory CSV files: a header ``t,q1,...,qn``, then time (s) and joint values (rad, m).

The one format every trajectory, path and control run is written in, and that
``kinematica animate`` and ``trajectory --via`` read: values with 17
significant digits (an exact round trip), ``nan`` where a sample has no
configuration. Reading checks everything its user relies on and says where a
file is wrong: line, column, what was found.
"""

from __future__ import annotations

import csv
import math
import os
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.errors import DimensionError, KinematicaError
from kinematica.io.atomic import atomic_path, write_failed
from kinematica.io.reading import read_limited

__all__ = [
    "MAX_BYTES",
    "TrajectoryFileError",
    "read_trajectory",
    "trajectory_arrays",
    "write_trajectory",
]

FloatArray = NDArray[np.float64]

#: Largest trajectory file read (64 MiB): about a million samples of six joints.
MAX_BYTES = 64 * 2**20


class TrajectoryFileError(KinematicaError, ValueError):
    """A trajectory CSV file is missing or malformed (the message says where)."""


def read_trajectory(
    path: str | os.PathLike[str], dof: int | None = None, *, allow_nan: bool = False
) -> tuple[FloatArray, FloatArray]:
    """Read a trajectory CSV file.

    Args:
        path: The file: a header row ``t,q1,...,qn``, then one row per sample
            with the time (s, strictly increasing) and the joint values in SI
            units (rad for revolute, m for prismatic joints). Blank lines and
            lines starting with ``#`` are skipped.
        dof: The number of joints expected (the robot's), or ``None``.
        allow_nan: Accept ``nan`` joint values (a sample with no configuration,
            as a Cartesian path writes one); time must be finite regardless.

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
                missing = allow_nan and j > 0 and math.isnan(v)  # a written "nan"
            except ValueError:
                v, missing = math.nan, False
            if not (math.isfinite(v) or missing):
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


def trajectory_arrays(t: ArrayLike, q: ArrayLike) -> tuple[FloatArray, FloatArray]:
    """``t (T,)`` and ``q (T, n)`` as float arrays (``q (T,)``: one joint).

    Raises:
        DimensionError: Not a time per row of joint values.
    """
    tt = np.asarray(t, dtype=float)
    qq = np.asarray(q, dtype=float)
    if qq.ndim == 1:
        qq = qq[:, None]
    if tt.ndim != 1 or qq.ndim != 2 or qq.shape[0] != tt.shape[0]:
        raise DimensionError(
            f"a trajectory needs t of shape (T,) and q of shape (T, n) with the same T, got "
            f"{tt.shape} and {qq.shape}"
        )
    return tt, qq


def write_trajectory(path: str | os.PathLike[str], t: ArrayLike, q: ArrayLike) -> Path:
    """Write a trajectory CSV file atomically (the old file stays whole if writing fails).

    Args:
        path: The file to write.
        t: ``(T,)`` times (s).
        q: ``(T, n)`` joint values (rad, m), or ``(T,)`` for one joint; ``nan``
            where a sample has no configuration.

    Returns:
        The path written.

    Raises:
        DimensionError: The shapes do not match.
        TrajectoryFileError: The file cannot be written (the old one is left as it was).
    """
    tt, qq = trajectory_arrays(t, q)
    p = Path(path)
    header = ",".join(["t", *(f"q{i}" for i in range(1, qq.shape[1] + 1))])
    try:
        with atomic_path(p) as tmp:
            np.savetxt(
                tmp,
                np.column_stack([tt, qq]),
                delimiter=",",
                header=header,
                comments="",
                fmt="%.17g",
            )
    except OSError as exc:
        raise TrajectoryFileError(write_failed(p, exc, "the trajectory")) from exc
    return p
