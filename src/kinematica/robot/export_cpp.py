"""A robot's chain and its closed-form IK solver as C++: the core's headers, filled in.

The closed forms are C++ structs (``cpp/include/kinematica/solvers/``) filled from
the geometry of the joint axes: by the core's builder beside the solver (a family
whose ``Params`` class names its ``cpp_build``), else by a Python builder.
:func:`cpp_header` writes a C++ header for one robot: a function building its
:cpp:`km::Chain`, one giving its solver's ``Params`` (the core's builder called on
that chain, or the Python builder's values written field by field), and its branch
labels, so that a C++ program (a ROS node, a controller) solves IK with the very code
``robot.ik`` runs. ``kinematica convert ROBOT --to cpp`` writes it.
"""

from __future__ import annotations

import enum
import math
import re
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from kinematica.errors import KinematicaError
from kinematica.ik import closed_form

if TYPE_CHECKING:
    from kinematica.robot.robot import Robot

__all__ = ["cpp_header", "cpp_identifier"]

FloatArray = NDArray[np.float64]


def cpp_identifier(name: str) -> str:
    """A C++ identifier made of ``name`` (letters, digits and underscores)."""
    ident = re.sub(r"\W+", "_", name.strip()).strip("_").lower() or "robot"
    return f"robot_{ident}" if ident[0].isdigit() else ident


def _number(v: float) -> str:
    """A C++ literal that reads back as exactly ``v``."""
    if math.isnan(v):
        return "km::NaN"
    if math.isinf(v):
        return "km::INF" if v > 0 else "-km::INF"
    text = repr(float(v))
    return text if ("." in text or "e" in text) else text + ".0"


def _scalar(v: Any) -> str:
    if isinstance(v, bool | np.bool_):
        return "true" if v else "false"
    if isinstance(v, int | np.integer):
        return str(int(v))
    return _number(float(v))


def _assignments(obj: Any, path: str) -> list[str]:
    """``path.field = value;`` for every writable field of a core struct, nested ones too."""
    lines: list[str] = []
    for name, attr in vars(type(obj)).items():
        if not isinstance(attr, property) or attr.fset is None:
            continue
        value = getattr(obj, name)
        target = f"{path}.{name}"
        if isinstance(value, enum.Enum):
            lines.append(f"{target} = static_cast<decltype({target})>({int(value.value)});")
        elif isinstance(value, np.ndarray) and value.shape[-2:] == (4, 4):
            # a Pose or double[4][4], or an array of them (Pose link[6])
            for index in np.ndindex(value.shape[:-2]):
                where = "".join(f"[{i}]" for i in index)
                rows = ", ".join(_scalar(v) for v in value[index].ravel())
                lines.append(
                    f"km::assign_rows({target}{where}, std::array<double, 16>{{{rows}}}.data());"
                )
        elif isinstance(value, np.ndarray):
            for index in np.ndindex(value.shape):
                where = "".join(f"[{i}]" for i in index)
                lines.append(f"{target}{where} = {_scalar(value[index])};")
        elif isinstance(value, bool | int | float | np.generic):
            lines.append(f"{target} = {_scalar(value)};")
        elif hasattr(type(value), "__dict__") and type(value).__module__.startswith("kinematica"):
            lines += _assignments(value, target)
        else:
            raise KinematicaError(f"cannot write field {target} of type {type(value).__name__}")
    return lines


def _array(name: str, ctype: str, values: Any) -> str:
    items = ", ".join(_scalar(v) for v in np.ravel(values))
    return f"    const {ctype} {name}[] = {{{items}}};"


def _pose(T: FloatArray) -> str:
    return (
        "km::Pose::from_rows(std::array<double, 16>{"
        + ", ".join(_number(v) for v in np.ravel(T))
        + "}.data())"
    )


def _chain_body(robot: Robot) -> list[str]:
    links, n = robot.links, robot.dof
    prismatic = [link.type == "P" for link in links]
    lims = [link.qlim if link.qlim is not None else (math.inf, math.inf) for link in links]
    lo = [
        lim[0] if link.qlim is not None else -math.inf
        for lim, link in zip(lims, links, strict=True)
    ]
    hi = [lim[1] for lim in lims]
    lines = [
        _array("prismatic", "bool", prismatic),
        _array("lo", "double", lo),
        _array("hi", "double", hi),
    ]
    if robot.transforms is None:
        lines += [
            _array("theta", "double", [link.theta for link in links]),
            _array("d", "double", [link.d for link in links]),
            _array("a", "double", [link.a for link in links]),
            _array("alpha", "double", [link.alpha for link in links]),
            f"    return km::Chain::from_dh({n}, prismatic, theta, d, a, alpha, lo, hi, "
            f"{'true' if robot.convention == 'modified' else 'false'},",
            f"                              {_pose(robot.base)},",
            f"                              {_pose(robot.tool)});",
        ]
        return lines
    t = robot.transforms
    between = ",\n        ".join(_pose(F) for F in t.between)
    offsets = ",\n        ".join(_pose(F) for F in t.frame_offsets)
    start, end, base = _pose(robot.base @ t.start), _pose(t.end @ robot.tool), _pose(robot.base)
    lines += [
        "    const km::Pose* between = nullptr;  // one joint: nothing between motions"
        if n == 1
        else f"    const km::Pose between[] = {{\n        {between}}};",
        f"    const km::Pose offsets[] = {{\n        {offsets}}};",
        f"    return km::Chain::from_transforms({n}, {start},",
        f"                                      between, {end},",
        f"                                      offsets, prismatic, lo, hi, {base});",
    ]
    return lines


def cpp_header(robot: Robot, namespace: str | None = None) -> str:
    """The C++ header of ``robot``'s chain and closed-form IK solver (pose targets).

    Args:
        robot: A robot with a closed-form solver for poses.
        namespace: The C++ namespace of the header's functions; default a C++
            identifier made of the robot's name.

    Returns:
        Header text defining, in ``namespace``: ``chain()`` (its ``km::Chain``),
        ``solver()`` (the filled ``Params``), ``Solver`` (the ``Params`` type),
        ``labels`` (the branch name of each candidate slot). An SRS 7R arm's
        solver solves at the arm angle in its field ``psi`` (0 as written).

    Raises:
        KinematicaError: When the robot has no closed-form solver for poses.
    """
    closed = closed_form(robot.chain, "pose")
    at_angle = closed is None and closed_form(robot.chain, "pose", "arm_angle") is not None
    if at_angle:  # an SRS arm: solved at the arm angle p.psi, which the program sets
        closed = closed_form(robot.chain, "pose", "arm_angle")
    if closed is None:
        raise KinematicaError(
            f"{robot.name} has no closed-form IK solver: nothing to write as C++ but its chain"
        )
    params = closed.params
    kind = type(params)
    ns = namespace or cpp_identifier(robot.name)
    build = getattr(kind, "cpp_build", None)
    if build is not None:  # the core builds it from the chain, as robot.ik does
        body = f"return *{build}(chain());"
    else:
        body = "\n    ".join(["Solver p;", *_assignments(params, "p"), "return p;"])
    labels = ", ".join('"' + label.replace('"', "'") + '"' for label in closed.labels)
    psi_note = "\n// It solves at the arm angle psi (rad; 0 as written): set it first." * at_angle
    return f"""\
// {robot.name}: its chain and its closed-form IK solver ({closed.method}), for C++.
// Written by kinematica (`kinematica convert ... --to cpp`) from the same values robot.ik
// uses; include the core's headers (cpp/include) to build it. Not to be edited by hand.{psi_note}
#pragma once

#include <array>

#include "kinematica/chain.hpp"
#include "kinematica/ik.hpp"
#include "{kind.cpp_header}"

namespace {ns} {{

//! The solver's Params type.
using Solver = {kind.cpp_type};

//! The robot's chain (FK, Jacobians, the check).
inline km::Chain chain() {{
{chr(10).join(_chain_body(robot))}
}}

//! The closed-form solver, filled for this robot.
inline Solver solver() {{
    {body}
}}

//! The branch name of each candidate slot.
constexpr const char* labels[{closed.slots}] = {{{labels}}};

}}  // namespace {ns}
"""
