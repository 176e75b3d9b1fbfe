"""The closed-form IK of 6R arms with axes 2, 3, 4 parallel (UR type): its spec.

The core solves (``cpp/include/kinematica/solvers/parallel.hpp``, where the method
is described) and builds (``parallel_build.hpp``: once per arm, from its joint axes
at q = 0 and its tool pose, the vectors and constants of equations (1) and (2) in
``(q1, q5)``, the planar triangle axis 2 -> 3 -> 4, a proven reach bound, and the
arm's mode: axes 5 and 6 meeting (every UR and its clones), parallel, or apart
(a5 != 0: the quartic)). Up to 8 solutions, exact, for any link values, offsets,
twists, base, tool and DH convention. This module names the family, its branches
and the arms it declines, and draws its sample arms.

Arms it declines (``None``: the numeric solver takes them): axis 1 or axis 5
parallel to axes 2-4 (four parallel axes), axes 5 and 6 on one line, or a
link of the triangle of length zero (axes 2 and 3, or 3 and 4, on one line).

Branch labels: where axes 5 and 6 meet, ``"shoulder right|left, elbow up|down,
wrist no-flip|flip"``:

* shoulder right: the wrist point (where axes 5 and 6 meet) lies on the
  ``h1 × k1`` side of axis 1 (``k1`` the current direction of axis 2);
* elbow up: the elbow (axis 3) lies on the side of the line axis 2 -> axis 4
  toward which ``h1`` points;
* wrist no-flip: ``(k1 × h6)·h5 >= 0`` for the current axes (for the UR5's
  table, ``sin q5 >= 0``).

Otherwise ``"root j, elbow up|down"``: root j is the j-th ``(q1, q5)`` pair in
increasing order of q1 in (-π, π].
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from kinematica import _core
from kinematica.core import Chain
from kinematica.dh.convert import convert_table
from kinematica.dh.joints import Convention, Revolute
from kinematica.ik.analytic import general_6r
from kinematica.ik.analytic.sampling import random_sign as _sign
from kinematica.ik.analytic.sampling import random_transform
from kinematica.ik.registry import ArmSample, ClosedForm, SolverSpec, TargetKind
from kinematica.ik.structure import Features

__all__ = ["DEGENERATE", "GENERAL_LABELS", "LABELS", "SPEC", "build", "sample_arm"]

FloatArray = NDArray[np.float64]

#: Labels where axes 5 and 6 meet: shoulder, then wrist, then elbow (fastest).
LABELS = tuple(
    f"shoulder {s}, elbow {e}, wrist {w}"
    for s in ("right", "left")
    for w in ("no-flip", "flip")
    for e in ("up", "down")
)
#: Labels where axes 5 and 6 do not meet: the j-th (q1, q5) pair by q1.
GENERAL_LABELS = tuple(f"root {j}, elbow {e}" for j in range(1, 5) for e in ("up", "down"))


def build(chain: Chain, features: Features, target: TargetKind) -> ClosedForm | None:
    """The closed-form solver of a UR-type arm for pose targets, or ``None``.

    The core builds it from the chain alone (``km::parallel::build``,
    ``cpp/include/kinematica/solvers/parallel_build.hpp``) and declines the arms the
    module docstring lists. An arm whose axes have the structure only within the line
    geometry's tolerance (``features.near_degenerate``) gets the general 6R's candidates
    too, when its builder finds a labelling (``km::build_near_parallel``,
    ``solvers/near_6r_build.hpp``: near the family's singular sets the real arm's
    solutions lie beyond the repair's reach of the family's); their branch labels follow
    the family's.
    """
    if target != "pose":
        return None
    params = _core.parallel.build(chain.core)
    if params is None:
        return None
    labels = LABELS if params.mode == _core.parallel.Mode.meet else GENERAL_LABELS
    if features.near_degenerate:
        near = _core.general6r.near_parallel(chain.core)
        if near is not None:
            return ClosedForm(
                name="three-parallel-6R", labels=labels + general_6r.LABELS, params=near
            )
    return ClosedForm(name="three-parallel-6R", labels=labels, params=params)


# ------------------------------------------------------------------ sample arms
#: The edge geometries sample_arm draws from (its note says which).
DEGENERATE = (
    "equal links",
    "offsets of 1e-10",
    "twists of axes 2-4 within 1e-9 of 0 or pi",
    "wrist twists of 90 degrees",
    "axes 5 and 6 1e-10 m apart",
    "axes 5 and 6 1e-9 m apart",
    "axes 5 and 6 parallel within 1e-10",
    "no offset along axis 2",
    "axes 4, 5, 6 meeting",
)


def _twist(rng: np.random.Generator, square: bool) -> float:
    """±90° (``square``: the wrist can align), else a twist well away from 0 and π (rad)."""
    if square:
        return _sign(rng) * math.pi / 2
    return _sign(rng) * float(rng.uniform(0.3, math.pi - 0.3))


def sample_arm(rng: np.random.Generator, degenerate: bool = False) -> ArmSample:
    """A random UR-type arm (axes 2, 3, 4 parallel) in a random DH convention.

    Axes 5 and 6 meet, lie apart or are parallel (drawn at random); a quarter of
    the generic arms have ±90° twists at joints 1, 4, 5 (the wrist can align).

    Args:
        rng: Random numbers.
        degenerate: Draw one of the edge geometries of :data:`DEGENERATE` (the
            sample's ``note``): equal links 2 and 3 (the elbow folds onto axis 2),
            offsets a1, d2, d3 of 1e-10 m, twists of axes 2-4 within 1e-9 rad of 0
            or π, ±90° twists, axes 5 and 6 1e-10 or 1e-9 m apart or parallel within
            1e-10 rad, nothing along axis 2 between axes 2 and 5 (the wrist point
            reaches axis 1), axes 4-6 meeting.

    Returns:
        The arm as DH rows (m, rad) with a random base and tool.
    """
    u = rng.uniform
    case = str(rng.choice(DEGENERATE)) if degenerate else ""
    mode = str(rng.choice(["meet", "apart", "parallel"]))
    square = case == "wrist twists of 90 degrees" or bool(rng.random() < 0.25)
    small = 1e-10 if case == "offsets of 1e-10" else 0.0
    a2 = u(0.2, 0.6) * _sign(rng)
    a3 = abs(a2) * _sign(rng) if case == "equal links" else u(0.2, 0.6) * _sign(rng)
    flat = [float(rng.choice([0.0, math.pi])) for _ in range(2)]
    if case == "twists of axes 2-4 within 1e-9 of 0 or pi":
        flat = [v + u(-5e-10, 5e-10) for v in flat]
    d4, a4, alpha4 = u(-0.2, 0.2), u(-0.1, 0.1), _twist(rng, square)
    d5, a5, alpha5 = u(-0.2, 0.2), 0.0, _twist(rng, square)
    if mode == "apart":
        a5 = u(0.03, 0.15) * _sign(rng)
    elif mode == "parallel":
        a5, alpha5 = u(0.03, 0.15), 0.0
    # (with a5 of 1e-9 or less, axes 5 and 6 need a twist: on one line they are declined)
    if case == "axes 5 and 6 1e-10 m apart":
        a5, alpha5 = 1e-10, _twist(rng, square)
    elif case == "axes 5 and 6 1e-9 m apart":
        a5, alpha5 = 1e-9, _twist(rng, square)
    elif case == "axes 5 and 6 parallel within 1e-10":
        a5, alpha5 = u(0.03, 0.15), 1e-10 * _sign(rng)
    elif case == "axes 4, 5, 6 meeting":
        d5, a5, alpha5 = 0.0, 0.0, _twist(rng, square)
    elif case == "no offset along axis 2":  # d5 runs along axis 5, across axis 4
        d4, a4, alpha4, a5, alpha5 = 0.0, 0.0, _twist(rng, True), 0.0, _twist(rng, square)
    rows = (
        Revolute(d=u(0.05, 0.4), a=small, alpha=_twist(rng, square), offset=u(-math.pi, math.pi)),
        Revolute(d=small, a=a2, alpha=flat[0]),
        Revolute(d=small, a=a3, alpha=flat[1]),
        Revolute(d=d4, a=a4, alpha=alpha4, offset=u(-math.pi, math.pi)),
        Revolute(d=d5, a=a5, alpha=alpha5, offset=u(-math.pi, math.pi)),
        Revolute(d=u(-0.2, 0.2), a=u(-0.1, 0.1), alpha=u(-math.pi, math.pi)),
    )
    base, tool = random_transform(rng, 0.5), random_transform(rng, 0.2)
    convention: Convention = "modified" if rng.random() < 0.5 else "standard"
    links, base, tool = convert_table(rows, "standard", convention, base, tool)
    return ArmSample(links, convention, base, tool, case)


def _handles(f: Features) -> bool:
    return f.joint_types == "RRRRRR" and {(1, 2), (2, 3)} <= set(f.parallel)


SPEC: SolverSpec = SolverSpec(
    kind="three-parallel-6R",
    summary="6R, three parallel axes (2-3-4), UR type",
    summary_es="6R con tres ejes paralelos (2-3-4), tipo UR",
    handles=_handles,
    build=build,
    sample_arm=sample_arm,
    singular=frozenset({"shoulder", "elbow", "wrist"}),
)
