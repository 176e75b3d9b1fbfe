"""Cylindrical arms (a turn, a lift along its axis, a reach across it, a roll): their closed form.

The lecture notes' 4-DOF example with two prismatic joints is one: ``x = (q3 + l4)
cos q1``, ``y = (q3 + l4) sin q1``, ``z = l1 + q2``. The turn (revolute, axis ``k``)
and the lift (a slide along ``k``) come first in either order (they commute), then
a slide across ``k`` (the reach), then, for four joints, a revolute roll whose axis
is not parallel to ``k``. The solver is ``cpp/include/kinematica/solvers/cylindrical.hpp``
(:class:`kinematica._core.cylindrical.CylindricalParams`), built in ``cylindrical_build.hpp``
from the joint axes at q = 0 and ``M = fk(0)``: any base, tool, offsets and DH convention.

Branch labels: ``"reach forward"``, the reach's direction (turned by q1) points
toward the target, seen across ``k`` from the turn's axis; ``"reach backward"``,
it points away (the arm reaches over the axis, as the lecture notes' ``q1 + π``
with a negative ``q3 + l4``). A pose target has one solution; a position target two,
and with a roll that does not move the tool origin the roll is free (``singular``).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from kinematica import _core
from kinematica.core import Chain
from kinematica.dh.convert import convert_table
from kinematica.dh.joints import Convention, Joint, Prismatic, Revolute
from kinematica.ik.analytic.sampling import random_transform
from kinematica.ik.analytic.small_samples import TINY
from kinematica.ik.registry import ArmSample, ClosedForm, SolverSpec, TargetKind
from kinematica.ik.structure import Features

__all__ = ["LABELS", "SPECS", "build", "sample"]

FloatArray = NDArray[np.float64]
PI = math.pi

#: Branch labels of the two candidate slots.
LABELS = ("reach forward", "reach backward")
#: Joint types of the family: the turn and the lift in either order, the reach, the roll.
_TYPES = ("RPP", "PRP", "RPPR", "PRPR")


def _cylindrical(f: Features) -> bool:
    if f.joint_types not in _TYPES:
        return False
    turn = f.joint_types.index("R")
    lift = 1 - turn
    return (
        f.is_parallel(turn, lift)
        and not f.is_parallel(turn, 2)
        and (f.dof == 3 or not f.is_parallel(turn, 3))
    )


def build(chain: Chain, features: Features, target: TargetKind) -> ClosedForm | None:
    """The closed form of a cylindrical arm, or None for another arm.

    The core builds it (``km::cylindrical::build``, ``cpp/include/kinematica/solvers/
    cylindrical_build.hpp``), for pose or (``build_position``) position targets.

    Args:
        chain: The arm.
        features: Its joint axes at q = 0 (``cylindrical-RPP`` or ``-RPPR``).
        target: ``"pose"`` or ``"position"`` targets.
    """
    core = _core.cylindrical.build if target == "pose" else _core.cylindrical.build_position
    params = core(chain.core) if _cylindrical(features) else None
    if params is None:
        return None
    position_only = target == "position"
    return ClosedForm(
        name=_kind(features.dof), labels=LABELS, params=params, position_only=position_only
    )


def _kind(n: int) -> str:
    return "cylindrical-RPP" if n == 3 else "cylindrical-RPPR"


def sample(n: int, rng: np.random.Generator, degenerate: bool) -> ArmSample:
    """A random cylindrical arm of ``n`` (3 or 4) joints, in either DH convention.

    Generic arms draw offsets, twists, the turn-lift order, base and tool at random,
    with slides without limits (they reach any distance: no gap to prove far away);
    degenerate ones draw one edge case: offsets of 1e-10 where they would be 0 (the
    reach's line through the turn's axis), twists 1e-10 off 0 or π (the lift parallel
    to the turn only within tolerance), or the reach normal to the turn and the tool on
    the roll's axis (the lecture notes' arm), and slides with limits.
    """
    u = rng.uniform
    case = str(rng.choice(("tiny offsets", "tilted axes", "notes"))) if degenerate else ""
    tiny, tilt, notes = case == "tiny offsets", case == "tilted axes", case == "notes"

    def near(v: float, on: bool) -> float:
        return v + (TINY * float(rng.choice([-1.0, 1.0])) if on else 0.0)

    def small(lo: float, hi: float) -> float:
        return near(0.0, tiny) if tiny or notes or rng.random() < 0.3 else float(u(lo, hi))

    flip = near(float(rng.choice([0.0, PI])), tilt)  # the lift parallel to the turn
    across = PI / 2 * float(rng.choice([-1.0, 1.0]))
    reach_twist = across if notes or rng.random() < 0.5 else float(u(0.4, 1.2) * np.sign(across))
    limits = (0.0, float(u(0.3, 0.8))) if degenerate else None
    turn_first = notes or rng.random() < 0.5
    turn_row = Revolute(d=u(0.2, 0.6), a=small(-0.2, 0.2), alpha=flip, offset=small(-PI, PI))
    lift_row = Prismatic(
        theta=PI / 2 if notes else u(-PI, PI), a=small(-0.2, 0.2), alpha=reach_twist, qlim=limits
    )
    if not turn_first:  # the lift first: its twist keeps the turn parallel, the turn's
        lift_row = Prismatic(theta=u(-PI, PI), a=small(-0.2, 0.2), alpha=flip, qlim=limits)
        turn_row = Revolute(d=u(-0.2, 0.2), a=small(-0.2, 0.2), alpha=reach_twist)
    rows: list[Joint] = [turn_row, lift_row] if turn_first else [lift_row, turn_row]
    roll_twist = 0.0 if notes else float(u(-PI, PI))
    rows.append(Prismatic(theta=small(-PI, PI), a=small(-0.2, 0.2), alpha=roll_twist, qlim=limits))
    on_axis = notes or rng.random() < 0.5
    if n == 4:
        rows.append(
            Revolute(
                d=u(0.05, 0.2),
                a=0.0 if on_axis else u(0.05, 0.2),
                alpha=0.0 if on_axis else u(-PI, PI),
                offset=small(-PI, PI),
            )
        )
    base = random_transform(rng, 0.5)
    # the tool origin on the roll's axis: a tool that only turns and slides along it
    tool = random_transform(rng, None if on_axis else 0.3)
    if on_axis:
        tool[:3, 3] = [0.0, 0.0, float(u(0.0, 0.1))]
    convention: Convention = "modified" if rng.random() < 0.5 else "standard"
    links, base, tool = convert_table(rows, "standard", convention, base, tool)
    return ArmSample(links, convention, base, tool, note=case)


def _handles(n: int) -> Callable[[Features], bool]:
    def handles(f: Features) -> bool:
        return f.dof == n and _cylindrical(f)

    return handles


def _sampler(n: int) -> Callable[[np.random.Generator, bool], ArmSample]:
    def sample_arm(rng: np.random.Generator, degenerate: bool) -> ArmSample:
        return sample(n, rng, degenerate)

    return sample_arm


SPECS: tuple[SolverSpec, ...] = tuple(
    SolverSpec(
        _kind(n),
        summary,
        summary_es,
        _handles(n),
        build,
        _sampler(n),
        ("pose", "position"),
    )
    for n, summary, summary_es in (
        (
            3,
            "cylindrical RPP (turn, lift, reach)",
            "brazo cilíndrico RPP (giro, elevación, alcance)",
        ),
        (
            4,
            "cylindrical RPPR (turn, lift, reach, roll)",
            "brazo cilíndrico RPPR (giro, elevación, alcance, giro de muñeca)",
        ),
    )
)
