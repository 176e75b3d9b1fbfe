"""Position targets of longer arms: joints 1-3 place the tool origin, the rest stay free.

For an arm of more than three joints whose first three (R, R, R|P) can move
the tool origin in three directions (PUMA, IRB 120, KR 6, Stanford, 7-DOF
arms whose first three axes qualify...), a position target ``(3,)`` has a
continuum of solutions. The core's solver
(``cpp/include/kinematica/solvers/arm_position.hpp``) returns its
representatives with joints 4..n at 0: up to four, one per arm branch
(shoulder × elbow), the target ``singular`` and joints 4..n free. This solver
names no structure: ``km.classify`` describes arms by their pose solver.
"""

from __future__ import annotations

import numpy as np

import kinematica._core as _core
from kinematica.core import Chain
from kinematica.dh.joints import Prismatic, Revolute
from kinematica.ik.analytic.arm_point import arm_geometry, places_point
from kinematica.ik.analytic.sampling import random_transform
from kinematica.ik.analytic.spherical_wrist import GEOMETRIES, random_wrist_rows
from kinematica.ik.registry import ArmSample, ClosedForm, SolverSpec, TargetKind
from kinematica.ik.structure import Features

__all__ = ["SPEC", "build", "reach_after_joint3"]


def reach_after_joint3(chain: Chain) -> float:
    """A bound (m) on how far joints 4..n move the tool origin from where it is at 0.

    Joint i's factor ``M_i(q_i) · Rot(z, θi) · Tras(t_i) · Rot(x, αi)`` (see
    ``cpp/include/kinematica/chain.hpp``; a DH row's ``t_i = (ai*, 0, di)``) moves
    the tool origin by at most ``|t_i|`` (bounded by the sum of its components)
    from the origin before it, a slide by that plus ``max |qi|`` (infinite without
    limits); joint 4's own ``t_z`` is fixed to link 3 (``Rot(z, q4)`` keeps it). The
    tool origin at any q and at joints 4..n = 0 both lie within that sum (plus the
    tool's offset) of one point of link 3: twice it bounds their distance.
    """
    half = float(np.linalg.norm(chain.tool[:3, 3]))
    for i in range(3, chain.dof):
        tx, ty, tz = (abs(float(v)) for v in chain.translations[i])
        half += tx
        half += ty
        if chain.prismatic[i]:
            half += tz + float(np.max(np.abs(chain.qlim[i])))
        elif i > 3:
            half += tz
    return 2.0 * half


def build(chain: Chain, f: Features, target: TargetKind) -> ClosedForm | None:
    """The arm-position solver for position targets, or None (pose targets, unusable arms)."""
    if target != "position" or not _handles(f):
        return None
    if chain.dof > _core.decoupled.MAX_POSITION_DOF or not places_point(chain, np.zeros(3)):
        return None
    M = chain.fk(np.zeros(chain.dof))[0]
    arm = arm_geometry(f.directions[:3], f.points[:3], f.joint_types[2] == "P", M[:3, 3], f.size)
    if arm is None:
        return None
    params = _core.decoupled.ArmPositionParams()
    params.arm = arm.arm
    params.reach = reach_after_joint3(chain)
    params.n = chain.dof
    return ClosedForm(
        name="arm-position",
        labels=arm.labels,
        params=params,
        position_only=True,
        partial=True,
    )


def _handles(f: Features) -> bool:
    return f.dof > 3 and f.joint_types[:2] == "RR"


def sample_arm(rng: np.random.Generator, degenerate: bool) -> ArmSample:
    """A random arm of 4 to 7 joints whose joints 1-3 place the tool origin.

    A spherical-wrist arm's table cut after joint 4 or 5, whole, or with a seventh
    joint; with ``degenerate``, the wrist centre as tool origin (joints 4..n then
    move it not at all: ``reach`` is 0 and a target out of reach is proven so), or
    a shoulder whose axes meet but for 1e-10.
    """
    edge = str(rng.choice(["wrist centre", "offset 1e-10"])) if degenerate else ""
    pairs = [g for g in GEOMETRIES if edge != "offset 1e-10" or g[0] == "meet"]
    rows = random_wrist_rows(rng, *pairs[int(rng.integers(len(pairs)))])
    tool = random_transform(rng, 0.2)
    note = ""
    if edge == "wrist centre":  # the flange at the wrist centre: no later joint moves it
        rows = [*rows[:5], Revolute(alpha=float(rng.uniform(-3.0, 3.0)))]
        tool = np.eye(4)
        note = "tool origin at the wrist centre"
    else:
        n = int(rng.integers(4, 8))
        if n < 6:
            rows = rows[:n]
        elif n == 7:
            rows.append(Revolute(d=rng.uniform(0.0, 0.2), alpha=float(rng.uniform(-3.0, 3.0))))
        if edge:  # axes 1 and 2 meant to meet, 1e-10 apart
            first = rows[0]
            assert isinstance(first, Revolute)
            rows[0] = Revolute(d=first.d, a=1e-10, alpha=first.alpha, offset=first.offset)
            note = "a1 = 1e-10"
    links: tuple[Revolute | Prismatic, ...] = tuple(rows)
    return ArmSample(links=links, base=random_transform(rng, 0.5), tool=tool, note=note)


#: Position targets of arms of more than three joints whose first three are R, R, R|P.
SPEC = SolverSpec(
    kind="arm-position",
    summary="position targets: joints 1-3 place the tool origin, the others free",
    summary_es=(
        "objetivos de posición: las articulaciones 1-3 colocan el origen de la herramienta, "
        "las demás quedan libres"
    ),
    handles=_handles,
    build=build,
    sample_arm=sample_arm,
    targets=("position",),
    describes=False,
)
