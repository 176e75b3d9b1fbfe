"""What every subcommand shares: common options, units, checked numbers, JSON output.

Each topic of the command line lives in its own module (``kinematics``, ...)
with a ``register(sub)`` function adding its subcommands;
:mod:`kinematica.cli.main` lists those modules. The helpers here are the only
code they share.

Units: the command line speaks degrees (``--rad`` for radians) and the robot
file's length unit (``--units m|mm`` to choose): a robot file in millimetres
reads and prints millimetres. The library underneath always works in radians
and metres; :func:`q_in`, :func:`lengths_in` and their ``_out`` twins convert
at the edge, and every output says which units it uses.
"""

from __future__ import annotations

import argparse
import math
from collections.abc import Sequence
from typing import Any, Final

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.cli.format import DEFAULT_PRECISION
from kinematica.errors import ArgumentError, DimensionError
from kinematica.robot import Robot, load

__all__ = [
    "PER_METRE",
    "add_common",
    "add_precision",
    "add_robot",
    "angle_unit",
    "clean",
    "dump",
    "finite",
    "joint_units",
    "length_unit",
    "lengths_in",
    "lengths_out",
    "q_in",
    "q_out",
    "robot_from_args",
    "transform_in",
    "transform_out",
    "units",
]

FloatArray = NDArray[np.float64]

#: Units of length the command line speaks, and how many of each make a metre.
PER_METRE: Final = {"m": 1.0, "mm": 1000.0}


def add_common(p: argparse.ArgumentParser, numbers: bool = True) -> None:
    """The options every command takes: ``--json``, ``--euler``, ``--rad``, ``--units``.

    ``numbers=False``: a command that prints no angle or length accepts ``--euler``,
    ``--rad`` and ``--units`` (every command does) but its help does not offer them.
    """
    shown = (lambda text: text) if numbers else (lambda text: argparse.SUPPRESS)
    p.add_argument("--json", action="store_true", help="machine-readable output (stable keys)")
    p.add_argument(
        "--euler",
        default="ZYZ",
        metavar="SEQ",
        help=shown(
            "Euler sequence, scipy naming: upper case intrinsic (ZYZ, XYZ...), "
            "lower case extrinsic (zyz, xyz...); default ZYZ"
        ),
    )
    p.add_argument("--rad", action="store_true", help=shown("angles in radians (default degrees)"))
    p.add_argument(
        "--units",
        choices=tuple(PER_METRE),
        default=None,
        help=shown(
            "unit of lengths in and out (default: the robot file's, metres for most "
            "built-in robots)"
        ),
    )


def _precision(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        value = 0
    if not 1 <= value <= 17:
        raise argparse.ArgumentTypeError(f"expected a whole number from 1 to 17, got {text!r}")
    return value


def add_pose(group: Any, help: str) -> None:
    """Add ``--pose X Y Z A B G`` (position, then three Euler angles) to ``group``.

    Args:
        group: A parser or a mutually exclusive group of one.
        help: What the pose is for, and its units.
    """
    group.add_argument(
        "--pose", nargs=6, type=float, metavar=("X", "Y", "Z", "A", "B", "G"), help=help
    )


def add_precision(p: argparse.ArgumentParser) -> None:
    """``--precision N``: significant digits of the text output (JSON is always full)."""
    p.add_argument(
        "--precision",
        type=_precision,
        default=DEFAULT_PRECISION,
        metavar="N",
        help=f"significant digits of numbers in the text output (default "
        f"{DEFAULT_PRECISION}, enough to paste T back into ik --matrix); --json "
        "always prints every digit",
    )


def add_robot(p: argparse.ArgumentParser) -> None:
    """The positional ``ROBOT`` (built-in name, robot file or URDF) and ``--base``/``--tip``."""
    p.add_argument("robot", metavar="ROBOT", help="built-in name, robot file or URDF")
    p.add_argument("--base", metavar="LINK", help="URDF only: base link of the chain")
    p.add_argument("--tip", metavar="LINK", help="URDF only: tip link of the chain")
    p.add_argument(
        "--xacro",
        action="store_true",
        help="URDF only: expand xacro in a .urdf file (a .xacro file always is)",
    )
    p.add_argument(
        "--xacro-env",
        action="store_true",
        help="URDF only: let xacro read environment variables ($(env ...), $(optenv ...))",
    )
    p.add_argument(
        "--trust-xacro",
        action="store_true",
        help="URDF only: expand xacro with the xacro package, which RUNS the file's code "
        "(only for files you trust); by default kinematica's own expander runs none",
    )
    p.add_argument(
        "--package",
        action="append",
        type=_package,
        default=[],
        metavar="NAME=DIR",
        help="URDF only: the folder of ROS package NAME, for $(find NAME) in xacro files "
        "(repeatable; ROS_PACKAGE_PATH, AMENT_PREFIX_PATH and the file's own package.xml "
        "find the others)",
    )
    p.add_argument(
        "--xacro-arg",
        action="append",
        type=_xacro_arg,
        default=[],
        metavar="NAME:=VALUE",
        help="URDF only: the value of the xacro file's <xacro:arg name=NAME> (repeatable)",
    )


def _package(text: str) -> tuple[str, str]:
    """``--package NAME=DIR`` as ``(name, dir)``."""
    from kinematica.io.packages import parse_package_option

    try:
        return parse_package_option(text)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from exc


def _xacro_arg(text: str) -> tuple[str, str]:
    """``--xacro-arg NAME:=VALUE`` as ``(name, value)``."""
    name, sep, value = text.partition(":=")
    if not sep or not name.strip() or " " in name.strip():
        raise argparse.ArgumentTypeError(f"--xacro-arg takes NAME:=VALUE, got {text!r}")
    return name.strip(), value


def urdf_options(args: argparse.Namespace) -> dict[str, Any]:
    """The URDF-only options given (``--base``, ``--tip``, xacro's), as keyword arguments."""
    given = {
        "base": args.base,
        "tip": args.tip,
        "xacro": args.xacro,
        "xacro_env": args.xacro_env,
        "trust_xacro": args.trust_xacro,
        "packages": dict(args.package) if args.package else None,
        "xacro_args": dict(args.xacro_arg) if args.xacro_arg else None,
    }
    return {k: v for k, v in given.items() if v}


def robot_from_args(args: argparse.Namespace) -> Robot:
    """The robot named by ``ROBOT`` (and, for a URDF, ``--base``/``--tip``/``--xacro``...).

    Sets ``args.length_shown``, the length unit its warnings speak (:func:`length_unit`).
    """
    robot = load(args.robot, **urdf_options(args))
    args.length_shown = length_unit(robot, args)
    return robot


def angle_unit(args: argparse.Namespace) -> str:
    """``"rad"`` or ``"deg"``, as the command line was asked."""
    return "rad" if getattr(args, "rad", False) else "deg"


def length_unit(robot: Robot, args: argparse.Namespace) -> str:
    """``"m"`` or ``"mm"``: ``--units``, else the robot file's length unit, else metres."""
    chosen = getattr(args, "units", None)
    if chosen is not None:
        return str(chosen)
    spec = robot.source_spec
    unit = None if spec is None else spec.units.get("length")
    return unit if unit in PER_METRE else "m"


def units(robot: Robot, args: argparse.Namespace) -> dict[str, str]:
    """The ``units`` of a JSON output: ``{"angle": "deg", "length": "mm"}``."""
    return {"angle": angle_unit(args), "length": length_unit(robot, args)}


def finite(values: Sequence[float], option: str) -> FloatArray:
    """The numbers of option ``option`` (e.g. ``"--pose"``), all finite, as an array.

    Raises:
        DimensionError: a value is NaN or infinite; the message names the option.
    """
    a = np.array(values, dtype=float)
    bad = [i for i, v in enumerate(a.ravel().tolist()) if not math.isfinite(v)]
    if bad:
        shown = ", ".join(f"{a.ravel()[i]:g} (value {i + 1})" for i in bad[:3])
        raise DimensionError(f"{option} needs finite numbers, got {shown}")
    return a


def lengths_in(values: ArrayLike, robot: Robot, args: argparse.Namespace) -> FloatArray:
    """Lengths typed on the command line (file or ``--units`` unit) to metres."""
    return np.asarray(values, dtype=float) / PER_METRE[length_unit(robot, args)]


def lengths_out(values: ArrayLike, robot: Robot, args: argparse.Namespace) -> FloatArray:
    """Lengths in metres to the command line's unit."""
    return np.asarray(values, dtype=float) * PER_METRE[length_unit(robot, args)]


def transform_in(T: ArrayLike, robot: Robot, args: argparse.Namespace) -> FloatArray:
    """``(..., 4, 4)`` transforms typed in the command line's length unit, to metres."""
    out = np.array(T, dtype=float)
    out[..., :3, 3] = lengths_in(out[..., :3, 3], robot, args)
    return out


def transform_out(T: ArrayLike, robot: Robot, args: argparse.Namespace) -> FloatArray:
    """``(..., 4, 4)`` transforms in metres, translation in the command line's unit."""
    out = np.array(T, dtype=float)
    out[..., :3, 3] = lengths_out(out[..., :3, 3], robot, args)
    return out


def q_in(robot: Robot, values: list[float], args: argparse.Namespace, name: str) -> FloatArray:
    """Joint values from the command line to SI (rad for revolute, m for prismatic).

    Args:
        robot: The robot the values are for.
        values: The numbers as typed: degrees (radians with ``--rad``) for
            revolute joints, the length unit for prismatic joints.
        args: The parsed arguments (``--rad``, ``--units``).
        name: The option's name, for messages (``"q"`` for ``--q``).

    Returns:
        ``(n,)`` joint values in rad and m.

    Raises:
        DimensionError: wrong count, or a value is NaN or infinite.
    """
    q = finite(values, f"--{name}")
    if q.shape != (robot.dof,):
        raise DimensionError(
            f"--{name} needs {robot.dof} values for {robot.name} ({robot.joint_types}), "
            f"got {q.size}"
        )
    angles = q if args.rad else np.deg2rad(q)
    return np.where(robot.is_prismatic, lengths_in(q, robot, args), angles)


def q_out(robot: Robot, q: FloatArray, args: argparse.Namespace) -> FloatArray:
    """Joint values ``(..., n)`` in SI to the command line's units."""
    angles = q if args.rad else np.rad2deg(q)
    return np.where(robot.is_prismatic, lengths_out(q, robot, args), angles)


def joint_units(robot: Robot, args: argparse.Namespace) -> list[str]:
    """The unit of each joint's value as :func:`q_out` gives it: ``["deg", "deg", "m"]``."""
    angle, length = angle_unit(args), length_unit(robot, args)
    return [length if p else angle for p in robot.is_prismatic]


def _jsonable(data: Any) -> Any:
    """``data`` with arrays as lists and every non-finite number as ``None``."""
    if isinstance(data, dict):
        return {str(k): _jsonable(v) for k, v in data.items()}
    if isinstance(data, list | tuple):
        return [_jsonable(v) for v in data]
    if isinstance(data, np.ndarray):
        return _jsonable(data.tolist())
    if isinstance(data, np.generic):
        return _jsonable(data.item())
    if isinstance(data, float) and not math.isfinite(data):
        return None
    return data


def dump(data: dict[str, Any]) -> None:
    """Print ``data`` as JSON: valid JSON always, ``null`` for NaN and infinities."""
    import json  # only for --json

    print(json.dumps(_jsonable(data), indent=2, allow_nan=False))


def clean(a: ArrayLike) -> Any:
    """An array as nested lists of floats for JSON, every digit kept; NaN/inf as ``None``."""
    return _jsonable(np.asarray(a, dtype=float).tolist())


def joint_in(robot: Robot, key: str, option: str) -> int:
    """The 0-based index of the joint ``key`` names on the command line: its name or ``qN``.

    Raises:
        ArgumentError: a bare number (the command line counts joints from 1: ``q7``),
            or a name no joint has; the message names ``option``.
    """
    text = key.strip()
    names = robot.joint_names
    numbered = (
        text.lower().startswith("q") and text[1:].isdigit() and 1 <= int(text[1:]) <= robot.dof
    )
    if text not in names and not numbered:
        own = [n for n in names if n != f"q{names.index(n) + 1}"]
        raise ArgumentError(
            f"{option}: name a joint as q1..q{robot.dof} (1-based, as the tables show)"
            + (f" or by its name ({', '.join(own)})" if own else "")
            + f", got {key!r}"
        )
    from kinematica.ik.fixed import joint_parameter

    return joint_parameter(robot.chain, text, robot.joint_names, arg=option).index


def joint_value_in(robot: Robot, joint: int, value: float, args: argparse.Namespace) -> float:
    """One joint's value as typed (degrees or --rad, the length unit) to rad or m."""
    if robot.is_prismatic[joint]:
        return float(lengths_in(value, robot, args))
    return float(value) if getattr(args, "rad", False) else math.radians(float(value))


def joint_value_out(robot: Robot, joint: int, value: float, args: argparse.Namespace) -> float:
    """One joint's value in rad or m to the command line's unit."""
    if robot.is_prismatic[joint]:
        return float(lengths_out(value, robot, args))
    return float(value) if getattr(args, "rad", False) else math.degrees(float(value))


def fixed_in(robot: Robot, text: str, args: argparse.Namespace) -> dict[int | str, float]:
    """``--fixed q7=30``: ``{6: 0.5236}`` (the value in degrees or --rad, or the length unit).

    Raises:
        ArgumentError: not ``JOINT=VALUE``, or a value that is not a finite number.
    """
    key, eq, number = text.partition("=")
    if not eq or not key.strip():
        raise ArgumentError(f"--fixed takes JOINT=VALUE, e.g. q7=30, got {text!r}")
    try:
        value = float(number)
    except ValueError:
        value = math.nan
    if not math.isfinite(value):
        raise ArgumentError(
            f"--fixed: the value of {key.strip()} must be a finite number, got {number!r}"
        )
    joint = joint_in(robot, key, "--fixed")
    return {joint: joint_value_in(robot, joint, value, args)}
