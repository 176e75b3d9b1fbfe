"""Random arms of the small families (planar 2R/3R/PR/PRR, SCARA, 3R elbow arms).

:func:`sample` is the ``sample_arm`` of every spec in
:mod:`kinematica.ik.analytic.planar_arms` and :mod:`kinematica.ik.analytic.elbow_arms`:
generic arms draw link lengths, offsets, twists, base and tool at random, in either
DH convention; degenerate ones draw one of the family's edge cases (equal triangle
links, offsets of 1e-10 where they would be 0, twists within 1e-10 of 0, ±π/2 or π,
a tool on the last axis, a slide with tight limits).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from kinematica.dh.convert import convert_table
from kinematica.dh.joints import Convention, Joint, Prismatic, Revolute
from kinematica.ik.analytic.sampling import random_transform
from kinematica.ik.registry import ArmSample

__all__ = ["DEGENERACIES", "FREE_LAST", "TINY", "edge_arm", "sample", "sampler"]

FloatArray = NDArray[np.float64]
PI = math.pi

#: Offsets and twists of "exactly" special values are off by this in degenerate arms
#: (m or rad): within the classification's tolerances (1e-9).
TINY = 1e-10

#: Kinds whose last revolute joint may carry the tool on its axis (the others need that
#: link to place the tool: without it they have no closed form).
FREE_LAST = ("planar-3R", "planar-PRR", "scara")
#: The edge cases a degenerate arm draws one of.
DEGENERACIES = ("equal links", "tiny offsets", "tilted axes", "tool on the last axis")


def sample(kind: str, rng: np.random.Generator, degenerate: bool) -> ArmSample:
    """A random arm of one small kind (see the module docstring).

    Args:
        kind: ``"planar-2R"``, ``"planar-3R"``, ``"planar-PR"``, ``"planar-PRR"``,
            ``"scara"``, ``"anthropomorphic-3R"`` or ``"elbow-3R"``.
        rng: The random source.
        degenerate: Draw one of :data:`DEGENERACIES` (else a generic arm).
    """
    case = str(rng.choice(DEGENERACIES)) if degenerate else ""
    if case == "tool on the last axis" and kind not in FREE_LAST:
        case = "equal links"  # elsewhere a link of length 0: no closed form
    return edge_arm(
        kind,
        rng,
        equal=case == "equal links",
        tiny=case == "tiny offsets",
        tilt=case == "tilted axes",
        on_axis=case == "tool on the last axis",
        limited=degenerate,
        note=case,
    )


def edge_arm(
    kind: str,
    rng: np.random.Generator,
    *,
    equal: bool = False,
    tiny: bool = False,
    tilt: bool = False,
    on_axis: bool = False,
    limited: bool = True,
    note: str = "",
) -> ArmSample:
    """A random arm of one small kind with any of the edge cases at once.

    Args:
        kind: As for :func:`sample`.
        rng: The random source.
        equal: The triangle's two links of equal length (the tool then only turns).
        tiny: Offsets and lengths that would be 0 are 1e-10 (``TINY``) instead.
        tilt: Twists 1e-10 off 0, ±90° and 180°: axes parallel or normal only
            within the line geometry's tolerance.
        on_axis: The tool origin on the last axis (kinds in ``FREE_LAST``).
        limited: A slide gets finite limits (else none).
        note: What the arm is, for messages.
    """
    u = rng.uniform

    def length() -> float:
        return float(u(0.2, 1.0) * rng.choice([-1.0, 1.0]))

    def near(v: float, on: bool) -> float:  # a special value, or 1e-10 off it
        return v + (TINY * float(rng.choice([-1.0, 1.0])) if on else 0.0)

    def flip() -> float:  # a twist keeping two axes parallel
        return near(float(rng.choice([0.0, PI])), tilt)

    def normal() -> float:  # a twist making two axes normal
        return near(PI / 2 * float(rng.choice([-1.0, 1.0])), tilt)

    def small(lo: float, hi: float) -> float:  # a constant that is often 0 (or 1e-10)
        return near(0.0, tiny) if rng.random() < 0.5 else float(u(lo, hi))

    a1 = length()
    a2 = a1 * float(rng.choice([-1.0, 1.0])) if equal else length()
    slide_limits = (-0.3, float(u(0.0, 0.4))) if limited else None
    rows: list[Joint]
    if kind == "planar-2R":
        rows = [
            Revolute(d=small(-0.3, 0.3), a=a1, alpha=flip(), offset=small(-PI, PI)),
            Revolute(d=small(-0.3, 0.3), a=a2, alpha=u(-PI, PI), offset=small(-PI, PI)),
        ]
    elif kind == "planar-3R":
        rows = [
            Revolute(d=small(-0.3, 0.3), a=a1, alpha=flip(), offset=small(-PI, PI)),
            Revolute(d=small(-0.3, 0.3), a=a2, alpha=flip(), offset=small(-PI, PI)),
            Revolute(d=small(-0.3, 0.3), a=length(), alpha=u(-PI, PI), offset=small(-PI, PI)),
        ]
    elif kind == "scara":
        rows = [
            Revolute(d=u(0.2, 0.5), a=a1, alpha=flip(), offset=small(-PI, PI)),
            Revolute(d=small(-0.1, 0.1), a=a2, alpha=flip(), offset=small(-PI, PI)),
            Prismatic(
                theta=small(-PI, PI),
                a=small(-0.1, 0.1),
                alpha=flip(),
                offset=small(-0.2, 0.2),
                qlim=slide_limits,
            ),
            Revolute(d=small(-0.1, 0.1), a=u(-0.2, 0.2), alpha=u(-PI, PI), offset=small(-PI, PI)),
        ]
    elif kind in ("planar-PR", "planar-PRR"):
        rows = [
            Prismatic(theta=small(-PI, PI), a=small(-0.3, 0.3), alpha=normal(), qlim=slide_limits),
            Revolute(d=small(-0.3, 0.3), a=a1, alpha=flip(), offset=small(-PI, PI)),
        ]
        if kind == "planar-PRR":
            rows.append(Revolute(d=small(-0.2, 0.2), a=a2, alpha=u(-PI, PI)))
    elif kind in ("anthropomorphic-3R", "elbow-3R"):
        shoulder = near(0.0, tiny) if kind == "anthropomorphic-3R" else length() / 3
        rows = [
            Revolute(d=u(0.2, 0.6), a=shoulder, alpha=normal(), offset=small(-PI, PI)),
            Revolute(d=small(-0.2, 0.2), a=a1, alpha=flip(), offset=small(-PI, PI)),
            Revolute(d=small(-0.2, 0.2), a=a2, alpha=u(-PI, PI), offset=small(-PI, PI)),
        ]
    else:
        raise ValueError(f"not a small arm kind: {kind!r}")
    if on_axis:  # the tool origin on the last axis: the last joint only turns the tool
        last = rows[-1]
        rows[-1] = Revolute(d=0.0, a=0.0, alpha=last.alpha, offset=last.offset)
    base = random_transform(rng, 0.5)
    # Equal links need the tool origin on the last DH frame's origin (the tool then only
    # turns the frame), as does a tool on the last axis.
    tool = random_transform(rng, None if equal or on_axis else 0.5)
    convention: Convention = "modified" if rng.random() < 0.5 else "standard"
    links, base, tool = convert_table(rows, "standard", convention, base, tool)
    return ArmSample(links, convention, base, tool, note=note)


def sampler(kind: str) -> Callable[[np.random.Generator, bool], ArmSample]:
    """``sample_arm`` of one kind: ``(rng, degenerate) -> ArmSample``."""

    def sample_arm(rng: np.random.Generator, degenerate: bool) -> ArmSample:
        return sample(kind, rng, degenerate)

    return sample_arm
