"""What the command line says, read as a user reads it (issue 22, item 13).

Each test pins one sentence that used to be wrong: a status said twice, a tool
that is not there, a number where the file gives a name, a column without its
unit, a note on a rotation copied with ten digits, a hint in the wrong unit, a
folder called an unknown file type, a GIF that browsers play ten times too slowly.
"""

from __future__ import annotations

import json
import warnings
from pathlib import Path

import numpy as np
import pytest
from test_cli_motion import run

import kinematica as km
from kinematica.ik.targets import QUIET_PROJECTION, ROTATION_TOL
from kinematica.spatial.checks import orthonormality_error

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


def test_trajectory_table_gives_each_joint_its_unit(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run(capsys, "trajectory", "planar-pr", "--from", "0", "0", "--to", "0.2", "30")
    assert code == 0 and "q1 (m)" in out and "q2 (deg)" in out
    code, out, _ = run(
        capsys, "trajectory", "planar-pr", "--from", "0", "0", "--to", "0.2", "0.5", "--rad"
    )
    assert "q2 (rad)" in out


def _scaled(T: np.ndarray, eps: float) -> np.ndarray:
    """T with its rotation scaled by 1 + eps: max |RᵀR − I| = 2 eps + eps²."""
    S = T.copy()
    S[:3, :3] *= 1.0 + eps
    return S


def test_projection_note_only_beyond_round_off_of_the_tolerance() -> None:
    arm = km.load("arm6-dh")
    T = arm.fk(Q6)
    assert QUIET_PROJECTION == ROTATION_TOL
    ten = np.round(T, 10)  # a copy printed with 10 decimals: ~5e-11 from orthonormal
    assert 0 < orthonormality_error(ten[:3, :3]) < QUIET_PROJECTION
    res = arm.ik(ten)
    assert res.status == "ok" and res.notes == ()
    six = np.round(T, 6)
    assert arm.ik(six).notes and "projected onto SO(3)" in arm.ik(six).notes[0]
    # both sides of the boundary: orthonormal to 0.9 and to 1.2 times the constant
    inside, outside = _scaled(T, 0.45 * QUIET_PROJECTION), _scaled(T, 0.6 * QUIET_PROJECTION)
    assert orthonormality_error(inside[:3, :3]) < QUIET_PROJECTION
    assert orthonormality_error(outside[:3, :3]) > QUIET_PROJECTION
    assert arm.ik(inside).notes == ()
    assert "projected onto SO(3)" in arm.ik(outside).notes[0]


def test_view_hint_gives_the_unit_of_each_joint(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    code, out, _ = run(capsys, "view", "planar-pr", "-o", str(tmp_path / "pr.html"))
    assert code == 0 and "q1 in m, q2 in degrees" in out and "#q=... in degrees" not in out
    code, out, _ = run(capsys, "view", "arm6-dh", "-o", str(tmp_path / "a.html"))
    assert "add #q=... in degrees to start there" in out


def test_a_folder_is_not_an_unknown_file_type(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    code, _, err = run(capsys, "fk", str(tmp_path), "--q", "0")
    assert code == 2 and err.count("\n") == 1
    assert "is a directory, not a robot file" in err and "no extension" not in err
    with pytest.raises(km.RobotFileError, match="is a directory, not a robot file"):
        km.load(tmp_path)


def test_degrees_given_to_the_radian_api_warn_without_limits() -> None:
    arm = km.load("arm6-dh")  # no joint limits: nothing else would say it
    with pytest.warns(km.UnitWarning, match=r"joint 1 = 30 rad is more than a full turn"):
        arm.fk([30, 40, -30, 10, 60, -20])
    with pytest.warns(km.UnitWarning, match=r"joint 2 \(row \(1,\)\) = 7 rad"):
        arm.fk(np.array([[0.0] * 6, [0.0, 7.0, 0, 0, 0, 0]]))
    with pytest.warns(km.UnitWarning, match="is it in degrees"):
        arm.jacobian([0, 0, 0, 0, 90, 0])
    assert issubclass(km.UnitWarning, km.KinematicaWarning)
    turn = 2 * np.pi  # the boundary, single call (the core) and batch (numpy) alike
    for q in ([turn * (1 - 1e-12), 0, 0, 0, 0, 0], [[-turn * (1 - 1e-12), 0, 0, 0, 0, 0]]):
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            arm.fk(q)
            arm.jacobian(q)
    for q in ([turn * (1 + 1e-12), 0, 0, 0, 0, 0], [[-turn * (1 + 1e-12), 0, 0, 0, 0, 0]]):
        with pytest.warns(km.UnitWarning):
            arm.fk(q)
    with warnings.catch_warnings():  # NaN and inf are said otherwise, not as a unit slip
        warnings.simplefilter("ignore", km.KinematicaWarning)
        warnings.simplefilter("error", km.UnitWarning)
        arm.fk([[np.inf, 0, 0, 0, 0, 0], [np.nan, 0, 0, 0, 0, 0]])
    # a joint with limits of its own is judged by them, a prismatic joint not at all
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        km.load("planar-prr").fk([0.1, 0.5, 0.5])
    with pytest.warns(km.KinematicaWarning, match="outside its limits") as caught:
        km.load("puma560").fk([30, 0, 0, 0, 0, 0])
    assert not any(issubclass(w.category, km.UnitWarning) for w in caught)


def test_robot_file_unit_slips_are_unit_warnings(tmp_path: Path) -> None:
    arm = tmp_path / "arm.toml"
    arm.write_text(
        'name = "r"\nconvention = "standard"\nunits = { angle = "rad", length = "m" }\n'
        'joints = [ { theta = "q1", d = 0, a = 0.3, alpha = 90 } ]\n'
    )
    with pytest.warns(km.UnitWarning, match="is it in degrees"):
        km.load(arm)


def test_gif_plays_at_most_50_fps(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    from PIL import Image

    from kinematica.viz import write_trajectory
    from kinematica.viz.animate import GIF_MAX_FPS, gif_rate

    assert GIF_MAX_FPS == 50.0 and gif_rate(100.0) == 50.0 and gif_rate(50.0) == 50.0
    assert gif_rate(51.0) == 50.0 and gif_rate(49.0) == 49.0 and gif_rate(8.0) == 8.0
    t = np.arange(0.0, 0.2001, 0.01)  # 100 samples a second, as `trajectory` writes
    csv = write_trajectory(tmp_path / "path.csv", t, np.outer(t, [1.0, 2.0]))
    out = tmp_path / "arm.gif"
    code, text, _ = run(
        capsys, "animate", "planar-pr", "--trajectory", str(csv), "-o", str(out), "--json"
    )
    data = json.loads(text)
    assert code == 0 and data["fps"] == 50.0 and data["frames"] == 11  # 0.2 s in real time
    assert "100 fps lowered to 50 fps" in data["note"]
    with Image.open(out) as gif:
        durations = []
        for k in range(gif.n_frames):
            gif.seek(k)
            durations.append(gif.info["duration"])
    assert set(durations) == {20}
    code, text, _ = run(capsys, "animate", "planar-pr", "--trajectory", str(csv), "-o", str(out))
    assert "note: 100 fps lowered to 50 fps" in text
    mp4 = tmp_path / "slow.gif"  # a rate a GIF plays as it is: no note
    csv = write_trajectory(tmp_path / "slow.csv", t[::5], np.outer(t[::5], [1.0, 2.0]))
    code, text, _ = run(
        capsys, "animate", "planar-pr", "--trajectory", str(csv), "-o", str(mp4), "--json"
    )
    assert json.loads(text)["fps"] == 20.0 and json.loads(text)["note"] is None


def test_one_solution_is_singular(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    out_file = tmp_path / "one.png"
    code, out, _ = run(
        capsys, "plot", "planar-pr", "--q", "0.2", "30", "--solutions", "-o", str(out_file)
    )
    assert code == 0 and "1 IK solution of" in out and "1 IK solutions" not in out
