"""Trajectory files: CSV header t,q1..qn (SI), exact round trip; JSON with null for NaN."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import kinematica as km
from kinematica.motion import joint_trajectory, read_csv, write_csv, write_json


def test_csv_header_and_exact_round_trip(tmp_path: Path) -> None:
    t, q, _, _ = joint_trajectory([0.1, -0.2, 0.3], [1.0, 0.5, -0.7], 1.0, dt=0.05)
    path = write_csv(tmp_path / "traj.csv", t, q)
    lines = path.read_text().splitlines()
    assert lines[0] == "t,q1,q2,q3"
    assert len(lines) == t.size + 1
    assert [float(v) for v in lines[1].split(",")] == [0.0, 0.1, -0.2, 0.3]
    t2, q2 = read_csv(path)
    assert np.array_equal(t2, t) and np.array_equal(q2, q)


def test_csv_keeps_nan_rows(tmp_path: Path) -> None:
    q = np.array([[0.0, 1.0], [np.nan, np.nan]])
    _, q2 = read_csv(write_csv(tmp_path / "p.csv", [0.0, 0.1], q))
    assert np.isnan(q2[1]).all() and q2[0].tolist() == [0.0, 1.0]


def test_json_is_valid_with_null_for_nan(tmp_path: Path) -> None:
    q = np.array([[0.0, 1.0], [np.nan, 2.0]])
    path = write_json(tmp_path / "p.json", [0.0, 0.1], q, joint_types="RP", meta={"robot": "x"})
    data = json.loads(path.read_text())
    assert data["q"] == [[0.0, 1.0], [None, 2.0]] and data["robot"] == "x"
    assert data["units"]["t"] == "s" and data["joint_types"] == "RP" and data["events"] == []


def test_read_csv_errors_say_where(tmp_path: Path) -> None:
    bad = tmp_path / "bad.csv"
    bad.write_text("time,q1\n0,1\n")
    with pytest.raises(km.KinematicaError, match="header must be t,q1"):
        read_csv(bad)
    bad.write_text("t,q1\n0,1\n0.1,x\n")
    with pytest.raises(km.KinematicaError, match="line 3"):
        read_csv(bad)
    bad.write_text("t,q1,q2\n0,1\n")
    with pytest.raises(km.KinematicaError, match="expected 3 values"):
        read_csv(bad)
    with pytest.raises(km.KinematicaError, match="file not found"):
        read_csv(tmp_path / "missing.csv")


def test_shapes_must_agree(tmp_path: Path) -> None:
    with pytest.raises(km.DimensionError, match="same T"):
        write_csv(tmp_path / "x.csv", [0.0, 1.0], np.zeros((3, 2)))
