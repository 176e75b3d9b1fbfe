"""``kinematica design``: files written, JSON output, exit codes, one-line errors."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import kinematica as km
from kinematica.cli.main import main
from kinematica.design import Task, load_template

TEMPLATE = """
name: planar 2R, l1 + l2 = 1
convention: standard
parameters:
  l1: {value: 0.3, min: 0.1, max: 0.9}
  l2: 1 - l1
joints:
  - {theta: q1, d: 0, a: l1, alpha: 0}
  - {theta: q2, d: 0, a: l2, alpha: 0}
"""


def run(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    try:
        code = main(list(argv))
    except SystemExit as exc:
        code = int(exc.code or 0)
    out, err = capsys.readouterr()
    return code, out, err


@pytest.fixture
def files(tmp_path: Path) -> Path:
    (tmp_path / "t.yaml").write_text(TEMPLATE)
    ring = Task.ring(0.6, 12).targets
    np.savetxt(tmp_path / "ring.csv", ring, delimiter=",", header="x,y,z", comments="")
    return tmp_path


def test_design_writes_robot_report_log_and_pictures(
    capsys: pytest.CaptureFixture[str], files: Path
) -> None:
    out_path = files / "best.yaml"
    code, out, err = run(
        capsys, "design", str(files / "t.yaml"), "--task", str(files / "ring.csv"),
        "--budget", "60", "--seed", "4", "-o", str(out_path), "--json",
    )  # fmt: skip
    assert code == 0, err
    data = json.loads(out)
    assert data["status"] == "ok" and data["seed"] == 4 and data["evaluations"] <= 60
    assert abs(data["best_params"]["l1"] - 0.5) < 0.02  # the optimum is 1/2 (see the API tests)
    assert data["best_measures"]["reached"] == 1.0 and data["front"] is None
    # the robot file is the template at the best values
    best = km.load(out_path)
    by_hand = load_template(files / "t.yaml").robot_at(data["best_params"])
    q = np.random.default_rng(0).uniform(-3, 3, (4, 2))
    np.testing.assert_allclose(best.fk(q), by_hand.fk(q), atol=1e-15)
    report = (files / "best_report.md").read_text()
    assert "# Design of planar 2R, l1 + l2 = 1" in report
    assert "![Task coverage, before and after](best_report_coverage.png)" in report
    for name in ("best_report_coverage.png", "best_report_progress.png"):
        assert (files / name).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    log = (files / "best_log.csv").read_text().splitlines()
    assert log[0].startswith("evaluation,l1,feasible,violation,min_manipulability")
    assert len(log) == 1 + data["evaluations"]
    assert data["files"]["robot"] == str(out_path)


def test_text_output_pareto_and_weights(capsys: pytest.CaptureFixture[str], files: Path) -> None:
    (files / "free.yaml").write_text(TEMPLATE.replace("1 - l1", "{value: 0.5, min: 0.1, max: 0.9}"))
    code, out, _ = run(
        capsys, "design", str(files / "free.yaml"), "--task", str(files / "ring.csv"),
        "--objective", "total_length", "min_manipulability", "--budget", "140",
        "-o", str(files / "front.json"), "--no-pictures",
    )  # fmt: skip
    assert code == 0
    assert "Pareto front:" in out and "robot: " in out
    assert "## Pareto front" in (files / "front_report.md").read_text()
    assert not (files / "front_report_coverage.png").exists()
    front_rows = [r for r in (files / "front_log.csv").read_text().splitlines() if r.endswith(",1")]
    assert len(front_rows) >= 3
    code, out, _ = run(
        capsys, "design", str(files / "free.yaml"), "--task", str(files / "ring.csv"),
        "--objective", "total_length=1", "min_manipulability=2.5", "--budget", "20",
        "-o", str(files / "w.toml"), "--json", "--no-pictures",
    )  # fmt: skip
    assert code == 0
    assert json.loads(out)["objective"] == "minimise 1·total_length + 2.5·-min_manipulability"


def test_pose_rows_follow_euler_and_rad(capsys: pytest.CaptureFixture[str], files: Path) -> None:
    # poses the template (l1 = 0.3) reaches, written as x y z + extrinsic xyz angles in rad;
    # read as degrees or as another sequence they would be out of reach of every design
    robot = load_template(files / "t.yaml").robot_at({})
    T = robot.fk(np.array([[0.3, 1.2], [-1.0, 2.0], [2.0, -0.7]]))
    np.savetxt(files / "poses.csv", km.to_pose(T, euler="xyz"), delimiter=",")
    argv = ["design", str(files / "t.yaml"), "--task", str(files / "poses.csv"), "--budget", "10",
            "-o", str(files / "p.yaml"), "--json", "--no-pictures"]  # fmt: skip
    code, out, err = run(capsys, *argv, "--euler", "xyz", "--rad")
    assert code == 0, err
    data = json.loads(out)
    assert data["task"]["kind"] == "pose" and data["best_measures"]["reached"] == 1.0
    code, out, _ = run(capsys, *argv, "--euler", "xyz")  # read as degrees: none reached
    assert code == 1 and json.loads(out)["best_measures"]["reached"] == 0.0


def test_checkpoint_from_the_command_line(capsys: pytest.CaptureFixture[str], files: Path) -> None:
    args = [
        "design", str(files / "t.yaml"), "--task", str(files / "ring.csv"), "--budget", "20",
        "--checkpoint", str(files / "run.ckpt"), "-o", str(files / "b.yaml"), "--json",
        "--no-pictures",
    ]  # fmt: skip
    first = json.loads(run(capsys, *args)[1])
    second = json.loads(run(capsys, *args)[1])
    assert first["reused"] == 0 and second["computed"] == 0
    assert second["reused"] == first["computed"]
    assert second["best_params"] == first["best_params"]


def test_no_design_reaches_every_target_exits_1(
    capsys: pytest.CaptureFixture[str], files: Path
) -> None:
    (files / "far.json").write_text('{"region": "ring", "radius": 1.5, "count": 6}')
    code, out, _ = run(
        capsys, "design", str(files / "t.yaml"), "--task", str(files / "far.json"),
        "--budget", "10", "-o", str(files / "none.yaml"),
    )  # fmt: skip
    assert code == 1
    assert "no robot file written" in out
    assert not (files / "none.yaml").exists()
    assert "no design reached every target" in (files / "none_report.md").read_text()
    code, out, _ = run(
        capsys, "design", str(files / "t.yaml"), "--task", str(files / "far.json"),
        "--budget", "10", "-o", str(files / "none.yaml"), "--json", "--no-pictures",
    )  # fmt: skip
    data = json.loads(out)  # valid JSON: NaN is null
    assert code == 1 and data["status"] == "infeasible" and data["best_value"] is None


@pytest.mark.parametrize(
    ("change", "match"),
    [
        ({"template": "missing.yaml"}, "missing.yaml: file not found"),
        ({"task": "missing.csv"}, "missing.csv: no such task file"),
        ({"objective": ["reach"]}, "unknown objective 'reach'"),
        ({"objective": ["total_length=heavy"]}, "the weight after '=' must be a number"),
        ({"output": "best.txt"}, "best robot file must end in"),
        ({"output": "no/such/best.yaml"}, "no such folder"),
        ({"budget": "3"}, "below one generation"),
        ({"workers": "0"}, "workers must be a positive whole number"),
    ],
)
def test_bad_input_is_one_line_and_exit_2(
    capsys: pytest.CaptureFixture[str], files: Path, change: dict[str, object], match: str
) -> None:
    opts: dict[str, object] = {
        "template": "t.yaml", "task": "ring.csv", "objective": ["min_manipulability"],
        "output": "best.yaml", "budget": "10",
    }  # fmt: skip
    opts.update(change)
    argv = [
        "design", str(files / str(opts["template"])), "--task", str(files / str(opts["task"])),
        "--objective", *opts["objective"],  # type: ignore[misc]
        "--budget", str(opts["budget"]), "-o", str(files / str(opts["output"])),
    ]  # fmt: skip
    if "workers" in opts:
        argv += ["--workers", str(opts["workers"])]
    code, _out, err = run(capsys, *argv)
    assert code == 2
    assert match in err and len(err.strip().splitlines()) == 1
    assert not (files / "best.yaml").exists()


def test_no_traceback_from_a_real_process(files: Path) -> None:
    proc = subprocess.run(
        [sys.executable, "-m", "kinematica.cli.main", "design", "t.yaml", "--task", "ring.csv",
         "-o", "b.yaml", "--scheduler", "nonsense"],
        capture_output=True, text=True, cwd=files, check=False,
    )  # fmt: skip
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr
    assert len(proc.stderr.strip().splitlines()) == 1


def test_a_task_of_three_points(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    (tmp_path / "t.yaml").write_text(TEMPLATE)
    np.savetxt(tmp_path / "three.csv", Task.ring(0.6, 3).targets, delimiter=",",
               header="x,y,z", comments="")  # fmt: skip
    code, out, err = run(
        capsys, "design", str(tmp_path / "t.yaml"), "--task", str(tmp_path / "three.csv"),
        "--budget", "20", "--seed", "1", "-o", str(tmp_path / "best.yaml"), "--json",
        "--no-pictures",
    )  # fmt: skip
    assert code == 0, err
    assert "internal error" not in err
    assert json.loads(out)["best_measures"]["reached"] == 1.0


def test_the_report_shows_names_literally(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    markdown_it = pytest.importorskip("markdown_it")
    evil = "<img src=x onerror=alert(1)> *b* [l](javascript:x)"
    (tmp_path / "t.yaml").write_text(TEMPLATE.replace("planar 2R, l1 + l2 = 1", f"'{evil}'"))
    np.savetxt(tmp_path / "ring.csv", Task.ring(0.6, 4).targets, delimiter=",",
               header="x,y,z", comments="")  # fmt: skip
    out = tmp_path / "best`x.yaml"
    code, _, err = run(
        capsys, "design", str(tmp_path / "t.yaml"), "--task", str(tmp_path / "ring.csv"),
        "--budget", "20", "--seed", "1", "-o", str(out), "--no-pictures",
    )  # fmt: skip
    assert code == 0, err
    page = markdown_it.MarkdownIt("commonmark").render((tmp_path / "best`x_report.md").read_text())
    for tag in ("<img", "<a ", "<em>"):
        assert tag not in page
    assert f"<h1>Design of {evil.replace('<', '&lt;').replace('>', '&gt;')}</h1>" in page
    assert "<code>best`x.yaml</code>" in page


def test_reach_measures_from_the_command_line(
    capsys: pytest.CaptureFixture[str], files: Path
) -> None:
    args = ["design", str(files / "t.yaml"), "--task", str(files / "ring.csv"), "--budget", "10",
            "-o", str(files / "r.yaml"), "--json", "--no-pictures"]  # fmt: skip
    reach = ["--tolerance", "10", "--samples", "8", "--region", "-0.5", "-0.5", "0", "0.5",
             "0.5", "0", "--reach-resolution", "0.25", "--reach-orientations", "4"]  # fmt: skip
    code, out, err = run(capsys, *args, *reach)
    assert code == 0, err
    measures = json.loads(out)["best_measures"]
    assert 0.0 <= measures["task_reachability"] <= 1.0
    assert measures["dexterous_volume"] >= 0.0
    code, out, err = run(capsys, *args, "--objective", "dexterous_volume")
    assert code == 2 and "region" in err and "Traceback" not in err
