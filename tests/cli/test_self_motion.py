"""``kinematica self-motion``: families and intervals printed, --json, --plot, exit codes."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from support.cli import one_line, run, strict_json

import kinematica as km

Q = np.array([0.3, 0.5, -0.2, -1.2, 0.4, 0.9, 0.2])


def matrix(q: np.ndarray = Q) -> list[str]:
    return [repr(float(v)) for v in km.load("iiwa14").fk(q).ravel()]


def test_families_and_intervals_in_degrees(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run(
        capsys,
        "self-motion",
        "iiwa14",
        "--matrix",
        *matrix(),
        "--parameter",
        "q1",
        "--samples",
        "37",
    )
    assert code == 0
    head = out.splitlines()[0]
    assert "self-motion over q1 (37 samples" in head and "deg apart" in head
    assert "within the limits (q1, deg)" in out
    assert "shoulder right" in out


def test_json_values_and_families_reach_the_pose(capsys: pytest.CaptureFixture[str]) -> None:
    robot = km.load("iiwa14")
    code, out, _ = run(
        capsys, "self-motion", "iiwa14", "--matrix", *matrix(), "--parameter", "q1",
        "--samples", "19", "--json", "--rad",
    )  # fmt: skip
    assert code == 0
    data = strict_json(out)
    assert data["parameter"] == {"name": "q1", "joint": "q1", "unit": "rad"}
    np.testing.assert_allclose(data["values"], np.linspace(*robot.qlim[0], 19))
    assert data["families"]
    for fam in data["families"]:
        q = np.array([[np.nan if v is None else v for v in row] for row in fam["q"]])
        rows = np.isfinite(q).all(axis=1)
        T = robot.fk(q[rows])
        np.testing.assert_allclose(T, np.broadcast_to(robot.fk(Q), T.shape), atol=1e-9)
        for a, b in fam["feasible"]:
            assert a <= b


def test_no_family_is_exit_1(capsys: pytest.CaptureFixture[str]) -> None:
    # the elbow (q4) sets the reach: the pose is met at isolated values only
    code, out, _ = run(
        capsys,
        "self-motion",
        "iiwa14",
        "--matrix",
        *matrix(),
        "--parameter",
        "q4",
        "--samples",
        "9",
    )
    assert code == 1
    assert "no solution at any sample" in out


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (["--parameter", "7"], "--parameter: name a joint as q1..q7"),
        (["--parameter", "q1", "--samples", "1"], "--samples"),
        (["--parameter", "q1", "--max-jump", "-1"], "--max-jump must be a positive number"),
        (["--parameter", "q1", "--plot", "/nonexistent-dir/x.png"], "does not exist"),
        (["--parameter", "q1", "--plot", "out.txt"], "cannot write a picture"),
    ],
)
def test_bad_input_is_exit_2_in_one_line(
    capsys: pytest.CaptureFixture[str], argv: list[str], words: str
) -> None:
    code, _, err = run(capsys, "self-motion", "iiwa14", "--matrix", *matrix(), *argv)
    assert code == 2
    assert words in one_line(err)


def test_plot_is_written(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    pytest.importorskip("matplotlib")
    path = tmp_path / "families.png"
    code, out, _ = run(
        capsys, "self-motion", "iiwa14", "--matrix", *matrix(), "--parameter", "q1",
        "--samples", "25", "--plot", str(path),
    )  # fmt: skip
    assert code == 0 and f"wrote {path}" in out
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_the_arm_angle_in_degrees(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run(
        capsys, "self-motion", "iiwa14", "--matrix", *matrix(), "--parameter", "arm-angle",
        "--samples", "13", "--json",
    )  # fmt: skip
    data = strict_json(out)
    assert code == 0
    assert data["parameter"] == {"name": "arm angle", "joint": None, "unit": "deg"}
    assert data["values"][0] == pytest.approx(-180.0) and data["values"][-1] == pytest.approx(180)
    assert len(data["families"]) >= 8
