"""Position targets of longer arms: joints 1-3 place the tool origin, the rest stay free.

For an arm of more than three joints whose first three (R, R, R|P) can move
the tool origin in three directions (PUMA, IRB 120, KR 6, Stanford, 7-DOF
arms whose first three axes qualify...), a position target ``(3,)`` has a
continuum of solutions. The core's solver
(``cpp/include/kinematica/solvers/arm_position.hpp``, built in ``arm_position_build.hpp``,
with the bounds on how far joints 4..n move the tool origin) returns its
representatives with joints 4..n at 0: up to four, one per arm branch
(shoulder × elbow), the target ``singular`` and joints 4..n free. This solver
names no structure: ``km.classify`` describes arms by their pose solver.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

import kinematica._core as _core
from kinematica.core import Chain
from kinematica.dh.joints import Prismatic, Revolute
from kinematica.ik.analytic.arm_point import geometry_of
from kinematica.ik.analytic.sampling import random_transform
from kinematica.ik.analytic.spherical_wrist import GEOMETRIES, random_wrist_rows
from kinematica.ik.registry import ArmSample, ClosedForm, SolverSpec, TargetKind
from kinematica.ik.structure import Features

__all__ = ["SPEC", "build"]

FloatArray = NDArray[np.float64]


def build(chain: Chain, f: Features, target: TargetKind) -> ClosedForm | None:
    """The arm-position solver for position targets, or None (pose targets, unusable arms).

    The core builds it (``km::decoupled::build_position``,
    ``cpp/include/kinematica/solvers/arm_position_build.hpp``); its branches are those of
    the joints 1-3 placing the tool origin.
    """
    if target != "position" or not _handles(f):
        return None
    params = _core.decoupled.build_arm_position(chain.core)
    if params is None:
        return None
    return ClosedForm(
        name="arm-position",
        labels=geometry_of(params.arm).labels,
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
