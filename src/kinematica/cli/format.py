"""Plain-text formatting for the command line: numbers, matrices, tables."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["fmt", "matrix", "table"]

#: Values closer to zero than this print as 0 (avoids "-0" and "1e-17" noise).
PRINT_ZERO = 5e-13


def fmt(value: float, digits: int = 6) -> str:
    """A number with ``digits`` significant decimals, without ``-0`` noise."""
    v = float(value)
    if abs(v) < PRINT_ZERO:
        v = 0.0
    text = f"{v:.{digits}f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def matrix(M: ArrayLike, digits: int = 6, indent: str = "  ") -> str:
    """A matrix as aligned rows."""
    rows = [[fmt(v, digits) for v in row] for row in np.asarray(M, dtype=float)]
    width = max(len(c) for row in rows for c in row)
    return "\n".join(indent + "  ".join(c.rjust(width) for c in row) for row in rows)


def table(header: Sequence[str], rows: Sequence[Sequence[str]], indent: str = "  ") -> str:
    """A left-aligned text table with a header rule."""
    cols = [header, *rows]
    widths = [max(len(str(r[i])) for r in cols) for i in range(len(header))]
    line = lambda r: indent + "  ".join(str(c).ljust(w) for c, w in zip(r, widths, strict=True))  # noqa: E731
    rule = indent + "  ".join("-" * w for w in widths)
    return "\n".join([line(header).rstrip(), rule, *(line(r).rstrip() for r in rows)])
