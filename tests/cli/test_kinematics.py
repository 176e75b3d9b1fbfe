"""The command line: output against the library, exit codes, one-line errors."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest
from support import DATA
from support.helpers import run_cli as run

import kinematica as km


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


Q6 = np.radians([30, 40, -30, 10, 60, -20])


def matrix_args(T: np.ndarray) -> list[str]:
    return ["--matrix", *(repr(float(v)) for v in T.ravel())]


def test_ik_status_is_said_once(capsys: pytest.CaptureFixture[str]) -> None:
    puma = km.load("puma560")
    wrist = puma.fk(np.radians([20, -30, 40, 10, 0, 0]))  # q5 = 0: wrist singular
    code, out, _ = run(capsys, "ik", "puma560", *matrix_args(wrist))
    first = out.splitlines()[0]
    assert code == 0 and "singular: infinitely many solutions" in first
    assert "singular — singular" not in first
    far = np.eye(4)
    far[:3, 3] = [5.0, 0.0, 0.0]
    code, out, _ = run(capsys, "ik", "puma560", *matrix_args(far))
    first = out.splitlines()[0]
    assert code == 1 and "unreachable: the target is at least" in first
    assert "unreachable — unreachable" not in first
    # a message that does not open with its status keeps it in front
    code, out, _ = run(capsys, "ik", "puma560", *matrix_args(puma.fk(Q6)))
    assert out.splitlines()[0].startswith(f"{puma.name}: ok — ")


def test_fk_frames_say_with_tool_only_for_a_tool(capsys: pytest.CaptureFixture[str]) -> None:
    q = ["--q", "30", "40", "-30", "10", "60", "-20"]
    code, out, _ = run(capsys, "fk", "arm6-dh", *q, "--frames")
    assert code == 0 and "\n0T6:\n" in out and "with tool" not in out
    code, out, _ = run(capsys, "fk", "panda", *q, "0", "--frames")  # panda has a flange
    assert code == 0 and "0T7 (with tool):" in out


def test_show_names_the_parameters_the_file_uses(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run(capsys, "show", "arm6-dh")
    assert code == 0
    rows = {line.split()[0]: line for line in out.splitlines() if line.strip()[:1].isdigit()}
    assert "l1 = 0.5" in rows["1"] and "l2 = 0.4" in rows["2"] and "l4 = 0.1" in rows["6"]
    code, out, _ = run(capsys, "show", "planar-pr")  # a prismatic offset written q1 + l1
    assert "q1 + l1 = q1 + 0.5" in out
    code, out, _ = run(capsys, "show", "arm6-dh", "--units", "mm")
    assert "l1 = 500" in out
