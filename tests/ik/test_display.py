"""IK results show as HTML tables in a notebook: every solution, its branch and status."""

from __future__ import annotations

import re

import numpy as np
from support.helpers import table_cells as _cells

import kinematica as km
from kinematica.ik.display import BATCH_ROWS_SHOWN


def test_an_ik_result_lists_every_solution_with_its_branch() -> None:
    puma = km.load("puma560")
    T = puma.fk([0.2, -0.5, 0.3, 0.4, 0.8, -0.1])
    res = puma.ik(T, respect_limits=False)
    rows = _cells(res._repr_html_())
    assert rows[0][:2] == ["#", "branch"] and len(rows) == 1 + res.count == 9
    for row, q, branch in zip(rows[1:], res.solutions, res.branches, strict=True):
        assert row[1] == branch
        shown = np.array([float(v.replace("−", "-")) for v in row[2:8]])
        np.testing.assert_allclose(shown, q, rtol=1e-5, atol=1e-6)  # 6 significant digits
    assert "ok: 8 solutions" in res._repr_html_()


def test_solutions_outside_the_limits_are_marked() -> None:
    puma = km.load("puma560")
    res = puma.ik(puma.fk([0.2, -0.5, 0.3, 0.4, 0.8, -0.1]))
    rows = _cells(res._repr_html_())
    outside = [r for r in rows[1:] if r[1].endswith("(outside the limits)")]
    assert len(outside) == len(res.out_of_limits) > 0
    assert len(rows) == 1 + res.count + len(res.out_of_limits)


def test_a_batch_shows_a_row_per_target_and_a_tally() -> None:
    puma = km.load("puma560")
    T = puma.fk(np.random.default_rng(1).uniform(-2, 2, (BATCH_ROWS_SHOWN + 5, 6)))
    T[3, :3, 3] = [5.0, 0.0, 0.0]  # out of reach
    res = puma.ik(T)
    text = res._repr_html_()
    rows = _cells(text)
    assert len(rows) == 1 + BATCH_ROWS_SHOWN
    assert rows[4][1] == "unreachable" and rows[4][2] == "0"
    assert "… and 5 more targets" in text
    tally = dict(re.findall(r"(\d+) (\w+)", text.split("targets (", 1)[1].split(";", 1)[0]))
    assert sum(int(k) for k in tally) == BATCH_ROWS_SHOWN + 5
