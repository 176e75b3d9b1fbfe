"""The arm classes of the pose audit (``tests/support/ik_pose_audit.py``): random 6R arms.

Generic random DH arms (standard and modified by turns, with a random base and tool),
arms on the edges of the general 6R (all links equal, a joint's offsets of 1e-10 m, two
axes parallel within 1e-9 rad, a calibrated UR5), and the degenerate arms of the
spherical-wrist, spherical-shoulder and three-parallel families (their spec's
``sample_arm(rng, degenerate=True)``).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

import kinematica as km
from kinematica.dh.convert import convert_table
from kinematica.dh.joints import Revolute
from kinematica.ik.analytic import SOLVERS
from kinematica.ik.analytic.sampling import random_transform
from kinematica.ik.registry import ArmSample

FloatArray = NDArray[np.float64]
PI = math.pi

#: The calibration error of a UR: every twist (rad) and every a, d (m) off by up to this.
CALIBRATION = 1e-3


# ------------------------------------------------------------------ arm classes
def _rows(rng: np.random.Generator) -> list[Revolute]:
    u = rng.uniform
    return [
        Revolute(d=u(-0.4, 0.4), a=u(-0.4, 0.4), alpha=u(-PI, PI), offset=u(-PI, PI))
        for _ in range(6)
    ]


def _placed(rows: list[Revolute], rng: np.random.Generator, note: str) -> ArmSample:
    """The rows in either convention (a coin), with a random base and tool."""
    convention = "modified" if rng.random() < 0.5 else "standard"
    base, tool = random_transform(rng, 0.5), random_transform(rng, 0.2)
    return ArmSample(tuple(rows), convention, base, tool, note)  # type: ignore[arg-type]


def generic(rng: np.random.Generator) -> ArmSample:
    """A random 6R arm: lengths and offsets in ±0.4 m, twists and joint offsets in ±π."""
    return _placed(_rows(rng), rng, "")


def equal_links(rng: np.random.Generator) -> ArmSample:
    """A random 6R arm whose six a are equal and six d are equal (its twists random)."""
    a, d = rng.uniform(0.1, 0.4), rng.uniform(0.1, 0.4)
    rows = [dataclasses.replace(r, a=a, d=d) for r in _rows(rng)]
    return _placed(rows, rng, f"a = {a:.4f}, d = {d:.4f} on every joint")


def tiny_offsets(rng: np.random.Generator) -> ArmSample:
    """A random 6R arm with one joint's a and d of ±1e-10 m (two axes meet but for that)."""
    rows, i = _rows(rng), int(rng.integers(6))
    s = rng.choice([-1.0, 1.0], 2)
    rows[i] = dataclasses.replace(rows[i], a=1e-10 * s[0], d=1e-10 * s[1])
    return _placed(rows, rng, f"joint {i + 1}: a, d = ±1e-10")


def near_parallel(rng: np.random.Generator) -> ArmSample:
    """A random 6R arm with one twist of ±1e-9 or π ± 1e-9 rad (axes parallel but for that)."""
    rows, i = _rows(rng), int(rng.integers(6))
    alpha = float(rng.choice([0.0, PI])) + 1e-9 * float(rng.choice([-1.0, 1.0]))
    rows[i] = dataclasses.replace(rows[i], alpha=alpha)
    return _placed(rows, rng, f"joint {i + 1}: alpha = {alpha!r}")


def calibrated_ur(rng: np.random.Generator) -> ArmSample:
    """The UR5 (the built-in model) with every twist, a and d off by up to
    :data:`CALIBRATION` (uniform), its limits dropped."""
    e = lambda: float(rng.uniform(-CALIBRATION, CALIBRATION))  # noqa: E731
    rows = [
        dataclasses.replace(j, d=j.d + e(), a=j.a + e(), alpha=j.alpha + e(), qlim=None)
        for j in km.load("ur5").links
    ]
    arm = _placed(rows, rng, "UR5, calibrated")
    if arm.convention == "standard":
        return arm
    # the same arm, its table in Craig's convention (the UR5's rows read as modified ones
    # would be another arm: 2-4 solutions a pose)
    links, b, t = convert_table(rows, "standard", "modified", np.eye(4), np.eye(4))
    assert arm.base is not None and arm.tool is not None
    return ArmSample(links, "modified", arm.base @ b, t @ arm.tool, arm.note)


def _family(kind: str) -> Callable[[np.random.Generator], ArmSample]:
    spec = next(s for s in SOLVERS if s.kind == kind)

    def sample(rng: np.random.Generator) -> ArmSample:
        return spec.sample_arm(rng, True)

    sample.__doc__ = f"A degenerate arm of the {kind} family (its spec's sample_arm)."
    return sample


#: The arm classes of the audit, by name: ``rng -> ArmSample``.
CLASSES: dict[str, Callable[[np.random.Generator], ArmSample]] = {
    "generic": generic,
    "equal links": equal_links,
    "offsets 1e-10": tiny_offsets,
    "parallel 1e-9": near_parallel,
    "calibrated UR": calibrated_ur,
    "spherical wrist": _family("spherical-wrist-6R"),
    "spherical shoulder": _family("spherical-shoulder-6R"),
    "three parallel": _family("three-parallel-6R"),
}


# ------------------------------------------------------------------ robots, poses
def robot_from(arm: ArmSample, name: str) -> km.Robot:
    """The robot of a sample arm, its limits kept."""
    return km.Robot.from_dh(
        arm.links, convention=arm.convention, base=arm.base, tool=arm.tool, name=name
    )


def configurations(robot: km.Robot, rng: np.random.Generator, n: int) -> FloatArray:
    """``(n, 6)`` random q within the limits (a joint without limits: one turn)."""
    lo, hi = robot.qlim[:, 0], robot.qlim[:, 1]
    lo, hi = np.where(np.isfinite(lo), lo, -PI), np.where(np.isfinite(hi), hi, PI)
    return rng.uniform(lo, hi, (n, robot.dof))
