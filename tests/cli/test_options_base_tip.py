"""``--base``/``--tip`` on every command that takes a robot: the chain they cut is the one used.

A small URDF (three revolute joints, then a fixed tool 0.1 m beyond the last)
is cut three ways: the whole chain (tip ``tool``, the single leaf), ``--tip
l3`` (no tool offset) and ``--base l1`` (joints 2 and 3). Each command's
output is compared with the library's answer for the robot loaded with the
same base and tip, and must change with them; for a robot that is not a
URDF, the options are refused.
"""

from __future__ import annotations

import json
import subprocess
from pathlib import Path

import numpy as np
import pytest
from support.cli import run_in
from support.helpers import assert_transform_close
from support.helpers import run_cli as run
from support.urdf import URDF_DIR, reference_file

import kinematica as km

URDF = """<robot name="tiny">
  <link name="base"/><link name="l1"/><link name="l2"/><link name="l3"/><link name="tool"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/>
    <origin xyz="0.3 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="j3" type="revolute"><parent link="l2"/><child link="l3"/>
    <origin xyz="0.25 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="fixed_tool" type="fixed"><parent link="l3"/><child link="tool"/>
    <origin xyz="0.1 0 0"/></joint>
</robot>
"""

#: The three cuts: options, and the keywords of km.load giving the same robot.
CUTS = {
    "whole": ((), {}),
    "tip": (("--tip", "l3"), {"tip": "l3"}),
    "base": (("--base", "l1"), {"base": "l1"}),
}


@pytest.fixture
def urdf(tmp_path: Path) -> str:
    path = tmp_path / "tiny.urdf"
    path.write_text(URDF)
    return str(path)


def answer(capsys: pytest.CaptureFixture[str], *argv: str) -> dict[str, object]:
    code, out, err = run(capsys, *argv, "--json")
    assert code == 0, err
    data: dict[str, object] = json.loads(out)
    return data


def test_the_cuts_are_different_robots(urdf: str) -> None:
    robots = {cut: km.load(urdf, **kw) for cut, (_, kw) in CUTS.items()}
    assert [r.dof for r in robots.values()] == [3, 3, 2]
    q = [0.2, 0.4, -0.3]
    assert not np.allclose(robots["whole"].fk(q), robots["tip"].fk(q))


def test_jacobian_uses_the_chain(capsys: pytest.CaptureFixture[str], urdf: str) -> None:
    q_deg = {"whole": ["10", "20", "30"], "tip": ["10", "20", "30"], "base": ["20", "30"]}
    seen = []
    for cut, (options, kw) in CUTS.items():
        out = answer(capsys, "jacobian", urdf, *options, "--q", *q_deg[cut])
        J = np.array(out["jacobian"], dtype=float)
        ref = km.load(urdf, **kw).jacobian(np.radians([float(v) for v in q_deg[cut]]))
        np.testing.assert_allclose(J, ref, atol=1e-12)
        seen.append(J)
    assert seen[0].shape == seen[1].shape and not np.allclose(seen[0], seen[1])
    assert seen[2].shape == (6, 2)


def test_workspace_uses_the_chain(capsys: pytest.CaptureFixture[str], urdf: str) -> None:
    bounds = {}
    for cut, (options, kw) in CUTS.items():
        out = answer(capsys, "workspace", urdf, *options, "--samples", "3000", "--seed", "4")
        ref = km.workspace(km.load(urdf, **kw), samples=3000, seed=4)
        np.testing.assert_allclose(np.array(out["bounds"], dtype=float), ref.bounds, atol=1e-12)
        bounds[cut] = ref.bounds
    # The tool sticks out 0.1 m beyond l3 (seen along x); from l1, joint 1 no longer
    # swings the arm about z, so y stays 0.
    assert bounds["whole"][1, 0] == pytest.approx(bounds["tip"][1, 0] + 0.1, abs=0.01)
    assert np.ptp(bounds["base"][:, 1]) < 1e-9 < np.ptp(bounds["whole"][:, 1])


def test_trajectory_uses_the_chain(capsys: pytest.CaptureFixture[str], urdf: str) -> None:
    out = answer(capsys, "trajectory", urdf, "--base", "l1", "--from", "0", "0", "--to", "10", "20")
    assert np.array(out["q"], dtype=float).shape[1] == 2
    code, _, err = run(capsys, "trajectory", urdf, "--base", "l1", "--from", "0", "0", "0",
                       "--to", "1", "2", "3")  # fmt: skip
    assert code == 2 and "--from needs 2 values" in err
    # Cartesian: the straight line of the tool, followed by the chain from l1 (two joints).
    out = answer(capsys, "trajectory", urdf, "--base", "l1", "--from", "20", "30",
                 "--to", "30", "40", "--cartesian", "--duration", "0.05")  # fmt: skip
    q = np.radians(np.array(out["q"], dtype=float))
    arm = km.load(urdf, base="l1")
    p0, p1 = arm.fk(q[0])[:3, 3], arm.fk(q[-1])[:3, 3]
    for i, (t, qi) in enumerate(zip(out["t"], q, strict=True)):  # type: ignore[call-overload]
        s = float(km.motion.time_scaling("quintic", [t], 0.05)[0][0])
        np.testing.assert_allclose(arm.fk(qi)[:3, 3], p0 + s * (p1 - p0), atol=1e-9, err_msg=i)


def test_plot_uses_the_chain(capsys: pytest.CaptureFixture[str], urdf: str, tmp_path: Path) -> None:
    pictures = []
    for cut, options in (("whole", ()), ("tip", ("--tip", "l3"))):
        out = tmp_path / f"{cut}.png"
        code, _, err = run(capsys, "plot", urdf, *options, "--q", "10", "20", "30",
                           "-o", str(out), "--size", "200", "160")  # fmt: skip
        assert code == 0, err
        pictures.append(out.read_bytes())
    assert pictures[0] != pictures[1]
    code, _, err = run(capsys, "plot", urdf, "--base", "l1", "--q", "10", "20", "30",
                       "-o", str(tmp_path / "x.png"))  # fmt: skip
    assert code == 2 and "--q needs 2 values" in err


def test_animate_uses_the_chain(
    capsys: pytest.CaptureFixture[str], urdf: str, tmp_path: Path
) -> None:
    csv = tmp_path / "path.csv"
    csv.write_text("t,q1,q2\n0,0,0\n0.1,0.1,0.2\n")
    gif = tmp_path / "arm.gif"
    code, _, err = run(capsys, "animate", urdf, "--trajectory", str(csv), "-o", str(gif))
    assert code == 2 and "2 joint column(s)" in err and "the robot has 3" in err
    code, _, err = run(capsys, "animate", urdf, "--base", "l1", "--trajectory", str(csv),
                       "-o", str(gif), "--size", "120", "100")  # fmt: skip
    assert code == 0, err
    assert gif.stat().st_size > 0


def test_derive_uses_the_chain(capsys: pytest.CaptureFixture[str], urdf: str) -> None:
    pytest.importorskip("sympy")
    # From l2 the chain is joint 3 alone (the whole URDF's report has q_{1}..q_{3}).
    code, out, err = run(capsys, "derive", urdf, "--base", "l2", "--lang", "en")
    assert code == 0, err
    assert "q_{1}" in out and "q_{2}" not in out and "q_{3}" not in out


@pytest.mark.parametrize(
    "argv",
    [
        ("jacobian", "planar-3r", "--q", "0", "0", "0"),
        ("workspace", "planar-3r", "--samples", "10"),
        ("trajectory", "planar-3r", "--from", "0", "0", "0", "--to", "1", "2", "3"),
        ("plot", "planar-3r", "--q", "0", "0", "0", "-o", "never.png"),
        ("animate", "planar-3r", "--trajectory", "never.csv", "-o", "never.gif"),
        ("view", "planar-3r", "-o", "never.html"),
        ("derive", "planar-3r"),
    ],
)
@pytest.mark.parametrize("option", [("--base", "link"), ("--tip", "link"), ("--xacro",)])
def test_base_and_tip_are_refused_for_a_robot_that_is_not_a_urdf(
    capsys: pytest.CaptureFixture[str],
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    argv: tuple[str, ...],
    option: tuple[str, ...],
) -> None:
    monkeypatch.chdir(tmp_path)  # were a file written, it would land here
    code, out, err = run(capsys, *argv, *option)
    assert code == 2
    assert err.count("\n") == 1 and f"{option[0][2:]}: only for URDF files" in err, err
    assert not out and not list(tmp_path.iterdir())


def test_every_command_takes_base_and_tip_for_a_urdf(tmp_path):
    ur5 = str(URDF_DIR / "ur5_robot.urdf")

    def run(*args: str) -> subprocess.CompletedProcess[str]:
        return run_in(tmp_path, *args)  # in-process: test_main runs the real script

    default = run("show", ur5)  # ee_link and tool0 both on wrist_3_link: tool0, said
    assert default.returncode == 0, default.stderr
    assert "warning" in default.stderr and "'tool0'" in default.stderr
    assert run("show", ur5, "--tip", "tool0", "--base", "base_link").returncode == 0
    q = [0, -60, 80, 10, 20, 30]
    proc = run("fk", ur5, "--tip", "tool0", "--json", "--q", *map(str, q))
    assert proc.returncode == 0, proc.stderr
    T = np.array(json.loads(proc.stdout)["T"])
    ref = reference_file("ur5_robot.urdf", None, "tool0")
    assert_transform_close(T, ref.fk(np.radians(q)), atol=1e-12)
    proc = run("ik", ur5, "--tip", "tool0", "--matrix", *map(str, T.ravel()), "--json")
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout)["method"] == "analytic:three-parallel-6R"
