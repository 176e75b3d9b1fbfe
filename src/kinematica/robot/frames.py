"""Base and tool transforms of a robot: checked, then made exactly rigid."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.errors import DimensionError
from kinematica.spatial import check_transform, orthonormalize

__all__ = ["rigid_frame", "short"]

FloatArray = NDArray[np.float64]


def short(value: object, limit: int = 60) -> str:
    """``repr(value)``, cut to ``limit`` characters for messages."""
    text = repr(value)
    return text if len(text) <= limit else text[: limit - 3] + "..."


def rigid_frame(T: ArrayLike | None, what: str) -> FloatArray:
    """A base or tool transform, checked as every transform is, then made exactly rigid.

    A rotation written with a few digits (orthonormal to ``ORTHONORMAL_TOL``) is
    accepted and replaced by the nearest rotation, so that forward kinematics
    stays rigid to round-off; one orthonormal to round-off is kept as given.
    """
    if T is None:
        return np.eye(4)
    try:
        raw = np.asarray(T)
    except (TypeError, ValueError) as exc:
        raise DimensionError(
            f"{what} must be a 4x4 matrix of real numbers, got {short(T)}"
        ) from exc
    if raw.dtype.kind not in "iuf":
        raise DimensionError(f"{what} must be a 4x4 matrix of real numbers, got {short(T)}")
    if raw.shape != (4, 4):
        raise DimensionError(f"{what} must be a 4x4 homogeneous transform, got shape {raw.shape}")
    M = np.array(check_transform(raw, name=what), dtype=float)
    M[:3, :3] = orthonormalize(M[:3, :3])[0]
    M[3] = [0.0, 0.0, 0.0, 1.0]
    return M
