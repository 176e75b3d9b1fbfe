"""Two consecutive revolute joints of a 6R arm on one line (:mod:`kinematica.ik.coaxial`).

The test alone, in a module of its own: the solver choice (:mod:`kinematica.ik.solvers`,
:mod:`kinematica.ik.choice`) and the held joints (:mod:`kinematica.ik.parameter`) ask it
without loading the solver, which itself asks for closed forms.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from kinematica.core import Chain
from kinematica.dh.lines import AXIS_EXACT_TOL, line_distance
from kinematica.ik.structure import features

__all__ = ["CoaxialPair", "coaxial_pair"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, slots=True)
class CoaxialPair:
    """Two consecutive revolute joints on one line.

    Attributes:
        first: The first joint of the pair (0-based); the second is ``first + 1``.
        sign: +1 when their axes point the same way (``q_a + q_(a+1)`` counts), -1 when
            opposite (``q_a - q_(a+1)``).
    """

    first: int
    sign: float

    @property
    def second(self) -> int:
        """The second joint of the pair (0-based)."""
        return self.first + 1

    def merged(self, q: FloatArray) -> FloatArray:
        """``(...)`` the angle that counts, ``q_a + σ q_(a+1)``, of configurations ``(..., 6)``."""
        return np.asarray(q[..., self.first] + self.sign * q[..., self.second])


def coaxial_pair(chain: Chain) -> CoaxialPair | None:
    """The first pair of consecutive joints of a 6R arm on one line, or None.

    One line to within :data:`~kinematica.dh.lines.AXIS_EXACT_TOL`: the sine of the
    axes' angle at most that, their distance at most that times ``1 + size``.
    """
    if chain.dof != 6 or bool(chain.prismatic.any()):
        return None
    f = features(chain)
    h, p = f.directions, f.points
    for i in range(5):
        sine = float(np.linalg.norm(np.cross(h[i], h[i + 1])))
        if sine > AXIS_EXACT_TOL:
            continue
        if line_distance(h[i], p[i], h[i + 1], p[i + 1]) <= AXIS_EXACT_TOL * (1.0 + f.size):
            return CoaxialPair(i, 1.0 if float(np.dot(h[i], h[i + 1])) > 0.0 else -1.0)
    return None
