"""Random rigid transforms for the solver specs' sample arms (their base and tool)."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

__all__ = ["random_sign", "random_transform", "random_twist"]

FloatArray = NDArray[np.float64]


def random_sign(rng: np.random.Generator) -> float:
    """-1.0 or 1.0, evenly."""
    return float(rng.choice([-1.0, 1.0]))


def random_twist(rng: np.random.Generator) -> float:
    """A twist well away from 0 and π, either sign (rad)."""
    return float(rng.uniform(0.3, np.pi - 0.3) * rng.choice([-1.0, 1.0]))


def random_transform(rng: np.random.Generator, reach: float | None) -> FloatArray:
    """``(4, 4)`` a random rigid transform: uniform rotation, translation within ``reach`` (m).

    ``reach=None``: no translation (and no random numbers drawn for it).
    """
    q = rng.normal(size=4)
    w, x, y, z = q / np.linalg.norm(q)
    T = np.eye(4)
    T[:3, :3] = [
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ]
    if reach is not None:
        T[:3, 3] = rng.uniform(-reach, reach, 3)
    return T
