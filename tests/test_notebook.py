"""The lecture-notes notebook under examples/ runs, and what it stores is what it shows."""

from __future__ import annotations

import copy
from typing import Any

import pytest
from support import ROOT

nbformat = pytest.importorskip("nbformat")
nbclient = pytest.importorskip("nbclient")

NOTEBOOK = ROOT / "examples" / "lecture_notes.ipynb"


def _outputs(nb: Any) -> list[tuple[str, list[str]]]:
    """Each code cell's printed text and HTML, as the docs site shows them."""
    found = []
    for cell in nb.cells:
        if cell.cell_type != "code":
            continue
        text = "".join(o.text for o in cell.outputs if o.output_type == "stream")
        html = [o.data["text/html"] for o in cell.outputs if "text/html" in o.get("data", {})]
        found.append((text, html))
    return found


@pytest.fixture(scope="module")
def executed() -> Any:
    stored = nbformat.read(NOTEBOOK, as_version=4)
    fresh = copy.deepcopy(stored)
    nbclient.NotebookClient(fresh, timeout=120, kernel_name="python3").execute()
    return stored, fresh


def test_the_notebook_runs_without_an_error_or_a_warning(executed: Any) -> None:
    _, fresh = executed
    outputs = [o for c in fresh.cells if c.cell_type == "code" for o in c.outputs]
    assert [o for o in outputs if o.output_type == "error"] == []
    assert [o.text for o in outputs if o.get("name") == "stderr"] == []


def test_the_robot_and_its_ik_results_show_as_tables(executed: Any) -> None:
    _, fresh = executed
    html = [h for _, shown in _outputs(fresh) for h in shown]
    assert any("q2 + 90°" in h and "<table>" in h for h in html)  # the DH table of seed 000
    assert any("shoulder left, elbow up, wrist flip" in h for h in html)  # the PUMA's 8
    assert any("<iframe srcdoc=" in h for h in html)  # the page in a cell


def test_the_stored_outputs_are_current(executed: Any) -> None:
    # The docs site shows the stored outputs: `make notebook` refreshes them.
    stored, fresh = executed
    assert _outputs(stored) == _outputs(fresh)
