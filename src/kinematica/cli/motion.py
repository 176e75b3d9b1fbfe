"""Subcommands ``jacobian``, ``workspace`` and ``trajectory``: the arm in motion."""

from __future__ import annotations

import argparse
import math
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from kinematica.cli.format import fmt, matrix, table
from kinematica.cli.options import (
    add_common,
    add_robot,
    angle_unit,
    dump,
    finite,
    joint_units,
    lengths_in,
    q_in,
    q_out,
    robot_from_args,
)
from kinematica.errors import KinematicaError
from kinematica.robot import Robot

if TYPE_CHECKING:  # kinematica.motion loads when one of these commands runs
    from kinematica.motion import CartesianPath
    from kinematica.motion.trajectory import Profile

__all__ = ["jacobian", "register", "trajectory", "workspace_cmd"]

FloatArray = NDArray[np.float64]

#: Sample counts from which the workspace command shows a progress bar.
PROGRESS_FROM = 200_000
#: Rows of a trajectory printed as text (every k-th sample, and the last).
PRINTED_ROWS = 12
#: Event kinds after which a Cartesian path cannot be executed as computed.
BLOCKING = {"unreachable", "joint_limit", "branch_change"}


def _safe(a: Any) -> Any:
    """Nested lists for JSON: NaN/inf as null, tiny values as 0."""
    if isinstance(a, np.ndarray):
        return _safe(a.tolist())
    if isinstance(a, list | tuple):
        return [_safe(v) for v in a]
    if isinstance(a, float):
        if not math.isfinite(a):
            return None
        return 0.0 if abs(a) < 5e-16 else a
    return a


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
            "jacobian": _safe(J),
            "rank": rank,
            "generic_rank": generic,
            "manipulability": w,
            "inverse_condition": inverse_condition,
            "min_singular_value": min_singular,
            "condition_number": _safe(cond),
            "singularities": [
                {"name": s.name, "direction": _safe(s.direction), "measure": s.measure}
                for s in sing
            ],
        }
        if Ja is not None:
            out["analytic"] = {"euler_sequence": args.euler, "jacobian": _safe(Ja)}
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
                "bounds": _safe(ws.bounds),
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


# ---------------------------------------------------------------- trajectory
def _limit(robot: Robot, values: list[float] | None, args: argparse.Namespace, name: str) -> Any:
    """A speed/acceleration limit from the command line (one or n values) in SI."""
    if values is None:
        return None
    if len(values) == 1:
        values = values * robot.dof
    return np.abs(q_in(robot, values, args, name))


def _print_events(path: CartesianPath) -> None:
    for e in path.events:
        print(f"event: {e.kind}: {e.message}")


#: Library argument names and the trajectory command's options for them.
_TRAJECTORY_OPTIONS = {
    "tacc": "--tacc",
    "times": "--times",
    "vmax": "--vmax",
    "amax": "--amax",
    "duration": "--duration",
    "blend": "--blend",
    "ends": "--ends",
    "sync": "--sync",
    "dt": "--dt",
}


def _waypoints(robot: Robot, args: argparse.Namespace) -> tuple[FloatArray, FloatArray | None]:
    """``(W (k, n) in SI, times (k,) or None)`` from --from/--via/--to or --waypoints."""
    from kinematica.motion import read_csv

    if args.waypoints:
        if args.q_from or args.q_to or args.via:
            raise KinematicaError("--waypoints holds every waypoint: drop --from, --to and --via")
        t, W = read_csv(args.waypoints)
        if W.shape[1] != robot.dof or W.shape[0] < 2:
            raise KinematicaError(
                f"--waypoints: {args.waypoints} must hold >= 2 rows of {robot.dof} joints "
                f"for {robot.name}, got {W.shape[0]} rows of {W.shape[1]}"
            )
        if args.times is not None:
            raise KinematicaError("--waypoints carries its times (column t): drop --times")
        return W, t - t[0]
    if not args.q_from or not args.q_to:
        raise KinematicaError("give --from and --to (and any --via), or --waypoints FILE.csv")
    vias = [q_in(robot, v, args, "via") for v in args.via or []]
    W = np.stack(
        [q_in(robot, args.q_from, args, "from"), *vias, q_in(robot, args.q_to, args, "to")]
    )
    times = None if args.times is None else np.asarray(args.times, dtype=float)
    return W, times


def trajectory(args: argparse.Namespace) -> int:
    """``kinematica trajectory ROBOT --from ... [--via ...] --to ...``: samples, events, a file."""
    from kinematica.motion import (
        cartesian_path,
        cartesian_via_path,
        joint_trajectory,
        time_scaling,
        via_trajectory,
        write_csv,
        write_json,
    )

    args.aliases = _TRAJECTORY_OPTIONS
    robot = robot_from_args(args)
    W, times = _waypoints(robot, args)
    qa, qb = W[0], W[-1]
    through = W.shape[0] > 2 or args.waypoints is not None or args.profile == "mstraj"
    out = Path(args.output) if args.output else None
    if out is not None and out.suffix.lower() not in (".csv", ".json"):
        raise KinematicaError(f"-o: the file must end in .csv or .json, got {out.name!r}")
    vmax = _limit(robot, args.vmax, args, "vmax")
    amax = _limit(robot, args.amax, args, "amax")
    duration = args.duration
    if times is not None and duration is not None:
        raise KinematicaError("--times sets the duration: drop --duration")
    if duration is None and times is None and vmax is None and amax is None:
        duration = 2.0
    if through and args.profile == "trapezoid":
        raise KinematicaError(
            "--profile trapezoid moves between two configurations; through --via points use "
            "mstraj (lines with parabolic blends), cubic or quintic"
        )
    if not through and (args.times is not None or args.tacc is not None):
        raise KinematicaError("--times and --tacc apply to moves through --via points")
    if args.blend is not None and not (args.cartesian and through):
        raise KinematicaError("--blend rounds the corners of a --cartesian path through --via")
    path: CartesianPath | None = None
    if args.cartesian:
        if vmax is not None or amax is not None:
            raise KinematicaError(
                "--vmax/--amax limit joint trajectories; with --cartesian give --duration"
            )
        T = float(times[-1]) if times is not None else float(duration)
        t = joint_trajectory(qa, qb, T, "quintic", args.dt).t  # checks T and dt
        # Rest to rest along the path: the trapezoid's time scaling for mstraj's blends.
        scaling: Profile = "trapezoid" if args.profile == "mstraj" else args.profile
        s, _, _ = time_scaling(scaling, t, T)
        if through:
            poses = robot.fk(W)
            blend = 0.0 if args.blend is None else float(lengths_in(args.blend, robot, args))
            path = cartesian_via_path(robot, poses, blend=blend, q0=qa, s=s)
        else:
            path = cartesian_path(robot, robot.fk(qa), robot.fk(qb), q0=qa, s=s, q1=qb)
        q, qd, qdd = path.q, None, None
    elif through:
        if times is None and vmax is None and amax is None:
            times = np.linspace(0.0, float(duration), W.shape[0])
        t, q, qd, qdd = via_trajectory(
            W,
            args.profile,
            times,
            args.dt,
            vmax,
            amax,
            tacc=args.tacc,
            ends=args.ends,
        )
    else:
        t, q, qd, qdd = joint_trajectory(
            qa, qb, duration, args.profile, args.dt, vmax, amax, sync=args.sync
        )
    events = path.events if path is not None else ()
    blocked = any(e.kind in BLOCKING for e in events)
    if out is not None:
        if out.suffix.lower() == ".csv":
            write_csv(out, t, q)
        else:
            meta = {
                "robot": robot.name,
                "profile": args.profile,
                "cartesian": args.cartesian,
                "waypoints": W.shape[0],
            }
            write_json(out, t, q, qd, qdd, joint_types=robot.joint_types, events=events, meta=meta)
    if args.json:
        dump(
            {
                "robot": robot.name,
                "profile": args.profile,
                "cartesian": bool(args.cartesian),
                "sync": None if through else args.sync,
                "waypoints": _safe(q_out(robot, W, args)),
                "units": {"t": "s", "angle": angle_unit(args), "length": "m"},
                "duration": float(t[-1]),
                "t": _safe(t),
                "q": _safe(q_out(robot, q, args)),
                "qd": None if qd is None else _safe(q_out(robot, qd, args)),
                "qdd": None if qdd is None else _safe(q_out(robot, qdd, args)),
                "events": [
                    {
                        "kind": e.kind,
                        "index": e.index,
                        "s": e.s,
                        "names": list(e.names),
                        "message": e.message,
                    }
                    for e in events
                ],
                "file": None if out is None else str(out),
            }
        )
        return 1 if blocked else 0
    kind = "Cartesian (line, slerp)" if args.cartesian else "joint"
    where = f" through {W.shape[0]} waypoints" if through else ""
    print(
        f"{robot.name}: {kind} trajectory{where}, {args.profile}, {fmt(t[-1], 4)} s, "
        f"{t.size} samples"
    )
    step = max(1, math.ceil(t.size / PRINTED_ROWS))
    idx = sorted(set(range(0, t.size, step)) | {t.size - 1})
    header = ("t (s)", *(f"q{i} ({u})" for i, u in enumerate(joint_units(robot, args), 1)))
    shown = q_out(robot, q[idx], args)
    print(
        table(
            header,
            [(fmt(t[i], 4), *(fmt(v, 4) for v in row)) for i, row in zip(idx, shown, strict=True)],
        )
    )
    if step > 1:
        print(f"  (every {step}th sample and the last; -o FILE or --json for all)")
    if path is not None:
        _print_events(path)
        if path.ok:
            print(f"followed on one branch, largest joint step {fmt(path.max_step, 4)} (rad, m)")
    if out is not None:
        print(f"written to {out} (t in s, joints in rad and m)")
    return 1 if blocked else 0


def register(sub: Any) -> None:
    """Add ``jacobian``, ``workspace`` and ``trajectory`` to the subparsers ``sub``."""
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

    p = sub.add_parser(
        "trajectory", help="joint or Cartesian trajectory between two q, or through --via points"
    )
    add_robot(p)
    p.add_argument("--from", dest="q_from", nargs="+", type=float, metavar="Q")
    p.add_argument(
        "--via",
        nargs="+",
        type=float,
        action="append",
        metavar="Q",
        help="a configuration to pass through (repeat for several, in order)",
    )
    p.add_argument("--to", dest="q_to", nargs="+", type=float, metavar="Q")
    p.add_argument(
        "--waypoints",
        metavar="FILE.csv",
        help="every waypoint instead of --from/--via/--to: t,q1,...,qn in s, rad and m "
        "(the format -o writes); t gives their times",
    )
    p.add_argument(
        "--profile",
        choices=("quintic", "cubic", "trapezoid", "mstraj"),
        default="quintic",
        help="between two q: quintic, cubic, trapezoid; through --via: the quintic (C4) or "
        "cubic (C2) spline through every point, or mstraj (lines with parabolic blends)",
    )
    p.add_argument(
        "--duration",
        type=float,
        help="seconds (default 2, or from the limits); --via points evenly spaced in it",
    )
    p.add_argument(
        "--times", nargs="+", type=float, metavar="T", help="waypoint times in s, from 0"
    )
    p.add_argument("--dt", type=float, default=0.01, help="sample spacing in s (default 0.01)")
    p.add_argument("--vmax", nargs="+", type=float, help="speed limit, one or n values (deg/s)")
    p.add_argument("--amax", nargs="+", type=float, help="acceleration limit (deg/s²)")
    p.add_argument(
        "--sync",
        choices=("each", "shared"),
        default="each",
        help="trapezoid: each joint its own profile in the slowest joint's minimum time "
        "(default), or one shared profile on the joint-space line",
    )
    p.add_argument("--tacc", type=float, help="mstraj: blend time at each via point (s)")
    p.add_argument(
        "--ends",
        choices=("clamped", "natural"),
        default="clamped",
        help="spline ends: at rest (default) or natural (free)",
    )
    p.add_argument(
        "--cartesian",
        action="store_true",
        help="straight tool lines through fk of each point, IK on --from's branch",
    )
    p.add_argument(
        "--blend", type=float, help="--cartesian through --via: corner radius (robot's length unit)"
    )
    p.add_argument("-o", "--output", metavar="PATH.csv", help="write t,q1..qn (SI) to .csv/.json")
    add_common(p)
    p.set_defaults(run=trajectory)
