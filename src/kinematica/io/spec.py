"""The neutral description of a robot that the io layer hands upwards.

A :class:`RobotSpec` is what a robot file says, checked and converted to SI
units (radians, metres), with the original expression text kept alongside so a
later layer (symbolic derivations, file writers) can show the table as written.
The robot layer turns a spec into a ``Robot``; nothing here computes kinematics
beyond building the 4x4 matrix of a base or tool placement.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any, Literal

import numpy as np

from kinematica.errors import ConventionWarning, RobotFileError, located

__all__ = [
    "CONVENTION_ALIASES",
    "ChainSpec",
    "Convention",
    "FrameSpec",
    "JointKind",
    "JointSpec",
    "RobotSpec",
    "convention_names",
    "missing_convention",
]

JointKind = Literal["R", "P"]
Convention = Literal["standard", "modified"]

#: Every name a DH convention goes by (lower case) -> its canonical name. The one
#: table of aliases: robot files and ``Robot.from_dh`` read conventions through it.
CONVENTION_ALIASES: dict[str, Convention] = {
    "standard": "standard",
    "dh": "standard",
    "paul": "standard",
    "distal": "standard",
    "modified": "modified",
    "mdh": "modified",
    "craig": "modified",
    "proximal": "modified",
}


def convention_names() -> str:
    """The aliases, for messages: ``"standard (also dh, paul, distal) or modified (...)"``."""
    parts = []
    for canonical in ("standard", "modified"):
        others = [k for k, v in CONVENTION_ALIASES.items() if v == canonical and k != canonical]
        parts.append(f"{canonical} (also {', '.join(others)})")
    return " or ".join(parts)


def missing_convention(path: str | None = None, *, stacklevel: int = 2) -> Convention:
    """The one rule for a DH table without a convention: standard, said aloud.

    Warns :class:`~kinematica.errors.ConventionWarning` (naming the file and the
    key ``convention`` when ``path`` is given) and returns ``"standard"``. Used
    by ``Robot.from_dh`` and by robot files alike.

    Args:
        path: The robot file, or ``None`` for a table given in Python.
        stacklevel: The caller's frame for the warning, as ``warnings.warn`` counts
            from the caller of this function.
    """
    say = "add convention: standard" if path is not None else "say convention='standard'"
    message = (
        f"no DH convention given: read as standard (Paul, distal); {say} "
        "or 'modified' (Craig, proximal)"
    )
    if path is not None:
        message = located(message, path=path, key="convention")
    warnings.warn(message, ConventionWarning, stacklevel=stacklevel + 1)
    return "standard"


@dataclass(frozen=True)
class JointSpec:
    """One row of a DH table, in radians and metres.

    For a revolute joint (``kind="R"``) the joint angle is ``q + theta``; for a
    prismatic joint (``kind="P"``) the offset along z is ``q + d``. In the
    modified (Craig) convention ``a`` and ``alpha`` are a(i-1) and alpha(i-1),
    as Craig tables are written row by row.

    Attributes:
        kind: ``"R"`` (revolute) or ``"P"`` (prismatic).
        theta: Rotation about z, rad (the constant offset for ``"R"``).
        d: Offset along z, m (the constant offset for ``"P"``).
        a: Link length along x, m.
        alpha: Link twist about x, rad.
        qlim: ``(lower, upper)`` joint limits in rad (R) or m (P), or ``None``.
        name: Optional joint name.
        expr: The text of ``theta``, ``d``, ``a`` and ``alpha`` as written in
            the file, in the file's units (empty when built in code). Not part
            of equality: two joints are equal when their numbers are.
    """

    kind: JointKind
    theta: float
    d: float
    a: float
    alpha: float
    qlim: tuple[float, float] | None = None
    name: str | None = None
    expr: Mapping[str, str] = field(default_factory=dict, compare=False)

    def __post_init__(self) -> None:
        if self.kind not in ("R", "P"):
            raise RobotFileError(f"joint kind must be 'R' or 'P', found {self.kind!r}")
        values = (self.theta, self.d, self.a, self.alpha, *(self.qlim or ()))
        if not all(math.isfinite(v) for v in values):
            raise RobotFileError(f"joint values must be finite numbers, found {values}")
        if self.qlim is not None and not self.qlim[0] < self.qlim[1]:
            raise RobotFileError(f"joint limits need lower < upper, found {self.qlim}")


@dataclass(frozen=True)
class FrameSpec:
    """A fixed placement (base or tool), in metres and radians.

    Either ``rpy`` or ``matrix`` is given, not both. ``rpy`` is URDF's
    fixed-axis roll-pitch-yaw: ``R = Rz(yaw) @ Ry(pitch) @ Rx(roll)``. When
    ``matrix`` is given, ``xyz`` is set to its translation column.

    Attributes:
        xyz: Translation, m.
        rpy: ``(roll, pitch, yaw)``, rad, or ``None``.
        matrix: The 4x4 homogeneous matrix as nested tuples (m), or ``None``.
    """

    xyz: tuple[float, float, float] = (0.0, 0.0, 0.0)
    rpy: tuple[float, float, float] | None = None
    matrix: tuple[tuple[float, ...], ...] | None = None

    def __post_init__(self) -> None:
        if self.matrix is None:
            return
        if self.rpy is not None:
            raise RobotFileError("a frame takes either rpy or matrix, not both")
        rows = tuple(tuple(float(v) for v in row) for row in self.matrix)
        if len(rows) != 4 or any(len(row) != 4 for row in rows):
            raise RobotFileError(f"a frame matrix must be 4x4, found {self.matrix}")
        translation = (rows[0][3], rows[1][3], rows[2][3])
        if self.xyz != (0.0, 0.0, 0.0) and tuple(self.xyz) != translation:
            raise RobotFileError(
                f"xyz {self.xyz} disagrees with the matrix translation {translation}"
            )
        object.__setattr__(self, "matrix", rows)
        object.__setattr__(self, "xyz", translation)

    def as_matrix(self) -> np.ndarray:
        """The placement as a 4x4 homogeneous transform, shape ``(4, 4)``."""
        if self.matrix is not None:
            return np.array(self.matrix, dtype=float)
        T = np.eye(4)
        if self.rpy is not None:
            r, p, y = self.rpy
            cr, sr = math.cos(r), math.sin(r)
            cp, sp = math.cos(p), math.sin(p)
            cy, sy = math.cos(y), math.sin(y)
            T[:3, :3] = [
                [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                [-sp, cp * sr, cp * cr],
            ]
        T[:3, 3] = self.xyz
        return T


def frame_of(T: np.ndarray) -> FrameSpec:
    """The :class:`FrameSpec` of a ``(4, 4)`` transform ``T``, written as its matrix (m)."""
    return FrameSpec(matrix=tuple(tuple(float(v) for v in row) for row in T))


@dataclass(frozen=True)
class ChainSpec:
    """An arm's own transforms, when its DH table only describes it (a URDF's, a calibration's).

    ``T = base · start · M1(q1) · between[0] ··· Mn(qn) · end · tool``, each ``Mi`` a
    turn about (or slide along) the z axis of the frame it acts in; relative to the DH
    frames 0 and n of the table (see :class:`kinematica.robot.transforms.ChainTransforms`).

    Attributes:
        start: DH frame 0 to the frame joint 1 moves in.
        between: ``n - 1`` transforms from the frame after each motion to the next
            joint's frame.
        end: From the frame after the last motion to DH frame n.
        frames: ``n`` placements of DH frame i in the frame after motion i.
    """

    start: FrameSpec
    between: tuple[FrameSpec, ...]
    end: FrameSpec
    frames: tuple[FrameSpec, ...]


@dataclass(frozen=True)
class RobotSpec:
    """A whole robot description: DH table, placements and provenance.

    Two specs compare equal when they describe the same robot: the numbers
    (SI), joint kinds and limits, placements, names and texts. How it was
    written down (``expr`` texts, ``parameters``, ``parameter_texts``,
    ``units``) and where it was read from (``source``) take no part: the same
    arm written in YAML, JSON or TOML gives equal specs, and so does a spec
    written out and read back.

    Attributes:
        name: Robot name.
        convention: ``"standard"`` (Paul, distal) or ``"modified"`` (Craig,
            proximal).
        joints: One :class:`JointSpec` per joint, base to tip.
        base: Placement of DH frame 0 in the world, or ``None`` (identity).
        tool: Placement of the tool in the last DH frame, or ``None``.
        parameters: Named values used by the expressions, in file units.
        source: Where the spec was read from: a path or ``"builtin:NAME"``.
        description: Free text.
        units: ``{"angle": "deg" | "rad", "length": "m" | "mm"}``: the units
            of ``expr`` texts and ``parameters``.
        reference: Where the numbers come from (book, paper, datasheet): the
            file's ``source`` key.
        parameter_texts: Each parameter as written (``"l1 + 0.1"``), in file
            units; a parameter without a text is written as its number.
        parameter_bounds: ``name -> (min, max)`` (file units) of the bounded
            parameters ``l1: {value: 0.3, min: 0.1, max: 0.9}`` of a design
            template; ``parameters`` holds their values.
        chain: The arm's own transforms (:class:`ChainSpec`), which its kinematics
            use, its DH table then describing it; ``None``: the DH table is the arm.
        document: The file's content as read (plain data), so that
            :func:`kinematica.io.with_parameters` can rebuild the spec with
            other parameter values; ``None`` for a spec built in code.
    """

    name: str
    convention: Convention
    joints: tuple[JointSpec, ...]
    base: FrameSpec | None = None
    tool: FrameSpec | None = None
    parameters: Mapping[str, float] = field(default_factory=dict, compare=False)
    source: str | None = field(default=None, compare=False)
    description: str | None = None
    units: Mapping[str, str] = field(
        default_factory=lambda: {"angle": "deg", "length": "m"}, compare=False
    )
    reference: str | None = None
    parameter_texts: Mapping[str, str] = field(default_factory=dict, compare=False)
    parameter_bounds: Mapping[str, tuple[float, float]] = field(default_factory=dict, compare=False)
    document: Mapping[str, Any] | None = field(default=None, compare=False, repr=False)
    chain: ChainSpec | None = field(default=None, repr=False)

    def __post_init__(self) -> None:
        if self.convention not in ("standard", "modified"):
            raise RobotFileError(
                f"convention must be 'standard' or 'modified', found {self.convention!r}"
            )
        if not self.joints:
            raise RobotFileError("a robot needs at least one joint")

    @property
    def dof(self) -> int:
        """Number of joints."""
        return len(self.joints)
