"""Checking loaded robot-file data and turning it into a :class:`RobotSpec`.

Every problem raises :class:`RobotFileError` naming the file, the joint number
(1-based), the key, what was expected and what was found.
"""

from __future__ import annotations

import copy
import math
import re
import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import PurePath
from typing import Any, Final, Literal

import numpy as np

from kinematica.errors import RobotFileError, UnitWarning, located
from kinematica.io import plausible
from kinematica.io.expr import Affine, Expression, ExpressionError, is_joint_variable
from kinematica.io.expr import parse_expression as _parse_expression
from kinematica.io.spec import (
    CONVENTION_ALIASES,
    ChainSpec,
    Convention,
    FrameSpec,
    JointKind,
    JointSpec,
    RobotSpec,
    convention_names,
    missing_convention,
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


def _suggest(word: str, allowed: Sequence[str]) -> str:
    import difflib  # only for a message: a correct file never needs it

    close = difflib.get_close_matches(word, allowed, n=1)
    return f" (did you mean {close[0]!r}?)" if close else ""


@dataclass
class _Reader:
    """State while reading one file: where it is, its units and parameters."""

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
                    f"unknown key{_suggest(k, allowed)}; allowed keys: {', '.join(allowed)}",
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
                f"no parameter {unknown[0]!r}{_suggest(unknown[0], list(params))} to set; "
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

    def joint(self, raw: object, i: int) -> JointSpec:
        where: dict[str, Any] = {"joint": i}
        data = self.mapping(raw, "a mapping with theta, d, a, alpha", **where)
        self.check_keys(data, JOINT_KEYS, **where)
        missing = [k for k in DH_KEYS if k not in data]
        if missing:
            raise self.error(
                f"missing {', '.join(missing)}: every joint needs theta, d, a and alpha", **where
            )
        quantity: dict[str, Quantity] = {"theta": "angle", "d": "length", "a": "length"}
        quantity["alpha"] = "angle"
        forms: dict[str, Affine] = {}
        texts: dict[str, str] = {}
        for key in DH_KEYS:
            forms[key], texts[key] = self.value(
                data[key], quantity[key], key, constant=False, **where
            )

        var = f"q{i}"
        for key in DH_KEYS:
            for other in forms[key].coeffs:
                if other != var:
                    raise self.error(
                        f"found {other}, but joint {i}'s variable is {var} "
                        "(joint i uses q<i> and no other)",
                        key=key,
                        **where,
                    )
        present = [k for k in DH_KEYS if forms[k].coeffs]
        if not present:
            raise self.error(
                f"the joint variable {var} appears nowhere: write it in theta "
                "(revolute joint) or in d (prismatic joint)",
                **where,
            )
        if len(present) > 1:
            raise self.error(
                f"{var} appears in {' and '.join(present)}; it must appear exactly once, "
                "in theta (revolute) or in d (prismatic)",
                key=present[1],
                **where,
            )
        key = present[0]
        if key not in ("theta", "d"):
            raise self.error(
                f"{var} appears in {key}; the joint variable goes in theta (revolute) "
                "or in d (prismatic), never in a or alpha",
                key=key,
                **where,
            )
        coeff = forms[key].coeffs[var]
        if coeff != 1.0:
            raise self.error(
                f"{var} must appear with coefficient exactly 1, found {coeff:g} "
                f"in {texts[key]!r} (write {var} + offset)",
                key=key,
                **where,
            )
        kind: JointKind = "R" if key == "theta" else "P"
        self.joint_type(data.get("type"), kind, key, **where)

        qlim = None
        if "limits" in data:
            qty: Quantity = "angle" if kind == "R" else "length"
            lo, hi = self.numbers(data["limits"], (qty, qty), "limits", **where)
            if not lo < hi:
                shown = ", ".join(str(v) for v in data["limits"])
                raise self.error(
                    f"expected [lower, upper] with lower < upper, found [{shown}] "
                    f"(lower {'=' if lo == hi else '>'} upper; swap them?)",
                    key="limits",
                    **where,
                )
            qlim = (lo, hi)
        self.check_joint(forms, kind, qlim, data.get("limits"), i)
        angle, length = self.to_si("angle"), self.to_si("length")
        return JointSpec(
            kind=kind,
            theta=angle(forms["theta"].const),
            d=length(forms["d"].const),
            a=length(forms["a"].const),
            alpha=angle(forms["alpha"].const),
            qlim=qlim,
            name=self.text(data.get("name"), "name", **where),
            expr=texts,
        )

    def check_joint(
        self,
        forms: Mapping[str, Affine],
        kind: JointKind,
        qlim: tuple[float, float] | None,
        raw_limits: object,
        i: int,
    ) -> None:
        """Warn about values implausible for the file's units (degrees as radians...)."""
        for key in ("theta", "alpha"):
            self.check_angle(forms[key].const, key, i)
        to_m = self.to_si("length")
        for key in () if self.described else ("d", "a"):
            message = plausible.check_length(to_m(forms[key].const), self.length_unit)
            self.warn(message, joint=i, key=key)
        if qlim is None or kind != "R" or not isinstance(raw_limits, list | tuple):
            return
        for lim in qlim:
            if self.angle_unit == "deg":
                message = plausible.check_degrees(math.degrees(lim))
            else:
                message = plausible.check_limit(lim)
            if message is not None:
                self.warn(message, joint=i, key="limits")
                return

    def joint_type(self, raw: object, kind: JointKind, key: str, **where: Any) -> None:
        if raw is None:
            return
        stated = JOINT_TYPES.get(raw.strip().lower()) if isinstance(raw, str) else None
        if stated is None:
            raise self.error(
                f"expected R, P, revolute or prismatic, found {describe(raw)}", key="type", **where
            )
        if stated != kind:
            words = {"R": "revolute", "P": "prismatic"}
            raise self.error(
                f"type says {words[stated]}, but the joint variable is in {key}, "
                f"which makes the joint {words[kind]}",
                key="type",
                **where,
            )

    def frame(self, raw: object, which: str) -> FrameSpec | None:
        if raw is None:
            return None
        data = self.mapping(raw, "a mapping with xyz and rpy, or with matrix", key=which)
        self.check_keys(data, FRAME_KEYS, f"{which}.")
        if "matrix" in data:
            if "xyz" in data or "rpy" in data:
                raise self.error(
                    "give either matrix, or xyz and rpy, not both", key=f"{which}.matrix"
                )
            return FrameSpec(*self.matrix(data["matrix"], f"{which}.matrix"))
        x, y, z = self.numbers(data.get("xyz", (0, 0, 0)), ("length",) * 3, f"{which}.xyz")
        if "rpy" not in data:
            return FrameSpec(xyz=(x, y, z))
        roll, pitch, yaw = self.numbers(data["rpy"], ("angle",) * 3, f"{which}.rpy")
        for angle in (roll, pitch, yaw):
            written = math.degrees(angle) if self.angle_unit == "deg" else angle
            self.check_angle(written, f"{which}.rpy")
        return FrameSpec(xyz=(x, y, z), rpy=(roll, pitch, yaw))

    def chain(self, raw: object, n: int) -> ChainSpec | None:
        """The optional ``chain`` block: start, n - 1 between, end, n frames."""
        if raw is None:
            return None
        data = self.mapping(raw, "a mapping with start, between, end and frames", key="chain")
        self.check_keys(data, CHAIN_KEYS, "chain.")
        missing = [k for k in CHAIN_KEYS if k not in data]
        if missing:
            raise self.error(f"missing {', '.join(missing)}", key="chain")
        lists = {}
        for key, count in (("between", n - 1), ("frames", n)):
            items = data[key]
            if not isinstance(items, list | tuple) or len(items) != count:
                raise self.error(
                    f"expected a list of {count} frames (the robot has {n} joints), "
                    f"found {describe(items)}",
                    key=f"chain.{key}",
                )
            lists[key] = tuple(
                self.frame(item, f"chain.{key}[{i}]") or FrameSpec() for i, item in enumerate(items)
            )
        return ChainSpec(
            start=self.frame(data["start"], "chain.start") or FrameSpec(),
            between=lists["between"],
            end=self.frame(data["end"], "chain.end") or FrameSpec(),
            frames=lists["frames"],
        )

    def matrix(
        self, raw: object, key: str
    ) -> tuple[tuple[float, float, float], None, tuple[tuple[float, ...], ...]]:
        if not isinstance(raw, list | tuple) or len(raw) != 4:
            raise self.error(f"expected 4 rows of 4 numbers, found {describe(raw)}", key=key)
        # The translation column is a length; the bottom row is plain numbers.
        qty: tuple[Quantity, ...] = ("number", "number", "number", "length")
        plain: tuple[Quantity, ...] = ("number",) * 4
        rows = tuple(self.numbers(row, qty if i < 3 else plain, key) for i, row in enumerate(raw))
        M = np.array(rows)
        R = M[:3, :3]
        bottom = float(np.abs(M[3] - (0.0, 0.0, 0.0, 1.0)).max())
        if bottom > MATRIX_TOL:
            raise self.error(f"the last row must be [0, 0, 0, 1], found {list(rows[3])}", key=key)
        ortho = float(np.abs(R.T @ R - np.eye(3)).max())
        if ortho > MATRIX_TOL or np.linalg.det(R) < 0:
            raise self.error(
                f"the rotation part is not a rotation (max |R^T R - I| = {ortho:.1e}, "
                f"det = {np.linalg.det(R):.3g}; tolerance {MATRIX_TOL:g}): "
                "give more digits, or use rpy",
                key=key,
            )
        xyz = (rows[0][3], rows[1][3], rows[2][3])
        return xyz, None, rows


def _default_name(source: str | None) -> str:
    if source is None or source.startswith("builtin:"):
        return "robot"
    return PurePath(source).stem or "robot"


def parse_robot_dict(
    data: object, *, source: str | None = None, parameters: Mapping[str, float] | None = None
) -> RobotSpec:
    """Check already-loaded robot-file data and build its :class:`RobotSpec`.

    Args:
        data: The file's content as loaded by a YAML/JSON/TOML reader: a
            mapping with the keys described in :mod:`kinematica.io.robotfile`.
        source: Where the data came from (a path, or ``"builtin:NAME"``);
            named in error messages and kept in ``RobotSpec.source``.
        parameters: Values (file units) replacing those of the named
            parameters before anything else is evaluated, so expressions that
            use them (``l2: 1 - l1``, DH cells, limits, base, tool) follow. Only
            parameters that use no other parameter can be set, and a bounded
            parameter only within its ``[min, max]``.

    Returns:
        The robot description in radians and metres.

    Raises:
        RobotFileError: naming the file, joint, key, what was expected and
            what was found.
    """
    r = _Reader(source, overrides=dict(parameters or {}))
    top = r.mapping(data, f"a mapping with the keys {', '.join(TOP_KEYS)}")
    r.check_keys(top, TOP_KEYS)

    name = r.text(top.get("name"), "name")
    if name is not None and not name.strip():
        raise r.error("expected a non-empty name", key="name")

    word = top.get("convention")
    if "convention" not in top:
        convention: Convention | None = missing_convention(r.path or "the robot data", stacklevel=2)
    else:
        convention = CONVENTION_ALIASES.get(word.strip().lower()) if isinstance(word, str) else None
    if convention is None:
        raise r.error(
            f"expected {convention_names()}, found {describe(word)}",
            key="convention",
        )

    r.units(top.get("units"))
    r.read_parameters(top.get("parameters"))
    r.described = top.get("chain") is not None

    if "joints" not in top:
        raise r.error("missing key 'joints': the DH table, one entry per joint")
    rows = top["joints"]
    if not isinstance(rows, list | tuple):
        raise r.error(f"expected a list of joints, found {describe(rows)}", key="joints")
    if not rows:
        raise r.error("expected at least one joint, found an empty list", key="joints")
    if len(rows) > MAX_JOINTS:
        raise r.error(f"{len(rows)} joints; at most {MAX_JOINTS} are accepted", key="joints")
    joints = tuple(r.joint(row, i) for i, row in enumerate(rows, start=1))

    return RobotSpec(
        name=name if name is not None else _default_name(source),
        convention=convention,
        joints=joints,
        base=r.frame(top.get("base"), "base"),
        tool=r.frame(top.get("tool"), "tool"),
        parameters=dict(r.parameters),
        parameter_texts=dict(r.parameter_texts),
        source=source,
        description=r.text(top.get("description"), "description"),
        units={"angle": r.angle_unit, "length": r.length_unit},
        reference=r.text(top.get("source"), "source"),
        parameter_bounds=dict(r.bounds),
        document=_document(r, top),
        chain=r.chain(top.get("chain"), len(joints)),
    )


def _document(r: _Reader, top: Mapping[str, Any]) -> dict[str, Any]:
    """A private copy of the checked file data, kept so the spec can be rebuilt."""
    try:
        return copy.deepcopy(dict(top))
    except RecursionError as exc:
        raise r.error("the file is nested too deeply") from exc
