"""Any 6R arm: the general 6R solver (Raghavan-Roth, Manocha-Canny) and its family's spec.

The core solves the arm written as a loop ``I = Rz(q'1) L1 ... Rz(q'6) L6`` (one link
holding the target, ``cpp/include/kinematica/solvers/general_6r.hpp``), by eliminating
q'3, then the 8 products of (q'1, q'2), leaving a 12 x 12 matrix quadratic in tan(q'6/2)
whose determinant's roots are a 16 x 16 eigenproblem (its 8 roots at ±i deflated from
the 24 x 24 companion matrix). The core also builds it (``general_6r_build.hpp``): the
loop from the joint axes at q = 0 (product of exponentials: any base, tool, convention
or URDF chain), and of its twelve labellings (the loop turned cyclically or reversed)
the one for which the elimination is well posed: those on which probe poses are solved
(the generating configuration found among the candidates), the first accurate to
round-off, else the one whose eigenvalues are the most accurate there, and up to two
more that pass, tried where the chosen one's candidates close no loop for a target.
Where no candidate closes and every eigenvalue of the pencil lies far from the real axis
against its error bound, the core proves the target out of reach ("unreachable").
This module names the family, its branches and notes, and draws its sample arms.
"""

from __future__ import annotations

import functools
import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

import kinematica._core as _core
from kinematica.core import Chain
from kinematica.dh.convert import convert_table
from kinematica.dh.joints import Joint, Revolute
from kinematica.ik.analytic.sampling import random_transform
from kinematica.ik.rank_five import RANK_FIVE_HELD
from kinematica.ik.registry import ArmSample, ClosedForm, SolverSpec, TargetKind
from kinematica.ik.structure import Features

__all__ = ["LABELS", "SEARCH_NOTE", "SPEC", "build", "free_joints", "mark_continua"]

FloatArray = NDArray[np.float64]
PI = math.pi
_G = _core.general6r

#: Said of a target the elimination found nothing for and proved nothing of (the core's
#: not_found, its near flag raised: no candidate within the check's polish, no reach gap,
#: a root of det M(x6) on or near the real axis), answered by the numeric search. Where
#: det M(x6) has no real root, proven, the core's answer is unreachable.
SEARCH_NOTE = (
    "the general 6R elimination gave no candidate closing the loop for this target "
    "(the target at the workspace boundary, or its eigenproblem degenerate there): "
    "not proven unreachable; the numeric search answered"
)


def _class_label(cls: int, k: int) -> str:
    signs = [(cls >> 2) & 1, (cls >> 1) & 1, cls & 1]
    parts = [f"q{j} {'>' if s else '<'} 0" for j, s in zip((2, 3, 5), signs, strict=True)]
    return f"{', '.join(parts)} #{k + 1}"


#: Branch names of the candidate slots: the signs of q2, q3, q5 (wrapped to (-π, π]),
#: the members of a class numbered by increasing q1; then members beyond PER_CLASS.
LABELS: tuple[str, ...] = tuple(
    _class_label(c, k) for c in range(_G.CLASSES) for k in range(_G.PER_CLASS)
) + tuple(f"further solution #{k + 1}" for k in range(_G.FURTHER))


# ---------------------------------------------------------------- the builder
def build(chain: Chain, f: Features, target: TargetKind) -> ClosedForm | None:
    """The general 6R solver of a 6R arm, or None (position targets; no labelling works).

    The core's builder (``general_6r_build.hpp``): of the twelve labellings, the first
    accurate to round-off (ACCURATE) whose probes pass, else the most accurate of those
    whose probes pass after Newton's step (PROBE_TOL). None without trying on an arm a
    held joint leaves of rank 5 whatever its value (``RANK_FIVE_HELD``): the builder
    declines every exact rank-5 arm.
    """
    if target != "pose" or f.joint_types != "RRRRRR" or chain.memo.get(RANK_FIVE_HELD):
        return None
    params = _G.build(chain.core)
    return None if params is None else _closed_form(params)


def _closed_form(params: Any) -> ClosedForm:
    return ClosedForm(
        name="general-6R",
        labels=LABELS,
        params=params,
        exact=True,
        search_note=SEARCH_NOTE,
        mark_searched=functools.partial(mark_continua, params),
    )


# ------------------------------------------------------ continua of a search's answers
def free_joints(params: Any, T: FloatArray, q: FloatArray) -> tuple[int, ...]:
    """The joints free along the continuum of solutions through ``q``, or ``()``.

    The core's self-motion test (``general_6r.hpp``: the loop's Jacobian rank-deficient
    at q, a step along its null direction, the loop closed again with one joint held),
    the one the elimination's own candidates go through.

    Args:
        params: The arm's ``General6RParams``.
        T: ``(4, 4)`` the target (base frame, m).
        q: ``(6,)`` a solution of T (rad), e.g. the numeric search's.

    Returns:
        0-based indices of the free joints (ascending); ``()`` when q is regular, at a
        fold, or not a solution to within the loop's closure tolerance.
    """
    return tuple(sorted(_G.free_joints(params, T, q)))


def mark_continua(params: Any, poses: FloatArray, q: FloatArray, status: Any, free: Any) -> None:
    """Say ``singular`` where the numeric search's answer lies on a continuum (in place).

    The search answers the targets the elimination found nothing for (its candidates
    lost where the method degenerates, a continuum among them): a solution on a
    continuum is one point of infinitely many, so its status becomes singular and the
    joints free along it are named, as the closed form says of its own.

    Args:
        params: The arm's ``General6RParams``.
        poses: ``(k, 4, 4)`` the targets searched.
        q: ``(k, 6)`` the search's solution of each (NaN: none).
        status: ``(k,)`` int status codes, changed in place.
        free: ``(k, 6)`` bool free joints, changed in place.
    """
    solved, singular = _core.STATUS["ok"], _core.STATUS["singular"]
    for i in range(len(poses)):
        if int(status[i]) != solved or not np.isfinite(q[i]).all():
            continue
        joints = free_joints(params, poses[i], q[i])
        if joints:
            status[i] = singular
            free[i, list(joints)] = True


# ------------------------------------------------------------- sample arms
def _random_rows(rng: np.random.Generator) -> list[Revolute]:
    u = rng.uniform
    return [
        Revolute(d=u(-0.4, 0.4), a=u(-0.4, 0.4), alpha=u(-PI, PI), offset=u(-PI, PI))
        for _ in range(6)
    ]


#: The UR5's DH table (standard; m, rad), perturbed for the "calibrated UR" edge.
_UR5 = (
    (0.089159, 0.0, PI / 2),
    (0.0, -0.425, 0.0),
    (0.0, -0.39225, 0.0),
    (0.10915, 0.0, PI / 2),
    (0.09465, 0.0, -PI / 2),
    (0.0823, 0.0, 0.0),
)


#: The edges of the general family a degenerate sample arm is drawn from.
_EDGES = (
    "equal links",
    "offset 1e-10",
    "parallel 1e-9",
    "calibrated UR",
    "one common normal",
    "two pairs meet",
    "parallel pairs",
)


def _edge(rng: np.random.Generator) -> tuple[list[Revolute], str, bool]:
    """A 6R arm on an edge of the general family: ``(rows, what it is, standard)``.

    ``standard``: the rows are a real arm's table in the standard convention (a
    calibrated UR's), to be converted for Craig's; the others are random tables that
    serve either convention as they are.
    """
    u = rng.uniform
    edge = str(rng.choice(_EDGES))
    if edge in ("one common normal", "two pairs meet", "parallel pairs"):
        return _special(rng, edge), edge, False
    if edge == "calibrated UR":
        rows = [
            Revolute(d=d, a=a, alpha=al + 1e-3 * float(rng.choice([-1.0, 1.0])), offset=u(-PI, PI))
            for d, a, al in _UR5
        ]
        return rows, "UR5 with every twist 1e-3 off", True
    rows = _random_rows(rng)
    i = int(rng.integers(6))
    r = rows[i]
    if edge == "equal links":
        a, d = u(0.2, 0.4), u(0.1, 0.3)
        rows = [Revolute(d=d, a=a, alpha=x.alpha, offset=x.offset) for x in rows]
    elif edge == "offset 1e-10":
        rows[i] = Revolute(d=1e-10, a=1e-10, alpha=r.alpha, offset=r.offset)
        edge = f"joint {i + 1}: d = a = 1e-10"
    else:
        rows[i] = Revolute(
            d=r.d, a=r.a, alpha=1e-9 * float(rng.choice([-1.0, 1.0])), offset=r.offset
        )
        edge = f"axes {i + 1} and {i + 2} parallel but for 1e-9" if i < 5 else "alpha6 = 1e-9"
    return rows, edge, False


def _special(rng: np.random.Generator, edge: str) -> list[Revolute]:
    """A random table with the special axes of makers' cobots (FANUC CRX, Kinova JACO 2).

    "one common normal": every a but one 0 (consecutive axes meet), the twists right
    angles or random (the one beside the nonzero a may be 0 or π: a parallel pair, the
    CRX's 2 ∥ 3); "two pairs meet": two a's 0; "parallel pairs": one or two twists 0 or π
    (a pair of parallel axes anywhere).
    """
    rows = _random_rows(rng)
    u = rng.uniform
    a = [r.a for r in rows]
    alpha = [r.alpha for r in rows]
    if edge == "one common normal":
        k = int(rng.integers(6))
        a = [u(0.2, 0.6) if i == k else 0.0 for i in range(6)]
        for i in range(6):
            if rng.random() < 0.6:  # coaxial consecutive joints (a = 0, α = 0 or π) excluded
                alpha[i] = float(rng.choice([PI / 2, -PI / 2] + ([0.0, PI] if i == k else [])))
    elif edge == "two pairs meet":
        for i in rng.choice(6, 2, replace=False):
            a[int(i)] = 0.0
    else:
        for i in rng.choice(6, int(rng.integers(1, 3)), replace=False):
            alpha[int(i)] = float(rng.choice([0.0, PI]))
            a[int(i)] = u(0.1, 0.4)
    return [Revolute(d=r.d, a=a[i], alpha=alpha[i], offset=r.offset) for i, r in enumerate(rows)]


def sample_arm(rng: np.random.Generator, degenerate: bool) -> ArmSample:
    """A random 6R arm of general geometry (an edge case with ``degenerate``)."""
    rows, note, standard = _edge(rng) if degenerate else (_random_rows(rng), "", False)
    modified = str(rng.choice(["standard", "modified"])) == "modified"
    base, tool = random_transform(rng, 0.5), random_transform(rng, 0.2)
    links: tuple[Joint, ...] = tuple(rows)
    if modified and standard:  # the same arm, its table in Craig's convention
        links, b, t = convert_table(links, "standard", "modified", np.eye(4), np.eye(4))
        base, tool = base @ b, t @ tool
    return ArmSample(
        links=links,
        convention="modified" if modified else "standard",
        base=base,
        tool=tool,
        note=note,
    )


SPEC = SolverSpec(
    kind="general-6R",
    summary="6R, general geometry",
    summary_es="6R de geometría general",
    handles=lambda f: f.joint_types == "RRRRRR",
    build=build,
    sample_arm=sample_arm,
)
