"""A robot's DH table as sympy expressions, from a robot, a built-in name or a file.

From a built-in name or a robot file the named parameters stay symbols (``l1``,
``L2``, as the file writes them), built by walking the expression tree of our own
parser (never ``sympify`` on raw text). From a :class:`~kinematica.Robot`,
numbers stay numbers. Either way angles become exact where they are exact:
degrees written in a file are exact multiples of pi (``90`` is ``pi/2``), and a
number within :data:`ANGLE_SNAP_TOL` of a multiple of pi/12 becomes that
multiple. Joint variables are the symbols ``q1 ... qn``.

Every expression is in SI units: a parameter symbol stands for its value in
metres or radians, whatever the file's units (``units: {length: mm}`` turns the
literal ``290`` into ``0.29``; a symbol ``l1`` then means l1 in metres).
"""

from __future__ import annotations

import os
import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from functools import cache
from pathlib import Path
from typing import Final, Literal

import numpy as np
import sympy as sp
from numpy.typing import NDArray

from kinematica.errors import KinematicaError, UnknownRobotError
from kinematica.io import (
    ROBOT_FILE_SUFFIXES,
    FrameSpec,
    JointSpec,
    RobotSpec,
    parse_expression,
    read_builtin,
    read_robot_file,
)
from kinematica.robot import Robot, load, robot_from_spec

__all__ = [
    "ANGLE_SNAP_TOL",
    "RobotLike",
    "SymbolicError",
    "SymbolicRobot",
    "SymbolicRow",
    "exact_angle",
    "exact_matrix",
    "exact_number",
    "joint_symbols",
    "numeric_model",
    "symbolic_robot",
]

FloatArray = NDArray[np.float64]

#: An angle within this of a multiple of pi/12 (rad) is taken as that exact multiple.
ANGLE_SNAP_TOL: Final = 1e-12
#: A rotation-matrix entry within this of an exact value (cos of a multiple of
#: pi/12: 0, 1/2, sqrt(2)/2, ...) is taken as that exact value.
ENTRY_SNAP_TOL: Final = 1e-12
#: Largest denominator kept for a rational number written in a file (``l2/2``,
#: ``22.5`` degrees); larger ones (``0.4318``) print as decimals.
MAX_DENOMINATOR: Final = 12

_JOINT = re.compile(r"q([0-9]+)")


@cache
def _exact_entries() -> tuple[sp.Expr, ...]:
    """The exact values of ±cos(k pi/12), the entries of a 15-degree-step rotation."""
    values = {sp.cos(k * sp.pi / 12) for k in range(13)}
    return tuple(values | {-v for v in values})


class SymbolicError(KinematicaError, ValueError):
    """A symbolic derivation was asked of something it cannot describe."""


@dataclass(frozen=True)
class SymbolicRow:
    """One DH row as sympy expressions (SI units).

    Attributes:
        kind: ``"R"`` (the joint symbol is in ``theta``) or ``"P"`` (in ``d``).
        q: The joint symbol ``q<i>``.
        theta: Rotation about z, rad.
        d: Offset along z, m.
        a: Length along x, m (``a(i-1)`` in the modified convention).
        alpha: Twist about x, rad (``alpha(i-1)`` in the modified convention).
        text: The cells as written in the file (file units), or empty.
    """

    kind: Literal["R", "P"]
    q: sp.Symbol
    theta: sp.Expr
    d: sp.Expr
    a: sp.Expr
    alpha: sp.Expr
    text: Mapping[str, str] = field(default_factory=dict, compare=False)


@dataclass(frozen=True)
class SymbolicRobot:
    """A robot's description in sympy, with the numeric robot it stands for.

    Attributes:
        name: Display name.
        convention: ``"standard"`` or ``"modified"``.
        rows: One :class:`SymbolicRow` per joint, base to tip.
        base: ``(4, 4)`` placement of DH frame 0 in the world frame.
        tool: ``(4, 4)`` placement of the tool in the last DH frame.
        values: Each parameter symbol and its value (m or rad).
        robot: The numeric robot with the same kinematics.
        source: ``"builtin:NAME"``, a path, or ``None`` for a ``Robot``.
        units: The units the file was written in (``angle``, ``length``).
    """

    name: str
    convention: Literal["standard", "modified"]
    rows: tuple[SymbolicRow, ...]
    base: sp.ImmutableMatrix
    tool: sp.ImmutableMatrix
    values: Mapping[sp.Symbol, float]
    robot: Robot
    source: str | None = None
    units: Mapping[str, str] = field(default_factory=lambda: {"angle": "rad", "length": "m"})

    @property
    def dof(self) -> int:
        """Number of joints."""
        return len(self.rows)

    @property
    def q(self) -> tuple[sp.Symbol, ...]:
        """The joint symbols ``q1 ... qn``."""
        return tuple(row.q for row in self.rows)

    @property
    def joint_types(self) -> str:
        """One letter per joint, e.g. ``"RRPR"``."""
        return "".join(row.kind for row in self.rows)


RobotLike = Robot | SymbolicRobot | str | os.PathLike[str]


def joint_symbols(n: int) -> tuple[sp.Symbol, ...]:
    """The joint symbols ``q1 ... qn`` (real)."""
    return tuple(sp.Symbol(f"q{i}") for i in range(1, n + 1))


def joint_index(symbol: sp.Basic) -> int | None:
    """``i`` for the joint symbol ``q<i>``, else ``None``."""
    if isinstance(symbol, sp.Symbol):
        m = _JOINT.fullmatch(symbol.name)
        if m:
            return int(m.group(1))
    return None


# --------------------------------------------------------------- exact numbers
def exact_number(x: float) -> sp.Expr:
    """A length (or any plain number) as sympy: an Integer when integral, else a Float."""
    v = float(x)
    if v.is_integer() and abs(v) < 1e15:
        return sp.Integer(int(v))
    return sp.Float(v)


def exact_angle(x: float) -> sp.Expr:
    """An angle (rad) as sympy: ``k*pi/12`` within :data:`ANGLE_SNAP_TOL`, else a Float."""
    v = float(x)
    k = round(v / (np.pi / 12))
    if abs(v - k * np.pi / 12) <= ANGLE_SNAP_TOL:
        return sp.Rational(k, 12) * sp.pi
    return sp.Float(v)


def _exact_entry(x: float) -> sp.Expr:
    v = float(x)
    best = min(_exact_entries(), key=lambda e: abs(float(e) - v))
    if abs(float(best) - v) <= ENTRY_SNAP_TOL:
        return best
    return sp.Float(v)


def exact_matrix(T: FloatArray) -> sp.ImmutableMatrix:
    """A ``(4, 4)`` rigid transform with exact rotation entries where they are exact.

    Rotation entries within :data:`ENTRY_SNAP_TOL` of cos(k pi/12) become that
    exact value (``sqrt(2)/2``, ``1/2``, ...); the translation follows
    :func:`exact_number`.
    """
    M = np.asarray(T, dtype=float)
    rows = [
        [_exact_entry(M[i, j]) if j < 3 else exact_number(M[i, j]) for j in range(4)]
        for i in range(3)
    ]
    return sp.ImmutableMatrix([*rows, [0, 0, 0, 1]])


def _rpy_matrix(xyz: tuple[float, float, float], rpy: tuple[float, float, float]) -> sp.Matrix:
    roll, pitch, yaw = (exact_angle(v) for v in rpy)
    R = rot("z", yaw) * rot("y", pitch) * rot("x", roll)
    R[:3, 3] = sp.Matrix([exact_number(v) for v in xyz])
    return R


def rot(axis: str, angle: sp.Expr) -> sp.Matrix:
    """``(4, 4)`` homogeneous rotation about ``x``, ``y`` or ``z``."""
    c, s = sp.cos(angle), sp.sin(angle)
    m = {
        "x": [[1, 0, 0], [0, c, -s], [0, s, c]],
        "y": [[c, 0, s], [0, 1, 0], [-s, 0, c]],
        "z": [[c, -s, 0], [s, c, 0], [0, 0, 1]],
    }[axis]
    T = sp.eye(4)
    T[:3, :3] = sp.Matrix(m)
    return T


def trans(axis: str, distance: sp.Expr) -> sp.Matrix:
    """``(4, 4)`` homogeneous translation along ``x``, ``y`` or ``z``."""
    T = sp.eye(4)
    T["xyz".index(axis), 3] = distance
    return T


# ------------------------------------------------------------------ from a Robot
def _exact_plus_residual(x: float) -> sp.Expr:
    """``k*pi/12 + (x - k*pi/12)``: exact where x is, the float's residue kept otherwise."""
    exact = exact_angle(x)
    if isinstance(exact, sp.Float):
        return exact
    residual = float(x) - float(exact)
    return exact if residual == 0.0 else exact + sp.Float(residual)


def _from_robot(robot: Robot, snap: bool = True) -> SymbolicRobot:
    """The robot's numbers as sympy; ``snap=False`` keeps what snapping would drop."""
    angle = exact_angle if snap else _exact_plus_residual
    rows = []
    for link, q in zip(robot.links, joint_symbols(robot.dof), strict=True):
        a, alpha = exact_number(link.a), angle(link.alpha)
        if link.type == "R":
            theta, d = q + angle(link.offset), exact_number(link.d)
        else:
            theta, d = angle(link.theta), q + exact_number(link.offset)
        rows.append(SymbolicRow(link.type, q, theta, d, a, alpha))

    def frame(T: FloatArray) -> sp.ImmutableMatrix:
        M = exact_matrix(T)
        if snap:
            return M
        # Entries off their exact value by a residue keep it (see numeric_model).
        return sp.ImmutableMatrix(
            4,
            4,
            [
                e if float(e) == v else exact_number(v)
                for e, v in zip(M, np.asarray(T).flat, strict=True)
            ],
        )

    return SymbolicRobot(
        name=robot.name,
        convention=robot.convention,
        rows=tuple(rows),
        base=frame(robot.base),
        tool=frame(robot.tool),
        values={},
        robot=robot,
    )


def numeric_model(robot: RobotLike) -> SymbolicRobot:
    """The model :func:`~kinematica.symbolic.lambdify` compiles.

    From a ``Robot``, an angle near a multiple of pi/12 keeps its residue: a
    twist of ``pi/2 + 1e-13`` is ``pi/2 + 1.0e-13``, what ``robot.fk`` uses, so
    the compiled function equals it to rounding (snapping alone would move the
    tool by the angle error times the arm's reach). Angles that are exact
    floats (``np.pi / 2``) stay exact, and cheap. Other sources as
    :func:`symbolic_robot`.
    """
    if isinstance(robot, Robot):
        return _from_robot(robot, snap=False)
    return symbolic_robot(robot)


# -------------------------------------------------------------- from a RobotSpec
def _file_number(value: float) -> sp.Expr:
    """A number written in a file: exact when it is a short rational."""
    exact = sp.Rational(repr(float(value)))
    if exact.q <= MAX_DENOMINATOR:
        return exact
    return sp.Float(value)


def _tidy_constant(c: sp.Expr, angle: bool) -> sp.Expr:
    """A cell's constant part in SI: exact angles snapped, long rationals as decimals."""
    if c.free_symbols:
        return c
    if angle:
        ratio = sp.nsimplify(c / sp.pi) if not c.has(sp.Float) else None
        if ratio is not None and ratio.is_Rational and ratio.q <= 180 * 10:
            return ratio * sp.pi
        return exact_angle(float(c))
    if c.is_Rational and not c.is_Integer:  # a length reads best as a decimal: 0.5, 0.29
        return sp.Float(float(c))
    return c


class _CellBuilder:
    """Turns the cells of one spec into SI sympy expressions."""

    def __init__(self, spec: RobotSpec) -> None:
        self.spec = spec
        self.deg = spec.units.get("angle", "rad") == "deg"
        self.mm = spec.units.get("length", "m") == "mm"
        self.symbols = {name: sp.Symbol(name) for name in spec.parameters}
        self.kinds = self._parameter_kinds()
        self.values: dict[sp.Symbol, float] = {}

    def factor(self, angle: bool) -> sp.Expr:
        if angle:
            return sp.pi / 180 if self.deg else sp.Integer(1)
        return sp.Rational(1, 1000) if self.mm else sp.Integer(1)

    def _parameter_kinds(self) -> dict[str, set[bool]]:
        kinds: dict[str, set[bool]] = {}
        for joint in self.spec.joints:
            for key, text in joint.expr.items():
                for name in parse_expression(text).names:
                    kinds.setdefault(name, set()).add(key in ("theta", "alpha"))
        return kinds

    def cell(self, joint: JointSpec, i: int, key: str) -> sp.Expr:
        angle = key in ("theta", "alpha")
        f = self.factor(angle)
        text = joint.expr.get(key)
        q = sp.Symbol(f"q{i}")
        if text is None:  # a spec built in code: numbers only
            value = getattr(joint, key)
            const = exact_angle(value) if angle else exact_number(value)
            variable = (key, joint.kind) in (("theta", "R"), ("d", "P"))
            return q + const if variable else const

        def name(n: str) -> sp.Expr:
            if n == f"q{i}":
                return q / f
            if n == "pi":
                return sp.pi
            # A parameter symbol stands for its SI value; one used in angles and
            # lengths of a file in non-SI units has no single SI value: its
            # number is used instead.
            if len(self.kinds.get(n, ())) > 1 and (self.deg or self.mm):
                return sp.Rational(repr(float(self.spec.parameters[n])))
            symbol = self.symbols[n]
            self.values[symbol] = float(self.spec.parameters[n]) * float(f)
            return symbol / f

        def binary(op: str, left: sp.Expr, right: sp.Expr) -> sp.Expr:
            if op == "+":
                return left + right
            if op == "-":
                return left - right
            if op == "*":
                return left * right
            return left / right

        raw = parse_expression(text).fold(
            number=_file_number,
            name=name,
            unary=lambda op, x: -x if op == "-" else x,
            binary=binary,
        )
        expr = sp.expand(f * raw)
        var = expr.coeff(q)
        const = _tidy_constant(sp.expand(expr - var * q), angle)
        return var * q + const

    def frame(self, frame: FrameSpec | None) -> sp.ImmutableMatrix:
        if frame is None:
            return sp.ImmutableMatrix(sp.eye(4))
        if frame.matrix is not None:
            return exact_matrix(frame.as_matrix())
        return sp.ImmutableMatrix(_rpy_matrix(frame.xyz, frame.rpy or (0.0, 0.0, 0.0)))


def _from_spec(spec: RobotSpec) -> SymbolicRobot:
    build = _CellBuilder(spec)
    rows = []
    for i, joint in enumerate(spec.joints, start=1):
        cells = {key: build.cell(joint, i, key) for key in ("theta", "d", "a", "alpha")}
        rows.append(
            SymbolicRow(
                joint.kind,
                sp.Symbol(f"q{i}"),
                cells["theta"],
                cells["d"],
                cells["a"],
                cells["alpha"],
                dict(joint.expr),
            )
        )
    return SymbolicRobot(
        name=spec.name,
        convention=spec.convention,
        rows=tuple(rows),
        base=build.frame(spec.base),
        tool=build.frame(spec.tool),
        values=dict(build.values),
        robot=robot_from_spec(spec),
        source=spec.source,
        units=dict(spec.units),
    )


def symbolic_robot(robot: RobotLike) -> SymbolicRobot:
    """The symbolic description of a robot.

    Args:
        robot: A :class:`~kinematica.Robot` (numbers stay numbers), a built-in
            name or a robot-file path (named parameters stay symbols), or a
            :class:`SymbolicRobot` (returned as is).

    Returns:
        The DH rows, base and tool as sympy expressions in SI units.

    Raises:
        UnknownRobotError: neither a built-in name nor an existing file.
        RobotFileError: the file is malformed (the message says where).
        SymbolicError: ``robot`` is none of the above.
    """
    if isinstance(robot, SymbolicRobot):
        return robot
    if isinstance(robot, Robot):
        return _from_robot(robot)
    if not isinstance(robot, str | os.PathLike):
        raise SymbolicError(
            "expected a Robot, a built-in robot name or a robot-file path, "
            f"got {type(robot).__name__}"
        )
    text = os.fspath(robot)
    path = Path(text)
    if path.suffix.lower() in ROBOT_FILE_SUFFIXES:
        if not path.is_file():
            raise UnknownRobotError(f"{text}: no such robot file")
        return _from_spec(read_robot_file(path))
    if path.exists() or os.sep in text:
        return _from_robot(load(text))  # e.g. a URDF: numbers only
    return _from_spec(read_builtin(text))
