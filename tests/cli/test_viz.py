"""``kinematica plot``, ``animate`` and ``view``: files written, exit codes, one-line errors."""

from __future__ import annotations

import json
import subprocess
import sys
import urllib.request
from pathlib import Path

import numpy as np
import pytest

import kinematica as km

pytest.importorskip("matplotlib")


import pytest
from PIL import Image
from support import DATA
from support.helpers import run_cli

from kinematica.cli.main import main
from kinematica.viz import write_trajectory
from kinematica.viz.server import TOKEN_HEADER


def run(args: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, str, str]:
    code = main(args)
    out, err = capsys.readouterr()
    return code, out, err


def test_plot_writes_a_png_of_the_asked_size(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "arm.png"
    code, text, _ = run(
        [
            "plot",
            "puma560",
            "--q",
            "0",
            "45",
            "-30",
            "0",
            "0",
            "0",
            "-o",
            str(out),
            "--frames",
            "--size",
            "500",
            "400",
            "--json",
        ],
        capsys,
    )
    assert code == 0
    assert json.loads(text) == {
        "robot": "PUMA 560",
        "kind": "arm",
        "output": str(out),
        "size": [500, 400],
    }
    with Image.open(out) as im:
        assert im.size == (500, 400)


def test_plot_solutions_counts_every_ik_solution(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "s.png"
    q = [10, -30, 20, 40, 50, -10]
    code, text, _ = run(
        [
            "plot",
            "puma560",
            "--q",
            *map(str, q),
            "--solutions",
            "--ignore-limits",
            "-o",
            str(out),
            "--json",
        ],
        capsys,
    )
    assert code == 0
    robot = km.load("puma560")
    expected = robot.ik(robot.fk(np.radians(q)), respect_limits=False).count
    assert json.loads(text)["solutions"] == expected == 8
    with Image.open(out) as im:
        assert im.size == tuple(json.loads(text)["size"])


def test_plot_unreachable_pose_exits_1(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    code, text, _ = run(
        ["plot", "puma560", "--pose", "5", "0", "0", "0", "0", "0", "-o", str(tmp_path / "x.png")],
        capsys,
    )
    assert code == 1
    assert "unreachable" in text
    assert not (tmp_path / "x.png").exists()


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["plot", "puma560"], "plot needs --q"),
        (["plot", "puma560", "--q", "1", "2"], "--q needs 6 values"),
        (["plot", "puma560", "--q", "0", "0", "0", "0", "0", "0", "-o", "a.txt"], "type '.txt'"),
        (["animate", "puma560", "--trajectory", "missing.csv"], "missing.csv: file not found"),
        (["plot", "nosuchrobot", "--q", "0"], "nosuchrobot"),
    ],
)
def test_bad_input_is_one_line_exit_2(
    args: list[str],
    message: str,
    capsys: pytest.CaptureFixture[str],
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.chdir(tmp_path)
    code, _, err = run(args, capsys)
    assert code == 2
    assert message in err
    assert len(err.strip().splitlines()) == 1


def test_animate_gif_from_a_csv(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    t = np.linspace(0.0, 0.5, 6)
    q = np.outer(t, [0.4, 0.3])
    csv = write_trajectory(tmp_path / "path.csv", t, q)
    out = tmp_path / "arm.gif"
    code, text, _ = run(
        [
            "animate",
            "planar-pr",
            "--trajectory",
            str(csv),
            "-o",
            str(out),
            "--size",
            "200",
            "160",
            "--json",
        ],
        capsys,
    )
    assert code == 0
    info = json.loads(text)
    assert (info["frames"], info["samples"], info["size"]) == (6, 6, [200, 160])
    with Image.open(out) as im:
        assert (im.n_frames, im.size) == (6, (200, 160))


def test_animate_bad_csv_says_the_line(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    csv = tmp_path / "bad.csv"
    csv.write_text("t,q1,q2\n0,0,0\n0.1,0,x\n")
    code, _, err = run(
        ["animate", "planar-pr", "--trajectory", str(csv), "-o", str(tmp_path / "a.gif")], capsys
    )
    assert code == 2
    assert "line 3, column q2" in err


def test_view_writes_the_page(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    code, text, _ = run(["view", "arm6-dh"], capsys)
    assert code == 0
    page = tmp_path / "arm6-dh.html"
    assert page.exists() and str(page.name) in text
    assert 'id="T"' in page.read_text()
    code, text, _ = run(
        [
            "view",
            "puma560",
            "-o",
            str(tmp_path / "p.html"),
            "--q",
            "0",
            "30",
            "0",
            "0",
            "0",
            "0",
            "--json",
        ],
        capsys,
    )
    assert code == 0 and json.loads(text)["output"] == str(tmp_path / "p.html")
    assert f"{float(np.radians(30))!r}" in (tmp_path / "p.html").read_text()


@pytest.mark.parametrize(
    ("source", "units"),
    [
        (DATA / "urdf" / "abb_irb140.urdf", {"angle": "deg", "length": "m"}),
        (DATA / "robots" / "craig_rrp.yaml", {"angle": "deg", "length": "mm"}),
        (DATA / "robots" / "seed_arm_rad_mm.yaml", {"angle": "rad", "length": "mm"}),
        ("puma560", {"angle": "deg", "length": "m"}),
    ],
)
def test_view_takes_every_robot_source(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], source: Path | str, units: dict[str, str]
) -> None:
    out = tmp_path / "page.html"
    code, text, err = run(["view", str(source), "-o", str(out), "--json"], capsys)
    assert (code, err) == (0, "")
    robot = km.load(source)
    assert json.loads(text) == {"robot": robot.name, "output": str(out), "units": units}
    page = out.read_text()
    start = page.index('id="robot-data">') + len('id="robot-data">')
    data = json.loads(page[start : page.index("</script>", start)])
    assert data["units"] == units
    assert [j["name"] for j in data["joints"]] == [link.name for link in robot.links]


def test_view_serve_answers_then_stops(tmp_path: Path) -> None:
    proc = subprocess.Popen(
        [sys.executable, "-m", "kinematica.cli.main", "view", "planar-3r", "--serve", "--json"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        cwd=tmp_path,
    )
    try:
        assert proc.stdout is not None
        lines = []
        while not "".join(lines).rstrip().endswith("}"):
            line = proc.stdout.readline()
            assert line, proc.stderr.read() if proc.stderr else ""
            lines.append(line)
        url = json.loads("".join(lines))["url"]
        with urllib.request.urlopen(url, timeout=10) as r:
            page = r.read().decode()
        assert "Planar 3R" in page
        start = page.index('id="robot-data">') + len('id="robot-data">')
        token = json.loads(page[start : page.index("</script>", start)])["token"]
        robot = km.load("planar-3r")
        T = robot.fk(np.radians([20, 40, -30]))
        req = urllib.request.Request(
            url + "api/ik",
            data=json.dumps({"T": T.tolist()}).encode(),
            method="POST",
            headers={"Content-Type": "application/json", TOKEN_HEADER: token},
        )
        with urllib.request.urlopen(req, timeout=30) as r:
            res = json.loads(r.read())
        assert res["status"] == "ok" and len(res["solutions"]) == 2
    finally:
        proc.terminate()
        proc.wait(timeout=10)
    assert list(tmp_path.iterdir()) == []  # --serve without -o writes no file


def test_view_hint_gives_the_unit_of_each_joint(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    code, out, _ = run_cli(capsys, "view", "planar-pr", "-o", str(tmp_path / "pr.html"))
    assert code == 0 and "q1 in m, q2 in degrees" in out and "#q=... in degrees" not in out
    code, out, _ = run_cli(capsys, "view", "arm6-dh", "-o", str(tmp_path / "a.html"))
    assert "add #q=... in degrees to start there" in out


def test_one_solution_is_singular(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    out_file = tmp_path / "one.png"
    code, out, _ = run_cli(
        capsys, "plot", "planar-pr", "--q", "0.2", "30", "--solutions", "-o", str(out_file)
    )
    assert code == 0 and "1 IK solution of" in out and "1 IK solutions" not in out


def test_plot_with_an_ellipsoid(tmp_path) -> None:  # type: ignore[no-untyped-def]
    pytest.importorskip("matplotlib")
    from kinematica.cli.main import main

    out = tmp_path / "arm.png"
    code = main(
        [
            "plot",
            "puma560",
            "--q",
            "10",
            "-30",
            "40",
            "20",
            "50",
            "0",
            "--ellipsoid",
            "velocity",
            "-o",
            str(out),
            "--json",
        ]
    )
    assert code == 0 and out.stat().st_size > 0
    assert (
        main(
            [
                "plot",
                "puma560",
                "--q",
                "0",
                "0",
                "0",
                "0",
                "0",
                "0",
                "--ellipsoid",
                "force",
                "--solutions",
                "-o",
                str(out),
            ]
        )
        == 2
    )
