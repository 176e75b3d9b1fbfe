"""A design result shows as an HTML table in a notebook: the template and the best design."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from support.helpers import table_cells as _cells


def test_a_design_result_shows_template_and_best(tmp_path: Path) -> None:
    from kinematica import design

    path = tmp_path / "arm2r.yaml"
    path.write_text(
        "name: 2R\nconvention: standard\nparameters:\n  l1: {value: 0.3, min: 0.1, max: 0.9}\n"
        "  l2: 1 - l1\njoints:\n  - {theta: q1, d: 0, a: l1, alpha: 0}\n"
        "  - {theta: q2, d: 0, a: l2, alpha: 0}\n"
    )
    res = design.optimize(path, design.Task.ring(0.6, 8), objective="min_manipulability",
                          budget=30, seed=1)  # fmt: skip
    rows = {r[0]: r[1:] for r in _cells(res._repr_html_())[1:]}
    assert rows["l1"][0] == "0.3"
    assert float(rows["l1"][1]) == pytest.approx(res.best_params["l1"], rel=1e-5)
    best = res.best_values["min_manipulability"]
    assert float(rows["min_manipulability"][1]) == pytest.approx(best, rel=1e-5)
    # at the template's l1 = 0.3 the worst manipulability on the ring is 0.64·l1·l2 − 0.1024
    w = np.sqrt(0.64 * 0.3 * 0.7 - 0.1024)
    assert float(rows["min_manipulability"][0]) == pytest.approx(w, rel=1e-5)
