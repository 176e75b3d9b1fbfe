"""Trajectories to files: CSV (``t,q1,...,qn``) and JSON.

The CSV format is :mod:`kinematica.io.trajectory_csv`'s (the one ``kinematica
animate`` reads): ``write_csv`` is its writer; JSON adds velocities,
accelerations, units and path events.
"""

from __future__ import annotations

import json
import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.errors import KinematicaError
from kinematica.io.atomic import write_failed, write_text_atomic
from kinematica.io.trajectory_csv import read_trajectory, trajectory_arrays
from kinematica.io.trajectory_csv import write_trajectory as write_csv

__all__ = ["read_csv", "write_csv", "write_json"]

FloatArray = NDArray[np.float64]


def read_csv(path: str | Path) -> tuple[FloatArray, FloatArray]:
    """Read a trajectory CSV file (:func:`write_csv`'s format; ``nan`` allowed).

    Returns:
        ``(t (m,), q (m, n))``.

    Raises:
        TrajectoryFileError: The file is missing or not a regular file, its header is
            not ``t,q1,...,qn``, or a row is malformed (the message says which line).
    """
    return read_trajectory(path, allow_nan=True)


def _json_safe(a: Any) -> Any:
    """Nested lists with ``None`` for NaN/inf (JSON has no NaN)."""
    if isinstance(a, np.ndarray):
        return _json_safe(a.tolist())
    if isinstance(a, list | tuple):
        return [_json_safe(v) for v in a]
    if isinstance(a, float) and not math.isfinite(a):
        return None
    return a


def write_json(
    path: str | Path,
    t: ArrayLike,
    q: ArrayLike,
    qd: ArrayLike | None = None,
    qdd: ArrayLike | None = None,
    *,
    joint_types: str | None = None,
    events: Sequence[Any] = (),
    meta: dict[str, Any] | None = None,
) -> Path:
    """Write a trajectory as JSON.

    Keys: ``t`` (s), ``q`` (rad, m), optional ``qd``, ``qdd``, ``units``,
    ``joint_types``, ``events`` (kind, index, s, names, message) and any
    ``meta`` entries. NaN is written as ``null``.

    Args:
        path: The file to write.
        t: ``(m,)`` times (s).
        q: ``(m, n)`` joint values.
        qd: ``(m, n)`` velocities, or ``None``.
        qdd: ``(m, n)`` accelerations, or ``None``.
        joint_types: e.g. ``"RRPRRR"`` (says which columns are metres).
        events: :class:`~kinematica.motion.cartesian.PathEvent` objects.
        meta: Extra top-level entries (robot name, profile...).

    Returns:
        The path written.
    """
    ta, qa = trajectory_arrays(t, q)
    data: dict[str, Any] = dict(meta or {})
    data["units"] = {"t": "s", "revolute": "rad", "prismatic": "m"}
    if joint_types is not None:
        data["joint_types"] = joint_types
    data["t"] = _json_safe(ta)
    data["q"] = _json_safe(qa)
    for key, val in (("qd", qd), ("qdd", qdd)):
        if val is not None:
            data[key] = _json_safe(trajectory_arrays(ta, val)[1])
    data["events"] = [
        {
            "kind": e.kind,
            "index": e.index,
            "stop": e.stop,
            "s": e.s,
            "names": list(e.names),
            "message": e.message,
        }
        for e in events
    ]
    out = Path(path)
    text = json.dumps(data, indent=1, allow_nan=False) + "\n"
    try:
        write_text_atomic(out, text)
    except OSError as exc:
        raise KinematicaError(write_failed(out, exc, "the trajectory")) from exc
    return out
