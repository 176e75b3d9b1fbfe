"""Subcommands ``jacobian`` and ``workspace``: the arm's velocities and where it reaches."""

from __future__ import annotations

import argparse
from typing import Any

from kinematica.cli.format import fmt, json_numbers, matrix, table
from kinematica.cli.options import (
    add_common,
    add_robot,
    angle_unit,
    dump,
    finite,
    q_in,
    robot_from_args,
)

__all__ = ["jacobian", "register", "workspace_cmd"]

#: Sample counts from which the workspace command shows a progress bar.
PROGRESS_FROM = 200_000


# ------------------------------------------------------------------ jacobian
def jacobian(args: argparse.Namespace) -> int:
    """``kinematica jacobian ROBOT --q ...``: J, rank, manipulability, singularities."""
    from kinematica.motion import (
        analytic_jacobian,
        condition_number,
        jacobian_rank,
        manipulability,
        singularities,
    )

    robot = robot_from_args(args)
    q = q_in(robot, args.q, args, "q")
    J = robot.jacobian(q, frame=args.frame)
    rank, generic = jacobian_rank(robot, q)
    w = float(manipulability(robot, q))
    inverse_condition = float(manipulability(robot, q, method="inverse_condition"))
    min_singular = float(manipulability(robot, q, method="min_singular"))
    cond = float(condition_number(robot, q))
    sing = singularities(robot, q, detail=True)
    Ja = analytic_jacobian(robot, q, args.euler) if args.analytic else None
    if args.json:
        out: dict[str, Any] = {
            "robot": robot.name,
            "q": list(args.q),
            "units": {"angle": angle_unit(args), "length": "m", "jacobian": "SI (per rad, per m)"},
            "frame": args.frame,
            "jacobian": json_numbers(J),
            "rank": rank,
            "generic_rank": generic,
            "manipulability": w,
            "inverse_condition": inverse_condition,
            "min_singular_value": min_singular,
            "condition_number": json_numbers(cond),
            "singularities": [
                {"name": s.name, "direction": json_numbers(s.direction), "measure": s.measure}
                for s in sing
            ],
        }
        if Ja is not None:
            out["analytic"] = {"euler_sequence": args.euler, "jacobian": json_numbers(Ja)}
        dump(out)
        return 0
    unit = "rad" if args.rad else "deg"
    print(f"{robot.name}, q = [{', '.join(fmt(v, 6) for v in args.q)}] ({unit})")
    print(
        f"\ngeometric Jacobian, {args.frame} frame (rows vx vy vz in m, wx wy wz in rad; "
        "per rad of a revolute joint, per m of a prismatic one):"
    )
    print(matrix(J))
    if Ja is not None:
        rates = "rotation vector" if args.euler == "exp" else f"Euler {args.euler} angles"
        print(f"\nanalytic Jacobian (x y z, {rates}):")
        print(matrix(Ja))
    print(f"\nrank {rank} (regular: {generic})")
    print(
        f"manipulability {fmt(w, 6)} (Yoshikawa), inverse condition {fmt(inverse_condition, 6)}, "
        f"smallest singular value {fmt(min_singular, 6)}, condition number {cond:.4g}"
    )
    if not sing:
        print("singularities: none")
    for s in sing:
        v, om = s.direction[:3], s.direction[3:]
        print(
            f"singularity: {s.name}, lost direction v = [{', '.join(fmt(x, 4) for x in v)}], "
            f"w = [{', '.join(fmt(x, 4) for x in om)}] (base frame)"
        )
    return 0


# ----------------------------------------------------------------- workspace
def workspace_cmd(args: argparse.Namespace) -> int:
    """``kinematica workspace ROBOT``: bounds, volume, a slice, a map."""
    from kinematica.motion import workspace

    robot = robot_from_args(args)
    if args.at is not None:
        finite([args.at], "--at")  # before sampling: the slice comes last
    if args.output:  # a file no map can be written as: said before sampling
        from kinematica.motion.plot import check_map_path

        check_map_path(args.output)
    bar = None
    if args.samples >= PROGRESS_FROM:
        from tqdm import tqdm

        # disable=None: the bar shows on a terminal only, never in a pipe or a log.
        bar = tqdm(total=args.samples, unit="q", desc="sampling", disable=None, leave=False)
    try:
        ws = workspace(
            robot,
            samples=args.samples,
            seed=args.seed,
            voxel=args.voxel,
            progress=None if bar is None else bar.update,
        )
    finally:
        if bar is not None:
            bar.close()
    plane = args.plane or ws.plane or "xz"
    sl = ws.slice(plane, at=args.at) if (args.plane or args.output or ws.planar) else None
    if args.output and sl is not None:
        from kinematica.motion.plot import plot_workspace_slice

        plot_workspace_slice(sl, args.output, title=f"{robot.name}: {args.samples} samples")
    if args.json:
        dump(
            {
                "robot": robot.name,
                "samples": args.samples,
                "units": {"length": "m", "volume": "m^3", "area": "m^2"},
                "voxel": ws.voxel,
                "bounds": json_numbers(ws.bounds),
                "reach": ws.reach,
                "volume": ws.volume,
                "area": ws.area,
                "planar": ws.planar,
                "plane": ws.plane,
                "slice": None
                if sl is None
                else {"plane": sl.plane, "at": sl.at, "area": sl.area, "extent": list(sl.extent)},
                "map": None if not args.output else str(args.output),
            }
        )
        return 0
    print(f"{robot.name}: {args.samples} samples, voxel {fmt(ws.voxel, 4)} m")
    rows = [(ax, fmt(lo, 4), fmt(hi, 4)) for ax, lo, hi in zip("xyz", *ws.bounds, strict=True)]
    print(table(("axis", "min (m)", "max (m)"), rows))
    print(f"reach {fmt(ws.reach, 4)} m")
    if ws.planar:
        print(f"planar workspace in the {ws.plane} plane: area {fmt(ws.area or 0.0, 4)} m²")
    else:
        print(f"volume {fmt(ws.volume, 4)} m³")
    if sl is not None:
        other = ({"x", "y", "z"} - set(sl.plane)).pop()
        print(f"{sl.plane} slice at {other} = {fmt(sl.at, 4)} m: area {fmt(sl.area, 4)} m²")
    if args.output:
        print(f"map written to {args.output}")
    return 0


def register(sub: Any) -> None:
    """Add ``jacobian`` and ``workspace`` to the subparsers ``sub``."""
    qhelp = "degrees for revolute joints (or radians with --rad), metres for prismatic joints"
    p = sub.add_parser("jacobian", help="Jacobian, rank, manipulability, named singularities")
    add_robot(p)
    p.add_argument("--q", nargs="+", type=float, required=True, metavar="Q", help=qhelp)
    p.add_argument(
        "--frame", choices=("base", "tool", "spatial"), default="base", help="frame of J"
    )
    p.add_argument(
        "--analytic",
        action="store_true",
        help="also the analytic Jacobian for --euler (--euler exp: rotation-vector rates)",
    )
    add_common(p)
    p.set_defaults(run=jacobian)

    p = sub.add_parser("workspace", help="sampled workspace: bounds, volume, slice, map")
    add_robot(p)
    p.add_argument("--samples", type=int, default=100_000, help="configurations (default 1e5)")
    p.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    p.add_argument("--voxel", type=float, help="voxel side in m (default: ~6 samples each)")
    p.add_argument("--plane", choices=("xy", "xz", "yz"), help="print (and draw) this slice")
    p.add_argument("--at", type=float, help="slice position along the third axis (m)")
    p.add_argument(
        "-o", "--output", metavar="MAP.png", help="draw the slice map (needs matplotlib)"
    )
    add_common(p)
    p.set_defaults(run=workspace_cmd)
