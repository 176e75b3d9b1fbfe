"""The map object, its files, its blocks and its Dask runs."""

from __future__ import annotations

import base64
import xml.etree.ElementTree as ET
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from support.reach_arms import R_IN, R_OUT, elbow_wrist

import kinematica as km
from kinematica.errors import ArgumentError, KinematicaError
from kinematica.reach import compute, load_map, save_map
from kinematica.reach.reachmap import ReachabilityMap

REGION = [[-0.45, -0.45, -0.45], [0.45, 0.45, 0.45]]


@pytest.fixture(scope="module")
def robot() -> km.Robot:
    return elbow_wrist(0.1)


@pytest.fixture(scope="module")
def serial(robot: km.Robot) -> ReachabilityMap:
    return km.reachability(robot, REGION, resolution=0.1, orientations=16)


def assert_same_map(a: ReachabilityMap, b: ReachabilityMap) -> None:
    for name in ("origin", "orientations", "reached", "solutions", "manipulability", "centre"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name), err_msg=name)
    assert (a.resolution, a.radius, a.robot, a.plane) == (b.resolution, b.radius, b.robot, b.plane)
    assert (a.complete, a.held) == (b.complete, b.held)


def test_region_grid_and_volumes(serial: ReachabilityMap) -> None:
    assert serial.shape == (9, 9, 9) and serial.count == 16 and serial.queries == 729 * 16
    np.testing.assert_allclose(serial.origin, REGION[0])
    np.testing.assert_allclose(serial.centres()[0, 0, 0], [-0.4, -0.4, -0.4], atol=1e-15)
    assert serial.reachable_volume == pytest.approx(np.count_nonzero(serial.reached) * 1e-3)
    assert 0 < serial.dexterous_volume < serial.reachable_volume
    sl = serial.slice("zx", at=0.0)
    assert sl.plane == "xz" and sl.index.shape == (9, 9) and sl.at == pytest.approx(0.0, abs=1e-15)
    np.testing.assert_array_equal(sl.index, serial.index[:, 4, :])
    assert sl.extent == pytest.approx((-0.45, 0.45, -0.45, 0.45))
    centres = serial.centres()
    np.testing.assert_array_equal(serial.index_at(centres), serial.index)
    assert serial.index_at(np.array([5.0, 0, 0])) == 0.0


def test_blocks_do_not_change_the_map(
    robot: km.Robot, serial: ReachabilityMap, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(compute, "CHUNK_QUERIES", 48)  # 3 voxels a block
    done: list[int] = []
    small = km.reachability(
        robot, REGION, resolution=0.1, orientations=16, threads=1, progress=done.append
    )
    assert_same_map(serial, small)
    assert (
        set(done[:-1]) == {48}
        and sum(done)
        == np.count_nonzero(
            np.linalg.norm(serial.centres() - serial.centre, axis=-1) <= serial.radius
        )
        * 16
    )


def test_npz_round_trip_and_vti_that_vtk_reads(serial: ReachabilityMap, tmp_path: Path) -> None:
    back = load_map(save_map(serial, tmp_path / "map.npz"))
    assert_same_map(serial, back)
    save_map(serial, tmp_path / "map.vti")
    root = ET.parse(tmp_path / "map.vti").getroot()
    assert root.get("type") == "ImageData" and root.get("header_type") == "UInt64"
    image = root.find("ImageData")
    assert image is not None
    assert image.get("WholeExtent") == "0 9 0 9 0 9"
    np.testing.assert_allclose([float(v) for v in image.get("Origin", "").split()], REGION[0])
    arrays = {}
    for da in root.iter("DataArray"):
        text = da.text or ""
        # VTK's layout: the UInt64 byte count, then the data, each base64-encoded alone
        header = np.frombuffer(base64.b64decode(text[:12]), "<u8")[0]
        data = base64.b64decode(text[12:])
        assert header == len(data)
        dtype = {"Float64": "<f8", "Int32": "<i4", "UInt8": "u1"}[da.get("type", "")]
        arrays[da.get("Name")] = np.frombuffer(data, dtype).reshape(9, 9, 9).transpose()
    np.testing.assert_array_equal(arrays["reachability_index"], serial.index)
    np.testing.assert_array_equal(arrays["reached"], serial.reached)
    np.testing.assert_array_equal(arrays["dexterous"], serial.dexterous)
    np.testing.assert_array_equal(arrays["manipulability"], serial.manipulability)
    with pytest.raises(ArgumentError, match=r"\.vti .* or \.npz"):
        save_map(serial, tmp_path / "map.nc")
    with pytest.raises(KinematicaError, match="cannot write"):
        save_map(serial, tmp_path / "no" / "map.npz")
    (tmp_path / "bad.npz").write_bytes(b"not a zip")
    with pytest.raises(KinematicaError, match="not a reachability map"):
        load_map(tmp_path / "bad.npz")


def test_approach_cone_asks_tool_axes_near_the_direction(robot: km.Robot) -> None:
    m = km.reachability(robot, REGION, 0.1, orientations=8, approach=([0, 0, -1], 0.2))
    assert m.approach is not None and m.approach[1] == 0.2
    np.testing.assert_allclose(m.approach[0], [0, 0, -1])
    cos = m.orientations[:, :, 2] @ np.array([0, 0, -1.0])
    assert np.all(cos >= np.cos(0.2) - 1e-12)
    # pointing down, the tool reaches p iff the wrist centre p + 0.1 z... is in the shell
    wc = m.centres()[..., None, :] - 0.1 * m.orientations[:, :, 2]
    r = np.linalg.norm(wc, axis=-1)
    clear = np.all((np.abs(r - R_IN) > 1e-7) & (np.abs(r - R_OUT) > 1e-7), axis=-1)
    expected = ((r >= R_IN) & (r <= R_OUT)).sum(axis=-1)
    np.testing.assert_array_equal(m.reached[clear], expected[clear])


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"resolution": 0.0}, "resolution"),
        ({"resolution": 1e-5}, "voxels"),
        ({"region": [[0, 0, 0], [0, 1, 1]]}, "region"),
        ({"region": [0, 1]}, "region"),
        ({"orientations": 0}, "orientations"),
        ({"orientations": np.eye(3)}, "orientations"),
        ({"orientations": 2 * np.eye(3)[None]}, "orientations"),
        ({"approach": ([0, 0, 1],)}, "approach"),
        ({"approach": ([0, 0, 1], "wide")}, "half_angle"),
        ({"approach": (["a", 0, 1], 0.1)}, "approach"),
        ({"approach": ([0, 0, 1], 0.1), "orientations": None}, "approach"),
        ({"manipulability": "yes"}, "manipulability"),
        ({"workers": 0}, "workers"),
        ({"workers": 2, "scheduler": "tcp://127.0.0.1:9"}, "workers"),
        ({"scheduler": 3}, "scheduler"),
    ],
)
def test_bad_arguments_are_clear_errors(
    robot: km.Robot, kwargs: dict[str, Any], match: str
) -> None:
    with pytest.raises(KinematicaError, match=match):
        km.reachability(robot, **{"resolution": 0.2, **kwargs})


def test_own_orientations(robot: km.Robot) -> None:
    R = km.rotx(np.array([0.0, np.pi]))
    m = km.reachability(robot, REGION, 0.1, orientations=R, manipulability=False)
    np.testing.assert_array_equal(m.orientations, R)
    assert m.count == 2 and m.reached.max() == 2


@pytest.fixture(scope="module")
def cluster() -> Iterator[Any]:
    import dask
    from dask.distributed import LocalCluster

    from kinematica.reach.cluster import worker_config

    with (
        dask.config.set(worker_config()),  # as scheduler="local" starts one
        LocalCluster(
            n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
        ) as c,
    ):
        yield c


def test_dask_map_is_the_serial_map_bit_for_bit(
    robot: km.Robot, serial: ReachabilityMap, cluster: Any
) -> None:
    import distributed

    by_address = km.reachability(
        robot, REGION, 0.1, orientations=16, scheduler=cluster.scheduler_address
    )
    assert_same_map(serial, by_address)
    with distributed.Client(cluster) as client:
        by_client = km.reachability(robot, REGION, 0.1, orientations=16, scheduler=client)
        assert client.status == "running"
        # the workers got worker_config's malloc thresholds (through the nanny) and no profiler
        from kinematica.reach.cluster import MALLOC_MMAP_THRESHOLD, MALLOC_TRIM_THRESHOLD

        def settings() -> tuple[str | None, str | None, bool]:  # sent by value, run there
            import os

            import dask

            return (
                os.environ.get("MALLOC_TRIM_THRESHOLD_"),
                os.environ.get("MALLOC_MMAP_THRESHOLD_"),
                bool(dask.config.get("distributed.worker.profile.enabled")),
            )

        expected = (str(MALLOC_TRIM_THRESHOLD), str(MALLOC_MMAP_THRESHOLD), False)
        assert set(client.run(settings).values()) == {expected}
    assert_same_map(serial, by_client)


def test_a_planar_arm_in_a_tilted_plane_is_refused() -> None:
    from support.reach_arms import planar

    arm = planar(3)
    base = km.make_transform(km.rotx(0.3), [0, 0, 0])
    tilted = km.Robot.from_dh(arm.links, base=base, name="tilted", convention="standard")
    with pytest.raises(KinematicaError, match="not a base axis"):
        km.reachability(tilted, resolution=0.2)


def test_index_at_reads_a_planar_map_anywhere_in_its_plane() -> None:
    from support.reach_arms import L1, L2, planar

    m = km.reachability(planar(2), resolution=0.05, orientations=None)
    inside = np.array([[0.0, (L1 + L2) / 2 + 0.01, 0.0], [0.0, (L1 + L2) / 2 + 0.01, 5.0]])
    np.testing.assert_array_equal(m.index_at(inside), [1.0, 1.0])
    assert m.index_at(np.array([0.0, 0.0, 0.0])) == 0.0  # the hole of the annulus


def test_vtk_itself_reads_the_vti(serial: ReachabilityMap, tmp_path: Path) -> None:
    # VTK (a 140 MB wheel) is no test dependency: run where it is installed (it was with
    # VTK 9.7.2 when this was written, every array equal, cell centres the voxel centres).
    vtk = pytest.importorskip("vtk")
    from vtk.util.numpy_support import vtk_to_numpy

    save_map(serial, tmp_path / "map.vti")
    reader = vtk.vtkXMLImageDataReader()
    reader.SetFileName(str(tmp_path / "map.vti"))
    reader.Update()
    image = reader.GetOutput()
    assert image.GetDimensions() == (10, 10, 10)
    np.testing.assert_allclose(image.GetOrigin(), REGION[0])
    index = vtk_to_numpy(image.GetCellData().GetArray("reachability_index"))
    np.testing.assert_array_equal(index.reshape(9, 9, 9).transpose(2, 1, 0), serial.index)


def test_a_redundant_arm_says_which_parameter_its_map_holds(tmp_path: Path) -> None:
    iiwa = km.load("iiwa14")
    m = km.reachability(iiwa, resolution=0.4, orientations=4, manipulability=False)
    assert m.held == "arm angle" and m.reachable.any()
    back = load_map(save_map(m, tmp_path / "iiwa.npz"))
    assert back.held == "arm angle"
    assert km.reachability(elbow_wrist(), resolution=0.4, orientations=2).held is None


@pytest.mark.parametrize(
    ("count", "per_block", "workers"), [(31_000, 256, 2), (7, 256, 2), (10**6, 256, 3)]
)
def test_dask_shares_are_dealt_evenly_and_bounded(count: int, per_block: int, workers: int) -> None:
    places = compute.shares(count, per_block, True, workers)
    taken = np.concatenate([np.arange(count)[p] for p in places])
    assert np.array_equal(np.sort(taken), np.arange(count))  # each voxel once
    sizes = [np.arange(count)[p].size for p in places]
    assert max(sizes) - min(sizes) <= 1  # balanced to a voxel
    assert len(places) >= min(count, workers * compute.TASKS_PER_WORKER)
    assert max(sizes) <= compute.MAX_BLOCKS * per_block
    # each task reaches across the whole ball: its voxels span the range
    if count > 100:
        assert all(np.arange(count)[p][-1] >= count - len(places) for p in places)
    serial = compute.shares(count, per_block, False, workers)
    assert [s.start for s in serial] == list(range(0, count, per_block))
