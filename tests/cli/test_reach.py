"""``kinematica reach`` and ``kinematica place``: the library's answers, printed."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from support.cli import run, strict_json

import kinematica as km
from kinematica.reach import load_map
from kinematica.reach.placement import yaw_pose


def test_reach_prints_volumes_and_writes_the_map_and_picture(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    out_map, out_png = tmp_path / "map.npz", tmp_path / "map.png"
    args = ["reach", "planar-3r", "--resolution", "0.1", "--orientations", "12"]
    code, out, err = run(capsys, *args, "-o", str(out_map), "--plot", str(out_png), "--json")
    assert code == 0, err
    data = strict_json(out)
    m = load_map(out_map)
    expected = km.reachability(km.load("planar-3r"), resolution=0.1, orientations=12)
    np.testing.assert_array_equal(m.reached, expected.reached)
    assert data["reachable_voxels"] == int(expected.reachable.sum())
    assert data["dexterous_volume"] == pytest.approx(expected.dexterous_volume)
    assert data["units"]["volume"] == "m^2" and data["orientations"] == 12
    assert out_png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    code, out, _ = run(capsys, *args, "--positions", "--no-manipulability")
    assert code == 0 and "positions only" in out and "manipulability" not in out


def test_reach_with_an_approach_cone_in_degrees(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run(
        capsys, "reach", "puma560", "--resolution", "0.2", "--orientations", "4",
        "--approach", "0", "0", "-1", "10", "--json",
    )  # fmt: skip
    assert code == 0
    data = strict_json(out)
    assert data["approach"]["half_angle_rad"] == pytest.approx(np.radians(10))


def test_reach_nothing_reachable_is_exit_1(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run(
        capsys, "reach", "puma560", "--region", "5", "5", "5", "6", "6", "6",
        "--resolution", "0.5", "--orientations", "2",
    )  # fmt: skip
    assert code == 1 and "reachable: 0 voxels" in out


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        (["--resolution", "0"], "--resolution must be"),
        (["--orientations", "0"], "--orientations must be"),
        (["-o", "map.nc"], "-o map.nc: a map is written as .vti"),
        (["--plot", "/no/such/dir/m.png"], "no such folder"),
        (["--approach", "0", "0", "0", "10"], "zero vector"),
    ],
)
def test_reach_bad_input_is_exit_2(
    capsys: pytest.CaptureFixture[str], extra: list[str], message: str
) -> None:
    code, _, err = run(capsys, "reach", "puma560", *extra)
    assert code == 2 and message in err and "Traceback" not in err


@pytest.fixture(scope="module")
def task_file(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, np.ndarray]:
    robot = km.load("puma560")
    base = yaw_pose([0.4, -0.2, 0.0], np.pi / 2)
    q = np.random.default_rng(3).uniform(0.5 * robot.qlim[:, 0], 0.5 * robot.qlim[:, 1], (4, 6))
    task = base @ robot.fk(q)
    pose = km.to_pose(task, euler="ZYZ")
    pose[:, 3:] = np.degrees(pose[:, 3:])
    path = tmp_path_factory.mktemp("place") / "poses.csv"
    np.savetxt(path, pose, delimiter=",", fmt="%.17g")
    return path, task


def test_place_prints_the_best_bases_and_draws_them(
    capsys: pytest.CaptureFixture[str], task_file: tuple[Path, np.ndarray], tmp_path: Path
) -> None:
    path, task = task_file
    png = tmp_path / "place.png"
    region = ["0", "-0.6", "0", "0.8", "0.2", "0"]
    code, out, err = run(
        capsys, "place", "puma560", "--task", str(path), "--region", *region,
        "--resolution", "0.2", "--yaws", "4", "--plot", str(png), "--json",
    )  # fmt: skip
    assert code == 0, err
    data = strict_json(out)
    found = km.base_placement(
        km.load("puma560"), task, np.reshape(np.array(region, float), (2, 3)), resolution=0.2,
        yaw=4,
    )  # fmt: skip
    assert data["feasible"] == found.count > 0
    best = data["best"][0]
    np.testing.assert_allclose(best["position"], found.positions[found.order[0]], atol=1e-12)
    assert best["yaw"] == pytest.approx(np.degrees(found.yaws[found.order[0]]))
    assert png.stat().st_size > 1000
    code, out, _ = run(capsys, "place", "puma560", "--task", str(path), "--region", *region,
                       "--resolution", "0.2", "--yaw", "90")  # fmt: skip
    assert code == 0 and "90" in out and "candidate bases" in out


def test_place_unreachable_task_is_exit_1_and_positions_are_refused(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    far = tmp_path / "far.csv"
    np.savetxt(far, [[9, 0, 0, 0, 0, 0], [-9, 0, 0, 0, 0, 0]], delimiter=",")
    code, out, _ = run(capsys, "place", "puma560", "--task", str(far), "--resolution", "1")
    assert code == 1 and "no base" in out
    pos = tmp_path / "pos.csv"
    np.savetxt(pos, [[0.5, 0, 0.2]], delimiter=",")
    code, _, err = run(capsys, "place", "puma560", "--task", str(pos))
    assert code == 2 and "needs poses" in err
