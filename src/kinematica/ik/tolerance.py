"""Acceptance tolerances of an IK solution: the defaults, and the ``tol`` argument read.

Apart from :mod:`kinematica.ik.targets` (which re-exports them): a request
(:mod:`kinematica.ik.request`) reads ``tol`` without the targets' parsing.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from kinematica import _core
from kinematica.errors import KinematicaError

__all__ = ["POSITION_TOL", "ROTATION_TOL", "Tolerance", "parse_tolerance"]

_CORE = _core.Tolerance()  # the defaults, written once: km::Tolerance in ik_types.hpp
#: A solution must put the tool within this distance of the target (metres, 1e-10)...
POSITION_TOL: float = _CORE.position
#: ... and within this rotation angle of the target orientation (radians, 1e-10).
ROTATION_TOL: float = _CORE.rotation


@dataclass(frozen=True, slots=True)
class Tolerance:
    """Acceptance tolerances of a solution: position (m) and rotation (rad)."""

    position: float = POSITION_TOL
    rotation: float = ROTATION_TOL


_DEFAULT_TOLERANCE = Tolerance()


def parse_tolerance(tol: float | tuple[float, float] | Tolerance | None) -> Tolerance:
    """A :class:`Tolerance` from one number (both), a pair (m, rad) or a Tolerance."""
    if tol is None:
        return _DEFAULT_TOLERANCE
    values: tuple[float, ...]
    if isinstance(tol, Tolerance):
        values = (tol.position, tol.rotation)
    elif isinstance(tol, int | float | np.floating | np.integer) and not isinstance(tol, bool):
        values = (float(tol), float(tol))
    else:
        try:
            values = tuple(float(v) for v in tol)  # type: ignore[union-attr]
        except (TypeError, ValueError):
            values = ()
        if len(values) != 2:
            raise KinematicaError(
                f"tol must be a number or a pair (position m, rotation rad), got {tol!r}",
                arg="tol",
            )
    for name, v in zip(("position", "rotation"), values, strict=True):
        if not (math.isfinite(v) and v > 0):
            raise KinematicaError(f"tol ({name}) must be a positive number, got {v!r}", arg="tol")
    return Tolerance(values[0], values[1])
