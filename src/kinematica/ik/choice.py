"""Which solver ``robot.ik`` gives an arm, in words: a closed form's name, or why the search.

``kinematica show`` prints, for the arm's pose targets, the closed form ``auto`` takes
(a redundant arm's at its redundancy parameter) or the numeric search and the reason
its answers' notes give (:mod:`kinematica.ik.local_search`): :func:`pose_choice`.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from kinematica.core import Chain
from kinematica.ik.local_search import numeric_reason
from kinematica.ik.registry import ClosedForm
from kinematica.ik.structure import features

__all__ = ["SolverChoice", "pose_choice"]

#: The joints a pose fixes: an arm of more is redundant.
_POSE_DOF = 6


@dataclass(frozen=True, slots=True, eq=False)
class SolverChoice:
    """The solver ``robot.ik(T)`` (``method="auto"``) gives an arm's pose targets.

    Attributes:
        method: What its results' ``method`` says: ``"analytic:<family>"`` or
            ``"numeric:lm"``.
        parameter: For a redundant arm solved at a value of its redundancy parameter,
            its name (a joint's, e.g. ``"q7"``, or ``"arm angle"``); else None.
        reason: For ``"numeric:lm"``, why no closed form applies (the reason the
            results' note gives); else None.
        complete: Its results give every solution: a closed form, on an arm whose axes
            have the family's structure exactly (a near-degenerate arm's, only to within
            the line geometry's tolerances, may miss some: :mod:`kinematica.ik.fallback`).
    """

    method: str
    parameter: str | None = None
    reason: str | None = None
    complete: bool = True


def pose_choice(chain: Chain, names: Sequence[str] | None = None) -> SolverChoice:
    """The solver ``robot.ik(T)`` gives this arm's pose targets, as its results name it.

    A 7-joint arm that ``auto`` solves at a value of a redundancy parameter names the
    closed form of the arm held there (:func:`kinematica.ik.redundancy.choose`).
    Builds the closed form when no call has yet (a few milliseconds for a general 6R).

    Args:
        chain: The arm.
        names: Its joints' display names (``q1..qn`` when None).
    """
    from kinematica.ik.solvers import closed_form, rank_five_of

    if chain.dof == _POSE_DOF + 1:
        from kinematica.ik.arm_angle import ArmAngleParameter
        from kinematica.ik.parameter import JointParameter, locked_chain
        from kinematica.ik.redundancy import choose

        joint = choose(chain, names)
        held = None
        if isinstance(joint, ArmAngleParameter):
            held = closed_form(chain, "pose", "arm_angle")
        elif isinstance(joint, JointParameter):
            held = closed_form(locked_chain(chain, joint.index, joint.default(chain)), "pose")
        if joint is not None and held is not None:
            return SolverChoice(held.method, joint.name, complete=_complete(chain, held))
    closed = closed_form(chain, "pose")
    five = rank_five_of(chain, closed)
    if five is not None:  # a continuum at every pose it reaches, or near one
        from kinematica.ik.continuum_6r import METHOD as CONTINUUM
        from kinematica.ik.near_rank_five import METHOD as NEAR

        return SolverChoice(CONTINUUM if five.exact else NEAR, complete=False)
    if closed is not None:
        return SolverChoice(closed.method, complete=_complete(chain, closed))
    from kinematica.ik.coaxial import METHOD
    from kinematica.ik.coaxial_pair import coaxial_pair

    if coaxial_pair(chain) is not None:  # a continuum at every pose it reaches
        return SolverChoice(METHOD)
    from kinematica.ik.numeric import METHOD as SEARCH  # an arm without a closed form

    return SolverChoice(SEARCH, reason=numeric_reason(chain, "pose", False), complete=False)


def _complete(chain: Chain, closed: ClosedForm) -> bool:
    """The closed form gives every solution of this arm (as ``solve_ik`` marks its results)."""
    return closed.exact or features(chain).slack == 0.0
