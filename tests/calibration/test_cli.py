"""``kinematica calibrate`` (cli/calibrate.py) and the measurement CSV format (datafile.py)."""

from __future__ import annotations

import json
import math
import warnings

import numpy as np
import pytest
from support.calibration import NOISE, perturbed
from support.cli import run

import kinematica as km
from kinematica import calibration
from kinematica.calibration.datafile import MeasurementFileError, read_measurements


def _csv(path, robot, m=40, seed=5, kind="pose"):
    true = perturbed(robot, seed)
    q = robot.random_q(m, seed=seed)
    measured = calibration.simulate(true, q, NOISE, kind=kind, seed=seed)
    if kind == "pose":
        cols = km.to_pose(measured, euler="ZYZ")
        cols[:, 3:] = np.degrees(cols[:, 3:])
    else:
        cols = measured
    rows = np.hstack([np.degrees(q), cols])
    head = ",".join(
        [f"q{i + 1}" for i in range(robot.dof)] + ["x", "y", "z", "a", "b", "c"][: cols.shape[1]]
    )
    lines = ["# tracker session", head] + [",".join(repr(float(v)) for v in r) for r in rows]
    path.write_text("\n".join(lines) + "\n")
    return true, q


def test_calibrate_writes_robot_urdf_and_report(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    robot = km.load("puma560")
    true, _ = _csv(tmp_path / "data.csv", robot)
    code, out, err = run(
        capsys, "calibrate", "puma560", "data.csv", "-o", "cal.yaml", "--urdf", "cal.urdf",
        "--report", "cal.md", "--lang", "en", "--noise", "0.00001", "0.001",
    )  # fmt: skip
    assert code == 0, err
    assert "identified 30 parameters" in out
    assert "d1 and base z move the tool alike" in out
    back = km.load(tmp_path / "cal.urdf")
    q = robot.random_q(10, seed=3)
    assert np.abs(back.fk(q) - true.fk(q)).max() < 1e-4  # the arm as it is, to the noise
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # far common normals are no unit slip here
        table = km.load(tmp_path / "cal.yaml")  # its DH table and its own transforms
    assert np.abs(table.fk(q) - back.fk(q)).max() < 1e-12
    code, out, err = run(capsys, "show", "cal.urdf")
    assert code == 0 and "6R, general geometry" in out  # IK: the general 6R, every solution
    text = (tmp_path / "cal.md").read_text()
    assert "# Kinematic calibration of PUMA 560" in text
    assert "pose measurements (least squares)" in text  # the loss in words
    assert "![Residual histograms](cal-histogram.png)" in text
    for png in ("cal-histogram.png", "cal-residuals.png"):
        assert (tmp_path / png).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_calibrate_json_and_spanish_report(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    robot = km.load("puma560").with_tool(km.transl(0.05, 0.03, 0.1))
    robot.save(tmp_path / "arm.yaml")
    _csv(tmp_path / "points.csv", robot, m=40, kind="position")
    code, out, err = run(
        capsys, "calibrate", "arm.yaml", "points.csv", "--json", "--report", "r.md",
        "--noise", "0.00001", "0.001", "--loss", "huber", "--units", "m",
    )  # fmt: skip
    assert code == 0, err
    data = json.loads(out)
    assert data["kind"] == "position" and data["rank"] == 27 and data["generic_count"] == 27
    # 120 residuals, 27 parameters: the residuals keep 93/120 of the noise's variance
    expected = math.sqrt(3) * NOISE[0] * math.sqrt(1 - 27 / 120)
    assert data["rms_after"]["position_m"] == pytest.approx(expected, rel=0.2)
    assert {"tool_rx", "tool_ry", "tool_rz"} <= {u["name"] for u in data["undetermined"]}
    text = (tmp_path / "r.md").read_text()
    assert "# Calibración cinemática de PUMA 560" in text
    assert "tool rx no mueve el punto medido." in text
    assert "medidas de posición (pérdida robusta de Huber)" in text


def test_bad_csv_is_a_one_line_error(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "bad.csv").write_text("q1,q2,q3,q4,q5,q6,x,y,z\n0,0,0,0,0,0,1,2\n")
    code, _, err = run(capsys, "calibrate", "puma560", "bad.csv")
    assert code == 2
    assert "bad.csv: line 2: 8 columns; expected 9" in err
    (tmp_path / "few.csv").write_text("0,0,0,0,0,0,1,2,3\n")
    code, _, err = run(capsys, "calibrate", "puma560", "few.csv")
    assert code == 2 and "too few measurements" in err and "got 1" in err


def test_read_measurements_names_line_and_column(tmp_path):
    p = tmp_path / "m.csv"
    p.write_text("0,0,1,2\n0,x,1,2\n")
    with pytest.raises(MeasurementFileError, match="line 2, column 2: expected a finite number"):
        read_measurements(p, 1)
    p.write_text("# only a comment\n")
    with pytest.raises(MeasurementFileError, match="no measurements"):
        read_measurements(p, 1)
    p.write_text("0,1,2,3\n0,1,2,3,4,5,6\n")
    with pytest.raises(MeasurementFileError, match="line 2: 7 columns, the rows before have 4"):
        read_measurements(p, 1)
    p.write_text("q,x,y,z\n0.5,1,2,3\n")
    q, m, kind = read_measurements(p, 1)
    assert kind == "position" and q.tolist() == [[0.5]] and m.tolist() == [[1, 2, 3]]


def test_every_loss_is_named_in_both_languages():
    from kinematica.calibration.fit import LOSSES
    from kinematica.calibration.words import LANGS, phrase

    for loss in LOSSES:
        names = {phrase(f"loss.{loss}", lang) for lang in LANGS}
        assert len(names) == len(LANGS) and loss not in names
