"""What every subcommand shares: common options, unit conversion, JSON output.

Each topic of the command line lives in its own module (``kinematics``, ...)
with a ``register(sub)`` function adding its subcommands; :mod:`main` lists
those modules. The helpers here are the only code they share.
"""

from __future__ import annotations

import argparse
import json
from typing import Any

import numpy as np
from numpy.typing import NDArray

from kinematica.errors import DimensionError
from kinematica.robot import Robot, load

__all__ = [
    "add_common",
    "add_robot",
    "angle_unit",
    "clean",
    "dump",
    "q_in",
    "q_out",
    "robot_from_args",
]

FloatArray = NDArray[np.float64]


def add_common(p: argparse.ArgumentParser) -> None:
    """The options every command takes: ``--json``, ``--euler``, ``--rad``."""
    p.add_argument("--json", action="store_true", help="machine-readable output (stable keys)")
    p.add_argument(
        "--euler",
        default="ZYZ",
        metavar="SEQ",
        help="Euler sequence, scipy naming: upper case intrinsic (ZYZ, XYZ...), "
        "lower case extrinsic (zyz, xyz...); default ZYZ",
    )
    p.add_argument("--rad", action="store_true", help="angles in radians (default degrees)")


def add_robot(p: argparse.ArgumentParser) -> None:
    """The positional ``ROBOT`` (built-in name, robot file or URDF) and ``--base``/``--tip``."""
    p.add_argument("robot", metavar="ROBOT", help="built-in name, robot file or URDF")
    p.add_argument("--base", metavar="LINK", help="URDF only: base link of the chain")
    p.add_argument("--tip", metavar="LINK", help="URDF only: tip link of the chain")


def robot_from_args(args: argparse.Namespace) -> Robot:
    """The robot named by ``ROBOT`` (and, for a URDF, ``--base``/``--tip``)."""
    return load(args.robot, base=args.base, tip=args.tip)


def angle_unit(args: argparse.Namespace) -> str:
    """``"rad"`` or ``"deg"``, as the command line was asked."""
    return "rad" if getattr(args, "rad", False) else "deg"


def q_in(robot: Robot, values: list[float], args: argparse.Namespace, name: str) -> FloatArray:
    """Joint values from the command line (deg or rad; metres for prismatic) to SI.

    Args:
        robot: The robot the values are for.
        values: The numbers as typed.
        args: The parsed arguments (``--rad``).
        name: The option's name, for messages (``"q"`` for ``--q``).

    Returns:
        ``(n,)`` joint values in rad and m.
    """
    q = np.array(values, dtype=float)
    if q.shape != (robot.dof,):
        raise DimensionError(
            f"--{name} needs {robot.dof} values for {robot.name} ({robot.joint_types}), "
            f"got {q.size}"
        )
    if not np.all(np.isfinite(q)):
        raise DimensionError(f"--{name} holds NaN or inf: {values}")
    if not args.rad:
        q = np.where(robot.is_prismatic, q, np.deg2rad(q))
    return q


def q_out(robot: Robot, q: FloatArray, args: argparse.Namespace) -> FloatArray:
    """Joint values ``(..., n)`` in SI to the command line's units."""
    return q if args.rad else np.where(robot.is_prismatic, q, np.rad2deg(q))


def dump(data: dict[str, Any]) -> None:
    """Print ``data`` as JSON."""
    print(json.dumps(data, indent=2, allow_nan=False))


def clean(a: FloatArray) -> Any:
    """Array to nested lists, tiny values as 0 (JSON output)."""
    return np.where(np.abs(a) < 5e-16, 0.0, a).tolist()
