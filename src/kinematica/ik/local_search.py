"""What an answer of the numeric search says of itself, where ``auto`` fell back to it.

``method="auto"`` answers a target by the closed form the arm's structure has, else
by the numeric search (``numeric:lm``): a local search (Levenberg-Marquardt from one
initial guess, with seeded restarts) that finds one solution at most where more may
exist. An answer of the search that the caller did not ask for carries a note
saying so (:data:`LOCAL_SEARCH`) and why no closed form applied (:func:`search_note`,
from :func:`numeric_reason`). A module of words only, below every path that says them.
"""

from __future__ import annotations

from kinematica.core import Chain
from kinematica.ik.analytic import SOLVERS
from kinematica.ik.registry import TargetKind, describe
from kinematica.ik.structure import features

__all__ = ["LOCAL_SEARCH", "numeric_reason", "search_note"]

#: What every answer of the search that ``auto`` fell back to says of it (its notes end so).
LOCAL_SEARCH = "a local search that finds one solution at most; more may exist"
#: The joints a pose fixes: an arm of more is redundant.
_POSE_DOF = 6


def numeric_reason(chain: Chain, kind: TargetKind, masked: bool) -> str:
    """Why no closed form answers this chain's targets of ``kind``: the structure, or a mask.

    Args:
        chain: The arm solved (for ``robot.ik(T, fixed=...)``, the arm the lock leaves).
        kind: ``"pose"`` or ``"position"``.
        masked: A mask weights the error components.
    """
    if masked:
        return "a mask (the closed forms solve whole poses and positions)"
    f = features(chain)
    n, types = f.dof, f.joint_types
    summary = describe(f, SOLVERS)[1]  # the registry's words for the structure
    if kind == "position":
        return f"position targets of this structure ({summary}), which no closed-form family solves"
    if n > _POSE_DOF + 1:
        return f"{n} joints, {n - _POSE_DOF} more than a pose fixes"
    if n == _POSE_DOF + 1:
        return (
            f"{n} joints and no joint held (auto holds one only where, held at its default "
            "value, it leaves an arm with a closed form)"
        )
    if n == _POSE_DOF and "P" in types:
        slides = ", ".join(str(i + 1) for i, t in enumerate(types) if t == "P")
        return (
            f"a slide outside the closed-form families ({n} joints, {types}), and the general "
            f"6R elimination takes revolute joints only (joint {slides} slides)"
        )
    if n == _POSE_DOF:
        return f"{summary}: the general 6R elimination is ill-posed in every ordering of its joints"
    return f"{summary}, a structure no closed-form family solves"


def search_note(reason: str) -> str:
    """The note of an answer of the search ``auto`` fell back to, no closed form applying."""
    return f"no closed form applies: {reason}; the numeric search answered, {LOCAL_SEARCH}"
