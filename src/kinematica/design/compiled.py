"""A design template compiled once: the DH values as functions of the design variables.

A design search builds the arm at hundreds of candidates. Reading the template
file again for each (:meth:`DesignTemplate.robot_at`: every cell parsed and
checked, every key validated) costs more than solving a few hundred poses. Most
templates vary link lengths and offsets only: the design variables reach the
DH table (directly, or through parameters defined from them, ``l2: 1 - l1``)
and nothing else. For those, :func:`compile_template` reads the file once and
keeps, for each DH cell that depends on a design variable, its parsed
expression; a candidate then evaluates those expressions (with numbers, or with
numpy arrays for many candidates at once, :meth:`CompiledTemplate.table`) and
builds the :class:`~kinematica.Robot` from the table. The arithmetic is the
file reader's own, operation for operation (the parsed tree of
:mod:`kinematica.io.expr` folded with ``+ - * /`` on floats), so the table is
equal bit for bit to the one :meth:`DesignTemplate.robot_at` gives.

A template whose design variables reach a joint limit, the base, the tool or a
``chain`` block is not compiled (:attr:`CompiledTemplate.reason` says why) and
its candidates are read from the file as before.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, Final

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.dh import Prismatic, Revolute
from kinematica.dh.joints import values_checked
from kinematica.errors import KinematicaError
from kinematica.io.expr import Expression, is_joint_variable, parse_expression
from kinematica.robot import Robot, robot_from_spec

__all__ = ["CompiledTemplate", "compile_template"]

FloatArray = NDArray[np.float64]

#: The DH cells of a joint, in the order of :meth:`CompiledTemplate.table`'s columns.
CELLS: Final = ("theta", "d", "a", "alpha")
_DEG: Final = math.pi / 180.0


def _strings(raw: object) -> list[str]:
    """Every text inside a loaded file value (lists and mappings walked)."""
    if isinstance(raw, str):
        return [raw]
    if isinstance(raw, Mapping):
        return [s for v in raw.values() for s in _strings(v)]
    if isinstance(raw, list | tuple):
        return [s for v in raw for s in _strings(v)]
    return []


def _uses(raw: object, names: set[str]) -> bool:
    """Whether an expression written in ``raw`` names one of ``names``."""
    for text in _strings(raw):
        try:
            if parse_expression(text).names & names:
                return True
        except KinematicaError:  # a text that is no expression (a joint's name): no variable
            continue
    return False


def _to_si(value: Any, unit: str) -> Any:
    """A value in the file's ``unit`` in rad or m, by the operation the reader uses."""
    if unit == "deg":
        return value * _DEG
    if unit == "mm":
        return value / 1000.0
    return value


def _fold(expr: Expression, env: Mapping[str, Any]) -> Any:
    """The expression's constant part: ``env``'s values (floats or arrays), joint variables 0."""

    def name(n: str) -> Any:
        if is_joint_variable(n):
            return 0.0
        if n in env:
            return env[n]
        return math.pi  # the reader accepted the text: the only other name is pi

    def unary(op: str, v: Any) -> Any:
        return -v if op == "-" else v

    def binary(op: str, a: Any, b: Any) -> Any:
        if op == "+":
            return a + b
        if op == "-":
            return a - b
        if op == "*":
            return a * b
        return a / b

    return expr.fold(float, name, unary, binary)


@dataclass(frozen=True, eq=False)
class CompiledTemplate:
    """The DH table of a template as a function of its design variables.

    Attributes:
        template: The template (its ``spec`` at the nominal values).
        reason: Why it is not compiled (candidates are then read from the
            file), or None.
        nominal: ``(n, 4)`` the table at the nominal values: theta, d, a, alpha
            (rad, m; a revolute joint's theta and a prismatic joint's d are
            its offset).
        parameters: ``(name, expression)`` of the parameters that follow a
            design variable, in file order.
        cells: ``(row, column, expression, unit)`` of the cells that follow
            one (``unit``: the file's unit of the cell, converted to rad or m
            as the reader converts it).
        base: ``(4, 4)`` the base (it does not depend on a design variable).
        tool: ``(4, 4)`` the tool (likewise).
        links: The joints at the nominal values (those no variable reaches are
            used as they are).
    """

    template: Any
    reason: str | None
    nominal: FloatArray
    parameters: tuple[tuple[str, Expression], ...]
    cells: tuple[tuple[int, int, Expression, str], ...]
    base: FloatArray
    tool: FloatArray
    links: tuple[Revolute | Prismatic, ...]

    def table(self, X: ArrayLike) -> FloatArray:
        """``(..., n, 4)`` the DH table (rad, m) at design variables ``X`` ``(..., p)``.

        Raises:
            RuntimeError: The template is not compiled (see :attr:`reason`).
        """
        if self.reason is not None:
            raise RuntimeError(f"the template is not compiled: {self.reason}")
        Xa = np.asarray(X, dtype=np.float64)
        scalar = Xa.ndim == 1
        spec = self.template.spec
        env: dict[str, Any] = dict(spec.parameters)
        for j, name in enumerate(self.template.names):
            env[name] = float(Xa[j]) if scalar else Xa[..., j]
        for name, expr in self.parameters:
            env[name] = _fold(expr, env)
        out = np.array(np.broadcast_to(self.nominal, (*Xa.shape[:-1], *self.nominal.shape)))
        for row, col, expr, unit in self.cells:
            out[..., row, col] = _to_si(_fold(expr, env), unit)
        return out

    def robot(self, x: ArrayLike) -> Robot:
        """The robot at the design variables ``x`` ``(p,)`` (file units, within the bounds).

        Falls back on :meth:`DesignTemplate.robot_at` (which reads the file and
        says what is wrong) for a value outside its bounds, a table that is not
        finite (a division by zero), or a template that is not compiled.
        """
        tmpl = self.template
        xa = np.asarray(x, dtype=np.float64)
        inside = xa.shape == tmpl.lower.shape and bool(
            np.all((tmpl.lower <= xa) & (xa <= tmpl.upper))
        )
        if self.reason is not None or not inside:
            robot: Robot = tmpl.robot_at(xa)
            return robot
        table = self.table(xa)
        if not np.all(np.isfinite(table)):
            robot = tmpl.robot_at(xa)
            return robot
        spec = tmpl.spec
        links: list[Revolute | Prismatic] = list(self.links)  # rows no variable reaches
        with values_checked():  # the file's reader warned about implausible values
            for row in sorted({row for row, _, _, _ in self.cells}):
                joint = spec.joints[row]
                theta, d, a, alpha = table[row].tolist()
                if joint.kind == "R":
                    links[row] = Revolute(
                        d=d, a=a, alpha=alpha, offset=theta, qlim=joint.qlim, name=joint.name
                    )
                else:
                    links[row] = Prismatic(
                        theta=theta, a=a, alpha=alpha, offset=d, qlim=joint.qlim, name=joint.name
                    )
        return Robot(
            links=tuple(links),
            convention=spec.convention,
            name=spec.name,
            base=self.base,
            tool=self.tool,
            description=spec.description,
        )


def compile_template(template: Any) -> CompiledTemplate:
    """Compile a :class:`~kinematica.design.template.DesignTemplate` (module docs).

    Args:
        template: The design template.

    Returns:
        The compiled template; its ``reason`` is set where it cannot be compiled.
    """
    spec = template.spec
    doc = spec.document
    names = set(template.names)
    nominal = np.array([(j.theta, j.d, j.a, j.alpha) for j in spec.joints], dtype=np.float64)

    base = np.eye(4) if spec.base is None else spec.base.as_matrix()
    tool = np.eye(4) if spec.tool is None else spec.tool.as_matrix()

    def empty(reason: str) -> CompiledTemplate:
        return CompiledTemplate(template, reason, nominal, (), (), base, tool, ())

    if spec.chain is not None:
        return empty("the file describes its own transforms (chain)")
    raw_params = doc.get("parameters") or {}
    follows = set(names)
    parameters: list[tuple[str, Expression]] = []
    for name in raw_params:
        if name in names:
            continue
        text = spec.parameter_texts.get(name)
        if text is None:
            continue
        expr = parse_expression(text)
        if expr.names & follows:
            follows.add(name)
            parameters.append((name, expr))
    for key in ("base", "tool"):
        if _uses(doc.get(key), follows):
            return empty(f"the {key} depends on a design variable")
    angle, length = spec.units.get("angle", "deg"), spec.units.get("length", "m")
    units = {"theta": angle, "d": length, "a": length, "alpha": angle}
    cells: list[tuple[int, int, Expression, str]] = []
    for row, (raw, joint) in enumerate(zip(doc["joints"], spec.joints, strict=True)):
        if _uses(raw.get("limits"), follows):
            return empty(f"the limits of joint {row + 1} depend on a design variable")
        for col, key in enumerate(CELLS):
            expr = parse_expression(joint.expr[key])
            if expr.names & follows:
                cells.append((row, col, expr, units[key]))
    links = robot_from_spec(spec).links
    return CompiledTemplate(
        template, None, nominal, tuple(parameters), tuple(cells), base, tool, links
    )
