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

import itertools

import numpy as np
from numpy.typing import NDArray

import kinematica._core as _core
from kinematica.core import Chain
from kinematica.dh.joints import Prismatic, Revolute
from kinematica.ik.analytic.arm_point import arm_geometry, places_point
from kinematica.ik.analytic.sampling import random_transform
from kinematica.ik.analytic.spherical_wrist import GEOMETRIES, random_wrist_rows
from kinematica.ik.registry import ArmSample, ClosedForm, SolverSpec, TargetKind
from kinematica.ik.structure import Features

__all__ = ["PARALLEL_SIN2", "SPEC", "build", "reach_after_joint3", "wrist_chain"]

FloatArray = NDArray[np.float64]

#: Two axes whose sine squared is below this are treated as parallel when a point of one
#: nearest the other is chosen (:func:`wrist_chain`): the choice decides only how tight
#: the bound is, never whether it holds (any point of an axis would do); nearly parallel
#: axes would put their common perpendicular's feet far away, and the bound out of use.
PARALLEL_SIN2 = 1e-12


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


def wrist_chain(chain: Chain, f: Features) -> tuple[FloatArray, float] | None:
    """A point C on axis 4 and a bound (m) on the tool origin's distance from it, or None.

    A point on a revolute joint's axis is fixed to the links before and after it, so
    the distance of two points on consecutive axes k and k + 1 (both fixed to the link
    between them) is the same at every q, as is that of the tool origin from a point on
    axis n. With B_k on axis k (k = 4..n), the foot of the common perpendicular towards
    axis k + 1 (axis n: towards axis n - 1; parallel axes: the tool origin's foot),
    the triangle inequality gives, at every q (limits or not),

        |tool origin - B_4| <= sum_k |B_(k+1) - B_k| + |tool origin - B_n|.

    For a spherical wrist every B_k is the wrist centre and the bound is the exact
    wrist-to-tool distance. None when a joint after the third slides (its link moves
    along, not about, its axis).

    Args:
        chain: The arm (n > 3 joints).
        f: Its features: ``directions``, ``points`` ``(n, 3)`` at q = 0 (base frame).

    Returns:
        ``(C, R)``: C ``(3,)`` (base frame at q = 0, m) and R (m).
    """
    if any(chain.prismatic[3:]):
        return None
    tool = chain.fk(np.zeros(chain.dof))[0][:3, 3]
    n = chain.dof
    feet = []
    for k in range(3, n):
        other = k + 1 if k + 1 < n else k - 1
        feet.append(_foot(f.points[k], f.directions[k], f.points[other], f.directions[other], tool))
    steps = [np.linalg.norm(b - a) for a, b in itertools.pairwise(feet)]
    return feet[0], float(sum(steps) + np.linalg.norm(tool - feet[-1]))


def _foot(p: FloatArray, h: FloatArray, q: FloatArray, g: FloatArray, x: FloatArray) -> FloatArray:
    """``(3,)`` the point of line (p, h) nearest line (q, g); parallel lines: nearest ``x``."""
    h = h / np.linalg.norm(h)
    g = g / np.linalg.norm(g)
    c = float(h @ g)
    det = 1.0 - c * c
    if det < PARALLEL_SIN2:  # parallel (any point of the line would do): the one nearest x
        return p + float(h @ (x - p)) * h
    w = q - p
    return p + (float(h @ w) - c * float(g @ w)) / det * h


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
    wrist = wrist_chain(chain, f)
    centre = (
        None
        if wrist is None
        else arm_geometry(f.directions[:3], f.points[:3], f.joint_types[2] == "P", wrist[0], f.size)
    )
    if wrist is not None and centre is not None:
        params.centre = centre.arm
        params.centre_reach = wrist[1]
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
