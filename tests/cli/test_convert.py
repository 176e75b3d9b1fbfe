"""Subcommand ``convert`` (``cli/convert.py``): a robot as URDF, a DH table or a robot file."""

from __future__ import annotations

import json

import numpy as np
import pytest
import yaml
from support.cli import run_in
from support.helpers import assert_transform_close
from support.urdf import URDF_DIR, reference_chain

import kinematica as km


# ------------------------------------------------------------------ kinematica convert
def run(tmp_path, *args):
    return run_in(tmp_path, "convert", *args)  # in-process: test_main runs the real script


def test_convert_to_urdf_prints_a_urdf_with_the_same_fk(tmp_path):
    proc = run(tmp_path, "ur5", "--to", "urdf")
    assert proc.returncode == 0, proc.stderr
    ref = reference_chain(proc.stdout, tip="tool0")
    ur5 = km.load("ur5")
    q = np.random.default_rng(1).uniform(-3, 3, (5, 6))
    assert_transform_close(ref.fk_batch(q), ur5.fk(q), atol=1e-12)


@pytest.mark.parametrize("convention", ["standard", "modified"])
def test_convert_urdf_to_dh_robot_files(tmp_path, convention):
    src = URDF_DIR / "kuka_kr16_2.urdf"
    proc = run(tmp_path, str(src), "--to", f"dh-{convention}")
    assert proc.returncode == 0, proc.stderr
    head = f"# {convention} DH frames placed by the Denavit-Hartenberg rules"
    assert proc.stdout.startswith(head)
    data = yaml.safe_load(proc.stdout)
    assert data["convention"] == convention
    assert len(data["joints"]) == 6
    ref = reference_chain(src.read_text(), tip="tool0")
    q = np.random.default_rng(2).uniform(-2, 2, (5, 6))
    for suffix in (".yaml", ".json", ".toml"):
        out = tmp_path / f"kr16{suffix}"
        proc = run(tmp_path, str(src), "--to", f"dh-{convention}", "-o", str(out))
        assert proc.returncode == 0, proc.stderr
        assert proc.stdout.startswith(f"wrote {out}")
        assert "S0:" in proc.stdout
        robot = km.load(out)
        assert robot.convention == convention
        # the file's numbers are rounded within the line tolerances (1e-9 rad and m; issue
        # 35: no `q1 + 1.185e-11`): the same arm to what those tolerances allow
        assert_transform_close(robot.fk(q), ref.fk_batch(q), atol=1e-8)


def test_convert_json_and_yaml(tmp_path):
    proc = run(tmp_path, "puma560", "--to", "dh-modified", "--json")
    assert proc.returncode == 0, proc.stderr
    data = json.loads(proc.stdout)
    assert data["to"] == "dh-modified"
    assert data["convention"] == "modified"
    assert data["output"] is None
    assert [r["frame"] for r in data["rules"]] == list(range(7))
    assert yaml.safe_load(data["text"])["convention"] == "modified"
    proc = run(tmp_path, "planar-pr", "--to", "yaml", "--rad")
    assert proc.returncode == 0, proc.stderr
    assert yaml.safe_load(proc.stdout)["units"]["angle"] == "rad"


@pytest.mark.parametrize(
    ("args", "pattern"),
    [
        (["puma560", "--to", "yaml", "-o", "x.urdf"], "unknown file type '.urdf'"),
        (["puma560", "--to", "urdf", "--tip", "tool0"], "only for URDF files"),
        (["puma560", "--to", "urdf", "-o", "."], "cannot write the file"),
        (["nope.urdf", "--to", "urdf"], "no such URDF file"),
        (["puma560", "--to", "sdf"], "invalid choice"),
    ],
)
def test_convert_bad_input_exits_2_with_one_line(tmp_path, args, pattern):
    proc = run(tmp_path, *args)
    assert proc.returncode == 2
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1
    assert pattern in lines[0]
