"""Subcommand ``trajectory``: joint and Cartesian trajectories, timed as asked."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from kinematica.cli.format import fmt, json_numbers, printed_rows, table
from kinematica.cli.jerk import add_jerk_options, jerk_json, jerk_text
from kinematica.cli.motion_optimal import add_optimal_options, optimal_trajectory
from kinematica.cli.options import (
    add_common,
    add_robot,
    angle_unit,
    dump,
    joint_units,
    lengths_in,
    q_in,
    q_out,
    robot_from_args,
)
from kinematica.errors import KinematicaError
from kinematica.robot import Robot

if TYPE_CHECKING:  # kinematica.motion loads when one of these commands runs
    from kinematica.motion import CartesianPath, JointTrajectory
    from kinematica.motion.trajectory import Profile

__all__ = ["register", "trajectory"]

FloatArray = NDArray[np.float64]

#: Sample counts from which the workspace command shows a progress bar.
PROGRESS_FROM = 200_000
#: Event kinds after which a Cartesian path cannot be executed as computed.
BLOCKING = {"unreachable", "joint_limit", "branch_change"}


# ---------------------------------------------------------------- trajectory
def _limit(robot: Robot, values: list[float] | None, args: argparse.Namespace, name: str) -> Any:
    """A speed/acceleration limit from the command line (one or n values) in SI."""
    if values is None:
        return None
    if len(values) == 1:
        values = values * robot.dof
    return np.abs(q_in(robot, values, args, name))


#: Library argument names and the trajectory command's options for them.
_TRAJECTORY_OPTIONS = {
    "tacc": "--tacc",
    "times": "--times",
    "vmax": "--vmax",
    "amax": "--amax",
    "jmax": "--jmax",
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
    jmax = _limit(robot, args.jmax, args, "jmax")
    scurve = args.profile == "scurve"
    if (jmax is not None) != scurve or (scurve and (args.cartesian or times is not None)):
        raise KinematicaError(
            "--profile scurve times joint moves from --vmax, --amax and --jmax (only it takes "
            "--jmax; not with --cartesian, --times or --waypoints)"
        )
    duration = args.duration
    if times is not None and duration is not None:
        raise KinematicaError("--times sets the duration: drop --duration")
    if duration is None and times is None and vmax is None and amax is None and not scurve:
        duration = 2.0
    if args.optimal:
        return optimal_trajectory(args, robot, W, vmax, amax, json_numbers)
    if args.tcp_speed is not None:
        raise KinematicaError("--tcp-speed goes with --optimal")
    if through and args.profile == "trapezoid":
        raise KinematicaError(
            "--profile trapezoid moves between two configurations; through --via points use "
            "mstraj (the Robotics Toolbox's lines with blends), cubic or quintic"
        )
    if not through and (args.times is not None or args.tacc is not None):
        raise KinematicaError("--times and --tacc apply to moves through --via points")
    if args.blend is not None and not (args.cartesian and through):
        raise KinematicaError("--blend rounds the corners of a --cartesian path through --via")
    path: CartesianPath | None = None
    traj: JointTrajectory | None = None
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
    elif through and scurve:
        traj = via_trajectory(W, "scurve", None, args.dt, vmax, amax, jmax=jmax, qlim=robot.qlim)
        t, q, qd, qdd = traj
    elif through:
        if times is None and vmax is None and amax is None:
            times = np.linspace(0.0, float(duration), W.shape[0])
        tacc = args.tacc[0] if args.tacc is not None and len(args.tacc) == 1 else args.tacc
        traj = via_trajectory(
            W, args.profile, times, args.dt, vmax, amax, tacc=tacc, ends=args.ends
        )
        t, q, qd, qdd = traj
    else:
        traj = joint_trajectory(
            qa, qb, duration, args.profile, args.dt, vmax, amax, sync=args.sync, jmax=jmax
        )
        t, q, qd, qdd = traj
    if args.plot:
        from kinematica.viz.limits import save_limits

        if traj is None:
            raise KinematicaError("--plot draws joint trajectories: drop --cartesian")
        save_limits(traj, args.plot, vmax=vmax, amax=amax, jmax=jmax, title=robot.name)
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
                "waypoints": json_numbers(q_out(robot, W, args)),
                "units": {"t": "s", "angle": angle_unit(args), "length": "m"},
                "duration": float(t[-1]),
                "t": json_numbers(t),
                "q": json_numbers(q_out(robot, q, args)),
                "qd": None if qd is None else json_numbers(q_out(robot, qd, args)),
                "qdd": None if qdd is None else json_numbers(q_out(robot, qdd, args)),
                **jerk_json(traj, robot, args, json_numbers),
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
                "plot": args.plot,
            }
        )
        return 1 if blocked else 0
    kind = "Cartesian (line, slerp)" if args.cartesian else "joint"
    where = f" through {W.shape[0]} waypoints" if through else ""
    print(
        f"{robot.name}: {kind} trajectory{where}, {args.profile}, {fmt(t[-1], 4)} s, "
        f"{t.size} samples"
    )
    idx, step = printed_rows(t.size)
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
    jerk_text(traj)
    if args.plot:
        print(f"figure written to {args.plot}")
    if path is not None:
        for e in path.events:
            print(f"event: {e.kind}: {e.message}")
        if path.ok:
            print(f"followed on one branch, largest joint step {fmt(path.max_step, 4)} (rad, m)")
    if out is not None:
        print(f"written to {out} (t in s, joints in rad and m)")
    return 1 if blocked else 0


def register(sub: Any) -> None:
    """Add ``trajectory`` to the subparsers ``sub``."""
    p = sub.add_parser(
        "trajectory", help="joint or Cartesian trajectory between two q, or through --via points"
    )
    add_robot(p)
    p.add_argument(
        "--from",
        dest="q_from",
        nargs="+",
        type=float,
        metavar="Q",
        help="the first configuration: degrees for revolute joints (radians with --rad), "
        "the length unit for prismatic joints",
    )
    p.add_argument(
        "--via",
        nargs="+",
        type=float,
        action="append",
        metavar="Q",
        help="a configuration to pass through (repeat for several, in order)",
    )
    p.add_argument(
        "--to",
        dest="q_to",
        nargs="+",
        type=float,
        metavar="Q",
        help="the last configuration, in the units of --from",
    )
    p.add_argument(
        "--waypoints",
        metavar="FILE.csv",
        help="every waypoint instead of --from/--via/--to: t,q1,...,qn in s, rad and m "
        "(the format -o writes); t gives their times",
    )
    p.add_argument(
        "--profile",
        choices=("quintic", "cubic", "trapezoid", "mstraj", "scurve"),
        default="quintic",
        help="between two q: quintic, cubic, trapezoid; through --via: the quintic (C4) or "
        "cubic (C2) spline through every point, or mstraj (the Robotics Toolbox's lines with "
        "quintic blends, times rounded up to --dt); "
        "scurve: jerk-limited (--vmax --amax --jmax), between two q (needs ruckig) or "
        "through --via points without stopping",
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
    p.add_argument(
        "--tacc",
        nargs="+",
        type=float,
        help="mstraj: blend time at each via point (s; 0 for none), or one per segment",
    )
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
    add_optimal_options(p)
    p.add_argument("-o", "--output", metavar="PATH.csv", help="write t,q1..qn (SI) to .csv/.json")
    add_jerk_options(p)
    add_common(p)
    p.set_defaults(run=trajectory)
