"""Which solver ``robot.ik`` gives an arm, in words: a closed form's name, or why the search.

``method="auto"`` answers a target by the closed form the arm's structure has, else
by the numeric search (``numeric:lm``): a local search (Levenberg-Marquardt from one
initial guess, with seeded restarts) that finds one solution at most where more may
exist. An answer of the search that the caller did not ask for carries a note
saying so and why no closed form applied (:func:`search_note`, from
:func:`numeric_reason`); ``kinematica show`` prints the same choice, and the same
reason, for the arm's pose targets (:func:`pose_choice`).
"""

from __future__ import annotations

from collections.abc import Sequence

from kinematica._record import record
from kinematica.core import Chain
from kinematica.ik.registry import ClosedForm, TargetKind
from kinematica.ik.structure import features

__all__ = ["LOCAL_SEARCH", "SolverChoice", "numeric_reason", "pose_choice", "search_note"]

#: What every answer of the search that ``auto`` fell back to says of it (its notes end so).
LOCAL_SEARCH = "a local search that finds one solution at most; more may exist"
#: The joints a pose fixes: an arm of more is redundant.
_POSE_DOF = 6


@record
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


def numeric_reason(chain: Chain, kind: TargetKind, masked: bool) -> str:
    """Why no closed form answers this chain's targets of ``kind``: the structure, or a mask.

    Args:
        chain: The arm solved (for ``robot.ik(T, fixed=...)``, the arm the lock leaves).
        kind: ``"pose"`` or ``"position"``.
        masked: A mask weights the error components.
    """
    if masked:
        return "a mask (the closed forms solve whole poses and positions)"
    from kinematica.ik.solvers import structure_of  # the registry's words for the structure

    f = features(chain)
    n, types = f.dof, f.joint_types
    summary = structure_of(chain)[1]
    if kind == "position":
        return f"position targets of this structure ({summary}), which no closed-form family solves"
    if n > _POSE_DOF + 1:
        return f"{n} joints, {n - _POSE_DOF} more than a pose fixes"
    if n == _POSE_DOF + 1:
        from kinematica.ik.redundancy import choose  # a redundant arm only

        if choose(chain) is None:
            return (
                f"{n} joints and no joint held (none, held at its default value, "
                "leaves an arm with a closed form)"
            )
        return f"{n} joints and no joint held"
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


def pose_choice(chain: Chain, names: Sequence[str] | None = None) -> SolverChoice:
    """The solver ``robot.ik(T)`` gives this arm's pose targets, as its results name it.

    A 7-joint arm that ``auto`` solves at a value of a redundancy parameter names the
    closed form of the arm held there (:func:`kinematica.ik.redundancy.choose`).
    Builds the closed form when no call has yet (a few milliseconds for a general 6R).

    Args:
        chain: The arm.
        names: Its joints' display names (``q1..qn`` when None).
    """
    from kinematica.ik.solvers import closed_form

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
    if closed is not None:
        return SolverChoice(closed.method, complete=_complete(chain, closed))
    from kinematica.ik.numeric import METHOD  # an arm without a closed form

    return SolverChoice(METHOD, reason=numeric_reason(chain, "pose", False), complete=False)


def _complete(chain: Chain, closed: ClosedForm) -> bool:
    """The closed form gives every solution of this arm (as ``solve_ik`` marks its results)."""
    return closed.exact or features(chain).slack == 0.0
