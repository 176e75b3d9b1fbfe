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

from kinematica.cli import derive, kinematics
from kinematica.errors import KinematicaError

__all__ = ["main"]

EXIT_OK, EXIT_NO_ANSWER, EXIT_BAD_INPUT = 0, 1, 2

#: The modules of subcommands, each with ``register(subparsers)``, in help order.
COMMAND_MODULES = (kinematics, derive)


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


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of every subcommand."""
    parser = _Parser(
        prog="kinematica",
        description="Kinematics of serial robot manipulators: DH tables, forward "
        "kinematics, every inverse-kinematics solution.",
    )
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    sub.required = True

    for module in COMMAND_MODULES:
        module.register(sub)
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
