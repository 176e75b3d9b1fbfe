"""SRS 7R arms (KUKA iiwa type): all 8 solutions at a given arm angle.

Axes 1, 2, 3 meet at the shoulder S, axes 5, 6, 7 at the wrist W, and axis 4
(the elbow) passes through neither. The arm has one degree of redundancy; its
parameter is the **arm angle** ψ (rad): the angle, right-handed about the unit
vector n from S to W, from the reference half-plane (bounded by the line S-W and
containing axis 1's direction h1) to the arm half-plane (bounded by S-W and
containing the elbow point E, the foot of the perpendicular from S onto axis 4).
It is the "conventional SEW angle" of Elias and Wen (IK-Geo, "Redundancy
parameterization and inverse kinematics of 7-DOF revolute manipulators", 2022)
with axis 1 as reference vector, chosen because it is defined by the target
alone, for any SRS geometry, with no solution of another arm to compute first.
Shimizu et al. (2008) measure from the plane S-E-W of the solution with q3 = 0;
on the iiwa that plane contains axis 1 (axes 2 and 4 are then parallel), so it
is this reference plane, and ψ = 0 is the half-plane on the side axis 1 points
to (elbow up). It is undefined where the elbow lies on S-W (stretched or
folded), where W is on S, and where S-W lies along axis 1.

The core's solver (``cpp/include/kinematica/solvers/srs.hpp``) gives 8 slots,
named base to tip by what each changes. At one arm angle the shoulder centre S,
the elbow point E and the wrist centre W are the same points in all 8 (so
"elbow up" or "down", where E lies, is the arm angle's to say: on the iiwa ψ = 0
is up, ψ = π down); what differs is how the joints around each point make it:

- ``shoulder no-flip / flip``: axes 1-3 split as a spherical wrist is: no-flip
  bends the shoulder as q2 > 0 bends it from q = 0, on the iiwa q2 > 0; flip is
  (q1 + π, -q2, q3 + π) there: joint 1 turned half a turn, the arm leaning back
  over it;
- ``elbow bent positive / negative``: q4 = q4* ± β, q4* where the elbow is
  stretched, β ∈ [0, π] its bend, turned either way about axis 4 (right-hand
  rule): on the iiwa (stretched at q4 = 0) the sign of q4, with q3 and q5 half
  a turn apart between the two (axes 3-5 meet at E there: an elbow flip);
- ``wrist no-flip / flip``: likewise for axes 5-7, q6 > 0 on the iiwa.

These are Shimizu et al.'s global configuration signs (GC2, GC4, GC6) and the
iiwa controller's status bits (A2, A4, A6 negative). This module reads the geometry from the joint
axes, fills its ``SRSParams``, and computes the arm angle of configurations
(:func:`arm_angle`) from forward kinematics.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

import kinematica._core as _core
from kinematica.core import Chain
from kinematica.dh.joints import Revolute
from kinematica.errors import DimensionError, KinematicaError
from kinematica.ik.analytic.sampling import random_transform
from kinematica.ik.analytic.sampling import random_twist as _twist
from kinematica.ik.registry import ArmSample, ClosedForm, SolverSpec, TargetKind
from kinematica.ik.structure import Features

__all__ = ["LABELS", "SPEC", "arm_angle", "build", "handles"]

FloatArray = NDArray[np.float64]
PI = math.pi

#: Branch names of the 8 slots, slot 4 e + 2 s + w (e: elbow bent positive, negative).
LABELS: tuple[str, ...] = tuple(
    f"shoulder {s}, elbow bent {e}, wrist {w}"
    for e in ("positive", "negative")
    for s in ("no-flip", "flip")
    for w in ("no-flip", "flip")
)


def handles(f: Features) -> bool:
    """True for SRS 7R arms: axes 1-3 meeting at S, axes 5-7 at W, axis 4 through neither.

    Axis 4 through S or W (within the line geometry's length tolerance) would leave
    ``|S - W|`` independent of q4. The structure only: the points themselves are the
    core's (``km::srs::srs_points``, ``srs_build.hpp``), which asks the same.
    """
    S, W = f.shoulder_center, f.wrist_center
    if f.joint_types != "RRRRRRR" or S is None or W is None:
        return False
    h4, p4 = f.directions[3], f.points[3]
    off = [r - float(r @ h4) * h4 for r in (S - p4, W - p4)]  # S, W across axis 4
    return min(float(np.linalg.norm(v)) for v in off) > f.length_tol


def build(chain: Chain, f: Features, target: TargetKind) -> ClosedForm | None:
    """The closed form of an SRS 7R arm (pose targets), or None.

    The core builds it (``km::srs::build``, ``cpp/include/kinematica/solvers/
    srs_build.hpp``) at the arm angle 0; it declines arms whose axis 4 passes through
    the shoulder or the wrist centre (|S - W| would not depend on q4), and arms two of
    whose consecutive shoulder or wrist axes coincide.
    """
    if target != "pose" or not handles(f):
        return None
    params = _core.srs.build(chain.core)
    return None if params is None else ClosedForm(name="srs", labels=LABELS, params=params)


def arm_angle(chain: Chain, q: ArrayLike) -> FloatArray:
    """The arm angle ψ (rad, in (-π, π]) of configurations of an SRS arm.

    Measured as the module docstring defines it, from the joint frames' forward
    kinematics (S, the elbow point E and the wrist centre W placed by frames 0, 3
    and 4), in the core (``km::srs::arm_angle``, ``cpp/include/kinematica/solvers/
    srs_angle.hpp``). NaN where it is undefined: the elbow on the line S-W or W on S,
    or S-W along axis 1 (within 1e-12 of the arm's size, resp. in sine: the
    solver's ``COLLINEAR_TOL`` and ``REFERENCE_TOL``), and where q is not finite.

    Args:
        chain: An SRS 7R chain.
        q: ``(..., 7)`` joint angles (rad).

    Returns:
        ``(...)`` arm angles (rad).

    Raises:
        KinematicaError: The chain is no SRS 7R arm.
        DimensionError: ``q`` does not hold 7 joint angles a row.
    """
    q = np.asarray(q, dtype=float)
    out = None
    if chain.dof == 7:  # (the core says whether it is an SRS arm)
        if q.ndim == 0 or q.shape[-1] != 7:
            raise DimensionError(f"q must hold 7 joint angles, got shape {q.shape}", arg="q")
        out = _core.srs.arm_angles(chain.core, np.ascontiguousarray(q.reshape(-1, 7)))
    if out is None:
        raise KinematicaError(
            "the arm angle is defined for SRS 7R arms only (axes 1-3 and 5-7 meeting, "
            "axis 4 through neither point)",
            arg="q",
        )
    angles: FloatArray = np.asarray(out).reshape(q.shape[:-1])
    return angles


# ------------------------------------------------------------- sample arms
#: The family's edge geometries (``sample_arm(rng, True)``).
EDGES: tuple[str, ...] = (
    "iiwa type",  # a = 0 everywhere, right-angle twists: the elbow stretches onto S-W
    "equal links",  # iiwa type with |SE| = |EW|: folded, W reaches S
    "shoulder offset 1e-10",  # axes 1-3 miss their common point by 1e-10
    "wrist offset 1e-10",  # axes 5-7 likewise
)


def random_srs_rows(rng: np.random.Generator, edge: str = "") -> list[Revolute]:
    """Standard DH rows of a random SRS 7R arm (an edge geometry by name, or generic).

    Axes 1-3 meet when a1 = a2 = d2 = 0, axes 5-7 when a5 = a6 = d6 = 0; the elbow
    (a3, d3, a4, d4, d5) is free, twists anything away from 0 and π.
    """
    u = rng.uniform
    sign = lambda: float(rng.choice([-1.0, 1.0]))  # noqa: E731
    upper, fore = u(0.25, 0.5), u(0.25, 0.5)
    if edge == "equal links":
        fore = upper
    iiwa = edge in ("iiwa type", "equal links")
    twists = [sign() * PI / 2 for _ in range(6)] if iiwa else [_twist(rng) for _ in range(6)]
    off = [0.0 if iiwa else float(v) for v in u(-PI, PI, 7)]
    a3, a4, d4 = (0.0, 0.0, 0.0) if iiwa else (u(-0.1, 0.1), u(-0.1, 0.1), u(-0.1, 0.1))
    d2 = 1e-10 * sign() if edge == "shoulder offset 1e-10" else 0.0
    d6 = 1e-10 * sign() if edge == "wrist offset 1e-10" else 0.0
    return [
        Revolute(d=u(0.2, 0.4), alpha=twists[0], offset=off[0]),
        Revolute(d=d2, alpha=twists[1], offset=off[1]),
        Revolute(d=upper, a=a3, alpha=twists[2], offset=off[2]),
        Revolute(d=d4, a=a4, alpha=twists[3], offset=off[3]),
        Revolute(d=fore, alpha=twists[4], offset=off[4]),
        Revolute(d=d6, alpha=twists[5], offset=off[5]),
        Revolute(d=u(0.0, 0.2), a=u(-0.05, 0.05), alpha=u(-PI, PI), offset=off[6]),
    ]


def sample_arm(rng: np.random.Generator, degenerate: bool) -> ArmSample:
    """A random SRS arm (an edge geometry of :data:`EDGES` with ``degenerate``)."""
    edge = str(rng.choice(EDGES)) if degenerate else ""
    return ArmSample(
        links=tuple(random_srs_rows(rng, edge)),
        base=random_transform(rng, 0.5),
        tool=random_transform(rng, 0.2),
        note=edge,
    )


SPEC = SolverSpec(
    kind="srs-7R",
    summary="7R, spherical shoulder and wrist (SRS)",
    summary_es="7R con hombro y muñeca esféricos (SRS)",
    handles=handles,
    build=build,
    sample_arm=sample_arm,
    parameter="arm_angle",
    parameter_of=arm_angle,
)
