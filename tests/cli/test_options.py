"""What every subcommand shares (``cli/options.py``): units, precision, checked numbers, JSON.

Expected numbers come from the library called directly (the CLI is a printing
layer over it).
"""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest
from support.cli import one_line, run, script, strict_json
from support.urdf import XACRO, write

import kinematica as km
import kinematica.io.xacro as xacro_module


def printed_matrix(out: str, title: str = "T:") -> np.ndarray:
    """The 4x4 matrix printed under ``title``."""
    lines = out.split(f"\n{title}\n", 1)[1].splitlines()[:4]
    return np.array([[float(v) for v in ln.split()] for ln in lines])


def test_minus_inf_in_q_is_a_number_rejected_naming_q() -> None:
    proc = script("fk", "puma560", "--q", "0", "-inf", "0", "0", "0", "0")  # console script
    assert proc.returncode == 2
    expected = "kinematica: error: --q needs finite numbers, got -inf (value 2)"
    assert one_line(proc.stderr) == expected


@pytest.mark.parametrize(
    ("argv", "expected"),
    [
        (("fk", "ur5", "--q", "0", "0", "-Infinity", "0", "nan", "0"), "--q needs finite numbers"),
        (("fk", "ur5", "--q", "0", "0", "0", "0", "0", "1e999"), "got inf (value 6)"),
        (("ik", "puma560", "--pose", "0.1", "0.1", "0.1", "0", "0", "nan"), "--pose needs finite"),
        (("ik", "puma560", "--pose", "-inf", "0.1", "0.1", "0", "0", "0"), "--pose needs finite"),
        (("ik", "puma560", "--position", "0.1", "inf", "0"), "--position needs finite numbers"),
        (("ik", "puma560", "--matrix", *["0"] * 15, "nan"), "--matrix needs finite numbers"),
        (("ik", "puma560", "--pose", *["0"] * 6, "--q0", *["0"] * 5, "-nan"), "--q0 needs finite"),
    ],
)
def test_non_finite_values_name_the_option(
    capsys: pytest.CaptureFixture[str], argv: tuple[str, ...], expected: str
) -> None:
    code, _, err = run(capsys, *argv)
    assert code == 2
    line = one_line(err)
    assert expected in line
    assert "p contains" not in line and "target" not in line


def test_a_bad_matrix_is_named_as_the_option(capsys: pytest.CaptureFixture[str]) -> None:
    rows = ["1", "0", "0", "0.3", "0", "1", "0", "0", "0", "0", "1.5", "0.2", "0", "0", "0", "1"]
    code, _, err = run(capsys, "ik", "puma560", "--matrix", *rows)
    assert code == 2
    assert one_line(err).startswith("kinematica: error: --matrix rotation is not orthonormal")


def test_precision_option(capsys: pytest.CaptureFixture[str]) -> None:
    q = ["10", "20", "30", "40", "50", "60"]
    code, out, _ = run(capsys, "fk", "puma560", "--q", *q, "--precision", "3")
    assert code == 0
    T = km.load("puma560").fk(np.radians([10, 20, 30, 40, 50, 60]))
    printed = printed_matrix(out)
    np.testing.assert_allclose(printed, T, rtol=5e-3, atol=1e-12)
    assert not np.allclose(printed, T, rtol=1e-4, atol=0)  # really rounded to 3 digits
    code, out, _ = run(capsys, "ik", "puma560", "--pose", "0.4", "0.1", "0.3", "0", "90", "0",
                       "--precision", "4")  # fmt: skip
    row = out.splitlines()[4].split()
    assert all(len(v.lstrip("-").replace(".", "").lstrip("0")) <= 4 for v in row[1:7])


def test_fk_json_has_every_digit(capsys: pytest.CaptureFixture[str]) -> None:
    q = [0.1, -0.7, 0.3, 1.1, -0.4, 2.0]
    code, out, _ = run(capsys, "fk", "ur5", "--q", *map(repr, q), "--rad", "--json", "--frames")
    assert code == 0
    data = strict_json(out)
    robot = km.load("ur5")
    assert data["T"] == robot.fk(q).tolist()  # exact: repr round trip
    assert data["frames"] == robot.fk(q, all_frames=True).tolist()
    assert data["position"] == robot.fk(q)[:3, 3].tolist()


def test_a_millimetre_robot_prints_millimetres(capsys: pytest.CaptureFixture[str]) -> None:
    q = [10, 20, 30, 40, 50, 60]
    T = km.load("irb120").fk(np.radians(q))
    code, out, _ = run(capsys, "fk", "irb120", "--q", *map(str, q), "--json")
    data = strict_json(out)
    assert data["units"] == {"angle": "deg", "length": "mm"}
    np.testing.assert_allclose(data["position"], T[:3, 3] * 1000, rtol=1e-15)
    np.testing.assert_allclose(np.array(data["T"])[:3, :3], T[:3, :3], rtol=0, atol=0)
    code, out, _ = run(capsys, "fk", "irb120", "--q", *map(str, q))
    assert code == 0
    assert "units: deg for angles, mm for lengths" in out
    assert "position (mm):" in out
    np.testing.assert_allclose(printed_matrix(out)[:3, 3], T[:3, 3] * 1000, rtol=1e-9)


def test_units_option_overrides_the_file(capsys: pytest.CaptureFixture[str]) -> None:
    q = [10, 20, 30, 40, 50, 60]
    code, out, _ = run(capsys, "fk", "irb120", "--q", *map(str, q), "--units", "m", "--json")
    data = strict_json(out)
    assert data["units"]["length"] == "m"
    assert data["position"] == km.load("irb120").fk(np.radians(q))[:3, 3].tolist()
    code, out, _ = run(capsys, "fk", "puma560", "--q", *map(str, q), "--units", "mm", "--json")
    assert code == 0
    data = strict_json(out)
    assert data["units"]["length"] == "mm"
    np.testing.assert_allclose(
        data["position"], km.load("puma560").fk(np.radians(q))[:3, 3] * 1000, rtol=1e-15
    )


def test_prismatic_joints_and_poses_in_millimetres(capsys: pytest.CaptureFixture[str]) -> None:
    robot = km.load("stanford")
    q = np.array([10.0, 20.0, 500.0, 40.0, 50.0, 60.0])  # q3 in mm
    q_si = np.where(robot.is_prismatic, q / 1000, np.radians(q))
    code, out, _ = run(capsys, "fk", "stanford", "--q", *map(str, q), "--units", "mm", "--json")
    data = strict_json(out)
    T = robot.fk(q_si)
    np.testing.assert_allclose(data["position"], T[:3, 3] * 1000, rtol=1e-14)
    pose = [*data["position"], *data["euler"]]
    code, out, err = run(capsys, "ik", "stanford", "--pose", *map(repr, pose), "--units", "mm",
                         "--json", "--ignore-limits")  # fmt: skip
    assert code == 0, err
    data = strict_json(out)
    assert data["units"] == {"angle": "deg", "length": "mm"}
    assert np.abs(np.array(data["solutions"]) - q).max(axis=1).min() < 1e-6


def test_ik_position_in_millimetres(capsys: pytest.CaptureFixture[str]) -> None:
    robot = km.load("irb120")
    q = np.radians([10, 20, 30, 40, 50, 60])
    p_mm = (robot.fk(q)[:3, 3] * 1000).tolist()
    code, out, err = run(capsys, "ik", "irb120", "--position", *map(repr, p_mm), "--json")
    assert code == 0, err
    solutions = strict_json(out)["solutions"]
    assert solutions
    for sol in solutions:
        np.testing.assert_allclose(robot.fk(np.radians(sol))[:3, 3] * 1000, p_mm, atol=1e-6)


def test_show_speaks_the_file_units(capsys: pytest.CaptureFixture[str]) -> None:
    spec = km.load("irb120").source_spec
    assert spec is not None
    code, out, _ = run(capsys, "show", "irb120", "--json")
    data = strict_json(out)
    assert data["units"] == {"angle": "deg", "length": "mm"}
    assert [row["d"] for row in data["dh"]] == pytest.approx([j.d * 1000 for j in spec.joints])
    assert [row["alpha"] for row in data["dh"]] == pytest.approx(
        [np.degrees(j.alpha) for j in spec.joints]
    )
    code, out, _ = run(capsys, "show", "irb120")
    assert "d (mm)" in out and "a (mm)" in out and "290" in out
    code, out, _ = run(capsys, "show", "stanford", "--units", "mm")
    assert code == 0
    assert "[304.8, 1270] mm" in out


def test_json_is_valid_when_numbers_are_not_finite(capsys: pytest.CaptureFixture[str]) -> None:
    pose = ["1e300", "0", "0", "0", "0", "0"]
    code, out, err = run(capsys, "ik", "panda", "--pose", *pose, "--json")
    assert code in (0, 1), err
    data = strict_json(out)
    assert data["status"] in ("unreachable", "not_found")


needs_xacro = pytest.mark.skipif(
    xacro_module._xacro_dir() is None, reason="the xacro package is not installed"
)


@needs_xacro
def test_the_command_line_option(tmp_path):
    path = write(tmp_path, XACRO, "arm.urdf")

    def show(*extra: str) -> subprocess.CompletedProcess[str]:
        return subprocess.run(
            [sys.executable, "-m", "kinematica.cli.main", "show", str(path), "--json", *extra],
            capture_output=True,
            text=True,
            cwd=tmp_path,
            check=False,
        )

    refused = show()
    assert refused.returncode == 2
    assert len(refused.stderr.strip().splitlines()) == 1
    assert "--xacro" in refused.stderr
    expanded = show("--xacro")
    assert expanded.returncode == 0, expanded.stderr
    assert '"xarm"' in expanded.stdout
