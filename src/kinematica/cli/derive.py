"""Subcommand ``derive``: the symbolic derivation of a robot, as a report.

sympy is imported only when the command runs, so that the other commands (and
``import kinematica``) never load it.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from kinematica.cli.options import add_common, add_robot, dump, robot_from_args, urdf_options
from kinematica.errors import KinematicaError
from kinematica.io.atomic import unchanged, write_text_atomic

__all__ = ["derive", "register"]

FORMATS = ("markdown", "latex", "html")
LANGS = ("es", "en")


def derive(args: argparse.Namespace) -> int:
    """``kinematica derive ROBOT``: DH table, link matrices, T, equations, inverse kinematics."""
    try:
        from kinematica.symbolic import report
    except ImportError as exc:
        raise KinematicaError(
            "kinematica derive needs sympy: pip install 'kinematica[symbolic]'"
        ) from exc
    # By name, a robot file's named lengths stay symbols; a URDF asked with its
    # own options (--base, --tip, --xacro, --package...) is loaded first (numbers only
    # either way).
    source = robot_from_args(args) if urdf_options(args) else args.robot
    text = report(source, format=args.format, lang=args.lang)
    if args.output is not None:
        path = Path(args.output)
        try:
            write_text_atomic(path, text)
        except OSError as exc:
            raise KinematicaError(
                f"cannot write {path}: {exc.strerror or exc}; {unchanged(path)}"
            ) from exc
    if args.json:
        dump(
            {
                "robot": args.robot,
                "format": args.format,
                "lang": args.lang,
                "output": None if args.output is None else str(args.output),
                "report": None if args.output is not None else text,
            }
        )
    elif args.output is None:
        sys.stdout.write(text)
    else:
        print(f"wrote {args.output} ({args.format}, {args.lang})")
    return 0


def register(sub: Any) -> None:
    """Add ``derive`` to the subparsers ``sub``."""
    p = sub.add_parser(
        "derive",
        help="symbolic derivation: DH matrices, T, position equations, inverse kinematics",
    )
    add_robot(p)
    p.add_argument("--format", choices=FORMATS, default="markdown", help="default markdown")
    p.add_argument("--lang", choices=LANGS, default="es", help="es (default) or en")
    p.add_argument("-o", "--output", metavar="FILE", help="write the report to FILE")
    add_common(p)
    p.set_defaults(run=derive)
