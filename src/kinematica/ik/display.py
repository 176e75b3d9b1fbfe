"""IK results as HTML tables, for notebooks (``_repr_html_``)."""

from __future__ import annotations

from typing import Any, Protocol

import numpy as np
from numpy.typing import NDArray

from kinematica.io.html_table import html_table, number

__all__ = ["batch_html", "result_html"]


class Answer(Protocol):
    """What a table of one target reads (an :class:`~kinematica.ik.result.IKResult`)."""

    @property
    def solutions(self) -> NDArray[np.float64]: ...

    @property
    def branches(self) -> tuple[str, ...]: ...

    @property
    def residuals(self) -> NDArray[np.float64]: ...

    @property
    def out_of_limits(self) -> NDArray[np.float64]: ...

    @property
    def out_of_limits_branches(self) -> tuple[str, ...]: ...

    @property
    def parameter(self) -> tuple[str, float] | None: ...

    @property
    def status(self) -> Any: ...

    @property
    def method(self) -> str: ...

    @property
    def count(self) -> int: ...

    @property
    def message(self) -> str: ...


class Answers(Protocol):
    """What a table of a batch reads (an :class:`~kinematica.ik.result.IKBatchResult`)."""

    @property
    def shape(self) -> tuple[int, ...]: ...

    @property
    def method(self) -> str: ...

    @property
    def parameter(self) -> tuple[str, NDArray[np.float64]] | None: ...

    @property
    def size(self) -> int: ...

    @property
    def status(self) -> NDArray[np.str_]: ...

    @property
    def count(self) -> NDArray[np.int64]: ...

    def __getitem__(self, idx: tuple[int, ...]) -> Answer: ...


#: Rows of a batch shown in its table; the caption says how many more there are.
BATCH_ROWS_SHOWN = 20


def result_html(res: Answer) -> str:
    """Every solution of one target, one row each: branch, joint values, residuals.

    Joint values are in the API's units: radians for revolute joints, metres
    for prismatic ones. Solutions outside the joint limits follow, marked.
    """
    n = res.solutions.shape[1] if res.solutions.ndim == 2 else 0
    header = ["#", "branch", *(f"q{j + 1}" for j in range(n)), "position error (m)",
              "rotation error (rad)"]  # fmt: skip
    rows: list[list[str]] = []
    for k, (q, branch) in enumerate(zip(res.solutions, res.branches, strict=True)):
        pos, rot = res.residuals[k]
        rows.append([str(k + 1), branch, *(number(v) for v in q), number(pos, 2), number(rot, 2)])
    for k, (q, branch) in enumerate(
        zip(res.out_of_limits, res.out_of_limits_branches, strict=True)
    ):
        label = f"{branch} (outside the limits)" if branch else "(outside the limits)"
        rows.append([f"{res.count + k + 1}", label, *(number(v) for v in q), "", ""])
    plural = "" if res.count == 1 else "s"
    held = "" if res.parameter is None else f"; {res.parameter[0]} held at {res.parameter[1]:.6g}"
    caption = f"{res.status}: {res.count} solution{plural} ({res.method}{held}; q in rad, m)"
    return html_table(header, rows, caption=caption, footer=(res.message,))


def batch_html(res: Answers) -> str:
    """One row per target (the first :data:`BATCH_ROWS_SHOWN`): status, count, message."""
    shown = min(res.size, BATCH_ROWS_SHOWN)
    rows = []
    status, count = res.status.reshape(-1), res.count.reshape(-1)
    for flat, idx in zip(range(shown), np.ndindex(*res.shape), strict=False):
        rows.append(
            [str(idx if len(idx) > 1 else idx[0]) if idx else "()", str(status[flat]),
             str(int(count[flat])), res[idx].message]
        )  # fmt: skip
    more = res.size - shown
    tally = ", ".join(
        f"{int(c)} {s}" for s, c in zip(*np.unique(status, return_counts=True), strict=True)
    )
    held = "" if res.parameter is None else f"; {res.parameter[0]} held at a value"
    caption = f"{res.size} targets ({tally}; {res.method}{held})"
    footer = (f"… and {more} more targets",) if more > 0 else ()
    return html_table(["target", "status", "solutions", "message"], rows, caption, footer)
