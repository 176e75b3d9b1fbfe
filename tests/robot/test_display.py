"""A robot shows as its DH table in a notebook (``robot/display.py``)."""

from __future__ import annotations

import numpy as np
from support.helpers import table_cells as _cells

import kinematica as km


def test_a_robot_shows_its_dh_table_as_the_slide_writes_it() -> None:
    rows = _cells(km.load("arm6-dh")._repr_html_())
    assert rows[0] == ["joint", "type", "θ", "d (m)", "a (m)", "α", "limits"]
    # seed 000's table: q2 + 90°, q3 − 90°, d1 = l1 = 0.5, a2 = l2 = 0.4, α1 = 90°
    assert rows[1][:6] == ["q1", "R", "q1", "0.5", "0", "90°"]
    assert rows[2][:6] == ["q2", "R", "q2 + 90°", "0", "0.4", "0"]
    assert rows[3][2] == "q3 − 90°" and rows[3][5] == "−90°"
    assert len(rows) == 1 + 6


def test_a_prismatic_joint_and_limits_show_in_their_units() -> None:
    robot = km.Robot.from_dh(
        [km.Prismatic(alpha=np.pi / 2, offset=0.1, qlim=(0.0, 0.5)),
         km.Revolute(a=0.3, qlim=(-np.pi / 2, np.pi / 2))],
        convention="modified", name="PR",
    )  # fmt: skip
    rows = _cells(robot._repr_html_())
    assert rows[0][4] == "a(i−1) (m)" and rows[0][5] == "α(i−1)"
    assert rows[1][1:4] == ["P", "0", "q1 + 0.1"]
    assert rows[1][6] == "[0, 0.5] m"
    assert rows[2][6] == "[−90°, 90°]"


def test_text_from_a_file_is_escaped() -> None:
    robot = km.Robot.from_dh(
        [km.Revolute(a=0.3, name="<img src=x onerror=alert(1)>")],
        name="<b>x</b>",
        convention="standard",
    )
    page = robot._repr_html_()
    assert "<img" not in page and "<b>" not in page
    assert "&lt;img src=x onerror=alert(1)&gt;" in page
