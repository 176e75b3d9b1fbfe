"""The command line: output against the library, exit codes, one-line errors."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import kinematica as km
from kinematica.cli.main import main

DATA = Path(__file__).parent / "data"


def run(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    """Run the CLI in-process; argparse's SystemExit becomes an exit code."""
    try:
        code = main(list(argv))
    except SystemExit as exc:
        code = int(exc.code or 0)
    out, err = capsys.readouterr()
    return code, out, err


def test_robots_lists_every_builtin(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run(capsys, "robots", "--json")
    assert code == 0
    ids = [r["id"] for r in json.loads(out)["robots"]]
    assert ids == km.builtin_names()
    for name in ("puma560", "ur5", "panda", "planar-pr", "arm6-dh", "anthropomorphic-3r"):
        assert name in ids


def test_show_prints_table_and_structure(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run(capsys, "show", "arm6-dh")
    assert code == 0
    assert "6R, spherical wrist" in out
    assert "q2 + 90°" in out and "q3 - 90°" in out and "q4 - 90°" in out
    code, out, _ = run(capsys, "show", "puma560", "--json")
    data = json.loads(out)
    assert data["structure"]["summary"] == "6R, spherical wrist"
    assert len(data["dh"]) == 6


def test_fk_json_matches_library(capsys: pytest.CaptureFixture[str]) -> None:
    q_deg = [10, 45, -30, 20, 35, -60]
    code, out, _ = run(capsys, "fk", "puma560", "--q", *map(str, q_deg), "--json", "--frames")
    assert code == 0
    data = json.loads(out)
    assert set(data) >= {"robot", "q", "T", "position", "euler", "frames"}
    robot = km.load("puma560")
    T = robot.fk(np.radians(q_deg))
    np.testing.assert_allclose(data["T"], T, atol=1e-15)
    np.testing.assert_allclose(data["position"], T[:3, 3], atol=1e-15)
    eul = km.euler_from_matrix(T[:3, :3], "ZYZ", degrees=True)
    np.testing.assert_allclose(data["euler"], eul, atol=1e-12)
    assert len(data["frames"]) == 7


def test_fk_radians_and_euler_sequence(capsys: pytest.CaptureFixture[str]) -> None:
    q = [0.1, -0.2, 0.3]
    code, out, _ = run(
        capsys, "fk", "planar-3r", "--q", *map(str, q), "--rad", "--euler", "xyz", "--json"
    )
    assert code == 0
    T = km.load("planar-3r").fk(q)
    np.testing.assert_allclose(
        json.loads(out)["euler"], km.euler_from_matrix(T[:3, :3], "xyz"), atol=1e-12
    )


def test_fk_text_output(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run(capsys, "fk", "planar-pr", "--q", "0.2", "90")
    assert code == 0
    # Seed 000: x = q1 + l1 + l2 cos q2, y = l2 sin q2.
    robot = km.load("planar-pr")
    T = robot.fk([0.2, np.pi / 2])
    assert f"x = {T[0, 3]:.6f}".rstrip("0") in out


@pytest.mark.parametrize(
    ("argv", "fragment"),
    [
        (("fk", "no-such-robot", "--q", "1"), "no-such-robot"),
        (("fk", "puma560", "--q", "1", "2"), "6 values"),
        (("fk", "puma560", "--q", "1", "2", "3", "4", "5", "nan"), "NaN"),
        (("fk", "puma560", "--q", "1", "2", "3", "4", "5", "abc"), "invalid float"),
        (("fk", "missing/file.yaml", "--q", "1"), "no such robot file"),
        (("fk", str(DATA / "robots" / "bad_typo_alfa.yaml"), "--q", "1"), "alfa"),
        (("fk", "puma560", "--q", "0", "0", "0", "0", "0", "0", "--euler", "ZYQ"), "ZYQ"),
        (("ik", "puma560", "--pose", "1", "2"), "expected 6"),
        (("nonsense",), "invalid choice"),
    ],
)
def test_bad_input_is_one_line_exit_2(
    capsys: pytest.CaptureFixture[str], argv: tuple[str, ...], fragment: str
) -> None:
    code, _, err = run(capsys, *argv)
    assert code == 2
    lines = [ln for ln in err.strip().splitlines() if ln]
    assert len(lines) == 1, err
    assert fragment.lower() in lines[0].lower()
    assert "Traceback" not in err


def test_console_script_runs_without_traceback() -> None:
    proc = subprocess.run(
        [sys.executable, "-m", "kinematica.cli.main", "fk", "ur5", "--q", "1"],
        capture_output=True,
        text=True,
        check=False,
    )
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr
    assert "6 values" in proc.stderr


def test_negative_numbers_in_e_notation(capsys: pytest.CaptureFixture[str]) -> None:
    # argparse alone would read "-1e-05" as an option.
    code, out, err = run(capsys, "fk", "planar-3r", "--q", "-1e-05", "-2.5E+1", "-.5", "--json")
    assert code == 0, err
    assert json.loads(out)["q"] == [-1e-05, -25.0, -0.5]
