"""Spherical-wrist arms (6R, and RRP of the Stanford type): their solver's spec.

The core's solver (``cpp/include/kinematica/solvers/spherical_wrist.hpp``) places the
wrist centre by joints 1-3 (any first three axes: meeting, parallel or skew
shoulders; the last needs Pieper's quartic) and solves the wrist for the rotation
left over; the core builds it once per arm from the joint axes
(``km::decoupled::build``, ``spherical_wrist_build.hpp``). It declines an arm whose
joints 1-3 cannot move the wrist centre in three directions, or two of whose
consecutive wrist axes coincide. This module names the family and its branches and
draws its sample arms.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

import kinematica._core as _core
from kinematica.core import Chain
from kinematica.dh.joints import Prismatic, Revolute
from kinematica.ik.analytic.arm_point import geometry_of
from kinematica.ik.analytic.sampling import random_sign as _sign
from kinematica.ik.analytic.sampling import random_transform
from kinematica.ik.analytic.sampling import random_twist as _twist
from kinematica.ik.registry import ArmSample, ClosedForm, SolverSpec, TargetKind
from kinematica.ik.structure import Features

__all__ = [
    "GEOMETRIES",
    "SPECS",
    "build",
    "random_wrist_rows",
    "sample_wrist_rows",
]

FloatArray = NDArray[np.float64]
PI = math.pi


def build(chain: Chain, f: Features, target: TargetKind) -> ClosedForm | None:
    """The closed form of a 6R or RRP arm whose last three axes meet, or None.

    None for position targets (see :mod:`kinematica.ik.analytic.arm_position`)
    and for the arms the core's builder declines (the module docstring says which).
    """
    if target != "pose" or f.wrist_center is None or f.dof != 6:
        return None
    params = _core.decoupled.build_spherical_wrist(chain.core)
    if params is None:
        return None
    arm = geometry_of(params.arm)
    labels = tuple(f"{pos}, wrist {w}" for pos in arm.labels for w in ("no-flip", "flip"))
    return ClosedForm(
        name="rrp-spherical-wrist" if arm.prismatic else "spherical-wrist",
        labels=labels,
        params=params,
    )


# ------------------------------------------------------------- sample arms
def _tiny(rng: np.random.Generator) -> float:
    """An offset of 1e-10 (m or rad), either sign: a zero of a DH table nudged."""
    return 1e-10 * _sign(rng)


#: The shoulders (axes 1, 2) and joints 3 of the family: every pair but three parallel
#: axes (a parallel shoulder with axes 2 ∥ 3 keeps the wrist centre in a plane).
GEOMETRIES: tuple[tuple[str, str], ...] = (
    ("meet", "R23"),
    ("meet", "R"),
    ("meet", "P"),
    ("parallel", "R"),
    ("parallel", "P"),
    ("general", "R23"),
    ("general", "R"),
    ("general", "P"),
)


def random_wrist_rows(
    rng: np.random.Generator, shoulder: str, joint3: str
) -> list[Revolute | Prismatic]:
    """Standard DH rows of a random spherical-wrist arm.

    Args:
        rng: Random numbers.
        shoulder: ``"meet"`` (axes 1, 2 meet), ``"parallel"`` or ``"general"`` (skew).
        joint3: ``"R23"`` (revolute, axis 3 ∥ axis 2), ``"R"`` (revolute, general)
            or ``"P"`` (a slide).
    """
    u = rng.uniform
    a1 = 0.0 if shoulder == "meet" else u(0.1, 0.4) * _sign(rng)
    alpha1 = float(rng.choice([0.0, PI])) if shoulder == "parallel" else _twist(rng)
    alpha2 = float(rng.choice([0.0, PI])) if joint3 == "R23" else _twist(rng)
    if joint3 == "P" and shoulder == "parallel":
        alpha2 = u(0.3, 1.2) * _sign(rng)  # the slide must have a part along axes 1, 2
    rows: list[Revolute | Prismatic] = [
        Revolute(d=u(0.1, 0.5), a=a1, alpha=alpha1, offset=u(-PI, PI)),
        Revolute(d=u(-0.2, 0.2), a=u(0.2, 0.5) * _sign(rng), alpha=alpha2, offset=u(-PI, PI)),
    ]
    if joint3 == "P":
        rows.append(Prismatic(theta=u(-PI, PI), a=u(-0.1, 0.1), alpha=_twist(rng), offset=0.3))
    else:
        rows.append(Revolute(d=u(-0.2, 0.2), a=u(-0.2, 0.2), alpha=_twist(rng), offset=u(-PI, PI)))
    rows += [  # a spherical wrist: a4 = a5 = d5 = 0, any twists
        Revolute(d=u(0.2, 0.5) * _sign(rng), alpha=_twist(rng), offset=u(-PI, PI)),
        Revolute(alpha=_twist(rng), offset=u(-PI, PI)),
        Revolute(d=u(0.0, 0.2), a=u(-0.1, 0.1), alpha=u(-PI, PI), offset=u(-PI, PI)),
    ]
    return rows


def _edge_6r(rng: np.random.Generator) -> tuple[list[Revolute | Prismatic], str]:
    """A 6R arm on one of the family's edges, and what it is.

    A PUMA-like arm (meeting shoulder, axes 2 ∥ 3, right-angle twists) with one of:
    an upper arm as long as the forearm (the elbow folds onto the shoulder), a zero
    of joints 1-3 nudged by 1e-10 (axes meant to meet miss by it), axes 2 and 3
    parallel but for 1e-10 (or anti-parallel), a wrist twist 1e-10 off its right
    angle (the flip is then solved, not twinned), or a skew shoulder whose axes are
    parallel but for 1e-10.
    """
    u = rng.uniform
    edge = str(
        rng.choice(
            ["equal links", "offset 1e-10", "twist 1e-10", "wrist twist 1e-10", "nearly parallel"]
        )
    )
    if edge == "nearly parallel":  # axes 1 and 2 parallel but for 1e-10 (skew)
        rows = random_wrist_rows(rng, "parallel", "R")
        first = rows[0]
        assert isinstance(first, Revolute)
        rows[0] = Revolute(
            d=first.d, a=first.a, alpha=first.alpha + _tiny(rng), offset=first.offset
        )
        return rows, "axes 1 and 2 parallel but for 1e-10"
    upper = u(0.2, 0.6)
    fore = upper if edge == "equal links" else u(0.2, 0.6)
    nudge = dict.fromkeys(("a1", "d2", "d3", "a3", "alpha2", "alpha4"), 0.0)
    if edge == "offset 1e-10":
        where = str(rng.choice(["a1", "d2", "d3", "a3"]))
        nudge[where] = _tiny(rng)
        edge = f"{where} = 1e-10"
    elif edge == "twist 1e-10":
        nudge["alpha2"] = float(rng.choice([0.0, PI])) + _tiny(rng)
        edge = "axes 2 and 3 parallel but for 1e-10"
    elif edge == "wrist twist 1e-10":
        nudge["alpha4"] = _tiny(rng)
    right = PI / 2
    offsets = [float(rng.choice([0.0, PI / 2, -PI / 2, u(-PI, PI)])) for _ in range(6)]
    arm: list[Revolute | Prismatic] = [
        Revolute(d=u(0.2, 0.6), a=nudge["a1"], alpha=_sign(rng) * right, offset=offsets[0]),
        Revolute(d=nudge["d2"], a=upper, alpha=nudge["alpha2"], offset=offsets[1]),
        Revolute(d=nudge["d3"], a=nudge["a3"], alpha=_sign(rng) * right, offset=offsets[2]),
        Revolute(d=fore, alpha=_sign(rng) * right + nudge["alpha4"], offset=offsets[3]),
        Revolute(alpha=_sign(rng) * right, offset=offsets[4]),
        Revolute(d=u(0.0, 0.2), offset=offsets[5]),
    ]
    return arm, edge


def _edge_rrp(rng: np.random.Generator) -> tuple[list[Revolute | Prismatic], str]:
    """An RRP arm on one of the family's edges (Stanford type), and what it is."""
    where = str(rng.choice(["a", "alpha", "offset", "d", "none"]))
    joint2 = {"d": rng.uniform(0.0, 0.3), "a": 0.0, "alpha": PI / 2, "offset": 0.0}
    if where != "none":
        joint2[where] += _tiny(rng)
    second = Revolute(d=joint2["d"], a=joint2["a"], alpha=joint2["alpha"], offset=joint2["offset"])
    rows: list[Revolute | Prismatic] = [
        Revolute(d=rng.uniform(0.2, 0.6), alpha=-PI / 2, offset=rng.uniform(-PI, PI)),
        second,
        Prismatic(theta=-PI / 2, a=float(rng.choice([0.0, rng.uniform(-0.1, 0.1)]))),
        Revolute(alpha=-PI / 2),
        Revolute(alpha=PI / 2),
        Revolute(d=rng.uniform(0.0, 0.3)),
    ]
    note = "Stanford type" if where == "none" else f"Stanford type, joint 2's {where} + 1e-10"
    return rows, note


def sample_wrist_rows(
    rng: np.random.Generator, slide: bool, degenerate: bool
) -> tuple[list[Revolute | Prismatic], str]:
    """Standard DH rows of a random arm of the family, and what is special about it.

    Args:
        rng: Random numbers.
        slide: An RRP arm (Stanford type) rather than a 6R one.
        degenerate: One of the family's edge geometries (see ``_edge_6r``,
            ``_edge_rrp``) rather than a generic arm of :data:`GEOMETRIES`.
    """
    if degenerate:
        return _edge_rrp(rng) if slide else _edge_6r(rng)
    pairs = [g for g in GEOMETRIES if (g[1] == "P") == slide]
    shoulder, kind = pairs[int(rng.integers(len(pairs)))]
    return random_wrist_rows(rng, shoulder, kind), ""


def _sample(slide: bool) -> Any:
    def sample_arm(rng: np.random.Generator, degenerate: bool) -> ArmSample:
        """A random arm of the family (an edge case with ``degenerate``)."""
        rows, note = sample_wrist_rows(rng, slide, degenerate)
        return ArmSample(
            links=tuple(rows),
            base=random_transform(rng, 0.5),
            tool=random_transform(rng, 0.2),
            note=note,
        )

    return sample_arm


def _wrist_arm(types: str) -> SolverSpec:
    kind = "spherical-wrist-6R" if types == "RRRRRR" else "rrp-spherical-wrist"
    return SolverSpec(
        kind=kind,
        summary="6R, spherical wrist"
        if types == "RRRRRR"
        else "RRP + spherical wrist (Stanford type)",
        summary_es="6R con muñeca esférica"
        if types == "RRRRRR"
        else "RRP con muñeca esférica (tipo Stanford)",
        handles=lambda f: f.joint_types == types and f.wrist_center is not None,
        build=build,
        sample_arm=_sample(types != "RRRRRR"),
        derivation="spherical-wrist" if types == "RRRRRR" else None,
        singular=frozenset({"shoulder", "elbow", "wrist"} if types == "RRRRRR" else {"wrist"}),
    )


#: The two structures: 6R, and RRP (Stanford type), each with a spherical wrist.
SPECS: tuple[SolverSpec, ...] = (_wrist_arm("RRRRRR"), _wrist_arm("RRPRRR"))
