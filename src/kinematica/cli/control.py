"""Subcommand ``control``: resolved-rate motion toward a pose or along a twist."""

from __future__ import annotations

import argparse
import math
from pathlib import Path
from typing import Any

import numpy as np

from kinematica.cli.format import fmt, printed_rows, table
from kinematica.cli.options import (
    add_common,
    add_pose,
    add_robot,
    angle_unit,
    dump,
    finite,
    lengths_in,
    q_in,
    q_out,
    robot_from_args,
)
from kinematica.errors import KinematicaError
from kinematica.spatial import from_pose

__all__ = ["control", "register"]

#: Rows of the run printed as text (every k-th sample, and the last).


def _damping(text: str) -> str | float | None:
    """``--damping``: none, manipulability, min_singular, or a constant λ."""
    if text == "none":
        return None
    if text in ("manipulability", "min_singular"):
        return text
    try:
        value = float(text)
    except ValueError:
        value = -1.0
    if not (math.isfinite(value) and value >= 0.0):
        raise argparse.ArgumentTypeError(
            f"expected none, manipulability, min_singular or a number >= 0, got {text!r}"
        )
    return value


def _null(values: list[Any]) -> list[Any]:
    return [None if isinstance(v, float) and not math.isfinite(v) else v for v in values]


def control(args: argparse.Namespace) -> int:
    """``kinematica control ROBOT --q0 ... --pose ...``: the run, its error, a file."""
    from kinematica.motion import resolved_rate, write_csv, write_json

    robot = robot_from_args(args)
    q0 = q_in(robot, args.q0, args, "q0")
    out = Path(args.output) if args.output else None
    if out is not None and out.suffix.lower() not in (".csv", ".json"):
        raise KinematicaError(f"-o: the file must end in .csv or .json, got {out.name!r}")
    target = twist = None
    if args.pose is not None:
        pose = finite(args.pose, "--pose")
        pose[:3] = lengths_in(pose[:3], robot, args)
        target = from_pose(pose, euler=args.euler, degrees=not args.rad)
    else:
        v = finite(args.twist, "--twist")
        v[:3] = lengths_in(v[:3], robot, args)
        twist = np.r_[v[:3], v[3:] if args.rad else np.deg2rad(v[3:])]
    qd_max = None
    if args.qd_max is not None:
        vals = args.qd_max * robot.dof if len(args.qd_max) == 1 else args.qd_max
        qd_max = np.abs(q_in(robot, vals, args, "qd-max"))
    args.aliases = {"qd_max": "--qd-max", "lambda_max": "--lambda-max", "gain": "--gain"}
    run = resolved_rate(
        robot,
        q0,
        target=target,
        twist=twist,
        dt=args.dt,
        steps=args.steps,
        duration=args.duration,
        gain=args.gain,
        damping=args.damping,
        threshold=args.threshold,
        lambda_max=args.lambda_max,
        qd_max=qd_max,
        respect_limits=not args.ignore_limits,
        nullspace=args.nullspace,
        nullspace_gain=args.nullspace_gain,
        tol=args.tol,
    )
    failed = run.reached is False
    if out is not None:
        if out.suffix.lower() == ".csv":
            write_csv(out, run.t, run.q)
        else:
            meta = {"robot": robot.name, "control": "resolved-rate", "reached": run.reached}
            write_json(out, run.t, run.q, run.qd, run.qdd, joint_types=robot.joint_types, meta=meta)
    if args.json:
        dump(
            {
                "robot": robot.name,
                "units": {"t": "s", "angle": angle_unit(args), "length": "m"},
                "reached": run.reached,
                "duration": float(run.t[-1]),
                "t": run.t.tolist(),
                "q": q_out(robot, run.q, args).tolist(),
                "qd": q_out(robot, run.qd, args).tolist(),
                "position_error": _null(run.error[:, 0].tolist()),
                "rotation_error": _null(run.error[:, 1].tolist()),
                "manipulability": run.manipulability.tolist(),
                "damping": run.damping.tolist(),
                "file": None if out is None else str(out),
            }
        )
        return 1 if failed else 0
    t = run.t
    print(f"{robot.name}: resolved-rate control, {fmt(t[-1], 4)} s, {t.size} samples")
    idx, step = printed_rows(t.size)
    header = ("t (s)", *(f"q{i}" for i in range(1, robot.dof + 1)), "w")
    shown = q_out(robot, run.q[idx], args)
    rows = [
        (fmt(t[i], 4), *(fmt(v, 4) for v in row), fmt(run.manipulability[i], 3))
        for i, row in zip(idx, shown, strict=True)
    ]
    print(table(header, rows))
    if step > 1:
        print(f"  (every {step}th sample and the last; -o FILE or --json for all)")
    if run.reached is not None:
        pos, rot = run.error[-1]
        verdict = "reached" if run.reached else "not reached within the steps"
        print(f"target {verdict}: position error {pos:.3g} m, rotation error {rot:.3g} rad")
    if out is not None:
        print(f"written to {out} (t in s, joints in rad and m)")
    return 1 if failed else 0


def register(sub: Any) -> None:
    """Add ``control`` to the subparsers ``sub``."""
    p = sub.add_parser("control", help="resolved-rate control toward a pose or along a twist")
    add_robot(p)
    p.add_argument(
        "--q0", nargs="+", type=float, required=True, metavar="Q", help="start (deg, or --rad)"
    )
    goal = p.add_mutually_exclusive_group(required=True)
    add_pose(goal, "target: position (length unit) and Euler angles (see --euler)")
    goal.add_argument(
        "--twist",
        nargs=6,
        type=float,
        metavar=("VX", "VY", "VZ", "WX", "WY", "WZ"),
        help="tool twist to follow, base frame (length unit/s, deg/s)",
    )
    p.add_argument("--dt", type=float, default=0.01, help="step in s (default 0.01)")
    p.add_argument("--steps", type=int, help="number of steps (default 2000)")
    p.add_argument("--duration", type=float, help="length of the run in s, instead of --steps")
    p.add_argument("--gain", type=float, default=5.0, help="gain toward the pose, 1/s (default 5)")
    p.add_argument(
        "--damping",
        type=_damping,
        default="min_singular",
        metavar="LAW",
        help="none, manipulability, min_singular (default) or a constant lambda",
    )
    p.add_argument("--threshold", type=float, default=0.05, help="w0 or eps of the damping law")
    p.add_argument("--lambda-max", type=float, default=0.05, help="largest damping (default 0.05)")
    p.add_argument("--qd-max", nargs="+", type=float, metavar="V", help="joint speed limit (deg/s)")
    p.add_argument("--ignore-limits", action="store_true", help="let joints pass their limits")
    p.add_argument("--nullspace", choices=("limits", "manipulability"), help="null-space objective")
    p.add_argument("--nullspace-gain", type=float, default=1.0, help="its gain (default 1)")
    p.add_argument("--tol", type=float, default=1e-10, help="reached within (m and rad)")
    p.add_argument("-o", "--output", metavar="PATH.csv", help="write t,q1..qn (SI) to .csv/.json")
    add_common(p)
    p.set_defaults(run=control)
