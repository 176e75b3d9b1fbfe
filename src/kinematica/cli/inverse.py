"""``kinematica ik``: every IK solution of a typed target, and the target options it shares."""

from __future__ import annotations

import argparse
import math
import sys
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from kinematica.cli.format import num, plain, table
from kinematica.cli.options import (
    PER_METRE,
    add_pose,
    clean,
    dump,
    finite,
    fixed_in,
    joint_value_out,
    length_unit,
    lengths_in,
    q_in,
    q_out,
    robot_from_args,
    transform_in,
    units,
)
from kinematica.errors import ArgumentError
from kinematica.robot import Robot
from kinematica.spatial import from_pose

if TYPE_CHECKING:  # the IK layer loads when `ik` runs: `fk` never imports it
    from kinematica.ik import IKResult

__all__ = ["ik", "parse_seed", "pose_target_args", "target_in"]

FloatArray = NDArray[np.float64]


def target_in(robot: Robot, args: argparse.Namespace) -> FloatArray:
    """The target in metres; library messages about it name the option it came from."""
    if getattr(args, "position", None) is not None:
        args.aliases = {"target position": "--position", "target": "--position"}
        return lengths_in(finite(args.position, "--position"), robot, args)
    if args.matrix is not None:
        args.aliases = {"target": "--matrix"}
        return transform_in(finite(args.matrix, "--matrix").reshape(4, 4), robot, args)
    args.aliases = {"target": "--pose"}
    pose = finite(args.pose, "--pose")
    pose[:3] = lengths_in(pose[:3], robot, args)
    return from_pose(pose, euler=args.euler, degrees=not args.rad)


def _precision(robot: Robot, args: argparse.Namespace) -> tuple[float, float] | None:
    """The precision the typed pose carries (position m, rotation entries), if printed.

    ``--matrix`` numbers as typed; ``--pose``: its lengths, and its angles, an error
    of δ (rad) in each of three moving a rotation's entries by at most 3δ.
    """
    typed = args.matrix if args.matrix is not None else args.pose
    if typed is None:
        return None
    from kinematica.ik.printed import half_unit, printed_digits

    digits = printed_digits(np.asarray(typed, dtype=float))
    if digits is None:
        return None
    if args.matrix is not None:
        m = np.asarray(args.matrix, dtype=float).reshape(4, 4)[:3]
        position, rotation = m[:, 3], half_unit(m[:, :3], digits)
    else:
        pose = np.asarray(args.pose, dtype=float)
        angle = half_unit(pose[3:], digits)
        position, rotation = pose[:3], 3.0 * (angle if args.rad else math.radians(angle))
    metres = float(lengths_in(half_unit(position, digits), robot, args))
    return metres, rotation


def _headline(status: str, message: str) -> str:
    """``status — message``, or the message alone when it already opens with the status."""
    if message.startswith((f"{status.replace('_', ' ')}:", f"{status.replace('_', ' ')} with ")):
        return plain(message)  # it names its status already: "singular: infinitely many ..."
    return f"{status} — {plain(message)}"


def ik(args: argparse.Namespace) -> int:
    """``kinematica ik ROBOT --pose ...``: every solution, one row each."""
    from kinematica.ik import IKOptions, IKResult

    robot = robot_from_args(args)
    target = target_in(robot, args)
    if args.steps:
        from kinematica.cli.steps import print_steps

        return print_steps(robot, target, args)
    q0 = None if args.q0 is None else q_in(robot, args.q0, args, "q0")
    tol = _tolerance(robot, args)
    arm_angle = args.arm_angle
    if arm_angle is not None and not args.rad:
        arm_angle = math.radians(arm_angle)
    options = IKOptions(
        method=args.method,
        tol=tol,
        respect_limits=not args.ignore_limits,
        q0=q0,
        seed=args.seed,
        precision=_precision(robot, args),
        fixed=None if args.fixed is None else fixed_in(robot, args.fixed, args),
        arm_angle=arm_angle,
    )
    res = robot.ik(target, options=options)
    assert isinstance(res, IKResult)
    solved = res.success
    for note in res.notes:  # e.g. a rotation projected onto SO(3): said on stderr too,
        if args.json or note not in res.message:  # unless the headline below says it
            print(f"kinematica: note: {plain(note)}", file=sys.stderr)
    if args.json:
        dump(
            {
                "robot": robot.name,
                "status": res.status,
                "method": res.method,
                "message": res.message,
                "units": units(robot, args),
                "solutions": clean(q_out(robot, res.solutions, args)),
                "branches": list(res.branches),
                "letters": list(res.letters),
                "residuals": {
                    "position_m": clean(res.residuals[:, 0]),
                    "rotation_rad": clean(res.residuals[:, 1]),
                },
                "out_of_limits": clean(q_out(robot, res.out_of_limits, args)),
                "out_of_limits_branches": list(res.out_of_limits_branches),
                "free_joints": list(res.free_names),
                "gap_m": res.gap,
                "notes": list(res.notes),
                "parameter": _parameter(robot, res, args),
                "tolerance": (
                    None if tol is None else {"position_m": tol[0], "rotation_rad": tol[1]}
                ),
            }
        )
        return 0 if solved else 1
    print(f"{plain(robot.name)}: {_headline(res.status, res.message)}")
    unit, metres = ("rad" if args.rad else "deg"), length_unit(robot, args)
    print(f"units: {unit} for angles, {metres} for lengths")
    held = _parameter(robot, res, args)
    if held is not None:
        print(f"parameter: {held['name']} = {num(held['value'], args.precision)} {held['unit']}")
    header = ("#", *(f"q{i}" for i in range(1, robot.dof + 1)), "branch", "error (m, rad)")

    def rows(
        sol: FloatArray, branches: tuple[str, ...], resid: FloatArray | None
    ) -> list[tuple[str, ...]]:
        out = []
        for k, (q, b) in enumerate(zip(q_out(robot, sol, args), branches, strict=True), start=1):
            err = "" if resid is None else f"{resid[k - 1, 0]:.1e}, {resid[k - 1, 1]:.1e}"
            out.append((str(k), *(num(v, args.precision) for v in q), plain(b), err))
        return out

    if solved:
        print(table(header, rows(res.solutions, res.branches, res.residuals)))
    if res.out_of_limits.shape[0]:
        print("\noutside the joint limits:")
        print(
            table(
                header[:-1],
                [r[:-1] for r in rows(res.out_of_limits, res.out_of_limits_branches, None)],
            )
        )
    return 0 if solved else 1


def _parameter(robot: Robot, res: IKResult, args: argparse.Namespace) -> dict[str, Any] | None:
    """The parameter held for this answer (a joint, an arm angle), in the CLI's units, or None."""
    if res.parameter is None:
        return None
    name, value = res.parameter
    if name not in robot.joint_names:  # an SRS arm's arm angle: an angle, no joint
        angle = float(value) if args.rad else math.degrees(float(value))
        return {"name": name, "joint": None, "value": angle, "unit": "rad" if args.rad else "deg"}
    joint = robot.joint_names.index(name)
    unit = length_unit(robot, args) if robot.is_prismatic[joint] else ("rad" if args.rad else "deg")
    return {
        "name": name,
        "joint": f"q{joint + 1}",
        "value": joint_value_out(robot, joint, value, args),
        "unit": unit,
    }


def _tolerance(robot: Robot, args: argparse.Namespace) -> tuple[float, float] | None:
    """``--tol P [R]`` in SI: P in the length unit, R in the angle unit (R = P when left out)."""
    if args.tol is None:
        return None
    if len(args.tol) > 2:
        raise ArgumentError(f"--tol takes 1 or 2 numbers (position, rotation), got {len(args.tol)}")
    position = float(args.tol[0]) / PER_METRE[length_unit(robot, args)]
    if len(args.tol) == 1:
        return position, position
    rotation = float(args.tol[1]) if args.rad else math.radians(float(args.tol[1]))
    return position, rotation


def parse_seed(text: str) -> int:
    """``--seed``: a whole number >= 0 (argparse's type)."""
    try:
        value = int(text)
    except ValueError:
        value = -1
    if value < 0:
        raise argparse.ArgumentTypeError(f"expected a whole number >= 0, got {text!r}")
    return value


def pose_target_args(p: argparse.ArgumentParser, position: bool = False) -> None:
    """The target options, one required: ``--pose``, ``--matrix`` (``--position`` if asked)."""
    target = p.add_mutually_exclusive_group(required=True)
    add_pose(target, "position (length unit, see --units) and three Euler angles (see --euler)")
    target.add_argument(
        "--matrix",
        nargs=16,
        type=float,
        metavar="M",
        help="the 4x4 pose, 16 numbers row by row (translation in the length unit)",
    )
    if position:
        target.add_argument(
            "--position",
            nargs=3,
            type=float,
            metavar=("X", "Y", "Z"),
            help="position only (length unit): orientation left free",
        )
