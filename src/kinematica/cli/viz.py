"""Subcommands ``plot``, ``animate`` and ``view``: pictures, animations, the interactive page.

matplotlib is imported (through :mod:`kinematica.viz`) only when one of these
commands runs, so the other commands start as fast without it.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from kinematica.cli.options import add_common, add_pose, add_robot, dump, q_in, robot_from_args
from kinematica.errors import DimensionError, KinematicaError, UnreachableError
from kinematica.robot import Robot
from kinematica.spatial import from_pose

__all__ = ["animate", "plot", "register", "view"]


def _target(args: argparse.Namespace) -> NDArray[np.float64]:
    if args.position is not None:
        return np.array(args.position, dtype=float)
    if args.matrix is not None:
        return np.array(args.matrix, dtype=float).reshape(4, 4)
    return from_pose(np.array(args.pose, dtype=float), euler=args.euler, degrees=not args.rad)


def _size(args: argparse.Namespace) -> tuple[int, int] | None:
    return None if args.size is None else (int(args.size[0]), int(args.size[1]))


def plot(args: argparse.Namespace) -> int:
    """``kinematica plot ROBOT --q ...``: the arm as a picture, or every IK solution."""
    from kinematica import viz

    robot = robot_from_args(args)
    q = None if args.q is None else q_in(robot, args.q, args, "q")
    given = [args.pose, args.matrix, args.position]
    solutions = args.solutions or any(v is not None for v in given)
    if q is None and not any(v is not None for v in given):
        raise DimensionError("plot needs --q Q... (or a target: --pose, --matrix, --position)")
    if solutions and args.ellipsoid is not None:
        raise KinematicaError(
            "--ellipsoid draws one configuration (--q), not IK solutions of a target"
        )
    out: dict[str, Any] = {"robot": robot.name, "kind": "solutions" if solutions else "arm"}
    if solutions:
        target = robot.fk(q) if q is not None else _target(args)
        try:
            path, count, size = viz.save_solutions(
                robot,
                target,
                args.output,
                respect_limits=not args.ignore_limits,
                frames=args.frames,
                labels=args.frames and not args.no_labels,
                degrees=not args.rad,
                size=_size(args),
                dpi=args.dpi,
            )
        except UnreachableError as exc:
            if args.json:
                dump({**out, "output": None, "solutions": 0, "message": str(exc)})
            else:
                print(f"no picture written: {exc}")
            return 1
        out.update(solutions=count)
    else:
        assert q is not None  # checked above: no target means --q was given
        size = _size(args) or (800, 700)
        path = viz.save_plot(
            robot,
            q,
            args.output,
            frames=args.frames,
            labels=not args.no_labels,
            size=size,
            dpi=args.dpi,
            title=f"{robot.name}   q = [{', '.join(f'{v:g}' for v in args.q)}] "
            f"({'rad' if args.rad else 'deg'}, m)",
            ellipsoid=args.ellipsoid,
        )
        if args.ellipsoid is not None:
            from kinematica.motion import ellipsoid

            e = ellipsoid(robot, q, args.ellipsoid)
            out["ellipsoid"] = {
                "kind": args.ellipsoid,
                "radii": e.radii.tolist(),
                "directions": e.directions.tolist(),
            }
    out.update(output=str(path), size=list(size))
    if args.json:
        dump(out)
    else:
        count = out.get("solutions", 0)
        what = f"{count} IK solution{'' if count == 1 else 's'}" if solutions else "the arm"
        print(f"wrote {path} ({size[0]} x {size[1]} px): {what} of {robot.name}")
    return 0


def animate(args: argparse.Namespace) -> int:
    """``kinematica animate ROBOT --trajectory path.csv -o arm.gif``."""
    from kinematica import viz

    robot = robot_from_args(args)
    t, q = viz.read_trajectory(args.trajectory, dof=robot.dof)
    anim = viz.animate(
        robot,
        q,
        args.output,
        t=t,
        fps=args.fps,
        frames=args.frames,
        labels=args.frames and not args.no_labels,
        size=_size(args) or (640, 560),
        dpi=args.dpi,
        max_frames=args.max_frames or None,
    )
    if args.json:
        dump(
            {
                "robot": robot.name,
                "output": str(anim.path),
                "frames": anim.frames,
                "fps": anim.fps,
                "note": anim.note or None,
                "size": list(anim.size),
                "samples": int(q.shape[0]),
            }
        )
    else:
        print(
            f"wrote {anim.path} ({anim.size[0]} x {anim.size[1]} px, {anim.frames} frames at "
            f"{anim.fps:.4g} fps) from {q.shape[0]} samples of {args.trajectory}"
        )
        if anim.note:
            print(f"note: {anim.note}")
    return 0


def _hash_hint(robot: Robot) -> str:
    """How to start the page at a configuration: ``#q=`` takes degrees and metres."""
    kinds = set(robot.joint_types)
    if len(kinds) == 1:
        return f"add #q=... in {'metres' if kinds == {'P'} else 'degrees'} to start there"
    each = ", ".join(
        f"q{i} in {'m' if kind == 'P' else 'degrees'}"
        for i, kind in enumerate(robot.joint_types, 1)
    )
    return f"add #q=... to start there: {each}"


def view(args: argparse.Namespace) -> int:
    """``kinematica view ROBOT [-o arm.html] [--serve] [--reach [MAP]]``: the interactive page."""
    from kinematica import viz

    robot = robot_from_args(args)
    units = viz.robot_units(robot)
    q = None if args.q is None else q_in(robot, args.q, args, "q")
    reach = None
    if args.reach is not None:  # a saved map, or (no file given) a coarse one computed now
        reach = viz.page_map(robot, args.reach) if args.reach else viz.coarse_map(robot)
    written = None
    if args.output is not None or not args.serve:
        name = args.output or f"{Path(args.robot).stem or 'arm'}.html"
        written = viz.write_page(robot, name, units=units, q=q, euler=args.euler, reach=reach)
    if not args.serve:
        if args.json:
            dump({"robot": robot.name, "output": str(written), "units": units})
        else:
            print(f"wrote {written}: open it in a browser ({_hash_hint(robot)})")
        return 0
    server = viz.serve(
        robot,
        host=args.host,
        port=args.port,
        units=units,
        q=q,
        euler=args.euler,
        start=False,
        reach=reach,
    )
    if args.json:
        dump({"robot": robot.name, "url": server.url, "output": str(written) if written else None})
    else:
        print(f"serving {robot.name} on {server.url} (Ctrl-C to stop)")
    sys.stdout.flush()
    if args.open:
        import webbrowser  # only for --open: importing it slows every command's start

        webbrowser.open(server.url)
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        pass
    finally:
        server.close()
    return 0


def _port(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        value = -1
    if not 0 <= value <= 65535:
        raise argparse.ArgumentTypeError(
            f"expected a port number from 0 to 65535 (0: a free one), got {text!r}"
        )
    return value


def _picture_options(p: argparse.ArgumentParser) -> None:
    p.add_argument("--frames", action="store_true", help="draw the DH frames S0..Sn and the tool")
    p.add_argument("--no-labels", action="store_true", help="do not name the frames")
    p.add_argument("--size", nargs=2, type=int, metavar=("W", "H"), help="picture size in pixels")
    p.add_argument(
        "--dpi", type=float, default=100.0, help="dots per inch (text size; default 100)"
    )


def register(sub: Any) -> None:
    """Add ``plot``, ``animate`` and ``view`` to the subparsers ``sub``."""
    p = sub.add_parser("plot", help="picture of the arm with its DH frames, or every IK solution")
    add_robot(p)
    p.add_argument(
        "--q",
        nargs="+",
        type=float,
        metavar="Q",
        help="joint values (degrees, or radians with --rad; metres for prismatic joints)",
    )
    target = p.add_mutually_exclusive_group()
    add_pose(
        target, "draw every IK solution of this pose: position (m), Euler angles (see --euler)"
    )
    target.add_argument(
        "--matrix", nargs=16, type=float, metavar="M", help="every IK solution of this 4x4 pose"
    )
    target.add_argument(
        "--position",
        nargs=3,
        type=float,
        metavar=("X", "Y", "Z"),
        help="draw every IK solution reaching this position (orientation free)",
    )
    p.add_argument(
        "--solutions", action="store_true", help="draw every IK solution of the pose fk(q)"
    )
    p.add_argument(
        "--ignore-limits", action="store_true", help="with --solutions: outside the limits too"
    )
    p.add_argument(
        "--ellipsoid",
        choices=("velocity", "force"),
        help="also draw the tool point's velocity or force ellipsoid (with --q)",
    )
    p.add_argument(
        "-o", "--output", default="arm.png", help="PNG, SVG or PDF file (default arm.png)"
    )
    _picture_options(p)
    add_common(p)
    p.set_defaults(run=plot)

    p = sub.add_parser("animate", help="animation (GIF, or MP4 with ffmpeg) of a trajectory")
    add_robot(p)
    p.add_argument(
        "--trajectory",
        required=True,
        metavar="CSV",
        help="CSV file: header t,q1,...,qn; time (s), joint values (rad, m)",
    )
    p.add_argument("-o", "--output", default="arm.gif", help=".gif or .mp4 (default arm.gif)")
    p.add_argument(
        "--fps", type=float, help="resample at this frame rate (default: one frame a row)"
    )
    p.add_argument(
        "--max-frames", type=int, default=300, help="keep at most this many frames (0: all)"
    )
    _picture_options(p)
    add_common(p)
    p.set_defaults(run=animate)

    p = sub.add_parser("view", help="interactive HTML page: sliders, frames, live T and pose")
    add_robot(p)
    p.add_argument("-o", "--output", help="page to write (default ROBOT.html; with --serve: none)")
    p.add_argument(
        "--q", nargs="+", type=float, metavar="Q", help="start configuration (units as for fk)"
    )
    p.add_argument("--serve", action="store_true", help="serve the page with a draggable IK target")
    p.add_argument("--host", default="127.0.0.1", help="address to serve on (default 127.0.0.1)")
    p.add_argument("--port", type=_port, default=0, help="port to serve on (default: a free one)")
    p.add_argument("--open", action="store_true", help="open the page in the web browser")
    p.add_argument(
        "--reach",
        nargs="?",
        const="",
        metavar="MAP.npz",
        help="show a reachability map: one saved by `kinematica reach ROBOT -o MAP.npz`, "
        "or, with no file, a coarse one computed now",
    )
    add_common(p)
    p.set_defaults(run=view)
