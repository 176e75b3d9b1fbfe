"""What an IK solver hands back before checking: raw candidate solutions.

Solvers (closed-form or numeric) fill a :class:`Candidates` for a batch of N
targets; :mod:`kinematica.ik.finalize` then checks every candidate by forward
kinematics, wraps angles, removes duplicates, separates those outside the joint
limits and decides each target's status. A solver never declares success.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np
from numpy.typing import NDArray

__all__ = ["AnalyticSolver", "Candidates"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class Candidates:
    """Raw candidate solutions for N targets.

    Attributes:
        q: ``(N, m, n)`` joint values, one slot per branch; NaN where that
            branch has no real solution for that target.
        labels: ``(m,)`` branch names, e.g. ``"shoulder left, elbow up, wrist no-flip"``.
        singular: ``(N,)`` True where the target has infinitely many solutions
            (the candidates are then representatives).
        free: ``(N, n)`` True for the joints left free in a singular case
            (e.g. q4 and q6 with the wrist aligned); all False otherwise.
        gap: ``(N,)`` for targets with no real branch, how far outside the
            reachable set the target is (metres, a lower bound; 0 if unknown);
            NaN where some branch is real.
    """

    q: FloatArray
    labels: tuple[str, ...]
    singular: NDArray[np.bool_]
    free: NDArray[np.bool_]
    gap: FloatArray

    @classmethod
    def empty(cls, N: int, m: int, n: int, labels: tuple[str, ...]) -> Candidates:
        """All-NaN candidates, no singularity, gap unknown (NaN)."""
        return cls(
            q=np.full((N, m, n), np.nan),
            labels=labels,
            singular=np.zeros(N, dtype=bool),
            free=np.zeros((N, n), dtype=bool),
            gap=np.full(N, np.nan),
        )


class AnalyticSolver(Protocol):
    """A closed-form solver built for one robot.

    Attributes:
        name: Short name used in ``IKResult.method`` as ``"analytic:<name>"``.
        position_only: True if it solves position targets ``(N, 3)`` (the tool
            origin), False if it solves full poses ``(N, 4, 4)``.
    """

    @property
    def name(self) -> str:
        """Short name, e.g. ``"spherical-wrist"``."""
        ...

    @property
    def position_only(self) -> bool:
        """True if the solver takes positions ``(N, 3)`` rather than poses."""
        ...

    def solve(self, targets: FloatArray) -> Candidates:
        """Every branch's solution for each target.

        Args:
            targets: ``(N, 4, 4)`` tool poses in the base frame, or ``(N, 3)``
                tool positions when ``position_only``.

        Returns:
            The candidates (not yet checked).
        """
        ...
