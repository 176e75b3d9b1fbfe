"""Robots and IK results show as HTML tables in a notebook; the page embeds in a cell."""

from __future__ import annotations

import html
import re
from pathlib import Path

import numpy as np
import pytest

import kinematica as km
from kinematica import viz
from kinematica.ik.display import BATCH_ROWS_SHOWN


def _cells(fragment: str) -> list[list[str]]:
    """The rows of an HTML table, each a list of its unescaped cell texts."""
    rows = re.findall(r"<tr>(.*?)</tr>", fragment, flags=re.S)
    return [[html.unescape(c) for c in re.findall(r"<t[dh]>(.*?)</t[dh]>", r)] for r in rows]


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
        [km.Revolute(a=0.3, name="<img src=x onerror=alert(1)>")], name="<b>x</b>"
    )
    page = robot._repr_html_()
    assert "<img" not in page and "<b>" not in page
    assert "&lt;img src=x onerror=alert(1)&gt;" in page


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


def test_a_trajectory_shows_evenly_spaced_samples_from_start_to_end() -> None:
    from kinematica.motion.display import SAMPLES_SHOWN

    traj = km.joint_trajectory([0.0, 0.0], [1.0, -0.5], 2.0, "quintic", dt=0.01)
    rows = _cells(traj._repr_html_())
    assert rows[0] == ["sample", "t (s)", "q1", "q2"]
    assert len(rows) == 1 + SAMPLES_SHOWN
    assert rows[1][1:] == ["0", "0", "0"] and rows[-1][1:] == ["2", "1", "−0.5"]
    assert rows[-1][0] == str(len(traj.t) - 1)
    short = km.joint_trajectory([0.0], [1.0], 0.05, "cubic", dt=0.01)
    assert len(_cells(short._repr_html_())) == 1 + len(short.t)  # every sample when few


def test_a_cartesian_path_lists_its_events() -> None:
    from kinematica.motion import cartesian_path

    puma = km.load("puma560")
    q_mid = np.radians([20, -30, 40, 10, 0, 0])  # wrist singular
    T = puma.fk(q_mid)
    T0, T1 = T.copy(), T.copy()
    T0[:3, 3] -= [0, 0.1, 0.05]
    T1[:3, 3] += [0, 0.1, 0.05]
    path = cartesian_path(puma, T0, T1, steps=41, q0=q_mid)
    text = path._repr_html_()
    assert path.events and all(html.escape(e.message) in text for e in path.events)
    k = len(path.events)
    assert (f"{k} events" if k > 1 else "1 event (") in text


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
