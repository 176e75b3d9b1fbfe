"""Angle wrapping."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.spatial.checks import as_float_array

__all__ = ["wrap_angle"]


def wrap_angle(angle: ArrayLike) -> NDArray[np.float64]:
    """Wrap angles to (−π, π] (radians), any shape; ``-0.0`` comes out as ``0.0``."""
    a = as_float_array(angle, "angle")
    return np.pi - np.mod(np.pi - a, 2.0 * np.pi) + 0.0
