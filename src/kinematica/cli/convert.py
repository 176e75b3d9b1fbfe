"""Subcommand ``convert``: a robot as URDF, a DH table by the rules, a robot file, or C++."""

from __future__ import annotations

import argparse
import dataclasses
from pathlib import Path
from typing import TYPE_CHECKING, Any

from kinematica.cli.options import add_common, add_robot, dump, robot_from_args
from kinematica.errors import RobotFileError
from kinematica.io.atomic import unchanged, write_text_atomic
from kinematica.io.reading import URDF_SUFFIXES

if TYPE_CHECKING:  # the library's modules load when the command runs
    from kinematica.dh import FrameRule
    from kinematica.robot import Robot

__all__ = ["FORMATS", "convert", "register"]

#: What ``--to`` accepts.
FORMATS = ("urdf", "dh-standard", "dh-modified", "yaml", "cpp")


def _extract(args: argparse.Namespace, convention: str) -> tuple[Robot, tuple[FrameRule, ...]]:
    """The robot's DH table by the rules, read from the URDF itself when it is one."""
    if Path(args.robot).name.lower().endswith(URDF_SUFFIXES):
        from kinematica.robot.urdf import urdf_to_dh

        ext = urdf_to_dh(args.robot, base=args.base, tip=args.tip, convention=convention)
    else:
        ext = robot_from_args(args).to_dh(convention)
    return ext.robot, ext.rules


def _robot_file(robot: Robot, suffix: str, rad: bool, rules: tuple[FrameRule, ...]) -> str:
    units = {"angle": "rad" if rad else "deg", "length": "m"}
    from kinematica.io.robotfile import dumps_robot_file
    from kinematica.robot.rounding import rounded_spec
    from kinematica.robot.save import spec_from_robot

    spec = dataclasses.replace(spec_from_robot(robot), units=units)
    if rules:  # --to dh-*: the DH table asked for, not the arm's own transforms beside it
        spec = dataclasses.replace(spec, chain=None)
    # an extracted table is written as a user reads it: its round-off within the line tolerances
    spec = rounded_spec(spec)
    text = dumps_robot_file(spec, suffix)
    if rules and suffix.lower() in (".yaml", ".yml", ".toml"):
        head = [f"# {robot.convention} DH frames placed by the Denavit-Hartenberg rules:"]
        text = "\n".join([*head, *(f"#   {r}" for r in rules)]) + "\n" + text
    return text


def convert(args: argparse.Namespace) -> int:
    """``kinematica convert ROBOT --to FORMAT [-o FILE]``."""
    rules: tuple[FrameRule, ...] = ()
    suffix = Path(args.output).suffix if args.output else ".yaml"
    if args.to == "urdf":
        robot = robot_from_args(args)
        text = robot.to_urdf()
    elif args.to == "cpp":
        robot = robot_from_args(args)
        from kinematica.robot.export_cpp import cpp_header

        text = cpp_header(robot)
    else:
        if args.to == "yaml":
            robot = robot_from_args(args)
        else:
            robot, rules = _extract(args, args.to.removeprefix("dh-"))
        text = _robot_file(robot, suffix, args.rad, rules)
    if args.output:
        path = Path(args.output)
        try:
            write_text_atomic(path, text)
        except OSError as exc:
            raise RobotFileError(
                f"cannot write the file: {exc.strerror or exc}; {unchanged(path)}", path=str(path)
            ) from exc
    if args.json:
        out: dict[str, Any] = {
            "robot": robot.name,
            "to": args.to,
            "convention": robot.convention,
            "output": args.output,
            "text": text,
            "rules": [{"frame": r.frame, "rule": r.rule, "text": r.text} for r in rules],
        }
        dump(out)
    elif args.output:
        print(f"wrote {args.output}: {robot.name} as {args.to}")
        for r in rules:
            print(f"  {r}")
    else:
        print(text, end="")
    return 0


def register(sub: Any) -> None:
    """Add ``convert`` to the subparsers ``sub``."""
    p = sub.add_parser(
        "convert",
        help="a robot as URDF, as a DH table by the rules (standard or modified), as YAML, "
        "or as a C++ header of its chain and closed-form IK solver",
    )
    add_robot(p)
    p.add_argument(
        "--to",
        required=True,
        choices=FORMATS,
        help="urdf: URDF text; dh-standard, dh-modified: the DH table read off the joint "
        "axes by the rules, as a robot file; yaml: the robot file as it is; cpp: a C++ "
        "header (the core's solver filled for this robot, for a C++ program)",
    )
    p.add_argument(
        "-o",
        "--output",
        metavar="FILE",
        help="write to FILE instead of printing; for robot files its suffix picks the "
        "format (.yaml, .yml, .json, .toml)",
    )
    add_common(p)
    p.set_defaults(run=convert)
