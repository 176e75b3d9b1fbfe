"""The ``kinematica`` command: parse, call the library, print, exit.

Exit codes: 0 success; 1 the question has no answer (IK unreachable, every
solution outside the limits, not found); 2 bad input or usage, reported in one
line on stderr without a traceback. Warnings of the library (a value
implausible for its unit, say) print as one line each on stderr,
``kinematica: warning: ...``; numpy's floating-point RuntimeWarnings are
noise at the command line and print nothing.
"""

from __future__ import annotations

import argparse
import contextlib
import importlib
import math
import os
import re
import sys
import warnings
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from typing import Any, NoReturn, TextIO

import numpy as np

from kinematica import __version__
from kinematica.cli.format import plain
from kinematica.errors import KinematicaError, LimitWarning

__all__ = ["main"]

EXIT_OK, EXIT_NO_ANSWER, EXIT_BAD_INPUT = 0, 1, 2
EXIT_INTERRUPTED = 130  # 128 + SIGINT, as shells report Ctrl-C

#: The modules of subcommands (in kinematica.cli), each with ``register(subparsers)``, in
#: help order.
COMMAND_MODULES = (
    "kinematics",
    "self_motion",
    "analysis",
    "motion",
    "control",
    "viz",
    "derive",
    "convert",
    "design",
    "calibrate",
    "reach",
    "place",
)

#: Each command and the module that registers it: a command line naming one imports and
#: registers that module alone (tests/cli/test_main.py holds this equal to what the
#: modules register).
COMMANDS = {
    "robots": "kinematics",
    "show": "kinematics",
    "fk": "kinematics",
    "ik": "kinematics",
    "self-motion": "self_motion",
    "jacobian": "analysis",
    "workspace": "analysis",
    "trajectory": "motion",
    "control": "control",
    "plot": "viz",
    "animate": "viz",
    "view": "viz",
    "derive": "derive",
    "convert": "convert",
    "design": "design",
    "calibrate": "calibrate",
    "reach": "reach",
    "place": "place",
}

#: Where to report an internal error (a bug: every bad input has its own message).
REPORT = "please report it to the kinematica developers, with the command line"

# argparse reads "-1e-05" or "-inf" as an option, not a negative number (its own
# pattern has no exponent); joint values and matrices printed by programs often
# hold one, and "-inf" must reach the check that names the option.
_NEGATIVE_NUMBER = re.compile(
    r"^-(?:(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?|inf(?:inity)?|nan)$", re.IGNORECASE
)

#: The command line's option for each argument the library's errors name (``arg=``).
_OPTIONS = {
    "method": "--method",
    "tol": "--tol",
    "seed": "--seed",
    "q0": "--q0",
    "fixed": "--fixed",
    "parameter": "--parameter",
    "max_jump": "--max-jump",
    "precision": "--precision",
    "euler": "--euler",
    "units": "--units",
    "frame": "--frame",
    "samples": "--samples",
    "voxel": "--voxel",
    "at": "--at",
    "duration": "--duration",
    "dt": "--dt",
    "duration/dt": "--duration/--dt",
    "vmax": "--vmax",
    "amax": "--amax",
    "vmax/amax": "--vmax/--amax",
    "dpi": "--dpi",
    "size": "--size",
    "fps": "--fps",
    "max_frames": "--max-frames",
    "arm_angle": "--arm-angle",
    "resolution": "--resolution",
    "orientations": "--orientations",
    "region": "--region",
    "approach": "--approach",
    "half_angle": "--approach",
    "yaw": "--yaw",
    "workers": "--workers",
}


def cli_words(message: str, aliases: dict[str, str] | None = None) -> str:
    """A library message on one line, safe to print, its first words renamed.

    Args:
        message: The message of an error or warning.
        aliases: Words to replace at the start of the message (longest first), e.g.
            ``{"target": "--matrix"}``: what the library calls the argument that
            came from that option.
    """
    for word in sorted(aliases or {}, key=len, reverse=True):
        if message == word or message.startswith((f"{word} ", f"{word}:", f"{word},")):
            message = (aliases or {})[word] + message[len(word) :]
            break
    return plain(message)


def cli_error(exc: KinematicaError, aliases: dict[str, str] | None = None) -> str:
    """An error in command-line words: the option it is about, and its suggestion as one.

    Read from the error's structured fields (``arg``, ``suggest``), not its text.
    """
    words = dict(aliases or {})
    if exc.arg is not None and exc.arg not in words and exc.arg in _OPTIONS:
        words[exc.arg] = _OPTIONS[exc.arg]
    text = cli_words(exc.message, words)
    if exc.suggest is not None:
        name, value = exc.suggest
        text += f"; use {_OPTIONS.get(name, '--' + name.replace('_', '-'))} {plain(str(value))}"
    return text


class _Parser(argparse.ArgumentParser):
    """argparse with one-line errors, exit code 2, and negative numbers in e-notation."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = _NEGATIVE_NUMBER

    def error(self, message: str) -> NoReturn:
        self.exit(EXIT_BAD_INPUT, f"{self.prog}: error: {plain(message)} (see --help)\n")


def build_parser(command: str | None = None) -> argparse.ArgumentParser:
    """The argument parser of every subcommand, or of ``command``'s module alone.

    Args:
        command: The command the line names; None, or a name no module registers
            (a typo, ``--help``): every module, so that help and errors list them all.
    """
    parser = _Parser(
        prog="kinematica",
        description="Kinematics of serial robot manipulators: DH tables, forward "
        "kinematics, every inverse-kinematics solution.",
    )
    parser.add_argument("--version", action="version", version=f"kinematica {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    sub.required = True

    for name in (COMMANDS[command],) if command in COMMANDS else COMMAND_MODULES:
        importlib.import_module(f"kinematica.cli.{name}").register(sub)
    return parser


def _aliases(args: argparse.Namespace) -> dict[str, str]:
    """Words of library messages a command renames (``args.aliases``, set as it runs)."""
    aliases = getattr(args, "aliases", None)
    return aliases if isinstance(aliases, dict) else {}


@contextmanager
def _warnings_as_lines(stream: TextIO, args: argparse.Namespace) -> Iterator[None]:
    """Print each library warning once, as one line; silence floating-point noise."""
    shown: set[str] = set()

    def show(message: Warning | str, category: type[Warning], *_: Any, **__: Any) -> None:
        if not issubclass(category, UserWarning):  # RuntimeWarning, DeprecationWarning...
            return
        if isinstance(message, LimitWarning):  # in the command line's units, not rad and m
            from kinematica.cli.options import PER_METRE

            length = getattr(args, "length_shown", None) or getattr(args, "units", None) or "m"
            per_rad, angle = (1.0, "rad") if getattr(args, "rad", False) else (180 / math.pi, "deg")
            message = message.in_units(per_rad, angle, PER_METRE.get(length, 1.0), length)
        line = f"kinematica: warning: {cli_words(str(message), _aliases(args))}"
        if line not in shown:
            shown.add(line)
            print(line, file=stream)

    with warnings.catch_warnings(), np.errstate(all="ignore"):
        warnings.simplefilter("always")
        warnings.showwarning = show
        yield


def _printable_everywhere() -> None:
    """Characters the terminal cannot show (°, —, π on an ASCII terminal) print as escapes."""
    for stream in (sys.stdout, sys.stderr):
        reconfigure = getattr(stream, "reconfigure", None)
        if reconfigure is not None:
            with contextlib.suppress(ValueError, OSError):  # a stream that refuses
                reconfigure(errors="backslashreplace")


def _quiet_stdout() -> None:
    """After a broken pipe, send what is left of stdout nowhere (no error at exit)."""
    with contextlib.suppress(OSError, ValueError, AttributeError):  # not a real file (pytest)
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit code.

    Args:
        argv: Arguments without the program name; ``sys.argv[1:]`` if None.
    """
    _printable_everywhere()
    words = sys.argv[1:] if argv is None else list(argv)
    parser = build_parser(words[0] if words else None)
    args = parser.parse_args(words)
    try:
        with _warnings_as_lines(sys.stderr, args):
            return int(args.run(args))
    except KinematicaError as exc:
        print(f"kinematica: error: {cli_error(exc, _aliases(args))}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except BrokenPipeError:  # e.g. `kinematica robots | head -1`
        _quiet_stdout()
        return EXIT_OK
    except KeyboardInterrupt:  # Ctrl-C: the shell's convention, no traceback
        return EXIT_INTERRUPTED
    except Exception as exc:  # the last resort: a bug, reported in one line, no traceback
        what = plain(f"{type(exc).__name__}: {exc}")
        print(f"kinematica: internal error: {what}; {REPORT}", file=sys.stderr)
        return EXIT_BAD_INPUT


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
