"""Angle wrapping."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

import kinematica._core as _core
from kinematica.spatial.checks import as_float_array

__all__ = ["wrap_angle"]


def wrap_angle(angle: ArrayLike) -> NDArray[np.float64]:
    """Wrap angles to (−π, π] (radians), any shape; ``-0.0`` comes out as ``0.0``.

    Values already in (−π, π] come back unchanged; NaN and ±inf give NaN. The
    core's ``wrap``, the one every IK solution goes through.
    """
    a = as_float_array(angle, "angle")
    flat = np.ascontiguousarray(a.reshape(-1), dtype=np.float64)
    return _core.wrap(flat).reshape(a.shape) + 0.0
