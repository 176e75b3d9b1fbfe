"""HTML tables for notebooks: what ``_repr_html_`` of a robot or a result shows.

Every cell is escaped: names come from robot files and URDFs, which are not
trusted to hold markup.
"""

from __future__ import annotations

import html
import math
from collections.abc import Sequence

__all__ = ["html_table", "number"]


def number(value: float, digits: int = 6) -> str:
    """``value`` with ``digits`` significant digits; ``-0`` shown as ``0``; ``∞`` for infinities."""
    if math.isnan(value):
        return "NaN"
    if math.isinf(value):
        return "∞" if value > 0 else "−∞"
    text = f"{value:.{digits}g}"
    return "0" if text in ("-0", "0") else text.replace("-", "−")


def html_table(
    header: Sequence[str],
    rows: Sequence[Sequence[str]],
    caption: str | None = None,
    footer: Sequence[str] = (),
) -> str:
    """A ``<table>`` of escaped text cells.

    Args:
        header: Column titles.
        rows: One sequence of cell texts per row (the same length as ``header``).
        caption: A line above the table.
        footer: Lines below the table (notes, messages), one paragraph each.

    Returns:
        The HTML fragment.
    """
    esc = html.escape
    head = "".join(f"<th>{esc(h)}</th>" for h in header)
    body = "".join(
        "<tr>" + "".join(f"<td>{esc(str(c))}</td>" for c in row) + "</tr>" for row in rows
    )
    cap = f"<caption style='text-align:left'>{esc(caption)}</caption>" if caption else ""
    notes = "".join(f"<p>{esc(line)}</p>" for line in footer)
    return (
        f"<div class='kinematica'><table>{cap}<thead><tr>{head}</tr></thead>"
        f"<tbody>{body}</tbody></table>{notes}</div>"
    )
