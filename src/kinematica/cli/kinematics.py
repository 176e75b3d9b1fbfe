"""Subcommands ``robots``, ``show``, ``fk`` and ``ik``: the robot and its kinematics."""

from __future__ import annotations

import argparse
import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from kinematica.cli.format import fmt, matrix, table
from kinematica.cli.options import (
    add_common,
    add_robot,
    angle_unit,
    clean,
    dump,
    q_in,
    q_out,
    robot_from_args,
)
from kinematica.ik.result import IKResult
from kinematica.io import builtin_names
from kinematica.robot import Robot, classify, load
from kinematica.spatial import euler_from_matrix, from_pose, gimbal_locked

__all__ = ["fk", "ik", "register", "robots", "show"]

FloatArray = NDArray[np.float64]


def robots(args: argparse.Namespace) -> int:
    """``kinematica robots``: the built-in models."""
    rows = []
    for name in builtin_names():
        robot = load(name)
        rows.append((name, robot.name, robot.joint_types, classify(robot).summary))
    if args.json:
        dump(
            {
                "robots": [
                    dict(zip(("id", "name", "joints", "structure"), r, strict=True)) for r in rows
                ]
            }
        )
    else:
        print(table(("ROBOT", "NAME", "JOINTS", "STRUCTURE"), rows, indent=""))
    return 0


def _dh_rows(robot: Robot, deg: bool) -> list[tuple[str, ...]]:
    unit = "°" if deg else ""

    def ang(v: float) -> str:
        return fmt(math.degrees(v) if deg else v, 4) + unit

    def var(name: str, offset: str) -> str:
        if offset in ("0", "0°"):
            return name
        return f"{name} - {offset.lstrip('-')}" if offset.startswith("-") else f"{name} + {offset}"

    rows: list[tuple[str, ...]] = []
    limits = robot.qlim
    for i, (link, lim) in enumerate(zip(robot.links, limits, strict=True), start=1):
        if link.type == "R":
            theta, d = var(f"q{i}", ang(link.offset)), fmt(link.d, 6)
            lim_text = f"[{ang(lim[0])}, {ang(lim[1])}]"
        else:
            theta, d = ang(link.theta), var(f"q{i}", fmt(link.offset, 6))
            lim_text = f"[{fmt(lim[0], 4)}, {fmt(lim[1], 4)}] m"
        free = "" if robot.has_limits[i - 1] else " (free)"
        rows.append((str(i), link.type, theta, d, fmt(link.a, 6), ang(link.alpha), lim_text + free))
    return rows


def show(args: argparse.Namespace) -> int:
    """``kinematica show ROBOT``: DH table, limits, structure."""
    robot = robot_from_args(args)
    structure = classify(robot)
    deg = not args.rad
    if args.json:
        dump(
            {
                "robot": robot.name,
                "convention": robot.convention,
                "joints": robot.joint_types,
                "structure": {"kind": structure.kind, "summary": structure.summary},
                "units": {"angle": angle_unit(args), "length": "m"},
                "dh": [
                    dict(zip(("theta", "d", "a", "alpha"), r, strict=True))
                    for r in clean(robot.dh_table())
                ],
                "qlim": clean(q_out(robot, robot.qlim.T, args).T),
                "base": clean(robot.base),
                "tool": clean(robot.tool),
                "description": robot.description,
            }
        )
        return 0
    a_name, alpha_name = (
        ("a(i-1)", "alpha(i-1)") if robot.convention == "modified" else ("a", "alpha")
    )
    print(f"{robot.name}: {structure.summary}")
    print(f"{robot.dof} joints ({robot.joint_types}), {robot.convention} DH convention")
    if robot.description:
        print(robot.description.strip())
    print()
    print(
        table(
            ("i", "type", "theta", "d (m)", f"{a_name} (m)", alpha_name, "limits"),
            _dh_rows(robot, deg),
        )
    )
    unit = "rad" if args.rad else "deg"
    for what, T in (("base", robot.base), ("tool", robot.tool)):
        if not np.array_equal(T, np.eye(4)):
            pos, eul, _ = _pose_parts(T, args)
            print(
                f"\n{what}: xyz = {', '.join(fmt(v) for v in pos)} m, "
                f"euler {args.euler} = {', '.join(fmt(v, 4) for v in eul)} {unit}"
            )
            print(matrix(T))
    return 0


def _pose_parts(T: FloatArray, args: argparse.Namespace) -> tuple[FloatArray, FloatArray, bool]:
    eul = euler_from_matrix(T[:3, :3], args.euler, degrees=not args.rad)
    return T[:3, 3], eul, bool(gimbal_locked(T[:3, :3], args.euler))


def fk(args: argparse.Namespace) -> int:
    """``kinematica fk ROBOT --q ...``: T, position and Euler angles."""
    robot = robot_from_args(args)
    q = q_in(robot, args.q, args, "q")
    T = robot.fk(q)
    pos, eul, locked = _pose_parts(T, args)
    frames = robot.fk(q, all_frames=True) if args.frames else None
    if args.json:
        out: dict[str, Any] = {
            "robot": robot.name,
            "q": list(args.q),
            "units": {"angle": angle_unit(args), "length": "m"},
            "T": clean(T),
            "position": clean(pos),
            "euler": clean(eul),
            "euler_sequence": args.euler,
            "gimbal_lock": locked,
        }
        if frames is not None:
            out["frames"] = clean(frames)
        dump(out)
        return 0
    unit = "rad" if args.rad else "deg"
    print(f"{robot.name}, q = [{', '.join(fmt(v, 6) for v in args.q)}]")
    if frames is not None:
        for i, F in enumerate(frames):
            label = (
                "0T0 (base)" if i == 0 else f"0T{i}" + (" (with tool)" if i == robot.dof else "")
            )
            print(f"\n{label}:\n{matrix(F)}")
    print(f"\nT:\n{matrix(T)}")
    print(f"\nposition (m):  x = {fmt(pos[0])}  y = {fmt(pos[1])}  z = {fmt(pos[2])}")
    note = "  (gimbal lock: third angle set to 0)" if locked else ""
    print(f"euler {args.euler} ({unit}):  " + "  ".join(fmt(v, 6) for v in eul) + note)
    return 0


def _target(args: argparse.Namespace) -> FloatArray:
    if args.position is not None:
        return np.array(args.position, dtype=float)
    if args.matrix is not None:
        return np.array(args.matrix, dtype=float).reshape(4, 4)
    return from_pose(np.array(args.pose, dtype=float), euler=args.euler, degrees=not args.rad)


def ik(args: argparse.Namespace) -> int:
    """``kinematica ik ROBOT --pose ...``: every solution, one row each."""
    robot = robot_from_args(args)
    target = _target(args)
    q0 = None if args.q0 is None else q_in(robot, args.q0, args, "q0")
    res = robot.ik(
        target, method=args.method, respect_limits=not args.ignore_limits, q0=q0, seed=args.seed
    )
    assert isinstance(res, IKResult)
    solved = res.success
    if args.json:
        dump(
            {
                "robot": robot.name,
                "status": res.status,
                "method": res.method,
                "message": res.message,
                "units": {"angle": angle_unit(args), "length": "m"},
                "solutions": clean(q_out(robot, res.solutions, args)),
                "branches": list(res.branches),
                "residuals": {
                    "position_m": clean(res.residuals[:, 0]),
                    "rotation_rad": clean(res.residuals[:, 1]),
                },
                "out_of_limits": clean(q_out(robot, res.out_of_limits, args)),
                "out_of_limits_branches": list(res.out_of_limits_branches),
                "free_joints": [f"q{i + 1}" for i in res.free_joints],
                "gap_m": res.gap,
            }
        )
        return 0 if solved else 1
    print(f"{robot.name}: {res.status} — {res.message}")
    header = ("#", *(f"q{i}" for i in range(1, robot.dof + 1)), "branch", "error (m, rad)")

    def rows(
        sol: FloatArray, branches: tuple[str, ...], resid: FloatArray | None
    ) -> list[tuple[str, ...]]:
        out = []
        for k, (q, b) in enumerate(zip(q_out(robot, sol, args), branches, strict=True), start=1):
            err = "" if resid is None else f"{resid[k - 1, 0]:.1e}, {resid[k - 1, 1]:.1e}"
            out.append((str(k), *(fmt(v, 4) for v in q), b, err))
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


def register(sub: Any) -> None:
    """Add ``robots``, ``show``, ``fk`` and ``ik`` to the subparsers ``sub``."""
    p = sub.add_parser("robots", help="list the built-in robot models")
    add_common(p)  # --euler/--rad accepted on every command; this one prints no angles
    p.set_defaults(run=robots)

    p = sub.add_parser("show", help="DH table, limits and structure of a robot")
    add_robot(p)
    add_common(p)
    p.set_defaults(run=show)

    p = sub.add_parser("fk", help="forward kinematics: T, position and Euler angles")
    add_robot(p)
    p.add_argument(
        "--q",
        nargs="+",
        type=float,
        required=True,
        metavar="Q",
        help="joint values: degrees for revolute joints (or radians with "
        "--rad), metres for prismatic joints",
    )
    p.add_argument("--frames", action="store_true", help="print every frame 0Ti")
    add_common(p)
    p.set_defaults(run=fk)

    p = sub.add_parser("ik", help="inverse kinematics: every solution, one row each")
    add_robot(p)
    target = p.add_mutually_exclusive_group(required=True)
    target.add_argument(
        "--pose",
        nargs=6,
        type=float,
        metavar=("X", "Y", "Z", "A", "B", "G"),
        help="position (m) and three Euler angles (see --euler)",
    )
    target.add_argument(
        "--matrix", nargs=16, type=float, metavar="M", help="the 4x4 pose, 16 numbers row by row"
    )
    target.add_argument(
        "--position",
        nargs=3,
        type=float,
        metavar=("X", "Y", "Z"),
        help="position only (m): orientation left free",
    )
    p.add_argument(
        "--method",
        choices=("auto", "analytic", "numeric"),
        default="auto",
        help="closed form when the structure allows (auto), or force one",
    )
    p.add_argument(
        "--q0",
        nargs="+",
        type=float,
        metavar="Q",
        help="initial guess / sort solutions by distance to it (units as --q)",
    )
    p.add_argument(
        "--ignore-limits",
        action="store_true",
        help="list solutions outside the joint limits among the others",
    )
    p.add_argument("--seed", type=int, default=0, help="seed of numeric restarts (default 0)")
    add_common(p)
    p.set_defaults(run=ik)
