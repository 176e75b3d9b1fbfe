"""``kinematica trajectory ... --optimal``: the fastest timing of the path within the limits."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from kinematica.cli.format import fmt, printed_rows, table
from kinematica.cli.options import angle_unit, dump, joint_units, lengths_in, q_out
from kinematica.errors import KinematicaError
from kinematica.robot import Robot

__all__ = ["add_optimal_options", "optimal_trajectory"]

FloatArray = NDArray[np.float64]


def add_optimal_options(p: argparse.ArgumentParser) -> None:
    """The trajectory command's ``--optimal`` and ``--tcp-speed`` (its figure: ``--plot``)."""
    p.add_argument(
        "--optimal",
        action="store_true",
        help="the fastest timing of the path (joint spline through the points, or --cartesian "
        "lines) within --vmax, --amax and --tcp-speed",
    )
    p.add_argument("--tcp-speed", type=float, help="--optimal: tool speed limit (length unit/s)")


def optimal_trajectory(
    args: argparse.Namespace,
    robot: Robot,
    W: FloatArray,
    vmax: FloatArray | None,
    amax: FloatArray | None,
    safe: Any,
) -> int:
    """Time the path through ``W`` (joint spline, or Cartesian lines) within the limits.

    Returns:
        The exit code: 0 when the whole path is timed, 1 when it cannot be followed
        to its end (the timing up to where it stops is printed).
    """
    from kinematica.motion import (
        cartesian_path,
        cartesian_via_path,
        time_optimal,
        write_csv,
        write_json,
    )

    if args.duration is not None or args.times is not None:
        raise KinematicaError("--optimal finds the duration: drop --duration and --times")
    tcp = None if args.tcp_speed is None else float(lengths_in(args.tcp_speed, robot, args))
    if vmax is None and amax is None and tcp is None:
        raise KinematicaError("--optimal needs limits: --vmax, --amax and/or --tcp-speed")
    if tcp is not None and not tcp > 0:
        raise KinematicaError(f"--tcp-speed must be a speed > 0, got {args.tcp_speed:g}")
    events: tuple[Any, ...] = ()
    path: Any = W
    if args.cartesian:
        if W.shape[0] > 2:
            blend = 0.0 if args.blend is None else float(lengths_in(args.blend, robot, args))
            path = cartesian_via_path(robot, robot.fk(W), blend=blend, q0=W[0], steps=200)
        else:
            path = cartesian_path(robot, robot.fk(W[0]), robot.fk(W[-1]), 200, q0=W[0], q1=W[-1])
        events = path.events
    res = time_optimal(path, vmax, amax, robot, tcp_speed=tcp, dt=args.dt)
    t, q, qd, qdd = res.trajectory
    if args.plot:
        from kinematica.motion.plot import plot_time_optimal

        plot_time_optimal(res, args.plot, title=robot.name)
    out = Path(args.output) if args.output else None
    if out is not None and out.suffix.lower() == ".csv":
        write_csv(out, t, q)
    elif out is not None:
        meta = {"robot": robot.name, "optimal": True, "status": res.status, "limit": res.limit}
        write_json(out, t, q, qd, qdd, joint_types=robot.joint_types, events=events, meta=meta)
    notes = [e.message for e in events]
    notes += [
        f"slowed at s = {w.s:.4g} to ṡ = {w.sd:.4g}/s by the {w.limit}" for w in res.slowdowns
    ]
    if not res.ok:
        notes.append(res.message)
    code = 0 if res.ok else 1
    if args.json:
        dump(
            {
                "robot": robot.name,
                "optimal": True,
                "cartesian": bool(args.cartesian),
                "status": res.status,
                "s_stop": res.s_stop,
                "limit": res.limit,
                "units": {"t": "s", "angle": angle_unit(args), "length": "m"},
                "duration": res.duration,
                "t": safe(t),
                "q": safe(q_out(robot, q, args)),
                "qd": safe(q_out(robot, qd, args)),
                "qdd": safe(q_out(robot, qdd, args)),
                "notes": notes,
                "file": args.output,
                "plot": args.plot,
            }
        )
        return code
    kind = "Cartesian" if args.cartesian else "joint spline"
    print(
        f"{robot.name}: time-optimal {kind} trajectory through {W.shape[0]} points, "
        f"{fmt(res.duration, 6)} s, {t.size} samples ({res.status})"
    )
    idx, step = printed_rows(t.size)
    header = ("t (s)", *(f"q{i} ({u})" for i, u in enumerate(joint_units(robot, args), 1)))
    shown = q_out(robot, q[idx], args)
    rows = [(fmt(t[i], 4), *(fmt(v, 4) for v in row)) for i, row in zip(idx, shown, strict=True)]
    print(table(header, rows))
    if step > 1:
        print(f"  (every {step}th sample and the last; -o FILE or --json for all)")
    for note in notes:
        print(f"note: {note}")
    if args.output:
        print(f"written to {args.output} (t in s, joints in rad and m)")
    if args.plot:
        print(f"figure written to {args.plot}")
    return code
