"""The jacobian, workspace and trajectory commands: output against the library, exit codes."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from support.helpers import run_cli as run

import kinematica as km


def test_jacobian_text_names_the_wrist(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run(capsys, "jacobian", "puma560", "--q", "10", "20", "30", "40", "0", "60")
    assert code == 0
    assert "rank 5 (regular: 6)" in out and "singularity: wrist" in out


def test_jacobian_json_matches_the_library(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run(
        capsys,
        "jacobian",
        "ur5",
        "--q",
        "10",
        "20",
        "30",
        "40",
        "50",
        "60",
        "--json",
        "--frame",
        "tool",
        "--analytic",
    )
    assert code == 0
    data = json.loads(out)
    ur5 = km.load("ur5")
    q = np.radians([10, 20, 30, 40, 50, 60])
    assert np.allclose(data["jacobian"], ur5.jacobian(q, frame="tool"))
    assert np.allclose(data["analytic"]["jacobian"], ur5.jacobian(q, euler="ZYZ"))
    assert data["rank"] == 6 and data["singularities"] == []
    assert np.isclose(data["manipulability"], km.manipulability(ur5, q))


def test_jacobian_bad_q_is_one_line(capsys: pytest.CaptureFixture[str]) -> None:
    code, _, err = run(capsys, "jacobian", "puma560", "--q", "1", "2")
    assert code == 2 and err.count("\n") == 1 and "6 values" in err


def test_workspace_json_area_of_planar_3r(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run(capsys, "workspace", "planar-3r", "--samples", "50000", "--json")
    assert code == 0
    data = json.loads(out)
    assert data["planar"] and abs(data["area"] / (np.pi * 0.81) - 1) < 0.02
    assert data["slice"]["plane"] == "xy"


def test_workspace_map_png(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    pytest.importorskip("matplotlib")
    png = tmp_path / "map.png"
    code, out, _ = run(
        capsys,
        "workspace",
        "anthropomorphic-3r",
        "--samples",
        "20000",
        "--plane",
        "xz",
        "-o",
        str(png),
    )
    assert code == 0 and "map written" in out and "volume" in out
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_workspace_bad_input(capsys: pytest.CaptureFixture[str]) -> None:
    code, _, err = run(capsys, "workspace", "planar-3r", "--samples", "0")
    assert code == 2 and "samples" in err and "Traceback" not in err
    code, _, err = run(capsys, "workspace", "planar-3r", "--samples", "100", "--at", "9")
    assert code == 2 and "outside the workspace" in err


def test_trajectory_csv(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    csv = tmp_path / "path.csv"
    code, out, _ = run(
        capsys,
        "trajectory",
        "puma560",
        "--from",
        "0",
        "0",
        "0",
        "0",
        "30",
        "0",
        "--to",
        "30",
        "-20",
        "10",
        "20",
        "40",
        "10",
        "--duration",
        "1",
        "-o",
        str(csv),
    )
    assert code == 0 and "written to" in out
    t, q = km.motion.read_csv(csv)
    assert t[0] == 0 and t[-1] == 1.0
    assert np.allclose(q[0], np.radians([0, 0, 0, 0, 30, 0]))
    assert np.allclose(q[-1], np.radians([30, -20, 10, 20, 40, 10]))


def test_trajectory_cartesian_json(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run(
        capsys,
        "trajectory",
        "puma560",
        "--from",
        "10",
        "-20",
        "10",
        "20",
        "40",
        "10",
        "--to",
        "30",
        "-20",
        "10",
        "20",
        "40",
        "10",
        "--cartesian",
        "--json",
    )
    assert code == 0
    data = json.loads(out)
    assert data["events"] == [] and data["duration"] == 2.0
    puma = km.load("puma560")
    q = np.radians(np.array(data["q"]))
    p = puma.fk(q)[:, :3, 3]
    a, b = p[0], p[-1]
    # every sample on the straight line between the end positions
    cross = np.cross(p - a, b - a)
    assert np.abs(cross).max() < 1e-9


def test_trajectory_cartesian_through_a_singularity_reports_it(
    capsys: pytest.CaptureFixture[str],
) -> None:
    code, out, _ = run(
        capsys,
        "trajectory",
        "puma560",
        "--from",
        "0",
        "-30",
        "20",
        "30",
        "10",
        "0",
        "--to",
        "0",
        "-30",
        "20",
        "30",
        "-10",
        "0",
        "--cartesian",
    )
    assert "event: singularity" in out and code in (0, 1)


def test_trajectory_bad_output_extension(capsys: pytest.CaptureFixture[str]) -> None:
    code, _, err = run(
        capsys,
        "trajectory",
        "puma560",
        "--from",
        *["0"] * 6,
        "--to",
        *["1"] * 6,
        "-o",
        "x.txt",
    )
    assert code == 2 and ".csv or .json" in err


PR_XZ_FILE = """\
name = "PR arm of the notes, no base"
convention = "standard"
units = { angle = "deg", length = "m" }
parameters = { l1 = 0.5, l2 = 0.4 }
joints = [
  { theta = 0,         d = "q1 + l1", a = 0,    alpha = 90, limits = [0, 0.5] },
  { theta = "q2 + 90", d = 0,         a = "l2", alpha = 0 },
]
"""


def test_workspace_of_a_planar_arm_out_of_xy_uses_its_plane(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    # It moves in the base's xz plane: the default slice is that plane, and the
    # area is that of tests/motion/test_workspace.py's PR_AREA (r = 0.4, stroke 0.5).
    arm = tmp_path / "pr.toml"
    arm.write_text(PR_XZ_FILE)
    png = tmp_path / "pr-map.png"
    code, out, _ = run(capsys, "workspace", str(arm), "--samples", "50000", "-o", str(png))
    assert code == 0 and png.stat().st_size > 0
    assert "planar workspace in the xz plane" in out and "xz slice at y = " in out
    lens = 2 * 0.4**2 * np.arccos(0.5 / 0.8) - 0.25 * np.sqrt(4 * 0.4**2 - 0.5**2)
    area = np.pi * 0.4**2 + 2 * 0.4 * 0.5 - lens
    code, out, _ = run(capsys, "workspace", str(arm), "--samples", "50000", "--json")
    data = json.loads(out)
    assert data["plane"] == "xz" and data["slice"]["plane"] == "xz"
    assert abs(data["slice"]["area"] / area - 1) < 0.03


def test_trajectory_table_gives_each_joint_its_unit(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run(capsys, "trajectory", "planar-pr", "--from", "0", "0", "--to", "0.2", "30")
    assert code == 0 and "q1 (m)" in out and "q2 (deg)" in out
    code, out, _ = run(
        capsys, "trajectory", "planar-pr", "--from", "0", "0", "--to", "0.2", "0.5", "--rad"
    )
    assert "q2 (rad)" in out


def test_the_cli_reports_the_three_events(tmp_path):
    cmd = [sys.executable, "-m", "kinematica.cli.main", "trajectory", "arm6-dh", "--json"]
    cmd += ["--from", "30", "40", "-30", "10", "10", "0", "--to", "30", "40", "-30", "10", "-10"]
    cmd += ["0", "--cartesian"]
    proc = subprocess.run(cmd, capture_output=True, text=True, cwd=tmp_path, check=False)
    assert proc.returncode == 0, proc.stderr
    kinds = [e["kind"] for e in json.loads(proc.stdout)["events"]]
    assert kinds == ["near_singularity", "speed_jump", "end_branch"]


def test_workspace_refusal_names_the_joint_and_file_needing_limits(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    # Issue 35, item 8: the refusal gave Python advice (robot.with_limits) to a CLI user
    path = tmp_path / "rp.yaml"
    path.write_text(
        "name: rp arm\nconvention: standard\nunits: {angle: deg, length: m}\njoints:\n"
        "  - {theta: q1, d: 0.3, a: 0, alpha: 90}\n  - {theta: 0, d: q2, a: 0, alpha: 0}\n"
    )
    code, _, err = run(capsys, "workspace", str(path))
    assert code == 2
    assert f"add `limits: [lower, upper]` to joint 2 (q2) of {path}" in err


@pytest.mark.parametrize("name", ["ws.txt", "ws.csv", "ws"])
def test_workspace_map_of_no_picture_type_is_refused_before_sampling(
    capsys: pytest.CaptureFixture[str], tmp_path: Path, name: str
) -> None:
    pytest.importorskip("matplotlib")
    target = tmp_path / name
    code, out, err = run(
        capsys, "workspace", "planar-3r", "--samples", "20000000", "-o", str(target)
    )  # 20 million samples would take minutes: refused before any is drawn
    assert code == 2 and out == ""
    assert "internal error" not in err and "Traceback" not in err
    assert f"{target}: cannot draw a map as a file of type" in err and ".png" in err
    assert not target.exists() and list(tmp_path.iterdir()) == []
