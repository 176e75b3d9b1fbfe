"""The trajectory command with --profile scurve: output against the library, the figure."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from support.cli import run

import kinematica as km
from kinematica.viz.limits import plot_limits

FROM = ["0", "-30", "20", "0", "40", "0"]
VIA = ["30", "-20", "30", "10", "30", "20"]
TO = ["60", "-10", "40", "30", "20", "45"]
LIMITS = ["--vmax", "90", "--amax", "180", "--jmax", "900"]


def _lim() -> dict[str, float]:
    return {"vmax": np.radians(90), "amax": np.radians(180), "jmax": np.radians(900)}


def test_state_to_state_json_equals_the_library(capsys: pytest.CaptureFixture[str]) -> None:
    argv = ["trajectory", "puma560", "--from", *FROM, "--to", *TO, "--profile", "scurve"]
    code, out, _ = run(capsys, *argv, *LIMITS, "--json")
    assert code == 0
    d = json.loads(out)
    a, b = np.radians(np.array(FROM, float)), np.radians(np.array(TO, float))
    ref = km.joint_trajectory(a, b, profile="scurve", **_lim())
    assert d["duration"] == ref.t[-1] and np.allclose(np.radians(d["q"]), ref.q, atol=1e-12)
    assert np.allclose(np.radians(d["qddd"]), ref.qddd, atol=1e-9)  # type: ignore[attr-defined]


def test_through_a_via_point_reports_the_margin(capsys: pytest.CaptureFixture[str]) -> None:
    argv = ["trajectory", "puma560", "--from", *FROM, "--via", *VIA, "--to", *TO]
    code, out, _ = run(capsys, *argv, "--profile", "scurve", *LIMITS, "--json")
    assert code == 0
    d = json.loads(out)
    W = np.radians(np.array([FROM, VIA, TO], float))
    ref = km.via_trajectory(W, "scurve", qlim=km.load("puma560").qlim, **_lim())
    assert d["margin"] == ref.margin and d["margin"] > 0  # type: ignore[attr-defined]
    assert np.allclose(d["waypoint_times"], ref.waypoint_times)  # type: ignore[attr-defined]
    code, out, _ = run(capsys, *argv, "--profile", "scurve", *LIMITS)
    assert code == 0 and "shorter than stopping at each" in out


def test_the_figure_shows_jerk_against_its_limit(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    png = tmp_path / "scurve.png"
    argv = ["trajectory", "puma560", "--from", *FROM, "--to", *TO, "--profile", "scurve"]
    code, out, _ = run(capsys, *argv, *LIMITS, "--plot", str(png))
    assert code == 0 and png.stat().st_size > 10_000 and "figure written" in out
    a, b = np.radians(np.array(FROM, float)), np.radians(np.array(TO, float))
    fig = plot_limits(km.joint_trajectory(a, b, profile="scurve", **_lim()))
    labels = [ax.get_label() for ax in fig.axes]
    assert labels == ["position", "velocity", "acceleration", "jerk"]
    jerk = fig.axes[3]
    limits = [ln for ln in jerk.get_lines() if ln.get_gid() == "q1-limit"]
    assert sorted(ln.get_ydata()[0] for ln in limits) == pytest.approx(
        [-np.radians(900), np.radians(900)]
    )
    curve = next(ln for ln in jerk.get_lines() if ln.get_gid() == "q1")
    assert np.abs(curve.get_ydata()).max() == pytest.approx(np.radians(900))


def test_a_quintic_figure_has_no_jerk_row(tmp_path: Path) -> None:
    fig = plot_limits(km.joint_trajectory([0.0], [1.0], 2.0), vmax=1.0)
    assert [ax.get_label() for ax in fig.axes] == ["position", "velocity", "acceleration"]


@pytest.mark.parametrize(
    ("extra", "match"),
    [
        (["--profile", "quintic", "--jmax", "900"], "only it takes --jmax"),
        (["--profile", "scurve", "--cartesian"], "not with --cartesian"),
        (["--profile", "scurve", "--vmax", "90", "--amax", "180"], "and --jmax"),
        (["--profile", "scurve", *LIMITS[:4], "--jmax", "0"], "jmax must be positive"),
    ],
)
def test_bad_options_exit_2(
    capsys: pytest.CaptureFixture[str], extra: list[str], match: str
) -> None:
    code, _, err = run(capsys, "trajectory", "puma560", "--from", *FROM, "--to", *TO, *extra)
    assert code == 2 and match in err
