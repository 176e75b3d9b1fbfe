"""The ``kinematica`` command: parse, call the library, print, exit.

Exit codes: 0 success; 1 the question has no answer (IK unreachable, every
solution outside the limits, not found); 2 bad input or usage, reported in one
line on stderr without a traceback.
"""

from __future__ import annotations

import argparse
import re
import sys
from collections.abc import Sequence
from typing import Any, NoReturn

from kinematica.cli import commands
from kinematica.errors import KinematicaError

__all__ = ["main"]

EXIT_OK, EXIT_NO_ANSWER, EXIT_BAD_INPUT = 0, 1, 2


# argparse reads "-1e-05" as an option, not a negative number (its own pattern
# has no exponent); joint values and matrices printed by programs often use one.
_NEGATIVE_NUMBER = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")


class _Parser(argparse.ArgumentParser):
    """argparse with one-line errors, exit code 2, and negative numbers in e-notation."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = _NEGATIVE_NUMBER

    def error(self, message: str) -> NoReturn:
        self.exit(EXIT_BAD_INPUT, f"{self.prog}: error: {message} (see --help)\n")


def _common(p: argparse.ArgumentParser) -> None:
    p.add_argument("--json", action="store_true", help="machine-readable output (stable keys)")
    p.add_argument(
        "--euler",
        default="ZYZ",
        metavar="SEQ",
        help="Euler sequence, scipy naming: upper case intrinsic (ZYZ, XYZ...), "
        "lower case extrinsic (zyz, xyz...); default ZYZ",
    )
    p.add_argument("--rad", action="store_true", help="angles in radians (default degrees)")


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of every subcommand."""
    parser = _Parser(
        prog="kinematica",
        description="Kinematics of serial robot manipulators: DH tables, forward "
        "kinematics, every inverse-kinematics solution.",
    )
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    sub.required = True

    p = sub.add_parser("robots", help="list the built-in robot models")
    _common(p)  # --euler/--rad accepted on every command; this one prints no angles
    p.set_defaults(run=commands.robots)

    p = sub.add_parser("show", help="DH table, limits and structure of a robot")
    p.add_argument("robot", metavar="ROBOT", help="built-in name or robot file")
    _common(p)
    p.set_defaults(run=commands.show)

    p = sub.add_parser("fk", help="forward kinematics: T, position and Euler angles")
    p.add_argument("robot", metavar="ROBOT", help="built-in name or robot file")
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
    _common(p)
    p.set_defaults(run=commands.fk)

    p = sub.add_parser("ik", help="inverse kinematics: every solution, one row each")
    p.add_argument("robot", metavar="ROBOT", help="built-in name or robot file")
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
    _common(p)
    p.set_defaults(run=commands.ik)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit code.

    Args:
        argv: Arguments without the program name; ``sys.argv[1:]`` if None.
    """
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return int(args.run(args))
    except KinematicaError as exc:
        print(f"kinematica: error: {exc}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except BrokenPipeError:  # e.g. `kinematica robots | head -1`
        return EXIT_OK


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
