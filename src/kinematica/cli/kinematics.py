"""Subcommands ``robots``, ``show``, ``fk`` and ``ik``: the robot and its kinematics."""

from __future__ import annotations

import argparse
import math
import re
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from kinematica.cli.format import fmt, matrix, num, plain, table
from kinematica.cli.inverse import ik, parse_seed, pose_target_args, target_in
from kinematica.cli.options import (
    add_common,
    add_precision,
    add_robot,
    clean,
    dump,
    length_unit,
    lengths_out,
    q_in,
    q_out,
    robot_from_args,
    transform_out,
    units,
)
from kinematica.robot import Robot, load
from kinematica.spatial import euler_from_matrix, gimbal_locked

if TYPE_CHECKING:  # the IK layer loads when `ik` runs: `fk` never imports it
    pass

__all__ = ["fk", "ik", "pose_target_args", "register", "robots", "show", "target_in"]

FloatArray = NDArray[np.float64]


def robots(args: argparse.Namespace) -> int:
    """``kinematica robots``: the built-in models."""
    from kinematica.io.builtin import builtin_names
    from kinematica.robot.structure import classify

    rows = []
    for name in builtin_names():
        robot = load(name)
        rows.append((name, plain(robot.name), robot.joint_types, classify(robot).summary))
    if args.json:
        keys = ("id", "name", "joints", "structure")
        dump({"robots": [dict(zip(keys, r, strict=True)) for r in rows]})
    else:
        print(table(("ROBOT", "NAME", "JOINTS", "STRUCTURE"), rows, indent=""))
    return 0


def _dh_rows(robot: Robot, args: argparse.Namespace) -> list[tuple[str, ...]]:
    deg = not args.rad
    unit = "°" if deg else ""
    metres = length_unit(robot, args)

    def ang(v: float) -> str:
        return fmt(math.degrees(v) if deg else v, 4) + unit

    def length(v: float, digits: int = 6) -> str:
        return fmt(float(lengths_out(v, robot, args)), digits)

    def var(name: str, offset: str) -> str:
        if offset in ("0", "0°"):
            return name
        return f"{name} - {offset.lstrip('-')}" if offset.startswith("-") else f"{name} + {offset}"

    rows: list[tuple[str, ...]] = []
    limits = robot.qlim
    written = _written(robot)
    for i, (link, lim) in enumerate(zip(robot.links, limits, strict=True), start=1):
        if link.type == "R":
            theta, d = var(f"q{i}", ang(link.offset)), length(link.d)
            lim_text = f"[{ang(lim[0])}, {ang(lim[1])}]"
        else:
            theta, d = ang(link.theta), var(f"q{i}", length(link.offset))
            lim_text = f"[{length(lim[0], 4)}, {length(lim[1], 4)}] {metres}"
        free = "" if robot.has_limits[i - 1] else " (free)"
        cells = dict(theta=theta, d=d, a=length(link.a), alpha=ang(link.alpha))
        for key, text in written[i - 1].items():  # "l1 = 0.5" where the file says l1
            cells[key] = f"{text} = {cells[key]}"
        rows.append((str(i), link.type, *cells.values(), lim_text + free))
    return rows


def _written(robot: Robot) -> list[dict[str, str]]:
    """Per joint, the DH entries the robot file writes with parameter names (``d: l1``).

    Only for rows the robot still has as written (a robot changed since it was read
    is shown by its numbers alone).
    """
    from kinematica.robot.save import spec_from_robot

    spec = spec_from_robot(robot)
    names = set(spec.parameters)
    out: list[dict[str, str]] = []
    for joint in spec.joints:
        named = {
            key: text
            for key, text in joint.expr.items()
            if key in ("theta", "d", "a", "alpha")
            and names & set(re.findall(r"[A-Za-z_]\w*", str(text)))
        }
        out.append(named)
    return out


def _pose_ik(robot: Robot) -> dict[str, Any]:
    """The solver ``robot.ik`` gives the arm's pose targets (``show``'s JSON key ``ik.pose``)."""
    from kinematica.ik.choice import pose_choice

    choice = pose_choice(robot.chain, robot.joint_names)
    return {
        "method": choice.method,
        "parameter": choice.parameter,
        "complete": choice.complete,
        "reason": choice.reason,
    }


def _pose_ik_lines(solver: dict[str, Any]) -> list[str]:
    """``IK of poses: analytic:spherical-wrist (closed form: every solution)`` and the like."""
    from kinematica.ik.local_search import LOCAL_SEARCH

    method, parameter, reason = solver["method"], solver["parameter"], solver["reason"]
    if reason is not None:
        return [f"IK of poses: {method} ({LOCAL_SEARCH})", f"  no closed form applies: {reason}"]
    what = "every solution" if solver["complete"] else "exact solutions, maybe not all"
    if parameter is not None:
        what += f" with {parameter} held at a value, its redundancy parameter"
    lines = [f"IK of poses: {method} (closed form: {what})"]
    if not solver["complete"]:
        lines.append(
            "  the axes have its structure only to within the line geometry's tolerances; "
            "a target it misses is searched numerically"
        )
    return lines


def show(args: argparse.Namespace) -> int:
    """``kinematica show ROBOT``: DH table, limits, structure, the IK solver of pose targets."""
    robot = robot_from_args(args)
    from kinematica.robot.structure import classify

    structure = classify(robot)
    solver = _pose_ik(robot)
    if args.json:
        dh = robot.dh_table()  # theta, d, a, alpha at q = 0, in rad and m
        angles = dh[:, [0, 3]] if args.rad else np.rad2deg(dh[:, [0, 3]])
        lengths = lengths_out(dh[:, [1, 2]], robot, args)
        table_out = np.column_stack([angles[:, 0], lengths[:, 0], lengths[:, 1], angles[:, 1]])
        dump(
            {
                "robot": robot.name,
                "convention": robot.convention,
                "joints": robot.joint_types,
                "structure": {"kind": structure.kind, "summary": structure.summary},
                "ik": {"pose": solver},
                "units": units(robot, args),
                "dh": [
                    dict(zip(("theta", "d", "a", "alpha"), r, strict=True))
                    for r in clean(table_out)
                ],
                "qlim": clean(q_out(robot, robot.qlim.T, args).T),
                "base": clean(transform_out(robot.base, robot, args)),
                "tool": clean(transform_out(robot.tool, robot, args)),
                "description": robot.description,
            }
        )
        return 0
    a_name, alpha_name = (
        ("a(i-1)", "alpha(i-1)") if robot.convention == "modified" else ("a", "alpha")
    )
    metres = length_unit(robot, args)
    print(f"{plain(robot.name)}: {structure.summary}")
    print(f"{robot.dof} joints ({robot.joint_types}), {robot.convention} DH convention")
    for line in _pose_ik_lines(solver):
        print(plain(line))
    if robot.description:
        print(plain(robot.description.strip()))
    print()
    print(
        table(
            ("i", "type", "theta", f"d ({metres})", f"{a_name} ({metres})", alpha_name, "limits"),
            _dh_rows(robot, args),
        )
    )
    unit = "rad" if args.rad else "deg"
    for what, T in (("base", robot.base), ("tool", robot.tool)):
        if not np.array_equal(T, np.eye(4)):
            T_out = transform_out(T, robot, args)
            pos, eul, _ = _pose_parts(T_out, args)
            print(
                f"\n{what}: xyz = {', '.join(fmt(v) for v in pos)} {metres}, "
                f"euler {args.euler} = {', '.join(fmt(v, 4) for v in eul)} {unit}"
            )
            print(matrix(T_out))
    return 0


def _pose_parts(T: FloatArray, args: argparse.Namespace) -> tuple[FloatArray, FloatArray, bool]:
    eul = euler_from_matrix(T[:3, :3], args.euler, degrees=not args.rad)
    return T[:3, 3], eul, bool(gimbal_locked(T[:3, :3], args.euler))


def fk(args: argparse.Namespace) -> int:
    """``kinematica fk ROBOT --q ...``: T, position and Euler angles."""
    robot = robot_from_args(args)
    q = q_in(robot, args.q, args, "q")
    T = transform_out(robot.fk(q), robot, args)
    pos, eul, locked = _pose_parts(T, args)
    frames = transform_out(robot.fk(q, all_frames=True), robot, args) if args.frames else None
    if args.json:
        out: dict[str, Any] = {
            "robot": robot.name,
            "q": list(args.q),
            "units": units(robot, args),
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
    unit, metres, digits = ("rad" if args.rad else "deg"), length_unit(robot, args), args.precision
    print(f"{plain(robot.name)}, q = [{', '.join(num(v, digits) for v in args.q)}]")
    print(f"units: {unit} for angles, {metres} for lengths")
    if frames is not None:
        has_tool = not np.array_equal(robot.tool, np.eye(4))
        for i, F in enumerate(frames):
            tool = " (with tool)" if i == robot.dof and has_tool else ""
            label = "0T0 (base)" if i == 0 else f"0T{i}{tool}"
            print(f"\n{label}:\n{matrix(F, precision=digits)}")
    print(f"\nT:\n{matrix(T, precision=digits)}")
    xyz = "  ".join(f"{c} = {num(v, digits)}" for c, v in zip("xyz", pos, strict=True))
    print(f"\nposition ({metres}):  {xyz}")
    note = "  (gimbal lock: third angle set to 0)" if locked else ""
    print(f"euler {args.euler} ({unit}):  " + "  ".join(num(v, digits) for v in eul) + note)
    return 0


def register(sub: Any) -> None:
    """Add ``robots``, ``show``, ``fk`` and ``ik`` to the subparsers ``sub``."""
    p = sub.add_parser("robots", help="list the built-in robot models")
    add_common(p, numbers=False)  # --euler/--rad/--units accepted, not offered: no numbers here
    p.set_defaults(run=robots)

    p = sub.add_parser(
        "show", help="DH table, limits and structure of a robot, and its IK solver of poses"
    )
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
        "--rad), the length unit (see --units) for prismatic joints",
    )
    p.add_argument("--frames", action="store_true", help="print every frame 0Ti")
    add_precision(p)
    add_common(p)
    p.set_defaults(run=fk)

    p = sub.add_parser("ik", help="inverse kinematics: every solution, one row each")
    add_robot(p)
    pose_target_args(p, position=True)
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
    p.add_argument(
        "--fixed",
        metavar="JOINT=VALUE",
        help="hold one joint at a value and give every solution there: JOINT is q1..qN "
        "(1-based, as the tables show) or the joint's name (URDF), VALUE in degrees (--rad: "
        "radians) or the length unit; e.g. --fixed q7=30. A 7-joint arm without it holds a "
        "parameter itself (an SRS arm's arm angle, else a joint whose locked arm has a closed "
        "form; at --q0's value, else the default or the nearest value with a solution) and "
        "prints which",
    )
    p.add_argument(
        "--seed", type=parse_seed, default=0, help="seed of numeric restarts (default 0)"
    )
    p.add_argument(
        "--arm-angle",
        type=float,
        metavar="PSI",
        help="SRS 7R arms (iiwa type): all 8 solutions at this arm angle (degrees, or "
        "radians with --rad): about the shoulder-wrist line, from the plane of that line "
        "and axis 1 to the elbow",
    )
    p.add_argument(
        "--tol",
        nargs="+",
        type=float,
        metavar="TOL",
        help="acceptance tolerance: position in the length unit, then rotation in the angle "
        "unit; one number: the position, and its value in metres as radians for the "
        "rotation; default 1e-10 m and 1e-10 rad",
    )
    p.add_argument(
        "--steps",
        action="store_true",
        help="a 6-joint arm with a spherical wrist: print the decoupling step by step (the "
        "wrist centre p_m, the arm solutions q1-q3, R03, R36 = R03^T R06, the wrist "
        "solutions q4-q6), every solution, also outside the limits",
    )
    add_precision(p)
    add_common(p)
    p.set_defaults(run=ik)
