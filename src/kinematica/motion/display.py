"""Trajectories and Cartesian paths as HTML tables, for notebooks (``_repr_html_``)."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from kinematica.io.html_table import html_table, number

__all__ = ["SAMPLES_SHOWN", "samples_html", "shown_rows"]

#: Samples of a trajectory shown in its table: evenly spaced, the first and last included.
SAMPLES_SHOWN = 11


def shown_rows(m: int) -> NDArray[np.intp]:
    """The samples shown: all up to :data:`SAMPLES_SHOWN`, else that many evenly spaced."""
    if m <= SAMPLES_SHOWN:
        return np.arange(m)
    return np.unique(np.round(np.linspace(0, m - 1, SAMPLES_SHOWN)).astype(np.intp))


def samples_html(
    time: NDArray[np.float64],
    q: NDArray[np.float64],
    *,
    time_name: str,
    caption: str,
    footer: tuple[str, ...] = (),
) -> str:
    """A table of joint values at a few samples of a trajectory or a path.

    Args:
        time: ``(m,)`` time (s) or path parameter of each sample.
        q: ``(m, n)`` joint values (rad, m).
        time_name: The first column's title (``"t (s)"``, ``"s"``).
        caption: The line above the table.
        footer: Lines below it (events, notes).

    Returns:
        The HTML fragment.
    """
    n = q.shape[1] if q.ndim == 2 else 0
    header = ["sample", time_name, *(f"q{j + 1}" for j in range(n))]
    rows = [
        [str(i), number(float(time[i])), *(number(float(v)) for v in q[i])]
        for i in shown_rows(len(time))
    ]
    return html_table(header, rows, caption=caption, footer=footer)
