"""Rebuilding a robot description with other parameter values (design templates).

A robot file's ``parameters`` name the lengths of its DH table. In a design
template some carry bounds, ``l1: {value: 0.3, min: 0.1, max: 0.9}``, and
others may be expressions of them, ``l2: 1 - l1``. :func:`with_parameters`
reads the same file content again with new values for the free parameters, so
every expression that uses them (other parameters, DH cells, limits, base,
tool) is evaluated afresh by the one parser.
"""

from __future__ import annotations

from collections.abc import Mapping

from kinematica.errors import RobotFileError
from kinematica.io._parse import parse_robot_dict
from kinematica.io.spec import RobotSpec

__all__ = ["with_parameters"]


def with_parameters(spec: RobotSpec, values: Mapping[str, float]) -> RobotSpec:
    """The description ``spec`` was read from, with other parameter values.

    Args:
        spec: A spec read from a robot file (it keeps the file's content).
        values: ``name -> value`` in the file's units (``spec.units``). Only
            parameters that use no other parameter can be set; a bounded one
            only within its ``[min, max]``. Parameters not named keep their
            values; expressions of the ones named are re-evaluated.

    Returns:
        The new spec, with the same ``source``, units and bounds.

    Raises:
        RobotFileError: the spec was not read from a file, a name is not a
            parameter (or is an expression of others), or a value is not a
            number within its bounds.
    """
    if spec.document is None:
        raise RobotFileError(
            f"{spec.name}: this description was not read from a robot file, "
            "so it has no parameters to set"
        )
    return parse_robot_dict(spec.document, source=spec.source, parameters=values)
