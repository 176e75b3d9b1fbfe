"""Tasks: files (CSV, JSON, numpy), arrays and sampled regions; bad input."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial.transform import Rotation
from support.helpers import assert_transform_close

import kinematica as km
from kinematica.design import Task, TaskError, as_task, load_task


def test_ring_is_evenly_spaced_on_the_circle() -> None:
    task = Task.ring(0.6, 8, center=(0.1, 0.2, 0.3))
    P = task.positions - [0.1, 0.2, 0.3]
    assert task.kind == "position" and len(task) == 8
    np.testing.assert_allclose(np.linalg.norm(P, axis=1), 0.6, rtol=1e-15)
    np.testing.assert_allclose(P[:, 2], 0.0, atol=1e-16)
    # the first point is along +x, then every 45 degrees counter-clockwise about z
    angles = np.arctan2(P[:, 1], P[:, 0])
    np.testing.assert_allclose(np.unwrap(angles), np.arange(8) * math.pi / 4, atol=1e-14)


def test_ring_about_another_normal() -> None:
    n = np.array([1.0, 1.0, 0.0]) / math.sqrt(2)
    P = Task.ring(0.5, 7, normal=n * 3).positions
    np.testing.assert_allclose(P @ n, 0.0, atol=1e-15)
    np.testing.assert_allclose(np.linalg.norm(P, axis=1), 0.5, rtol=1e-15)
    Px = Task.ring(0.5, 5, normal=(1, 0, 0)).positions
    np.testing.assert_allclose(Px[:, 0], 0.0, atol=1e-16)


def test_box_and_sphere_samples_are_inside_and_seeded() -> None:
    box = Task.box((-1, 0, 2), (1, 0.5, 2), 200, seed=3)
    P = box.positions
    assert np.all(P >= [-1, 0, 2]) and np.all(P <= [1, 0.5, 2])
    assert np.array_equal(P, Task.box((-1, 0, 2), (1, 0.5, 2), 200, seed=3).positions)
    assert not np.array_equal(P, Task.box((-1, 0, 2), (1, 0.5, 2), 200, seed=4).positions)
    ball = Task.sphere(0.3, 2000, center=(1, 1, 1), seed=0).positions - 1
    r = np.linalg.norm(ball, axis=1)
    assert r.max() <= 0.3
    # uniform in volume: P(r < R/2) = 1/8 (binomial sd ~ 0.0074 at n = 2000)
    assert abs(np.mean(r < 0.15) - 0.125) < 0.03
    shell = Task.sphere(0.3, 50, surface=True).positions
    np.testing.assert_allclose(np.linalg.norm(shell, axis=1), 0.3, rtol=1e-15)


def test_region_with_orientation_gives_poses() -> None:
    R = km.rotx(math.pi)[:3, :3]
    task = Task.ring(0.4, 6, orientation=R)
    assert task.kind == "pose" and task.targets.shape == (6, 4, 4)
    np.testing.assert_array_equal(task.targets[:, :3, :3], np.broadcast_to(R, (6, 3, 3)))
    np.testing.assert_array_equal(task.positions, Task.ring(0.4, 6).positions)
    with pytest.raises(TaskError, match="orientation must be a 3x3 rotation"):
        Task.ring(0.4, 6, orientation=np.eye(3) * 2)


def test_from_poses_rows_with_euler_angles() -> None:
    rows = np.array([[0.1, 0.2, 0.3, 10, 20, 30], [0, 0, 0, -40, 50, 60]], dtype=float)
    task = Task.from_poses(rows, euler="XYZ", degrees=True)
    R = Rotation.from_euler("XYZ", rows[:, 3:], degrees=True).as_matrix()
    np.testing.assert_allclose(task.targets[:, :3, :3], R, atol=1e-15)
    np.testing.assert_array_equal(task.positions, rows[:, :3])


def test_targets_are_read_only() -> None:
    task = Task.ring(0.4, 4)
    with pytest.raises(ValueError, match="read-only"):
        task.targets[0, 0] = 1.0


def test_csv_positions_with_header(tmp_path: Path) -> None:
    path = tmp_path / "t.csv"
    path.write_text("x,y,z\n0.1,0.2,0.3\n\n-1,2e-1,0\n")
    task = load_task(path)
    np.testing.assert_array_equal(task.targets, [[0.1, 0.2, 0.3], [-1, 0.2, 0]])
    assert task.name == str(path)


def test_csv_pose_rows_in_degrees_by_default_or_radians(tmp_path: Path) -> None:
    path = tmp_path / "p.csv"
    path.write_text("0.5,0,0.2,90,45,0\n")
    T = km.from_pose([0.5, 0, 0.2, 90, 45, 0], euler="ZYZ", degrees=True)
    assert_transform_close(load_task(path).targets[0], T, atol=1e-15)
    T_rad = km.from_pose([0.5, 0, 0.2, 90, 45, 0], euler="xyz")
    assert_transform_close(load_task(path, euler="xyz", degrees=False).targets[0], T_rad)


def test_csv_matrix_rows_and_numpy_files(tmp_path: Path) -> None:
    puma = km.load("puma560")
    T = puma.fk(np.random.default_rng(1).uniform(-1, 1, (4, 6)))
    np.savetxt(tmp_path / "m.csv", T.reshape(4, 16), delimiter=",")
    np.save(tmp_path / "m.npy", T)
    np.savez(tmp_path / "m.npz", targets=T, other=np.zeros(3))
    np.savez(tmp_path / "one.npz", anything=T[:, :3, 3])
    for name in ("m.csv", "m.npy", "m.npz"):
        assert_transform_close(load_task(tmp_path / name).targets, T, atol=1e-15)
    np.testing.assert_array_equal(load_task(tmp_path / "one.npz").targets, T[:, :3, 3])


def test_json_forms(tmp_path: Path) -> None:
    def task(data: object) -> Task:
        path = tmp_path / "t.json"
        path.write_text(json.dumps(data))
        return load_task(path)

    assert task({"positions": [[1, 2, 3]]}).targets.tolist() == [[1, 2, 3]]
    assert task([[1, 2, 3], [4, 5, 6]]).kind == "position"
    poses = task({"poses": [[0, 0, 0.5, 0, 0.5, 0]], "euler": "XYZ", "angle": "rad"})
    assert_transform_close(poses.targets[0], km.from_pose([0, 0, 0.5, 0, 0.5, 0], euler="XYZ"))
    assert task({"matrices": [np.eye(4).tolist()]}).kind == "pose"
    ring = task({"region": "ring", "radius": 0.6, "count": 12, "name": "ring"})
    np.testing.assert_array_equal(ring.targets, Task.ring(0.6, 12).targets)
    assert ring.name == "ring"
    box = task({"region": "box", "lower": [0, 0, 0], "upper": [1, 1, 1], "count": 5, "seed": 2})
    np.testing.assert_array_equal(box.targets, Task.box((0, 0, 0), (1, 1, 1), 5, seed=2).targets)
    ball = task({"region": "sphere", "radius": 0.2, "count": 5, "surface": True})
    np.testing.assert_allclose(np.linalg.norm(ball.targets, axis=1), 0.2, rtol=1e-15)


def test_as_task_takes_arrays_paths_and_tasks(tmp_path: Path) -> None:
    ring = Task.ring(0.3, 5)
    assert as_task(ring) is ring
    assert as_task(ring.targets).kind == "position"
    assert as_task(np.broadcast_to(np.eye(4), (2, 3, 4, 4))).targets.shape == (6, 4, 4)
    np.save(tmp_path / "r.npy", ring.targets)
    np.testing.assert_array_equal(as_task(tmp_path / "r.npy").targets, ring.targets)
    with pytest.raises(TaskError, match=r"got \(5, 2\)"):
        as_task(np.zeros((5, 2)))


@pytest.mark.parametrize(
    ("name", "text", "match"),
    [
        ("a.csv", "1,2,3\n4,5\n", r"a\.csv: row 2 has 2 columns, the first has 3"),
        ("b.csv", "1,2,3\n4,x,6\n", r"b\.csv: row 2, column 2: expected a number, found 'x'"),
        ("c.csv", "1,2,3,4\n", r"c\.csv: expected rows of 3 .* found shape \(1, 4\)"),
        ("d.csv", "x,y,z\n", r"d\.csv: no target rows"),
        ("e.csv", "1,nan,3\n", r"e\.csv: row 1, column 2 is not finite"),
        ("f.json", "{", r"f\.json: not valid JSON"),
        ("g.json", '{"positions": [[1, 2]]}', r"key 'positions': expected rows of 3"),
        ("h.json", '{"positions": [[1,2,3]], "poses": []}', r"exactly one of positions"),
        ("i.json", '{"region": "torus"}', r"expected ring, box or sphere, found 'torus'"),
        ("j.json", '{"region": "ring", "count": 3}', r"ring region: .*radius"),
        ("k.json", '{"region": "ring", "radius": -1, "count": 3}', r"radius must be a length .*-1"),
        ("l.json", '{"region": "ring", "radius": 1, "count": 0}', r"count must be .*1,000,000"),
        ("m.json", '{"positions": [[1,2,3]], "colour": 1}', r"unknown key 'colour'"),
        ("n.json", '{"poses": [[0,0,0,0,0,0]], "angle": "grad"}', r"expected deg or rad"),
        ("o.json", '{"matrices": [[[2,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]]}', r"target\[0\]"),
        ("p.txt", "1,2,3", r"unknown task file type '\.txt'"),
        ("q.json", "3", r"expected a list of targets or a mapping"),
        ("r.json", '{"region": "box", "lower": [1,1,1], "upper": [0,0,0], "count": 2}', "below"),
        ("s.json", '{"region": "ring", "radius": "abc", "count": 3}', r"radius must be a length"),
        ("t.json", '{"region": "ring", "radius": 1, "count": 1e12}', r"count must be a whole"),
        ("u.json", '{"region": "sphere", "radius": 1, "count": 2, "seed": "x"}', r"seed must be"),
        ("v.json", '{"region": "sphere", "radius": 1, "count": 2, "surface": "no"}', "surface"),
    ],
)
def test_bad_task_files_say_where(tmp_path: Path, name: str, text: str, match: str) -> None:
    path = tmp_path / name
    path.write_text(text)
    with pytest.raises(TaskError, match=match):
        load_task(path)


def test_missing_and_binary_files(tmp_path: Path) -> None:
    with pytest.raises(TaskError, match="no such task file"):
        load_task(tmp_path / "none.csv")
    (tmp_path / "bin.csv").write_bytes(b"\xff\xfe\x00")
    with pytest.raises(TaskError, match="not UTF-8"):
        load_task(tmp_path / "bin.csv")
    (tmp_path / "bad.npy").write_bytes(b"not numpy")
    with pytest.raises(TaskError, match="not a numpy file"):
        load_task(tmp_path / "bad.npy")
    np.savez(tmp_path / "two.npz", a=np.zeros((2, 3)), b=np.zeros((2, 3)))
    with pytest.raises(TaskError, match="name the array 'targets'"):
        load_task(tmp_path / "two.npz")


@pytest.mark.parametrize(
    ("targets", "match"),
    [
        (np.zeros((0, 3)), "no targets"),
        (np.array([[0.0, np.inf, 0.0]]), "target 0 holds NaN or inf"),
        (np.zeros((2, 3, 3)), r"got shape \(2, 3, 3\)"),
        (np.array([["a", "b", "c"]]), "must be numbers"),
    ],
)
def test_bad_target_arrays(targets: np.ndarray, match: str) -> None:
    with pytest.raises(TaskError, match=match):
        Task(targets)


def test_fingerprint_follows_the_targets() -> None:
    a, b = Task.ring(0.3, 5), Task.ring(0.3, 5)
    assert a.fingerprint == b.fingerprint
    assert a.fingerprint != Task.ring(0.30000000001, 5).fingerprint


def test_region_point_count_limit_at_its_boundary() -> None:
    from kinematica.design.task import MAX_REGION_POINTS

    assert len(Task.box((0, 0, 0), (1, 1, 1), MAX_REGION_POINTS)) == MAX_REGION_POINTS
    with pytest.raises(TaskError, match="from 1 to 1,000,000, got 1000001"):
        Task.box((0, 0, 0), (1, 1, 1), MAX_REGION_POINTS + 1)
    with pytest.raises(TaskError, match="count must be a whole number"):
        Task.ring(0.5, 3.0)  # type: ignore[arg-type]
