"""From a :class:`RobotSpec` back to robot-file data, and a small TOML writer.

The dump keeps the file as it was written when it can (expressions, units and
parameters); each number is written in the file's units with the shortest
decimal that reads back to the very same float. When that is not possible (a
spec built in code with inconsistent texts, say), it writes plain radians and
metres instead. Either way, reading the dump gives back an equal spec.
"""

from __future__ import annotations

import json
import math
import re
from collections.abc import Callable, Mapping
from typing import Any

from kinematica.errors import KinematicaError
from kinematica.io._parse import angle_to_si, length_to_si, parse_robot_dict
from kinematica.io.spec import FrameSpec, JointSpec, RobotSpec

__all__ = ["dump_robot_dict", "toml_dumps"]

_NUMBER_TEXT = re.compile(r"-?[0-9]+(\.[0-9]+)?([eE][-+]?[0-9]+)?", re.ASCII)
_ULP_STEPS = 4  # neighbours of the naive conversion tried, each side


def _exact(value: float, to_si: Callable[[float], float]) -> float | None:
    """A number ``c`` in file units with ``to_si(c) == value``, shortest first."""
    naive = value / to_si(1.0)
    candidates = [round(naive, digits) for digits in range(17)] + [naive]
    up = down = naive
    for _ in range(_ULP_STEPS):
        up, down = math.nextafter(up, math.inf), math.nextafter(down, -math.inf)
        candidates += [up, down]
    return next((c for c in candidates if to_si(c) == value), None)


class _InexactError(Exception):
    """A value has no exact representation in the file's units."""


def _number(c: float | None) -> int | float:
    if c is None:
        raise _InexactError
    return int(c) if c.is_integer() and abs(c) < 1e15 else c


def _text_value(text: str) -> int | float | str:
    """A cell's text as written: numbers stay numbers when that is lossless."""
    if _NUMBER_TEXT.fullmatch(text):
        number: int | float = int(text) if text.lstrip("-").isdigit() else float(text)
        if repr(number) == text:
            return number
    return text


def _cell(
    i: int, key: str, joint: JointSpec, value: float, to_si: Callable[[float], float]
) -> int | float | str:
    """The cell ``key`` of joint ``i`` rebuilt from its value."""
    c = _number(_exact(value, to_si)) if value != 0.0 else 0
    variable = (joint.kind == "R" and key == "theta") or (joint.kind == "P" and key == "d")
    if not variable:
        return c
    if c == 0:
        return f"q{i}"
    return f"q{i} + {c!r}" if c > 0 else f"q{i} - {-c!r}"


def _joint(
    i: int,
    joint: JointSpec,
    angle: Callable[[float], float],
    length: Callable[[float], float],
    use_text: bool,
) -> dict[str, Any]:
    values = {"theta": joint.theta, "d": joint.d, "a": joint.a, "alpha": joint.alpha}
    convert = {"theta": angle, "d": length, "a": length, "alpha": angle}
    row: dict[str, Any] = {}
    for key, value in values.items():
        if use_text and _has_text(joint):
            row[key] = _text_value(joint.expr[key])
        else:
            row[key] = _cell(i, key, joint, value, convert[key])
    if joint.qlim is not None:
        to_si = angle if joint.kind == "R" else length
        row["limits"] = [_number(_exact(v, to_si)) for v in joint.qlim]
    if joint.name is not None:
        row["name"] = joint.name
    return row


def _frame(
    frame: FrameSpec, angle: Callable[[float], float], length: Callable[[float], float]
) -> dict[str, Any]:
    if frame.matrix is not None:
        rows = [
            [_number(v) for v in row[:3]] + [_number(_exact(row[3], length) if i < 3 else row[3])]
            for i, row in enumerate(frame.matrix)
        ]
        return {"matrix": rows}
    out: dict[str, Any] = {}
    if frame.xyz != (0.0, 0.0, 0.0) or frame.rpy is None:
        out["xyz"] = [_number(_exact(v, length)) for v in frame.xyz]
    if frame.rpy is not None:
        out["rpy"] = [_number(_exact(v, angle)) for v in frame.rpy]
    return out


def _parameter(spec: RobotSpec, name: str, value: float) -> int | float | str | dict[str, Any]:
    """A parameter as written: bounded, its text, or its number.

    ``{value, min, max}`` when it has bounds, else its text (``"l1 + 0.1"``)
    when it has one, else its number.
    """
    if name not in spec.parameter_bounds:
        if name in spec.parameter_texts:
            return _text_value(spec.parameter_texts[name])
        return _number(value)
    lo, hi = spec.parameter_bounds[name]
    return {"value": _number(value), "min": _number(lo), "max": _number(hi)}


def _build(spec: RobotSpec, units: Mapping[str, str], use_text: bool) -> dict[str, Any]:
    angle = angle_to_si(units["angle"])
    length = length_to_si(units["length"])
    data: dict[str, Any] = {"name": spec.name, "convention": spec.convention}
    if spec.description is not None:
        data["description"] = spec.description
    if spec.reference is not None:
        data["source"] = spec.reference
    data["units"] = {"angle": units["angle"], "length": units["length"]}
    if use_text and spec.parameters:
        data["parameters"] = {k: _parameter(spec, k, v) for k, v in spec.parameters.items()}
    data["joints"] = [
        _joint(i, j, angle, length, use_text) for i, j in enumerate(spec.joints, start=1)
    ]
    if spec.base is not None:
        data["base"] = _frame(spec.base, angle, length)
    if spec.tool is not None:
        data["tool"] = _frame(spec.tool, angle, length)
    if spec.chain is not None:
        c = spec.chain
        data["chain"] = {
            "start": _frame(c.start, angle, length),
            "between": [_frame(f, angle, length) for f in c.between],
            "end": _frame(c.end, angle, length),
            "frames": [_frame(f, angle, length) for f in c.frames],
        }
    return data


def _has_text(joint: JointSpec) -> bool:
    """Whether the joint keeps the text of each of its four DH cells."""
    return set(joint.expr) >= {"theta", "d", "a", "alpha"}


def _identical(again: RobotSpec, spec: RobotSpec) -> bool:
    """Equal, and written the same way (units, parameters, every text ``spec`` keeps)."""
    return (
        again == spec
        and dict(again.units) == dict(spec.units)
        and dict(again.parameters) == dict(spec.parameters)
        and all(again.parameter_texts.get(k) == t for k, t in spec.parameter_texts.items())
        and all(
            dict(x.expr) == dict(y.expr)
            for x, y in zip(again.joints, spec.joints, strict=True)
            if _has_text(y)
        )
    )


def dump_robot_dict(spec: RobotSpec) -> dict[str, Any]:
    """The robot-file data (plain dicts, lists, numbers, strings) of ``spec``.

    Reading the result with :func:`parse_robot_dict` gives a spec equal to
    ``spec``; for a spec read from a file, also with the same units,
    parameters and expression texts (of every joint that keeps its texts: a
    joint changed in code is written as numbers, in the file's units).

    Args:
        spec: The robot description.

    Returns:
        A mapping with the robot-file keys, ready for JSON, TOML or YAML.
    """
    units = {"angle": spec.units.get("angle", "deg"), "length": spec.units.get("length", "m")}
    texts = any(_has_text(j) for j in spec.joints)
    for use_text in (True, False) if texts else (False,):
        try:
            data = _build(spec, units, use_text)
            again = parse_robot_dict(data)
        except (_InexactError, KinematicaError):
            continue
        if _identical(again, spec) if use_text else again == spec:
            return data
    return _build(spec, {"angle": "rad", "length": "m"}, use_text=False)


# --- TOML --------------------------------------------------------------------

_BARE_KEY = re.compile(r"[A-Za-z0-9_-]+", re.ASCII)


def _toml_key(key: str) -> str:
    return key if _BARE_KEY.fullmatch(key) else _toml_string(key)


def _toml_string(text: str) -> str:
    # JSON's escapes are valid TOML basic-string escapes; DEL must be escaped too.
    return json.dumps(text, ensure_ascii=False).replace("\x7f", "\\u007f")


def _toml_value(value: object) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return repr(value)
    if isinstance(value, str):
        return _toml_string(value)
    if isinstance(value, Mapping):
        items = ", ".join(f"{_toml_key(k)} = {_toml_value(v)}" for k, v in value.items())
        return "{ " + items + " }" if items else "{}"
    if isinstance(value, list | tuple):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    raise TypeError(f"cannot write {type(value).__name__} to TOML")


def toml_dumps(data: Mapping[str, Any]) -> str:
    """TOML text for ``data``, one ``key = value`` line per top-level key.

    Mappings become inline tables; a list of mappings (the joints) becomes an
    array of inline tables, one per line, so the DH table reads as a table.
    Enough for robot files; not a general TOML writer.
    """
    lines: list[str] = []
    for key, value in data.items():
        if isinstance(value, list) and value and all(isinstance(v, Mapping) for v in value):
            lines.append(f"{_toml_key(key)} = [")
            lines += [f"  {_toml_value(item)}," for item in value]
            lines.append("]")
        else:
            lines.append(f"{_toml_key(key)} = {_toml_value(value)}")
    return "\n".join(lines) + "\n"
