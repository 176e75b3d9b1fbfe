"""Text from robot files shown literally in Markdown (reports of derivations and designs).

Names come from robot files and URDFs, which are not trusted to hold markup: in a
report they are escaped so that any renderer (CommonMark, GitHub, Jupyter, one that
passes HTML through) shows them as written.
"""

from __future__ import annotations

import re
from typing import Final

__all__ = ["markdown_code", "markdown_text"]

#: The characters that start markup, escaped with a backslash (CommonMark escapes any
#: ASCII punctuation so); ``<``, ``>`` and ``&`` as entities, so that a renderer passing
#: HTML through gets none; line breaks as spaces (a name is one line).
_ESCAPES: Final = {
    **{ch: "\\" + ch for ch in "\\`*_[]{}#!|~$"},
    "<": "&lt;",
    ">": "&gt;",
    "&": "&amp;",
    "\n": " ",
    "\r": " ",
}


def markdown_text(text: str) -> str:
    """``text`` as Markdown that shows it literally, on one line."""
    return "".join(_ESCAPES.get(ch, ch) for ch in text)


def markdown_code(text: str) -> str:
    """``text`` as an inline code span (a file name), on one line.

    Fenced by more backticks than any run of them in it, so that nothing in it ends the
    span; inside a code span every other character is shown as it is.
    """
    one_line = text.replace("\r", " ").replace("\n", " ")
    longest = max((len(run) for run in re.findall(r"`+", one_line)), default=0)
    fence = "`" * (longest + 1)
    pad = " " if one_line.startswith("`") or one_line.endswith("`") else ""
    return f"{fence}{pad}{one_line}{pad}{fence}"
