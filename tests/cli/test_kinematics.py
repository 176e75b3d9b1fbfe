"""The command line: output against the library, exit codes, one-line errors."""

from __future__ import annotations

import json
import math
import subprocess
import sys
import warnings

import numpy as np
import pytest
from support import DATA
from support.cli import run_in
from support.helpers import run_cli as run
from support.urdf import URDF_DIR

import kinematica as km
from kinematica.cli.main import main
from kinematica.ik.letters import toolbox_letters

# ------------------------------------------------ item 2: over-determined targets


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


def test_cli_prints_the_arm_solutions_with_the_wrist_free(
    capsys: pytest.CaptureFixture[str],
) -> None:
    code = main(["ik", "puma560", "--position", "0.3", "0.2", "0.1", "--ignore-limits", "--json"])
    data = json.loads(capsys.readouterr().out)
    assert code == 0 and data["status"] == "singular"
    assert data["method"] == "analytic:arm-position"
    assert data["free_joints"] == ["q4", "q5", "q6"] and len(data["solutions"]) == 4
    puma = km.load("puma560")
    for q_deg in data["solutions"]:
        np.testing.assert_allclose(puma.fk(np.radians(q_deg))[:3, 3], [0.3, 0.2, 0.1], atol=1e-9)


def test_cli_huge_pose_is_unreachable(capsys: pytest.CaptureFixture[str]) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        code = main(["ik", "ur5", "--pose", "1e300", "0", "0", "0", "0", "0"])
    captured = capsys.readouterr()
    assert code == 1 and "unreachable" in captured.out
    assert "Warning" not in captured.err and "Traceback" not in captured.err
    code = main(["ik", "ur5", "--pose", "1e300", "0", "0", "0", "0", "0", "--json"])
    data = json.loads(capsys.readouterr().out)
    assert code == 1 and data["status"] == "unreachable" and data["gap_m"] == pytest.approx(1e300)


def test_scara_pose_message_is_in_radians_not_metres(capsys: pytest.CaptureFixture[str]) -> None:
    """The report: ``ik scara --pose 0.3 0.2 0.1 0 0 0`` said "3.14159 m outside the reach"."""
    code = main(
        ["ik", "scara", "--pose", "0.3", "0.2", "0.1", "0", "0", "0", "--method", "analytic"]
    )
    out = capsys.readouterr().out
    assert code == 1 and "unreachable" in out
    assert "m outside" not in out and "3.14 rad" in out


def test_position_targets_leave_the_last_joint_free(capsys: pytest.CaptureFixture[str]) -> None:
    """Issue 7 item 3: SCARA positions: q1, q2 by the triangle, q3 by the height, q4 free."""
    scara = km.load("scara")
    q = np.radians([30.0, -60.0, 0.0, 45.0])
    q[2] = 0.1
    res = scara.ik(scara.fk(q)[:3, 3])
    assert res.status == "singular" and res.free_joints == (3,) and res.count == 2
    assert res.branches == ("right-handed", "left-handed")
    d = res.solutions[:, :3] - q[:3]  # q4 aside
    d[:, :2] = km.wrap_angle(d[:, :2])
    assert np.abs(d).max(axis=1).min() < 1e-12
    code = main(
        ["ik", "scara", "--position", "0.3", "0.2", "0.3", "--method", "analytic", "--json"]
    )
    data = json.loads(capsys.readouterr().out)
    assert code == 0 and data["status"] == "singular" and data["free_joints"] == ["q4"]
    for name in ("planar-3r", "planar-prr"):
        robot = km.load(name)
        lo, hi = np.nan_to_num(robot.qlim, posinf=1.0, neginf=-1.0).T
        qs = np.random.default_rng(3).uniform(lo, hi, (20, robot.dof))
        res = robot.ik(robot.fk(qs)[:, :3, 3])
        assert (res.status == "singular").all() and res.free[:, -1].all()
        assert not res.free[:, :-1].any()


def test_huge_target_json_is_valid(capsys: pytest.CaptureFixture[str]) -> None:
    code = main(["ik", "anthropomorphic-3r", "--position", "1e300", "0", "0", "--json"])
    data = json.loads(capsys.readouterr().out)
    assert code == 1 and data["status"] == "unreachable" and data["gap_m"] == 1e300


def test_cli_huge_pose_exits_1_without_traceback(capsys: pytest.CaptureFixture[str]) -> None:
    code = main(["ik", "puma560", "--pose", "1e300", "0", "0", "0", "0", "0"])
    out = capsys.readouterr()
    assert code == 1 and "unreachable" in out.out and "Traceback" not in out.err


def test_cli_ik_json_has_the_letters(capsys: pytest.CaptureFixture[str]) -> None:
    from kinematica.cli.main import main

    code = main(["ik", "puma560", "--pose", "0.4", "0.1", "0.3", "0", "90", "0", "--json"])
    data = json.loads(capsys.readouterr().out)
    assert code == 0
    assert data["letters"] == [toolbox_letters(b) for b in data["branches"]]


def _strict_json(text: str):
    def refuse(token: str) -> None:
        raise AssertionError(f"not valid JSON: {token}")

    return json.loads(text, parse_constant=refuse)


@pytest.mark.parametrize(
    ("pose", "gap"),
    [
        (["1e300", "0", "0", "0", "0", "0"], 1e300),
        (["1.5e308", "1.5e308", "1.5e308", "0", "0", "0"], None),
    ],
    ids=["far", "overflow"],
)
def test_cli_json_of_a_huge_target(pose, gap, capsys: pytest.CaptureFixture[str]) -> None:
    code = main(["ik", "panda", "--pose", *pose, "--json"])
    out, err = capsys.readouterr()
    # a 7-joint arm is held at a joint first; nothing there, the search answers, and says so
    assert code == 1
    assert all(line.startswith("kinematica: note: ") for line in err.splitlines()), err
    data = _strict_json(out)
    assert data["status"] == "unreachable" and data["method"] == "numeric:lm"
    assert data["solutions"] == [] and "closed form" not in data["message"]
    if gap is None:
        assert data["gap_m"] is None  # JSON has no infinity
    else:
        assert math.isclose(data["gap_m"], gap, rel_tol=1e-12)


def test_the_cli_answers_a_pasted_pose(tmp_path):
    import json

    cmd = ["ik", "anthropomorphic-3r", "--json"]
    cmd += ["--pose", "0.52123", "0.30093", "0.80921", "-60", "90", "100"]
    proc = run_in(tmp_path, *cmd)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    out = json.loads(proc.stdout)
    assert out["status"] == "ok"
    assert any("precision its numbers carry" in n for n in out["notes"])


def test_cli_ik_json_and_exit_codes(capsys: pytest.CaptureFixture[str]) -> None:
    puma = km.load("puma560")
    T = puma.fk([0.3, -0.6, 0.2, 0.5, 0.9, -0.4])
    code = main(["ik", "puma560", "--matrix", *map(str, T.ravel()), "--json", "--ignore-limits"])
    data = json.loads(capsys.readouterr().out)
    assert code == 0
    assert data["status"] == "ok" and len(data["solutions"]) == 8
    for q_deg in data["solutions"]:
        np.testing.assert_allclose(puma.fk(np.radians(q_deg)), T, atol=1e-9)
    code = main(["ik", "puma560", "--position", "3", "0", "0"])
    out = capsys.readouterr().out
    assert code == 1
    assert "not found" in out or "unreachable" in out


def test_cli_ik_at_an_arm_angle(capsys: pytest.CaptureFixture[str]) -> None:
    iiwa = km.load("iiwa14")
    T = iiwa.fk([0.3, 0.7, -0.4, 1.2, 0.5, -0.8, 0.2])
    matrix = [*map(str, T.ravel())]
    code, out, _ = run(capsys, "ik", "iiwa14", "--matrix", *matrix, "--arm-angle", "30",
                       "--ignore-limits", "--json")  # fmt: skip
    data = json.loads(out)
    assert code == 0 and data["method"] == "analytic:srs" and len(data["solutions"]) == 8
    q = np.radians(data["solutions"])
    np.testing.assert_allclose(iiwa.fk(q), np.broadcast_to(T, (8, 4, 4)), atol=1e-9)
    np.testing.assert_allclose(iiwa.arm_angle(q), math.radians(30), atol=1e-9)
    psi = repr(math.radians(30))
    code, rad, _ = run(capsys, "ik", "iiwa14", "--matrix", *matrix, "--rad",
                       "--arm-angle", psi, "--ignore-limits", "--json")  # fmt: skip
    np.testing.assert_allclose(json.loads(rad)["solutions"], q, atol=1e-12)
    code, _, err = run(capsys, "ik", "puma560", "--pose", "0.5", "0", "0.5", "0", "180", "0",
                       "--arm-angle", "30")  # fmt: skip
    assert code == 2 and err.startswith("kinematica: error: --arm-angle is a parameter")
    code, out, _ = run(capsys, "ik", "iiwa14", "--pose", "5", "0", "0.5", "0", "180", "0",
                       "--arm-angle", "30")  # fmt: skip
    assert code == 1 and "unreachable" in out


def test_show_prints_the_extracted_table_of_a_urdf(tmp_path):
    proc = run_in(tmp_path, "show", str(URDF_DIR / "kuka_kr16_2.urdf"))
    assert proc.returncode == 0, proc.stderr
    out = proc.stdout
    assert "kuka_kr16_2: 6R, spherical wrist" in out
    assert "standard DH convention" in out
    # a1 = 0.26 (shoulder offset), a2 = 0.68, a3 = 0.035, d4 = 0.67 along -z3: the KR 16's lengths
    for cell in ("0.26", "0.68", "0.035", "-0.67", "[-185°, 185°]"):
        assert cell in out


# ------------------------------------------------ show: the IK solver of pose targets
_GENERAL_6R = """name: General 6R
convention: standard
units: {angle: rad, length: m}
joints:
  - {theta: q1, d: 0.2, a: 0.25, alpha: 0.8}
  - {theta: q2, d: -0.2, a: -0.35, alpha: -1.2}
  - {theta: q3, d: -0.1, a: -0.35, alpha: 2.1}
  - {theta: q4, d: 0.4, a: 0.1, alpha: -0.7}
  - {theta: q5, d: -0.05, a: 0.4, alpha: 1.4}
  - {theta: q6, d: 0.3, a: -0.1, alpha: -2.6}
"""
_SLIDE_6 = """name: RPRRRR arm
convention: standard
units: {angle: deg, length: m}
joints:
  - {theta: q1, d: 0.4, a: 0, alpha: 90}
  - {theta: 20, d: q2, a: 0.1, alpha: -60, limits: [0, 1]}
  - {theta: q3, d: 0.05, a: 0.3, alpha: 90}
  - {theta: q4, d: 0.3, a: 0.02, alpha: -90}
  - {theta: q5, d: 0, a: 0.01, alpha: 90}
  - {theta: q6, d: 0.1, a: 0, alpha: 0}
"""


@pytest.mark.parametrize(
    ("robot", "line"),
    [
        ("puma560", "IK of poses: analytic:spherical-wrist (closed form: every solution)"),
        ("ur5", "IK of poses: analytic:three-parallel-6R (closed form: every solution)"),
        ("general-6r.yaml", "IK of poses: analytic:general-6R (closed form: every solution)"),
        (
            "panda",
            "IK of poses: analytic:spherical-shoulder (closed form: every solution with q7 "
            "held at a value, its redundancy parameter)",
        ),
        (
            "slide-6.yaml",
            "IK of poses: numeric:lm (a local search that finds one solution at most; more "
            "may exist)\n  no closed form applies: a slide outside the closed-form families "
            "(6 joints, RPRRRR), and the general 6R elimination takes revolute joints only "
            "(joint 2 slides)",
        ),
    ],
)
def test_show_names_the_ik_solver_of_poses(tmp_path, robot: str, line: str) -> None:
    (tmp_path / "general-6r.yaml").write_text(_GENERAL_6R)
    (tmp_path / "slide-6.yaml").write_text(_SLIDE_6)
    proc = run_in(tmp_path, "show", robot)
    assert proc.returncode == 0, proc.stderr
    head = proc.stdout.split("\n\n")[0]  # before the DH table
    assert line in head
    proc = run_in(tmp_path, "show", robot, "--json")
    assert proc.returncode == 0, proc.stderr
    solver = json.loads(proc.stdout)["ik"]["pose"]
    assert set(solver) == {"method", "parameter", "complete", "reason"}
    assert line.startswith(f"IK of poses: {solver['method']} (")
    assert solver["parameter"] == ("q7" if robot == "panda" else None)
    assert solver["complete"] is (solver["method"] != "numeric:lm")
    # the reason the answers' note gives
    loaded = km.load(robot if "." not in robot else tmp_path / robot)
    res = loaded.ik(loaded.fk(np.full(loaded.dof, 0.3)), respect_limits=False)
    assert res.method == solver["method"]
    if solver["reason"] is None:
        assert not any("no closed form applies" in n for n in res.notes)
    else:
        assert solver["reason"] in line
        assert any(f"no closed form applies: {solver['reason']};" in n for n in res.notes)


def test_a_note_the_headline_says_is_said_once(capsys: pytest.CaptureFixture[str]) -> None:
    # Issue 35, item 6: the example-robot-data UR5 said "may not give all" twice per IK
    urdf = str(DATA / "urdf" / "ur5_robot.urdf")
    code, out, err = run(capsys, "ik", urdf, "--pose", "0.4", "0.1", "0.3", "0", "90", "0")
    assert code == 0
    assert (out + err).count("may not give all") == 1
