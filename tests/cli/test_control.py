"""The control command: output against the library, files, exit codes."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from support.helpers import run_cli as run

import kinematica as km
from kinematica.motion import read_csv, resolved_rate

Q0 = ["10", "-20", "10", "15", "40", "5"]
POSE = ["0.4", "0.1", "0.3", "20", "60", "30"]


def test_control_json_matches_the_library(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run(capsys, "control", "puma560", "--q0", *Q0, "--pose", *POSE, "--json")
    assert code == 0
    data = json.loads(out)
    puma = km.load("puma560")
    target = km.from_pose([0.4, 0.1, 0.3, 20, 60, 30], degrees=True)
    lib = resolved_rate(puma, np.radians([float(v) for v in Q0]), target=target)
    assert data["reached"] is True and lib.reached
    assert np.allclose(np.radians(data["q"]), lib.q, atol=1e-12)
    assert data["position_error"][-1] <= 1e-10


def test_control_writes_a_csv_and_prints_the_verdict(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    out_file = tmp_path / "run.csv"
    code, out, _ = run(
        capsys, "control", "puma560", "--q0", *Q0, "--pose", *POSE, "-o", str(out_file)
    )
    assert code == 0 and "target reached" in out
    t, q = read_csv(out_file)
    assert q.shape == (t.size, 6)


def test_control_exit_1_when_not_reached(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run(capsys, "control", "puma560", "--q0", *Q0, "--pose", *POSE, "--steps", "3")
    assert code == 1 and "not reached" in out


def test_control_twist_and_bad_input(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run(
        capsys,
        "control",
        "puma560",
        "--q0",
        *Q0,
        "--twist",
        "0.01",
        "0",
        "0",
        "0",
        "0",
        "0",
        "--steps",
        "10",
        "--damping",
        "0.02",
        "--json",
    )
    assert code == 0 and json.loads(out)["reached"] is None
    code, _, err = run(capsys, "control", "puma560", "--q0", *Q0, "--pose", *POSE, "--damping", "x")
    assert code == 2 and "--damping" in err and err.count("\n") == 1
    code, _, err = run(capsys, "control", "puma560", "--q0", "1", "--pose", *POSE)
    assert code == 2 and "--q0" in err
    code, _, err = run(capsys, "control", "puma560", "--q0", *Q0, "--pose", *POSE, "--dt", "0")
    assert code == 2 and "dt must be a positive number" in err


def test_no_false_limit_alarm_and_limits_in_degrees(capsys: pytest.CaptureFixture[str]) -> None:
    # Issue 35, item 6: the step that stops at a limit warned it was past it, in radians
    argv = ["control", "puma560", "--q0", "0", "0", "0", "0", "0", "0"]
    _, _, err = run(capsys, *argv, "--pose", "5", "0", "0", "0", "0", "0", "--steps", "50")
    assert "outside its limits" not in err
    _, _, err = run(capsys, "fk", "puma560", "--q", "0", "0", "100", "0", "0", "0")
    assert "joint 3 = 100 deg is outside its limits [-225, 45] deg" in err
    _, _, err = run(capsys, "fk", "puma560", "--q", "0", "0", "1", "0", "0", "0", "--rad")
    assert "joint 3 = 1 rad is outside its limits [-3.92699, 0.785398] rad" in err
