"""Workspace clouds, trajectory figures, trajectory CSV files and animations."""

from __future__ import annotations

import math
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
from support.helpers import JointSpec, RobotSpec

import kinematica as km

pytest.importorskip("matplotlib")
import json

import pytest
from matplotlib.figure import Figure
from PIL import Image
from support.helpers import run_cli as run

from kinematica import viz
from kinematica.errors import ArgumentError
from kinematica.viz._mpl import (
    VizError,
)
from kinematica.viz.animate import DEFAULT_FPS, MAX_FPS, MAX_RESAMPLED, MIN_FPS, animation_samples


def _gid(ax: object, gid: str) -> object:
    found = [a for a in ax.get_children() if a.get_gid() == gid]  # type: ignore[attr-defined]
    assert len(found) == 1
    return found[0]


class Workspace:
    """Stands in for kinematica.motion's workspace: anything with points (and manipulability)."""

    def __init__(self, points: np.ndarray, manipulability: np.ndarray | None = None) -> None:
        self.points = points
        if manipulability is not None:
            self.manipulability = manipulability


def test_workspace_points_and_colours() -> None:
    robot = km.load("puma560")
    q = np.random.default_rng(0).uniform(-3, 3, (400, 6))
    pts = robot.fk(q)[:, :3, 3]
    manip = np.abs(np.linalg.det(robot.jacobian(q)))
    ax = viz.plot_workspace(robot, Workspace(pts, manip), ax=Figure().add_subplot(projection="3d"))
    cloud = _gid(ax, "workspace")
    np.testing.assert_allclose(np.array(cloud._offsets3d).T, pts)  # type: ignore[attr-defined]
    np.testing.assert_allclose(cloud.get_array(), manip)  # type: ignore[attr-defined]
    assert len(ax.figure.axes) == 2  # the colour bar
    # an array alone, no robot: no colour bar, no arm
    ax = viz.plot_workspace(None, pts, ax=Figure().add_subplot(projection="3d"))
    assert len(ax.figure.axes) == 1
    assert not [a for a in ax.get_children() if a.get_gid() == "links"]


def test_workspace_of_a_planar_arm_in_2d() -> None:
    import matplotlib.pyplot as plt

    robot = km.load("planar-3r")
    pts = robot.fk(np.random.default_rng(1).uniform(-3, 3, (300, 3)))[:, :3, 3]
    try:
        ax = viz.plot_workspace(robot, pts)
        assert ax.name != "3d"
        np.testing.assert_allclose(_gid(ax, "workspace").get_offsets(), pts[:, :2])  # type: ignore[attr-defined]
    finally:
        plt.close("all")


def test_workspace_bad_input() -> None:
    with pytest.raises(km.DimensionError, match=r"\(N, 3\)"):
        viz.plot_workspace(None, np.zeros((5, 2)))
    with pytest.raises(km.DimensionError, match=r"\(5,\)"):
        viz.plot_workspace(None, Workspace(np.zeros((5, 3)), np.zeros(4)))


def test_trajectory_figure_data() -> None:
    spec = RobotSpec(
        joints=(
            JointSpec("R", 0.3, 0.2, math.pi / 2, 0.1),
            JointSpec("P", 0.0, 0.1, 0.0, 0.2),
            JointSpec("R", 0.0, 0.25, 0.0, -0.3),
        ),
        convention="modified",
        tool=km.transl(0.0, 0.0, 0.05),
    )
    robot = spec.build()
    t = np.linspace(0.0, 2.0, 21)
    q = np.stack([np.sin(t), 0.1 * t, np.cos(t)], axis=1)
    fig = viz.plot_trajectory(robot, t, q, fig=Figure())
    lines = {ln.get_gid(): ln for ax in fig.axes for ln in ax.get_lines()}
    np.testing.assert_allclose(lines["q1"].get_ydata(), np.degrees(q[:, 0]))
    np.testing.assert_allclose(lines["q2"].get_ydata(), q[:, 1])  # prismatic: metres
    np.testing.assert_allclose(lines["q3"].get_xdata(), t)
    path = np.array(lines["tool-path"].get_data_3d()).T
    np.testing.assert_allclose(path, [spec.ref_fk(qi)[:3, 3] for qi in q], atol=1e-12)
    with pytest.raises(km.DimensionError, match="strictly increasing"):
        viz.plot_trajectory(robot, t[::-1], q, fig=Figure())
    with pytest.raises(km.DimensionError, match=r"\(21,\)"):
        viz.plot_trajectory(robot, t[:5], q, fig=Figure())


# ------------------------------------------------------------------ CSV files
def test_csv_round_trip(tmp_path: Path) -> None:
    t = np.linspace(0, 1, 7)
    q = np.random.default_rng(2).normal(size=(7, 3))
    path = viz.write_trajectory(tmp_path / "p.csv", t, q)
    assert path.read_text().splitlines()[0] == "t,q1,q2,q3"
    t2, q2 = viz.read_trajectory(path, dof=3)
    np.testing.assert_array_equal(t2, t)
    np.testing.assert_array_equal(q2, q)


@pytest.mark.parametrize(
    ("text", "match"),
    [
        ("", "empty"),
        ("q1,q2\n0,1\n", "line 1: the header must be t,q1"),
        ("t,q1,q2\n", "not followed by any sample"),
        ("t,q1,q2\n0,1,2\n0.1,1\n", "line 3: expected 3 values"),
        (
            "t,q1,q2\n0,1,2\n# note\n0.1,1,abc\n",
            "line 4, column q2: expected a finite number, found 'abc'",
        ),
        ("t,q1,q2\n0,1,2\n0.1,1,nan\n", "line 3, column q2"),
        ("t,q1,q2\n0,1,2\n0.1,1,2\n0.1,1,2\n", "line 4: time must increase"),
        ("t,q1\n0,1\n", "1 joint column"),
    ],
)
def test_csv_errors_say_where(tmp_path: Path, text: str, match: str) -> None:
    path = tmp_path / "bad.csv"
    path.write_text(text)
    with pytest.raises(viz.TrajectoryFileError, match=match):
        viz.read_trajectory(path, dof=2)


def test_csv_missing_file(tmp_path: Path) -> None:
    with pytest.raises(viz.TrajectoryFileError, match=r"nope\.csv: file not found"):
        viz.read_trajectory(tmp_path / "nope.csv")


# ----------------------------------------------------------------- animation
def test_samples_one_frame_per_row_in_real_time() -> None:
    t = np.array([0.0, 0.5, 1.0, 2.0])
    q = np.zeros((4, 2))
    times, _, rate = animation_samples(t, q, None, None, timed=True)
    np.testing.assert_array_equal(times, t)
    assert rate == pytest.approx(3 / 2.0)
    assert animation_samples(t, q, None, None, timed=False)[2] == DEFAULT_FPS


def test_samples_resampled_at_fps_by_interpolation() -> None:
    t = np.array([0.0, 1.0, 2.5])
    q = np.array([[0.0], [1.0], [4.0]])
    times, qs, rate = animation_samples(t, q, 2.0, None, timed=True)
    np.testing.assert_allclose(times, [0, 0.5, 1, 1.5, 2, 2.5])  # floor(2.5 * 2) + 1 = 6 frames
    np.testing.assert_allclose(qs[:, 0], [0, 0.5, 1, 2, 3, 4])
    assert rate == 2.0


def test_samples_capped_keeping_first_and_last() -> None:
    t = np.linspace(0, 9.9, 100)
    q = t[:, None]
    times, _, rate = animation_samples(t, q, None, 10, timed=True)
    assert len(times) == 10 and times[0] == 0 and times[-1] == t[-1]
    assert rate == pytest.approx(9 / 9.9)  # same duration
    with pytest.raises(ArgumentError, match=r"^fps must be"):
        animation_samples(t, q, -1.0, None, timed=True)


def test_gif_size_and_frame_count(tmp_path: Path) -> None:
    robot = km.load("puma560")
    t = np.linspace(0.0, 1.0, 9)
    q = np.outer(t, [0.5, -0.3, 0.2, 0.1, 0.4, 0.0])
    q[-3:] = q[-3]  # the arm rests: identical arms, still one frame per sample
    anim = viz.animate(robot, q, tmp_path / "a.gif", t=t, size=(240, 200))
    assert (anim.frames, anim.fps, anim.size) == (9, pytest.approx(8.0), (240, 200))
    with Image.open(anim.path) as im:
        assert im.format == "GIF"
        assert im.size == (240, 200)
        assert im.n_frames == 9
        assert abs(im.info["duration"] - 125) <= 10  # 1000 / 8 fps, in GIF centiseconds
    anim = viz.animate(robot, q, tmp_path / "b.gif", t=t, fps=5.0, size=(160, 120))
    with Image.open(anim.path) as im:
        assert im.n_frames == anim.frames == 6  # floor(1.0 * 5) + 1


def test_planar_gif_and_bad_output(tmp_path: Path) -> None:
    robot = km.load("planar-3r")
    q = np.linspace([0, 0, 0], [1, -1, 0.5], 4)
    anim = viz.animate(robot, q, tmp_path / "p.gif", size=(160, 160))
    with Image.open(anim.path) as im:
        assert im.n_frames == 4
    with pytest.raises(viz.VizError, match=r"use \.gif or \.mp4"):
        viz.animate(robot, q, tmp_path / "p.avi")
    with pytest.raises(viz.VizError, match="does not exist"):
        viz.animate(robot, q, tmp_path / "no" / "p.gif")


@pytest.mark.skipif(shutil.which("ffmpeg") is None, reason="ffmpeg is not installed: no MP4")
def test_mp4_frame_count(tmp_path: Path) -> None:
    robot = km.load("planar-pr")
    q = np.linspace([0.0, 0.0], [0.4, 1.5], 7)
    anim = viz.animate(robot, q, tmp_path / "a.mp4", size=(201, 160))
    assert anim.size == (202, 160)  # even sizes for yuv420p
    probe = shutil.which("ffprobe")
    if probe:
        out = subprocess.run(
            [
                probe,
                "-v",
                "error",
                "-count_frames",
                "-select_streams",
                "v:0",
                "-show_entries",
                "stream=nb_read_frames,width,height",
                "-of",
                "csv=p=0",
                str(anim.path),
            ],
            capture_output=True,
            text=True,
            check=True,
        ).stdout.strip()
        assert out == "202,160,7"
    else:  # pragma: no cover
        assert anim.path.stat().st_size > 1000


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


def test_animation_frame_rates() -> None:
    q = np.zeros((2, 1))
    slow = np.array([0.0, 1.0 / MIN_FPS])  # two samples, 100 s apart
    assert animation_samples(slow, q, MIN_FPS, None, timed=True)[2] == MIN_FPS
    assert animation_samples(slow, q, None, None, timed=True)[2] == pytest.approx(MIN_FPS)
    with pytest.raises(VizError, match=r"would play at 0\.0099 frames a second .* slower than"):
        animation_samples(slow * 1.01, q, None, None, timed=True)
    for fps in (MIN_FPS * 0.99, MAX_FPS * 1.01):
        with pytest.raises(ArgumentError, match=r"^fps must be a number of frames a second from"):
            animation_samples(slow, q, fps, None, timed=True)
    assert animation_samples(slow, q, MAX_FPS, 300, timed=True)[2] == pytest.approx(
        MAX_FPS * 299 / (100 * MAX_FPS)
    )
    # fps times the duration: the frames resampled, counted before any is made.
    longest = np.array([0.0, (MAX_RESAMPLED - 1) / 100.0])
    assert len(animation_samples(longest, q, 100.0, None, timed=True)[0]) == MAX_RESAMPLED
    with pytest.raises(ArgumentError, match=r"^fps gives 1e\+06 frames over .* at most 1,000,000"):
        animation_samples(longest + np.array([0.0, 0.01]), q, 100.0, None, timed=True)
