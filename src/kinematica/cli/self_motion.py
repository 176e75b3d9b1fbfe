"""Subcommand ``self-motion``: a redundant arm's solution families over its parameter."""

from __future__ import annotations

import argparse
import math
from typing import Any

import numpy as np

from kinematica.cli.format import num, plain, table
from kinematica.cli.kinematics import pose_target_args, target_in
from kinematica.cli.options import (
    add_common,
    add_robot,
    clean,
    dump,
    joint_in,
    joint_value_out,
    length_unit,
    q_out,
    robot_from_args,
    units,
)
from kinematica.errors import ArgumentError

__all__ = ["register", "self_motion"]


def self_motion(args: argparse.Namespace) -> int:
    """``kinematica self-motion ROBOT --pose ... --parameter q7``: families and intervals."""
    robot = robot_from_args(args)
    if args.plot is not None:  # a path no picture can be written to: said before the sweep
        from kinematica.viz.plot import check_image_path

        check_image_path(args.plot)
    target = target_in(robot, args)
    from kinematica.ik.arm_angle import ARM_ANGLE_NAMES

    angle = args.parameter.strip().lower() in ARM_ANGLE_NAMES
    joint = None if angle else joint_in(robot, args.parameter, "--parameter")
    args.aliases = {
        **getattr(args, "aliases", {}),
        "samples": "--samples",
        "max_jump": "--max-jump",
    }
    motion = robot.self_motion(
        target,
        "arm_angle" if joint is None else joint,
        samples=args.samples,
        max_jump=_jump(args),
        method=args.method,
    )
    if args.plot is not None:
        from kinematica.viz.self_motion import save_self_motion

        save_self_motion(
            motion, args.plot, degrees=not args.rad, prismatic=tuple(robot.is_prismatic.tolist())
        )
    slide = joint is not None and bool(robot.is_prismatic[joint])
    unit = length_unit(robot, args) if slide else ("rad" if args.rad else "deg")

    def out(v: float) -> float:
        if joint is None:  # the arm angle: an angle like any revolute joint's
            return float(v) if args.rad else math.degrees(float(v))
        return joint_value_out(robot, joint, v, args)

    feasible = any(fam.feasible for fam in motion.families)
    if args.json:
        dump(
            {
                "robot": robot.name,
                "parameter": {
                    "name": motion.parameter,
                    "joint": None if joint is None else f"q{joint + 1}",
                    "unit": unit,
                },
                "method": motion.method,
                "units": units(robot, args),
                "values": [out(v) for v in motion.values],
                "max_jump": motion.max_jump,
                "families": [
                    {
                        "branch": fam.branch,
                        "q": clean(q_out(robot, fam.q, args)),
                        "within_limits": fam.within.tolist(),
                        "feasible": [[out(a), out(b)] for a, b in fam.feasible],
                    }
                    for fam in motion.families
                ],
                "plot": None if args.plot is None else str(args.plot),
            }
        )
        return 0 if feasible else 1
    step = out(motion.values[1]) - out(motion.values[0])
    print(
        f"{plain(robot.name)}: self-motion over {motion.parameter} "
        f"({len(motion.values)} samples, {num(step, 4)} {unit} apart; {motion.method}): "
        f"{len(motion.families)} families"
    )
    rows: list[tuple[str, ...]] = []
    for i, fam in enumerate(motion.families, start=1):
        spans = ", ".join(f"[{num(out(a), 4)}, {num(out(b), 4)}]" for a, b in fam.feasible)
        rows.append((str(i), plain(fam.branch), str(int(fam.present.sum())), spans or "none"))
    if rows:
        header = ("#", "branch", "samples", f"within the limits ({motion.parameter}, {unit})")
        print(table(header, rows))
    if not feasible:
        print(
            "no family is within the joint limits at any sample"
            if rows
            else "no solution at any sample: the pose is out of reach at every value sampled"
        )
    if args.plot is not None:
        print(f"wrote {args.plot}")
    return 0 if feasible else 1


def _jump(args: argparse.Namespace) -> float | None:
    """``--max-jump`` in rad (typed in degrees unless --rad), or None (the default)."""
    if args.max_jump is None:
        return None
    value = float(args.max_jump)
    if not np.isfinite(value) or value <= 0.0:
        raise ArgumentError(f"--max-jump must be a positive number, got {args.max_jump}")
    return value if args.rad else float(np.radians(value))


def register(sub: Any) -> None:
    """Add ``self-motion`` to the subparsers ``sub``."""
    p = sub.add_parser(
        "self-motion",
        help="a redundant arm's solution families at one pose, over a joint held at values "
        "(or an SRS arm's arm angle)",
    )
    add_robot(p)
    pose_target_args(p)
    p.add_argument(
        "--parameter",
        required=True,
        metavar="JOINT",
        help="the joint swept across its limits: q1..qN (1-based, as the tables show) or "
        "the joint's name (URDF); or arm-angle: an SRS arm's (iiwa type) arm angle, "
        "swept over a whole turn",
    )
    p.add_argument("--samples", type=int, default=73, help="values across its limits (default 73)")
    p.add_argument(
        "--max-jump",
        type=float,
        metavar="ANGLE",
        help="largest joint change between adjacent samples of one family, degrees "
        "(--rad: radians); default 0.5 rad",
    )
    p.add_argument(
        "--method",
        choices=("auto", "analytic", "numeric"),
        default="auto",
        help="how each sample is solved (auto: the locked arm's closed form when there is one)",
    )
    p.add_argument(
        "--plot",
        metavar="FILE",
        help="also draw each joint against the parameter, one line per family, limits "
        "shaded (PNG, SVG, PDF; needs the viz extra)",
    )
    add_common(p)
    p.set_defaults(run=self_motion)
