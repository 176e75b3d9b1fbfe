"""Position targets of longer arms: joints 1-3 place the tool origin, the rest stay free.

For an arm of more than three joints whose first three (R, R, R|P) can move
the tool origin in three directions (PUMA, IRB 120, KR 6, Stanford, 7-DOF
arms whose first three axes qualify...), a position target ``(3,)`` has a
continuum of solutions. The kernel (:mod:`kinematica.kernels.solvers.arm_position`)
returns its representatives with joints 4..n at 0: up to four, one per arm
branch (shoulder × elbow), the target ``singular`` and joints 4..n free. This
solver names no structure: ``km.classify`` describes arms by their pose solver.
"""

from __future__ import annotations

import numpy as np

from kinematica.dh import DHChain
from kinematica.ik.analytic.arm_point import arm_geometry, places_point
from kinematica.ik.registry import ClosedForm, SolverSpec, TargetKind
from kinematica.ik.structure import Features
from kinematica.kernels import fk
from kinematica.kernels.fk import LINK_A, LINK_D, LINK_PRISMATIC, TOOL
from kinematica.kernels.solvers import decoupled
from kinematica.kernels.solvers.arm_position import P_REACH, P_SIZE

__all__ = ["SPEC", "build", "reach_after_joint3"]


def reach_after_joint3(chain: DHChain) -> float:
    """A bound (m) on how far joints 4..n move the tool origin from where it is at 0.

    Joint i's factor ``Rot(z, θi) · Tras(z, di) · Tras(x, ai*) · Rot(x, αi*)`` (see
    :mod:`kinematica.dh.chain`) moves the tool origin by at most ``|di| + |ai*|``
    from the origin before it, a slide by ``|di| + max |qi|`` (infinite without
    limits); joint 4's own ``Tras(z, d4)`` is fixed to link 3. The tool origin
    at any q and at joints 4..n = 0 both lie within that sum (plus the tool's
    offset) of one point of link 3: twice it bounds their distance.
    """
    half = float(np.linalg.norm(chain.ends[TOOL][:3, 3]))
    for i in range(3, chain.dof):
        row = chain.links[i]
        half += abs(row[LINK_A])
        if row[LINK_PRISMATIC] != 0.0:
            half += abs(row[LINK_D]) + float(np.max(np.abs(chain.qlim[i])))
        elif i > 3:
            half += abs(row[LINK_D])
    return 2.0 * half


def build(chain: DHChain, f: Features, target: TargetKind) -> ClosedForm | None:
    """The arm-position solver for position targets, or None (pose targets, unusable arms)."""
    if target != "position" or not _handles(f):
        return None
    if not places_point(chain, np.zeros(3)):
        return None
    M, _, _ = fk(chain, np.zeros(chain.dof))
    arm = arm_geometry(f.directions[:3], f.points[:3], f.joint_types[2] == "P", M[:3, 3])
    if arm is None:
        return None
    params = np.zeros(P_SIZE)
    params[: arm.params.size] = arm.params
    params[decoupled.P_MODE] = decoupled.MODE_POSITION
    params[P_REACH] = reach_after_joint3(chain)
    params.flags.writeable = False
    return ClosedForm(
        name="arm-position",
        labels=arm.labels,
        params=params,
        solve_one=decoupled.solve,
        solve_batch=decoupled.solve_batch,
        position_only=True,
        partial=True,
    )


def _handles(f: Features) -> bool:
    return f.dof > 3 and f.joint_types[:2] == "RR"


#: Position targets of arms of more than three joints whose first three are R, R, R|P.
SPEC = SolverSpec(
    kind="arm-position",
    summary="position targets: joints 1-3 place the tool origin, the others free",
    handles=_handles,
    build=build,
    describes=False,
)
