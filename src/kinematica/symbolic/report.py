"""``report(robot, format=, lang=)``: the whole derivation a student reads.

The DH table, each row's four elementary transforms and its link matrix, T,
the position and orientation equations in short notation, the geometric
method where the seeds use it, and the inverse kinematics derived step by
step for the classes with a textbook closed form.
"""

from __future__ import annotations

from typing import Final

from kinematica.symbolic.document import build
from kinematica.symbolic.model import RobotLike, SymbolicError, symbolic_robot
from kinematica.symbolic.phrases import LANGS
from kinematica.symbolic.render import FORMATS, render

__all__ = ["report"]

_ALIASES: Final = {"md": "markdown", "tex": "latex", "htm": "html"}


def report(robot: RobotLike, format: str = "markdown", lang: str = "es") -> str:
    """A step-by-step derivation of a robot's kinematics, as a document.

    Args:
        robot: A ``Robot`` (numbers stay numbers), a built-in name or a
            robot-file path (named parameters stay symbols).
        format: ``"markdown"``, ``"latex"`` (a complete amsmath document) or
            ``"html"`` (one self-contained page, mathematics in MathML).
        lang: ``"es"`` (the seeds' Spanish) or ``"en"``.

    Returns:
        The document's text.

    Raises:
        SymbolicError: unknown format or language.
        UnknownRobotError, RobotFileError: the robot cannot be read.
    """
    fmt = _ALIASES.get(str(format).lower(), str(format).lower())
    if fmt not in FORMATS:
        raise SymbolicError(
            f"unknown report format {format!r}: expected one of {', '.join(FORMATS)}"
        )
    language = str(lang).lower()
    if language not in LANGS:
        raise SymbolicError(f"unknown report language {lang!r}: expected one of {', '.join(LANGS)}")
    model = symbolic_robot(robot)
    return render(build(model, language), fmt, language)
