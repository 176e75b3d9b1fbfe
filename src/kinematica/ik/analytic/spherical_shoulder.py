"""Spherical-shoulder arms (Pieper's second case): the spherical wrist, read backwards.

When the first three axes meet (at the shoulder centre), the arm read from the tool
back to the base is a spherical-wrist arm: ``T(q)⁻¹`` is the pose of the chain
:meth:`kinematica.core.Chain.reversed` at ``q'_j = -q_(7-j)``, whose last three axes
(this arm's 3, 2, 1) meet. This module builds that chain from the arm's own
transforms and builds the spherical-wrist solver of it, wrapped in its
``SphericalShoulderParams`` (``km::decoupled::build_shoulder``,
``cpp/include/kinematica/solvers/spherical_shoulder_build.hpp``; the solver,
``spherical_shoulder.hpp``, inverts the target and reads the candidates back).
This module names the family and its branches and draws its sample arms.

Branch labels, base to tip (slot ``2 k + s``):

* ``shoulder no-flip`` / ``shoulder flip`` (``s``): the shoulder's joints 1-3 (the
  reversed arm's wrist) have two ways to make one rotation, joint 2 bent to either
  side. "No-flip" bends joint 2 the way it is bent at q = 0, or, when q = 0 is itself
  singular there (axes 1 and 3 aligned, as on the Panda), the way q2 > 0 bends it:
  on the Panda, sin q2 > 0.
* then how joints 4-6 (the reversed arm's joints 3, 2, 1) place the shoulder centre
  as the tool sees it, named as for a spherical-wrist arm with its shoulder called
  the wrist: ``elbow up`` / ``elbow down`` (or, where axes 4 and 5 are not parallel,
  ``elbow bent positive`` / ``elbow bent negative``: q4 turned either way from its
  stretched angle q4*, right-hand rule about axis 4; on the Panda, whose q4 is
  always negative, bent negative; for a slide, ``slide out`` / ``slide in``: the
  larger and the smaller q4) for joint 4,
  ``wrist right`` / ``wrist left`` (or ``front`` / ``back``) for joints 6 and 5; arms
  whose last two axes neither meet nor are parallel number these
  ``wrist position 1..4``.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

import kinematica._core as _core
from kinematica.core import Chain
from kinematica.dh.joints import Prismatic, Revolute
from kinematica.ik.analytic.arm_point import geometry_of
from kinematica.ik.analytic.sampling import random_transform
from kinematica.ik.analytic.spherical_wrist import sample_wrist_rows
from kinematica.ik.registry import ArmSample, ClosedForm, SolverSpec, TargetKind
from kinematica.ik.structure import Features
from kinematica.spatial.transform import inv_transform

__all__ = ["SPECS", "build", "reversed_arm", "shoulder_labels"]

FloatArray = NDArray[np.float64]


def shoulder_labels(positions: tuple[str, ...]) -> tuple[str, ...]:
    """The 8 branch labels of a shoulder arm from its reversed arm's 4 position labels.

    The reversed arm's shoulder (its joints 1, 2) is this arm's wrist end, its
    elbow this arm's joint 4: ``"shoulder right, elbow up"`` becomes ``"elbow up,
    wrist right"``, ``"position 2"`` becomes ``"wrist position 2"``; a slide's
    ``"slide out"`` (the larger ``q'3 = -q4``) becomes ``"slide in"``.
    """
    # the reversed arm's slide out is its larger q'3 = -q4: this arm's slide in; its
    # elbow bent positive (q'3 > q'3*) is this arm's q4 < q4*: bent negative
    slide = {
        "slide out": "slide in",
        "slide in": "slide out",
        "elbow bent positive": "elbow bent negative",
        "elbow bent negative": "elbow bent positive",
    }
    labels = []
    for pos in positions:
        parts = [slide.get(p, p.replace("shoulder", "wrist")) for p in pos.split(", ")]
        far = ", ".join(parts[::-1]) if len(parts) > 1 else f"wrist {parts[0]}"
        labels += [f"shoulder {s}, {far}" for s in ("no-flip", "flip")]
    return tuple(labels)


def build(chain: Chain, f: Features, target: TargetKind) -> ClosedForm | None:
    """The closed form of a 6R or RRRPRR arm whose first three axes meet, or None.

    None for position targets, and where the reversed chain's spherical-wrist
    solver is none (joints 6, 5, 4 cannot move the shoulder centre in three
    directions, or two consecutive shoulder axes coincide).
    """
    if target != "pose" or f.shoulder_center is None or f.dof != 6:
        return None
    params = _core.decoupled.build_spherical_shoulder(chain.core)
    if params is None:
        return None
    slide = f.joint_types[3] == "P"
    return ClosedForm(
        name="spherical-shoulder-prr" if slide else "spherical-shoulder",
        labels=shoulder_labels(geometry_of(params.wrist.arm).labels),
        params=params,
    )


# ------------------------------------------------------------- sample arms
def reversed_arm(
    rows: list[Revolute | Prismatic], base: FloatArray, tool: FloatArray
) -> tuple[list[Revolute | Prismatic], FloatArray, FloatArray]:
    """The reversed arm of a standard DH table, as a modified one, with its base and tool.

    A standard row's ``Rz(θ_i) Tz(d_i) Tx(a_i) Rx(α_i)`` inverted is
    ``Rx(-α_i) Tx(-a_i) Rz(-θ_i) Tz(-d_i)``, a modified row: the reversed arm's row j
    is row ``n + 1 - j`` with every parameter negated (its variable too: ``q'_j =
    -q_(n+1-j)``), its base the tool's inverse and its tool the base's inverse.

    Returns:
        ``(modified rows, base (4, 4), tool (4, 4))``: ``fk'(q') = fk(q)⁻¹``.
    """
    back: list[Revolute | Prismatic] = []
    for r in rows[::-1]:
        if isinstance(r, Prismatic):
            back.append(Prismatic(theta=-r.theta, a=-r.a, alpha=-r.alpha, offset=-r.offset))
        else:
            back.append(Revolute(d=-r.d, a=-r.a, alpha=-r.alpha, offset=-r.offset))
    return back, inv_transform(tool), inv_transform(base)


def _sample(slide: bool) -> Callable[[np.random.Generator, bool], ArmSample]:
    def sample_arm(rng: np.random.Generator, degenerate: bool) -> ArmSample:
        """A random arm of the family: a spherical-wrist arm (of the same edges) reversed."""
        rows, note = sample_wrist_rows(rng, slide, degenerate)
        links, base, tool = reversed_arm(
            rows, random_transform(rng, 0.2), random_transform(rng, 0.5)
        )
        return ArmSample(
            links=tuple(links),
            convention="modified",
            base=base,
            tool=tool,
            note=f"reversed: {note}" if note else "",
        )

    return sample_arm


def _shoulder_arm(types: str) -> SolverSpec:
    six = types == "RRRRRR"
    return SolverSpec(
        kind="spherical-shoulder-6R" if six else "spherical-shoulder-prr",
        summary="6R, spherical shoulder" if six else "spherical shoulder + PRR",
        summary_es="6R con hombro esférico" if six else "hombro esférico con PRR",
        handles=lambda f: f.joint_types == types and f.shoulder_center is not None,
        build=build,
        sample_arm=_sample(not six),
        # kinematica.symbolic says the method in words (no symbolic steps for it)
        derivation="reversed-spherical-wrist",
    )


#: The two structures: 6R, and a slide after the shoulder (a Stanford arm reversed).
SPECS: tuple[SolverSpec, ...] = (_shoulder_arm("RRRRRR"), _shoulder_arm("RRRPRR"))
