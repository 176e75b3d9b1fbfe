"""Poses a 6R arm of rank 5 cannot reach, proved by the quantity its structure keeps fixed.

An arm of rank 5 everywhere (:mod:`kinematica.ik.rank_five`) reaches a five-dimensional
set of poses; where its structure is named, one scalar of the tool pose is the same at
every configuration:

- **a spherical shoulder and a spherical wrist**: the distance from the shoulder centre
  S (fixed in the base frame: it lies on axis 1) to the wrist centre W (fixed in the tool
  frame: it lies on axis 6) is the length of the middle link, whatever the joints;
- **axes 1-3 parallel (direction h), axes 4-6 meeting at W**: joints 1-3 move every
  point of link 3 in planes normal to h, and W is one of them: ``h · W`` is fixed;
- **axes 1-3 meeting at S, axes 4-6 parallel (direction h6, fixed in the tool frame)**:
  the same seen from the tool: ``h6 · (T⁻¹ S)`` is fixed.

A target whose value misses the arm's by more than the call's tolerance carried to it
is reached by no configuration within that tolerance, and is proved ``unreachable``.
The tolerance carried: a configuration meeting T within ``tol.position`` (m, the tool
origin) and ``tol.rotation`` (rad) puts the point (W, or S seen from the tool) within
``tol.position + r tol.rotation`` of where T puts it, r its distance from the tool
origin (or from the target's origin); to that, :data:`INVARIANT_ROUNDOFF` of the arm's
size for the round-off of the centres themselves. A value within that margin is not
proved anything: the search answers it.

Four concurrent and four parallel axes keep no such single quantity of the pose (the
two joints after them leave one scalar equation in a joint angle), and are not proved
unreachable here.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from kinematica.core import Chain
from kinematica.ik.rank_five import RankFive
from kinematica.ik.structure import features

__all__ = ["INVARIANT_ROUNDOFF", "Invariant", "invariant", "invariant_miss"]

FloatArray = NDArray[np.float64]

#: The centres of an exact arm of rank 5 are known to round-off of the arm's size (they
#: meet within 1e-13 of it on the arms of :mod:`kinematica.ik.rank_five`, whose ratio is
#: at most 1e-13): the margin adds this, relative to the size.
INVARIANT_ROUNDOFF = 1e-12


@dataclass(frozen=True, slots=True)
class Invariant:
    """The fixed quantity of an arm of rank 5 and the target's.

    Attributes:
        words: What it is (``"the distance from the shoulder centre to the wrist
            centre"``).
        fixed: The arm's value (m), the same at every configuration.
        value: The target's (m).
        margin: The call's tolerance carried to it, round-off included (m).
    """

    words: str
    fixed: float
    value: float
    margin: float

    @property
    def missed(self) -> bool:
        """True when the target's value misses the arm's by more than the margin."""
        return abs(self.value - self.fixed) > self.margin

    def note(self) -> str:
        """The proof, in words."""
        return (
            f"{self.words} is {self.fixed:.9g} m at every configuration, and "
            f"{self.value:.9g} m for this target: it misses by "
            f"{abs(self.value - self.fixed):.3g} m, "
            f"more than the tolerance carried to it ({self.margin:.3g} m)"
        )


def invariant(
    chain: Chain, five: RankFive, T: FloatArray, position: float, rotation: float
) -> Invariant | None:
    """The fixed quantity of the arm's structure at the target ``T (4, 4)``, or None.

    Args:
        chain: The 6R arm, of rank 5 everywhere (exact).
        five: Its structure (:func:`~kinematica.ik.rank_five.rank_five`).
        T: ``(4, 4)`` the target (base frame, m).
        position: The call's position tolerance (m).
        rotation: The call's rotation tolerance (rad).

    Returns:
        None where the structure keeps no single quantity (four concurrent or parallel
        axes, or none named).
    """
    f = features(chain)
    F0 = np.asarray(chain.fk(np.zeros(6))[0])
    roundoff = INVARIANT_ROUNDOFF * f.size
    T = np.asarray(T, dtype=np.float64)
    if five.kind == "shoulder-wrist" and f.shoulder_center is not None:
        assert f.wrist_center is not None
        S, W0 = f.shoulder_center, f.wrist_center
        w = np.linalg.solve(F0, np.append(W0, 1.0))[:3]  # W in the tool frame
        W = T[:3, :3] @ w + T[:3, 3]
        return Invariant(
            "the distance from the shoulder centre to the wrist centre",
            float(np.linalg.norm(W0 - S)),
            float(np.linalg.norm(W - S)),
            position + float(np.linalg.norm(w)) * rotation + roundoff,
        )
    if five.kind != "parallel-concurrent":
        return None
    if f.all_parallel(range(3)) and f.wrist_center is not None:
        h = f.directions[0]
        W0 = f.wrist_center
        w = np.linalg.solve(F0, np.append(W0, 1.0))[:3]
        return Invariant(
            "the wrist centre's height along the parallel axes 1-3",
            float(h @ W0),
            float(h @ (T[:3, :3] @ w + T[:3, 3])),
            position + float(np.linalg.norm(w)) * rotation + roundoff,
        )
    if f.shoulder_center is None:
        return None
    S = f.shoulder_center
    h6 = F0[:3, :3].T @ f.directions[5]  # axis 6 in the tool frame
    s0 = F0[:3, :3].T @ (S - F0[:3, 3])
    s = T[:3, :3].T @ (S - T[:3, 3])
    return Invariant(
        "the shoulder centre's height along the parallel axes 4-6, seen from the tool",
        float(h6 @ s0),
        float(h6 @ s),
        position + float(np.linalg.norm(S - T[:3, 3])) * rotation + roundoff,
    )


def invariant_miss(
    chain: Chain, five: RankFive, T: FloatArray, position: float, rotation: float
) -> Invariant | None:
    """:func:`invariant` where it proves ``T`` out of reach (:attr:`Invariant.missed`); None."""
    inv = invariant(chain, five, T, position, rotation)
    return inv if inv is not None and inv.missed else None
