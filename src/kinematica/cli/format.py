"""Plain-text formatting for the command line: numbers, matrices, tables, safe text."""

from __future__ import annotations

import math
import unicodedata
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

__all__ = [
    "DEFAULT_PRECISION",
    "PRINTED_ROWS",
    "fmt",
    "json_numbers",
    "matrix",
    "num",
    "plain",
    "printed_rows",
    "table",
]

#: Values closer to zero than this print as 0 (avoids "-0" and "1e-17" noise).
PRINT_ZERO = 5e-13

#: Significant digits of numbers in the text output of ``fk`` and ``ik``
#: (``--precision``). Ten digits put a printed rotation matrix within 1e-10 of
#: orthonormal, so that ``fk`` output pasted into ``ik --matrix`` is accepted
#: and solved back to the configuration it came from.
DEFAULT_PRECISION = 10

#: Below this magnitude (and at or above ``_BIG``), :func:`num` uses e-notation.
_SMALL, _BIG = 1e-6, 1e15


def fmt(value: float, digits: int = 6) -> str:
    """A number with at most ``digits`` decimals, without ``-0`` noise."""
    v = float(value)
    if not math.isfinite(v):
        return str(v)
    if abs(v) < PRINT_ZERO:
        v = 0.0
    text = f"{v:.{digits}f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def num(value: float, precision: int = DEFAULT_PRECISION) -> str:
    """A number with at most ``precision`` significant digits, as short as possible.

    ``0.5`` prints ``0.5``, ``cos(45°)`` prints ``0.7071067812`` (precision 10);
    magnitudes below 1e-6 or from 1e15 up use e-notation; values within
    ``PRINT_ZERO`` of zero print ``0``; NaN and infinities print ``nan``,
    ``inf``, ``-inf``.
    """
    v = float(value)
    if not math.isfinite(v):
        return str(v)
    if abs(v) < PRINT_ZERO:
        return "0"
    if _SMALL <= abs(v) < _BIG:
        return np.format_float_positional(
            v, precision=precision, unique=True, fractional=False, trim="-"
        )
    return np.format_float_scientific(v, precision=precision - 1, unique=True, trim="-")


def matrix(M: ArrayLike, digits: int = 6, indent: str = "  ", precision: int | None = None) -> str:
    """A matrix as aligned rows: ``digits`` decimals, or ``precision`` significant digits."""
    show: Callable[[float], str] = (
        (lambda v: fmt(v, digits)) if precision is None else (lambda v: num(v, precision))
    )
    rows = [[show(v) for v in row] for row in np.asarray(M, dtype=float)]
    width = max(len(c) for row in rows for c in row)
    return "\n".join(indent + "  ".join(c.rjust(width) for c in row) for row in rows)


def table(header: Sequence[str], rows: Sequence[Sequence[str]], indent: str = "  ") -> str:
    """A left-aligned text table with a header rule."""
    cols = [header, *rows]
    widths = [max(len(str(r[i])) for r in cols) for i in range(len(header))]
    line = lambda r: indent + "  ".join(str(c).ljust(w) for c, w in zip(r, widths, strict=True))  # noqa: E731
    rule = indent + "  ".join("-" * w for w in widths)
    return "\n".join([line(header).rstrip(), rule, *(line(r).rstrip() for r in rows)])


# Control characters (ESC starts terminal escape sequences), invisible format
# characters (bidirectional overrides), line and paragraph separators.
_UNSAFE_CATEGORIES = frozenset({"Cc", "Cf", "Zl", "Zp", "Cs"})


def plain(text: object) -> str:
    r"""``text`` safe to print on a terminal, on one line.

    Control characters, line breaks and invisible formatting characters (a
    robot name holding ``ESC[2J`` or a newline, say) are shown as escapes
    (``\x1b``, ``\n``) instead of acting on the terminal.
    """
    s = str(text)
    if all(ch.isprintable() for ch in s):  # the common case, and fast
        return s
    return "".join(
        ch.encode("unicode_escape").decode("ascii")
        if unicodedata.category(ch) in _UNSAFE_CATEGORIES
        else ch
        for ch in s
    )


def json_numbers(a: Any) -> Any:
    """Nested lists for JSON: NaN/inf as null, tiny values as 0."""
    if isinstance(a, np.ndarray):
        return json_numbers(a.tolist())
    if isinstance(a, list | tuple):
        return [json_numbers(v) for v in a]
    if isinstance(a, float):
        if not math.isfinite(a):
            return None
        return 0.0 if abs(a) < 5e-16 else a
    return a


#: Rows of a sampled trajectory printed as text (every k-th sample, and the last).
PRINTED_ROWS = 12


def printed_rows(count: int) -> tuple[list[int], int]:
    """``(indices, step)`` of the samples printed of ``count``: every step-th, and the last."""
    step = max(1, math.ceil(count / PRINTED_ROWS))
    return sorted(set(range(0, count, step)) | {count - 1}), step
