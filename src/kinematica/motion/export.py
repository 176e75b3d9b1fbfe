"""Trajectories to files: CSV (``t,q1,...,qn``) and JSON.

The CSV format is the one ``kinematica animate`` reads: a header
``t,q1,q2,...,qn``, then one row per sample, time in seconds first, then the
joint values in SI units (rad for revolute, m for prismatic joints), written
with 17 significant digits (exact round trip); ``nan`` where a sample has no
configuration.
"""

from __future__ import annotations

import json
import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.errors import DimensionError, KinematicaError
from kinematica.io.atomic import atomic_path, write_failed, write_text_atomic

__all__ = ["read_csv", "write_csv", "write_json"]

FloatArray = NDArray[np.float64]


def _check(t: ArrayLike, q: ArrayLike) -> tuple[FloatArray, FloatArray]:
    ta = np.asarray(t, dtype=float)
    qa = np.asarray(q, dtype=float)
    if qa.ndim == 1:
        qa = qa[:, None]
    if ta.ndim != 1 or qa.ndim != 2 or qa.shape[0] != ta.shape[0]:
        raise DimensionError(
            f"t must be (m,) and q (m, n) with the same m, got {ta.shape} and {qa.shape}"
        )
    return ta, qa


def write_csv(path: str | Path, t: ArrayLike, q: ArrayLike) -> Path:
    """Write ``t`` and ``q`` as CSV with the header ``t,q1,...,qn``.

    Args:
        path: The file to write.
        t: ``(m,)`` times (s).
        q: ``(m, n)`` joint values (rad, m).

    Returns:
        The path written.
    """
    ta, qa = _check(t, q)
    header = ",".join(["t"] + [f"q{i}" for i in range(1, qa.shape[1] + 1)])
    out = Path(path)
    try:
        with atomic_path(out) as tmp:
            np.savetxt(
                tmp,
                np.column_stack([ta, qa]),
                delimiter=",",
                header=header,
                comments="",
                fmt="%.17g",
            )
    except OSError as exc:
        raise KinematicaError(write_failed(out, exc, "the trajectory")) from exc
    return out


def read_csv(path: str | Path) -> tuple[FloatArray, FloatArray]:
    """Read a trajectory CSV written by :func:`write_csv`.

    Returns:
        ``(t (m,), q (m, n))``.

    Raises:
        KinematicaError: The file is missing, its header is not
            ``t,q1,...,qn`` or a row is malformed (the message says which).
    """
    p = Path(path)
    try:
        lines = p.read_text().splitlines()
    except OSError as exc:
        raise KinematicaError(f"{p}: cannot read ({exc.strerror})") from exc
    if not lines:
        raise KinematicaError(f"{p}: empty file, expected the header t,q1,...,qn")
    head = [h.strip() for h in lines[0].split(",")]
    want = ["t"] + [f"q{i}" for i in range(1, len(head))]
    if len(head) < 2 or head != want:
        raise KinematicaError(f"{p}: header must be {','.join(want)}, got {lines[0]!r}")
    rows = []
    for k, line in enumerate(lines[1:], start=2):
        if not line.strip():
            continue
        cells = line.split(",")
        try:
            rows.append([float(c) for c in cells])
        except ValueError as exc:
            raise KinematicaError(f"{p}, line {k}: not a number ({exc})") from exc
        if len(cells) != len(head):
            raise KinematicaError(f"{p}, line {k}: expected {len(head)} values, got {len(cells)}")
    data = np.array(rows, dtype=float).reshape(-1, len(head))
    return data[:, 0], data[:, 1:]


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
    ta, qa = _check(t, q)
    data: dict[str, Any] = dict(meta or {})
    data["units"] = {"t": "s", "revolute": "rad", "prismatic": "m"}
    if joint_types is not None:
        data["joint_types"] = joint_types
    data["t"] = _json_safe(ta)
    data["q"] = _json_safe(qa)
    for key, val in (("qd", qd), ("qdd", qdd)):
        if val is not None:
            data[key] = _json_safe(_check(ta, val)[1])
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
