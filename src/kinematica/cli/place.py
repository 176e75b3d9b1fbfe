"""Subcommand ``place``: where to put the robot's base to reach every pose of a task."""

from __future__ import annotations

import argparse
import math
from pathlib import Path
from typing import Any

import numpy as np

from kinematica.cli.format import fmt, table
from kinematica.cli.options import (
    add_common,
    add_robot,
    dump,
    length_unit,
    lengths_in,
    lengths_out,
    robot_from_args,
)
from kinematica.errors import KinematicaError

__all__ = ["place", "register"]


def place(args: argparse.Namespace) -> int:
    """``kinematica place ROBOT --task FILE``: the best bases, and a picture of them all."""
    from kinematica.design import load_task
    from kinematica.reach import base_placement

    robot = robot_from_args(args)
    if args.plot is not None and not Path(args.plot).parent.is_dir():
        raise KinematicaError(f"--plot {args.plot}: no such folder {str(Path(args.plot).parent)!r}")
    if args.top < 1:
        raise KinematicaError(f"--top must be a positive whole number, got {args.top}")
    task = load_task(args.task, euler=args.euler, degrees=not args.rad)
    if task.kind != "pose":
        raise KinematicaError(
            f"--task {args.task}: base placement needs poses (x y z and three Euler angles, "
            "or 16 matrix numbers a row), found positions"
        )
    region = None if args.region is None else lengths_in(args.region, robot, args).reshape(2, 3)
    if args.yaw is not None:
        yaw: int | np.ndarray = np.asarray(args.yaw, dtype=float)
        if not args.rad:
            yaw = np.radians(yaw)
    else:
        yaw = args.yaws
    found = base_placement(
        robot,
        task.targets,
        region,
        resolution=float(lengths_in(args.resolution, robot, args)),
        yaw=yaw,
    )
    if args.plot is not None:
        from kinematica.viz.reach import save_placement_plot

        save_placement_plot(found, args.plot, task.targets, title=robot.name)
    unit = length_unit(robot, args)
    angle = "rad" if args.rad else "deg"
    order = found.order[: args.top]
    rows = []
    for i in order:
        x, y, z = lengths_out(found.positions[i], robot, args)
        yaw_i = float(found.yaws[i]) if args.rad else math.degrees(float(found.yaws[i]))
        rows.append((x, y, z, yaw_i, float(found.worst_manipulability[i])))
    if args.json:
        dump(
            {
                "robot": robot.name,
                "task": {"file": str(args.task), "poses": len(task)},
                "units": {"length": unit, "angle": angle},
                "candidates": int(found.positions.shape[0]),
                "feasible": found.count,
                "best": [
                    {"position": [x, y, z], "yaw": w, "worst_manipulability": m}
                    for x, y, z, w, m in rows
                ],
                "plot": args.plot,
            }
        )
        return 0 if found.count else 1
    print(
        f"{robot.name}: {found.count} of {found.positions.shape[0]} candidate bases reach "
        f"all {len(task)} task poses"
    )
    if rows:
        print(
            table(
                (f"x ({unit})", f"y ({unit})", f"z ({unit})", f"yaw ({angle})", "worst manip."),
                [tuple(fmt(v, 4) for v in r) for r in rows],
            )
        )
    else:
        print("no base in the region reaches every pose: widen --region or add --yaws")
    if args.plot is not None:
        print(f"written: {args.plot}")
    return 0 if found.count else 1


def register(sub: Any) -> None:
    """Add ``place`` to the subparsers ``sub``."""
    p = sub.add_parser(
        "place",
        help="base placement: where the base must go to reach every pose of a task",
        description="Try base positions on a grid over --region (default: the floor z = 0 "
        "under the task, widened by the arm's reach) at several yaws; keep those from which "
        "the closed-form IK reaches every task pose within the joint limits, best (largest "
        "worst manipulability over the task) first. Exit code 1 when none does.",
    )
    add_robot(p)
    p.add_argument(
        "--task",
        required=True,
        metavar="FILE",
        help="task poses in the world frame: CSV/.npy rows of x y z + 3 Euler angles "
        "(see --euler, --rad) or 16 matrix numbers; or JSON",
    )
    p.add_argument(
        "--region",
        nargs=6,
        type=float,
        metavar=("XMIN", "YMIN", "ZMIN", "XMAX", "YMAX", "ZMAX"),
        help="box of base positions (equal bounds fix an axis)",
    )
    p.add_argument(
        "--resolution", type=float, default=0.05, help="spacing of base positions (0.05)"
    )
    p.add_argument("--yaws", type=int, default=8, help="yaws spread over a turn (default 8)")
    p.add_argument("--yaw", type=float, nargs="+", help="these yaws instead (deg, or --rad)")
    p.add_argument("--top", type=int, default=5, help="how many of the best to print (5)")
    p.add_argument("--plot", metavar="PLACE.png", help="draw the feasible bases from above")
    add_common(p)
    p.set_defaults(run=place)
