"""Subcommands ``robots``, ``show``, ``fk`` and ``ik``: the robot and its kinematics."""

from __future__ import annotations

import argparse
import math
import re
import sys
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from kinematica.cli.format import fmt, matrix, num, plain, table
from kinematica.cli.options import (
    PER_METRE,
    add_common,
    add_pose,
    add_precision,
    add_robot,
    clean,
    dump,
    finite,
    fixed_in,
    joint_value_out,
    length_unit,
    lengths_in,
    lengths_out,
    q_in,
    q_out,
    robot_from_args,
    transform_in,
    transform_out,
    units,
)
from kinematica.errors import ArgumentError
from kinematica.robot import Robot, load
from kinematica.spatial import euler_from_matrix, from_pose, gimbal_locked

if TYPE_CHECKING:  # the IK layer loads when `ik` runs: `fk` never imports it
    from kinematica.ik import IKResult

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


def target_in(robot: Robot, args: argparse.Namespace) -> FloatArray:
    """The target in metres; library messages about it name the option it came from."""
    if getattr(args, "position", None) is not None:
        args.aliases = {"target position": "--position", "target": "--position"}
        return lengths_in(finite(args.position, "--position"), robot, args)
    if args.matrix is not None:
        args.aliases = {"target": "--matrix"}
        return transform_in(finite(args.matrix, "--matrix").reshape(4, 4), robot, args)
    args.aliases = {"target": "--pose"}
    pose = finite(args.pose, "--pose")
    pose[:3] = lengths_in(pose[:3], robot, args)
    return from_pose(pose, euler=args.euler, degrees=not args.rad)


def _precision(robot: Robot, args: argparse.Namespace) -> tuple[float, float] | None:
    """The precision the typed pose carries (position m, rotation entries), if printed.

    ``--matrix`` numbers as typed; ``--pose``: its lengths, and its angles, an error
    of δ (rad) in each of three moving a rotation's entries by at most 3δ.
    """
    typed = args.matrix if args.matrix is not None else args.pose
    if typed is None:
        return None
    from kinematica.ik.printed import half_unit, printed_digits

    digits = printed_digits(np.asarray(typed, dtype=float))
    if digits is None:
        return None
    if args.matrix is not None:
        m = np.asarray(args.matrix, dtype=float).reshape(4, 4)[:3]
        position, rotation = m[:, 3], half_unit(m[:, :3], digits)
    else:
        pose = np.asarray(args.pose, dtype=float)
        angle = half_unit(pose[3:], digits)
        position, rotation = pose[:3], 3.0 * (angle if args.rad else math.radians(angle))
    metres = float(lengths_in(half_unit(position, digits), robot, args))
    return metres, rotation


def _headline(status: str, message: str) -> str:
    """``status — message``, or the message alone when it already opens with the status."""
    if message.startswith((f"{status.replace('_', ' ')}:", f"{status.replace('_', ' ')} with ")):
        return plain(message)  # it names its status already: "singular: infinitely many ..."
    return f"{status} — {plain(message)}"


def ik(args: argparse.Namespace) -> int:
    """``kinematica ik ROBOT --pose ...``: every solution, one row each."""
    from kinematica.ik import IKOptions, IKResult

    robot = robot_from_args(args)
    target = target_in(robot, args)
    if args.steps:
        from kinematica.cli.steps import print_steps

        return print_steps(robot, target, args)
    q0 = None if args.q0 is None else q_in(robot, args.q0, args, "q0")
    tol = _tolerance(robot, args)
    arm_angle = args.arm_angle
    if arm_angle is not None and not args.rad:
        arm_angle = math.radians(arm_angle)
    options = IKOptions(
        method=args.method,
        tol=tol,
        respect_limits=not args.ignore_limits,
        q0=q0,
        seed=args.seed,
        precision=_precision(robot, args),
        fixed=None if args.fixed is None else fixed_in(robot, args.fixed, args),
        arm_angle=arm_angle,
    )
    res = robot.ik(target, options=options)
    assert isinstance(res, IKResult)
    solved = res.success
    for note in res.notes:  # e.g. a rotation projected onto SO(3): said on stderr too,
        if args.json or note not in res.message:  # unless the headline below says it
            print(f"kinematica: note: {plain(note)}", file=sys.stderr)
    if args.json:
        dump(
            {
                "robot": robot.name,
                "status": res.status,
                "method": res.method,
                "message": res.message,
                "units": units(robot, args),
                "solutions": clean(q_out(robot, res.solutions, args)),
                "branches": list(res.branches),
                "letters": list(res.letters),
                "residuals": {
                    "position_m": clean(res.residuals[:, 0]),
                    "rotation_rad": clean(res.residuals[:, 1]),
                },
                "out_of_limits": clean(q_out(robot, res.out_of_limits, args)),
                "out_of_limits_branches": list(res.out_of_limits_branches),
                "free_joints": list(res.free_names),
                "gap_m": res.gap,
                "notes": list(res.notes),
                "parameter": _parameter(robot, res, args),
                "tolerance": (
                    None if tol is None else {"position_m": tol[0], "rotation_rad": tol[1]}
                ),
            }
        )
        return 0 if solved else 1
    print(f"{plain(robot.name)}: {_headline(res.status, res.message)}")
    unit, metres = ("rad" if args.rad else "deg"), length_unit(robot, args)
    print(f"units: {unit} for angles, {metres} for lengths")
    held = _parameter(robot, res, args)
    if held is not None:
        print(f"parameter: {held['name']} = {num(held['value'], args.precision)} {held['unit']}")
    header = ("#", *(f"q{i}" for i in range(1, robot.dof + 1)), "branch", "error (m, rad)")

    def rows(
        sol: FloatArray, branches: tuple[str, ...], resid: FloatArray | None
    ) -> list[tuple[str, ...]]:
        out = []
        for k, (q, b) in enumerate(zip(q_out(robot, sol, args), branches, strict=True), start=1):
            err = "" if resid is None else f"{resid[k - 1, 0]:.1e}, {resid[k - 1, 1]:.1e}"
            out.append((str(k), *(num(v, args.precision) for v in q), plain(b), err))
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


def _parameter(robot: Robot, res: IKResult, args: argparse.Namespace) -> dict[str, Any] | None:
    """The parameter held for this answer (a joint, an arm angle), in the CLI's units, or None."""
    if res.parameter is None:
        return None
    name, value = res.parameter
    if name not in robot.joint_names:  # an SRS arm's arm angle: an angle, no joint
        angle = float(value) if args.rad else math.degrees(float(value))
        return {"name": name, "joint": None, "value": angle, "unit": "rad" if args.rad else "deg"}
    joint = robot.joint_names.index(name)
    unit = length_unit(robot, args) if robot.is_prismatic[joint] else ("rad" if args.rad else "deg")
    return {
        "name": name,
        "joint": f"q{joint + 1}",
        "value": joint_value_out(robot, joint, value, args),
        "unit": unit,
    }


def _tolerance(robot: Robot, args: argparse.Namespace) -> tuple[float, float] | None:
    """``--tol P [R]`` in SI: P in the length unit, R in the angle unit (R = P when left out)."""
    if args.tol is None:
        return None
    if len(args.tol) > 2:
        raise ArgumentError(f"--tol takes 1 or 2 numbers (position, rotation), got {len(args.tol)}")
    position = float(args.tol[0]) / PER_METRE[length_unit(robot, args)]
    if len(args.tol) == 1:
        return position, position
    rotation = float(args.tol[1]) if args.rad else math.radians(float(args.tol[1]))
    return position, rotation


def _seed(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        value = -1
    if value < 0:
        raise argparse.ArgumentTypeError(f"expected a whole number >= 0, got {text!r}")
    return value


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
    p.add_argument("--seed", type=_seed, default=0, help="seed of numeric restarts (default 0)")
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


def pose_target_args(p: argparse.ArgumentParser, position: bool = False) -> None:
    """The target options, one required: ``--pose``, ``--matrix`` (``--position`` if asked)."""
    target = p.add_mutually_exclusive_group(required=True)
    add_pose(target, "position (length unit, see --units) and three Euler angles (see --euler)")
    target.add_argument(
        "--matrix",
        nargs=16,
        type=float,
        metavar="M",
        help="the 4x4 pose, 16 numbers row by row (translation in the length unit)",
    )
    if position:
        target.add_argument(
            "--position",
            nargs=3,
            type=float,
            metavar=("X", "Y", "Z"),
            help="position only (length unit): orientation left free",
        )
