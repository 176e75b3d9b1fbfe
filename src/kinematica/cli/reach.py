"""Subcommand ``reach``: the orientation-aware reachability map of an arm, by exact IK."""

from __future__ import annotations

import argparse
import math
from pathlib import Path
from typing import Any

import numpy as np

from kinematica.cli.format import fmt
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

__all__ = ["reach", "register"]

#: Poses from which the command shows a progress bar (on a terminal only).
PROGRESS_FROM = 1_000_000


def _outputs(args: argparse.Namespace) -> None:
    """Check where the files go before the (long) run."""
    for option, path in (("-o", args.output), ("--plot", args.plot)):
        if path is not None and not Path(path).parent.is_dir():
            raise KinematicaError(f"{option} {path}: no such folder {str(Path(path).parent)!r}")
    if args.output is not None and Path(args.output).suffix.lower() not in (".vti", ".npz"):
        raise KinematicaError(
            f"-o {args.output}: a map is written as .vti (VTK, ParaView) or .npz (numpy)"
        )


def reach(args: argparse.Namespace) -> int:
    """``kinematica reach ROBOT``: the map's volumes; a file and a picture of it."""
    from kinematica.reach import reachability, save_map

    robot = robot_from_args(args)
    _outputs(args)
    resolution = float(lengths_in(args.resolution, robot, args))
    region = None if args.region is None else lengths_in(args.region, robot, args).reshape(2, 3)
    approach = None
    if args.approach is not None:
        x, y, z, angle = args.approach
        approach = ((x, y, z), angle if args.rad else math.radians(angle))
    orientations = None if args.positions else args.orientations
    bar: Any = None
    try:
        if args.scheduler is None and args.workers is None:
            from tqdm import tqdm

            bar = tqdm(total=None, unit="pose", desc="reach", disable=None, leave=False)
        m = reachability(
            robot,
            region,
            resolution,
            orientations,
            approach,
            manipulability=not args.no_manipulability,
            scheduler=args.scheduler,
            workers=args.workers,
            progress=None if bar is None else bar.update,
        )
    finally:
        if bar is not None:
            bar.close()
    written = []
    if args.output is not None:
        written.append(str(save_map(m, args.output)))
    if args.plot is not None:
        from kinematica.viz.reach import save_reachability_plot

        written.append(str(save_reachability_plot(m, args.plot)))
    unit = length_unit(robot, args)
    per = float(lengths_out(1.0, robot, args))
    dims = 2 if m.plane is not None else 3
    vol_unit = f"{unit}^{dims}"
    reachable = m.reachable_volume * per**dims
    dexterous = m.dexterous_volume * per**dims
    best = float(np.nanmax(m.manipulability)) if np.isfinite(m.manipulability).any() else None
    if args.json:
        dump(
            {
                "robot": robot.name,
                "units": {"length": unit, "volume": vol_unit},
                "resolution": m.resolution * per,
                "shape": list(m.shape),
                "origin": (m.origin * per).tolist(),
                "orientations": m.count if m.orientations.shape[0] else None,
                "approach": None
                if m.approach is None
                else {"direction": m.approach[0].tolist(), "half_angle_rad": m.approach[1]},
                "queries": int(np.count_nonzero(
                    np.linalg.norm(m.centres() - m.centre, axis=-1) <= m.radius
                )) * m.count,
                "reachable_voxels": int(np.count_nonzero(m.reachable)),
                "dexterous_voxels": int(np.count_nonzero(m.dexterous)),
                "reachable_volume": reachable,
                "dexterous_volume": dexterous,
                "best_manipulability": best,
                "complete": m.complete,
                "held": m.held,
                "files": written,
            }
        )  # fmt: skip
    else:
        what = (
            "positions only"
            if not m.orientations.shape[0]
            else f"{m.count} orientations" + ("" if m.approach is None else " in the approach cone")
        )
        print(
            f"{robot.name}: {m.shape[0]} x {m.shape[1]} x {m.shape[2]} voxels of "
            f"{fmt(m.resolution * per, 4)} {unit}, {what} each"
        )
        print(f"reachable: {np.count_nonzero(m.reachable)} voxels, {fmt(reachable, 4)} {vol_unit}")
        print(f"dexterous: {np.count_nonzero(m.dexterous)} voxels, {fmt(dexterous, 4)} {vol_unit}")
        if best is not None:
            print(f"best manipulability: {fmt(best, 4)}")
        if m.held is not None:
            print(f"note: the IK held the {m.held} at its default: a lower bound of the reach")
        if not m.complete:
            print("note: some poses were solved numerically: a lower bound of the reach")
        for path in written:
            print(f"written: {path}")
    return 0 if m.reachable.any() else 1


def register(sub: Any) -> None:
    """Add ``reach`` to the subparsers ``sub``."""
    p = sub.add_parser(
        "reach",
        help="reachability map: which tool orientations the arm reaches where (exact IK)",
        description="Solve a fixed set of tool orientations, spread evenly over all "
        "rotations (or a cone about --approach), at every voxel centre of a grid over the "
        "workspace by the closed-form IK within the joint limits. Prints the reachable and "
        "dexterous volumes; writes the map (.vti for ParaView, .npz) and a picture. Exit "
        "code 1 when no voxel is reachable.",
    )
    add_robot(p)
    p.add_argument(
        "--resolution", type=float, default=0.05, help="voxel side (robot length unit; 0.05)"
    )
    p.add_argument(
        "--orientations", type=int, default=64, help="orientations per voxel (default 64)"
    )
    p.add_argument(
        "--positions", action="store_true", help="the tool position alone, any orientation"
    )
    p.add_argument(
        "--approach",
        nargs=4,
        type=float,
        metavar=("X", "Y", "Z", "ANGLE"),
        help="orientations whose tool z axis lies within ANGLE of the direction X Y Z",
    )
    p.add_argument(
        "--region",
        nargs=6,
        type=float,
        metavar=("XMIN", "YMIN", "ZMIN", "XMAX", "YMAX", "ZMAX"),
        help="the box mapped (default: the cube about the arm's reach)",
    )
    p.add_argument(
        "--no-manipulability", action="store_true", help="skip the manipulability (faster)"
    )
    p.add_argument(
        "--scheduler", metavar="local|ADDR", help="run on Dask: 'local' or tcp://host:port"
    )
    p.add_argument("--workers", type=int, help="worker processes of a local Dask cluster")
    p.add_argument("-o", "--output", metavar="MAP.vti", help="write the map: .vti or .npz")
    p.add_argument("--plot", metavar="MAP.png", help="draw slices and a 3-D view")
    add_common(p)
    p.set_defaults(run=reach)
