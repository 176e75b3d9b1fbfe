"""The interactive page embeds in a notebook cell (``viz/notebook.py``)."""

from __future__ import annotations

import html

import pytest

import kinematica as km
from kinematica import viz


def test_the_page_embeds_in_a_cell() -> None:
    view = viz.page_view(km.load("puma560"), q=[0.1, 0.2, 0.3, 0.0, 0.5, 0.0], height=400)
    frame = view._repr_html_()
    assert frame.startswith("<iframe srcdoc=") and "height:400px" in frame
    srcdoc = html.unescape(frame.split('srcdoc="', 1)[1].split('" style=', 1)[0])
    assert srcdoc == view.html and "PUMA 560" in srcdoc


@pytest.mark.parametrize("height", [199, 0, -5, 300.0, True, "400"])
def test_a_page_height_is_checked(height: object) -> None:
    with pytest.raises(km.KinematicaError, match="height must be an integer of at least 200"):
        viz.page_view(km.load("puma560"), height=height)  # type: ignore[arg-type]
