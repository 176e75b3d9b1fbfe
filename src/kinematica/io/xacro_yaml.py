"""``load_yaml`` for kinematica's xacro expander: YAML read safely into plain data.

The file is parsed by PyYAML's safe loader (the ``yaml`` extra), with xacro's
unit tags (``!degrees 90``, ``!millimeters 25``, ...) whose text is evaluated by
:mod:`kinematica.io.xacro_expr`. Mappings become
:class:`~kinematica.io.xacro_expr.YamlDict` (keys reachable as ``.key``) and
lists :class:`~kinematica.io.xacro_expr.YamlList`; shared and recursive
references are kept as such, so an alias bomb stays small.
"""

from __future__ import annotations

import math
from typing import Any, Final

from kinematica.io.xacro_expr import (
    MAX_TEXT,
    XacroExpressionError,
    YamlDict,
    YamlList,
    evaluate,
    flat_size,
)
from kinematica.io.xacro_scope import XacroError

__all__ = ["UNITS", "load_yaml"]

#: xacro's YAML tags of quantities with a unit, and the factor to SI (radians, metres).
UNITS: Final = {
    "!radians": 1.0,
    "!degrees": math.pi / 180.0,
    "!meters": 1.0,
    "!millimeters": 0.001,
    "!foot": 0.3048,
    "!inches": 0.0254,
}


def _no_names(name: str) -> Any:
    raise KeyError(name)


def _wrap(value: Any, seen: dict[int, Any]) -> Any:
    if not isinstance(value, dict | list):
        return value
    if id(value) in seen:
        return seen[id(value)]
    if isinstance(value, dict):
        out: Any = YamlDict()
        seen[id(value)] = out
        for key, item in value.items():
            out[key] = _wrap(item, seen)
        return out
    out = YamlList()
    seen[id(value)] = out
    out.extend(_wrap(item, seen) for item in value)
    return out


def load_yaml(data: bytes, source: str) -> Any:
    """The data of YAML file ``source`` (its bytes ``data``).

    Raises:
        XacroError: PyYAML is not installed, or the file is not valid YAML or
            holds a unit tag whose value is not a number.
    """
    try:
        import yaml
    except ImportError as exc:
        raise XacroError("load_yaml needs PyYAML: pip install 'kinematica[yaml]'") from exc

    class Loader(yaml.SafeLoader):
        """The safe loader with xacro's unit tags."""

    def unit(factor: float) -> Any:
        def construct(loader: Any, node: Any) -> float:
            text = str(loader.construct_scalar(node))
            try:
                return float(evaluate(text, _no_names)) * factor
            except (XacroExpressionError, TypeError, ValueError) as exc:
                raise XacroError(f"{source}: {node.tag} {text!r} is not a number") from exc

        return construct

    for tag, factor in UNITS.items():
        Loader.add_constructor(tag, unit(factor))
    try:
        value = yaml.load(data, Loader=Loader)
    except yaml.YAMLError as exc:
        problem = " ".join(str(getattr(exc, "problem", None) or exc).split())
        raise XacroError(f"{source}: not valid YAML: {problem}") from exc
    if flat_size(value) > MAX_TEXT:
        raise XacroError(f"{source}: the YAML data expands to more than {MAX_TEXT:,} items")
    return _wrap(value, {})
