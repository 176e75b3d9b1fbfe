"""Reading a robot file's values: units, numbers, expressions and parameters.

:class:`ValueReader` holds where a file is read (its path, units and parameters)
and reads one value at a time, with messages naming the file, joint and key;
:mod:`kinematica.io._parse` reads the file's sections (joints, frames, chain) on it.
"""

from __future__ import annotations

import math
import re
import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, Final, Literal

import numpy as np

from kinematica.errors import RobotFileError, UnitWarning, located
from kinematica.io import plausible
from kinematica.io.expr import Affine, Expression, ExpressionError, is_joint_variable
from kinematica.io.expr import parse_expression as _parse_expression
from kinematica.io.spec import (
    JointKind,
)

TOP_KEYS: Final = (
    "name",
    "convention",
    "units",
    "parameters",
    "joints",
    "base",
    "tool",
    "description",
    "source",
    "chain",
)
#: Keys of the optional ``chain`` block: an arm's own transforms (:class:`ChainSpec`).
CHAIN_KEYS: Final = ("start", "between", "end", "frames")
JOINT_KEYS: Final = ("theta", "d", "a", "alpha", "limits", "name", "type")
DH_KEYS: Final = ("theta", "d", "a", "alpha")
FRAME_KEYS: Final = ("xyz", "rpy", "matrix")
UNIT_KEYS: Final = ("angle", "length")
#: Keys of a bounded parameter, ``l1: {value: 0.3, min: 0.1, max: 0.9}`` (design templates).
BOUND_KEYS: Final = ("value", "min", "max")

JOINT_TYPES: Final[dict[str, JointKind]] = {
    "r": "R",
    "revolute": "R",
    "p": "P",
    "prismatic": "P",
}
ANGLE_UNITS: Final = {"deg": "deg", "degree": "deg", "degrees": "deg"} | {
    "rad": "rad",
    "radian": "rad",
    "radians": "rad",
}
LENGTH_UNITS: Final = {"m": "m", "metre": "m", "metres": "m", "meter": "m", "meters": "m"} | {
    "mm": "mm",
    "millimetre": "mm",
    "millimetres": "mm",
    "millimeter": "mm",
    "millimeters": "mm",
}
DEFAULT_UNITS: Final = {"angle": "deg", "length": "m"}

#: Radians per degree; a value ``v`` written in degrees is ``v * DEG`` radians.
DEG: Final = math.pi / 180.0
#: Most joints a robot file may have. Serial arms have up to a dozen, snake
#: robots a few dozen; a file with thousands is an error (and slow to check).
MAX_JOINTS: Final = 100
#: Most named parameters a robot file may have.
MAX_PARAMETERS: Final = 1000

#: Largest deviation tolerated in a frame matrix: max |R^T R - I| and the
#: bottom row's distance from (0, 0, 0, 1). Eight significant digits pass.
MATRIX_TOL: Final = 1e-6

_PARAMETER_NAME = re.compile(r"[A-Za-z_][A-Za-z_0-9]*", re.ASCII)

Quantity = Literal["angle", "length", "number"]


def angle_to_si(unit: str) -> Callable[[float], float]:
    """The conversion of an angle written in ``unit`` to radians."""
    return (lambda v: v * DEG) if unit == "deg" else (lambda v: v)


def length_to_si(unit: str) -> Callable[[float], float]:
    """The conversion of a length written in ``unit`` to metres."""
    return (lambda v: v / 1000.0) if unit == "mm" else (lambda v: v)


def describe(value: object) -> str:
    """A short description of a found value, for error messages."""
    if value is None:
        return "nothing"
    if isinstance(value, bool):
        return f"{str(value).lower()} (a boolean)"
    if isinstance(value, str):
        return repr(value)
    if isinstance(value, int | float):
        return repr(value)
    if isinstance(value, Mapping):
        return "a mapping"
    if isinstance(value, list | tuple):
        return f"a list of {len(value)}"
    return f"a {type(value).__name__}"


def suggest(word: str, allowed: Sequence[str]) -> str:
    import difflib  # only for a message: a correct file never needs it

    close = difflib.get_close_matches(word, allowed, n=1)
    return f" (did you mean {close[0]!r}?)" if close else ""


@dataclass
class ValueReader:
    """State while reading one file: where it is, its units and parameters; its values."""

    path: str | None
    angle_unit: str = "deg"
    length_unit: str = "m"
    parameters: dict[str, float] = field(default_factory=dict)
    parameter_texts: dict[str, str] = field(default_factory=dict)
    pi_parameters: set[str] = field(default_factory=set)
    bounds: dict[str, tuple[float, float]] = field(default_factory=dict)
    overrides: Mapping[str, float] = field(default_factory=dict)
    #: The file holds the arm's own transforms (``chain``): its DH table describes the
    #: arm, and nearly parallel axes give that table common normals far away (lengths of
    #: kilometres that are no unit slip).
    described: bool = False

    def error(
        self, message: str, *, joint: int | None = None, key: str | None = None
    ) -> RobotFileError:
        return RobotFileError(message, path=self.path, joint=joint, key=key)

    def warn(self, message: str | None, *, joint: int | None = None, key: str) -> None:
        """Warn (UnitWarning) that a value is implausible for its unit, if it is."""
        if message is None:
            return
        if key == "limits" or key.endswith(".rpy") or key in ("theta", "alpha"):
            advice = "set units.angle: deg" if self.angle_unit == "rad" else ""
        else:
            advice = "set units.length: mm" if self.length_unit == "m" else ""
        if advice and "is it in" in message:
            message += f"; {advice} if the file is in those units"
        text = located(message, path=self.path, joint=joint, key=key)
        warnings.warn(text, UnitWarning, stacklevel=3)

    def check_angle(self, written: float, key: str, joint: int | None = None) -> None:
        """Warn about a constant angle ``written`` in file units, if implausible."""
        if self.angle_unit == "deg":
            self.warn(plausible.check_degrees(written), joint=joint, key=key)
        else:
            self.warn(plausible.check_angle(written), joint=joint, key=key)

    # --- generic checks ---------------------------------------------------

    def mapping(self, value: object, what: str, **where: Any) -> Mapping[str, Any]:
        if not isinstance(value, Mapping):
            raise self.error(f"expected {what}, found {describe(value)}", **where)
        for k in value:
            if not isinstance(k, str):
                raise self.error(f"keys must be names, found the key {describe(k)}", **where)
        return value

    def check_keys(
        self, data: Mapping[str, Any], allowed: Sequence[str], prefix: str = "", **where: Any
    ) -> None:
        for k in data:
            if k not in allowed:
                raise self.error(
                    f"unknown key{suggest(k, allowed)}; allowed keys: {', '.join(allowed)}",
                    key=prefix + k,
                    **where,
                )

    def text(self, value: object, key: str, **where: Any) -> str | None:
        if value is None:
            return None
        if not isinstance(value, str):
            raise self.error(f"expected text, found {describe(value)}", key=key, **where)
        return value

    def expression(self, value: object, key: str, **where: Any) -> Expression:
        if isinstance(value, bool) or not isinstance(value, int | float | str):
            raise self.error(
                f"expected a number or an expression, found {describe(value)}", key=key, **where
            )
        if isinstance(value, float) and not math.isfinite(value):
            raise self.error(f"expected a finite number, found {value!r}", key=key, **where)
        try:
            text = repr(value) if isinstance(value, float) else str(value)
            return _parse_expression(text)
        except ValueError as exc:  # ExpressionError, or an int too long to print
            raise self.error(str(exc), key=key, **where) from exc

    def value(
        self, raw: object, quantity: Quantity, key: str, *, constant: bool = True, **where: Any
    ) -> tuple[Affine, str]:
        """Evaluate one cell; returns its affine form (file units) and its text."""
        expr = self.expression(raw, key, **where)
        if quantity == "angle" and self.angle_unit == "deg":
            tainted = sorted(expr.names & ({"pi"} | self.pi_parameters))
            if tainted:
                what = "pi" if "pi" in tainted else f"{tainted[0]!r} (defined with pi)"
                raise self.error(
                    f"{what} used in an angle while units.angle is deg: "
                    "write 90 for a right angle, or set units.angle: rad",
                    key=key,
                    **where,
                )
        if constant and expr.variables:
            found = ", ".join(sorted(expr.variables))
            raise self.error(
                f"expected a constant, found the joint variable {found} in {expr.text!r}",
                key=key,
                **where,
            )
        try:
            return expr.evaluate(self.parameters), expr.text
        except ExpressionError as exc:
            raise self.error(str(exc), key=key, **where) from exc

    def to_si(self, quantity: Quantity) -> Callable[[float], float]:
        if quantity == "angle":
            return angle_to_si(self.angle_unit)
        if quantity == "length":
            return length_to_si(self.length_unit)
        return lambda v: v

    def numbers(
        self, raw: object, quantities: Sequence[Quantity], key: str, **where: Any
    ) -> tuple[float, ...]:
        """A fixed-length list of constant numbers, converted to SI."""
        n = len(quantities)
        if not isinstance(raw, list | tuple) or len(raw) != n:
            raise self.error(
                f"expected a list of {n} numbers, found {describe(raw)}", key=key, **where
            )
        return tuple(
            self.to_si(qty)(self.value(item, qty, key, **where)[0].const)
            for item, qty in zip(raw, quantities, strict=True)
        )

    # --- sections -----------------------------------------------------------

    def units(self, raw: object) -> None:
        if raw is None:
            return
        units = self.mapping(raw, "a mapping like {angle: deg, length: m}", key="units")
        self.check_keys(units, UNIT_KEYS, "units.")
        for key, table in (("angle", ANGLE_UNITS), ("length", LENGTH_UNITS)):
            if key not in units:
                continue
            word = units[key]
            unit = table.get(word.strip().lower()) if isinstance(word, str) else None
            if unit is None:
                allowed = ", ".join(sorted(set(table.values())))
                raise self.error(
                    f"unknown unit {describe(word)}; expected one of: {allowed}",
                    key=f"units.{key}",
                )
            if key == "angle":
                self.angle_unit = unit
            else:
                self.length_unit = unit

    def read_parameters(self, raw: object) -> None:
        if raw is None and not self.overrides:
            return
        params = self.mapping(
            {} if raw is None else raw, "a mapping of names to numbers", key="parameters"
        )
        if len(params) > MAX_PARAMETERS:
            raise self.error(
                f"{len(params)} parameters; at most {MAX_PARAMETERS} are accepted",
                key="parameters",
            )
        for name, value in params.items():
            key = f"parameters.{name}"
            if not _PARAMETER_NAME.fullmatch(name) or name == "pi" or is_joint_variable(name):
                raise self.error(
                    "a parameter name must be a word (letters, digits, _) other than "
                    "pi and the joint variables q1, q2, ...",
                    key=key,
                )
            if isinstance(value, Mapping):
                self.parameters[name] = self.bounded_parameter(name, value, key)
                continue
            expr = self.expression(value, key)
            self.parameters[name] = self.constant(expr, key)
            self.parameter_texts[name] = expr.text
            if expr.names & ({"pi"} | self.pi_parameters):
                self.pi_parameters.add(name)
            if name in self.overrides:
                if expr.names - {"pi"}:
                    raise self.error(
                        f"cannot set {name}: it is the expression {expr.text!r} of other "
                        "parameters; set those instead",
                        key=key,
                    )
                self.parameters[name] = self.override(name, key)
        unknown = sorted(set(self.overrides) - set(params))
        if unknown:
            raise self.error(
                f"no parameter {unknown[0]!r}{suggest(unknown[0], list(params))} to set; "
                f"the file's parameters: {', '.join(params) or 'none'}",
                key="parameters",
            )

    def constant(self, expr: Expression, key: str) -> float:
        """The value of a parameter's expression (no joint variables)."""
        if expr.variables:
            found = ", ".join(sorted(expr.variables))
            raise self.error(f"parameters cannot use joint variables, found {found}", key=key)
        try:
            return expr.evaluate(self.parameters).const
        except ExpressionError as exc:
            raise self.error(
                f"{exc} (a parameter may use only pi and the parameters above it)", key=key
            ) from exc

    def bounded_parameter(self, name: str, raw: Mapping[str, Any], key: str) -> float:
        """A design variable ``{value: v, min: lo, max: hi}``; returns its value.

        ``value`` may be left out (the midpoint is used). The bounds are kept in
        :attr:`bounds`; an override replaces ``value`` and must lie within them.
        """
        self.mapping(raw, "a number, an expression or {value, min, max}", key=key)
        self.check_keys(raw, BOUND_KEYS, f"{key}.")
        missing = [k for k in ("min", "max") if k not in raw]
        if missing:
            raise self.error(
                f"a bounded parameter needs min and max (missing {', '.join(missing)}), "
                "e.g. {value: 0.3, min: 0.1, max: 0.9}",
                key=key,
            )
        found: dict[str, float] = {}
        for k in BOUND_KEYS:
            if k in raw:
                expr = self.expression(raw[k], f"{key}.{k}")
                found[k] = self.constant(expr, f"{key}.{k}")
                if expr.names & ({"pi"} | self.pi_parameters):
                    self.pi_parameters.add(name)
        lo, hi = found["min"], found["max"]
        if not lo < hi:
            raise self.error(f"expected min < max, found min {lo:g} and max {hi:g}", key=key)
        value = found.get("value", 0.5 * (lo + hi))
        if not lo <= value <= hi:
            raise self.error(
                f"value {value:g} is outside [min, max] = [{lo:g}, {hi:g}]", key=f"{key}.value"
            )
        self.bounds[name] = (lo, hi)
        return self.override(name, key) if name in self.overrides else value

    def override(self, name: str, key: str) -> float:
        """The value set for ``name`` by the caller (``parse_robot_dict(parameters=)``)."""
        raw = self.overrides[name]
        if isinstance(raw, bool) or not isinstance(raw, int | float | np.floating | np.integer):
            raise self.error(f"the value set for {name} must be a number, found {raw!r}", key=key)
        value = float(raw)
        lo, hi = self.bounds.get(name, (-math.inf, math.inf))
        if not lo <= value <= hi:  # also rejects NaN
            raise self.error(
                f"the value set for {name}, {value:g}, is outside its bounds [{lo:g}, {hi:g}]",
                key=key,
            )
        return value
