"""Reachability maps: pose queries per second on one core, memory, and Dask on 2 workers.

Run with ``.venv/bin/python benchmarks/reach.py`` (``--big`` poses for the memory
run, ``--dask`` poses for the cluster run, ``--skip-memory``, ``--skip-dask``).

Printed, each measured in the same run:

* one core (``threads=1``): a map of about a million poses (64 orientations per
  voxel) of a spherical-wrist arm (PUMA 560) and a three-parallel arm (UR5),
  without and with the manipulability, as poses per second of CPU time and of
  wall time, against the issue's target of 400,000 a second (a 1-million-pose
  map in under 3 s); and where the time goes in one block (the targets, the
  batched IK, the reduction per voxel, the Jacobians and their SVDs);
* the peak resident memory of a ``--big`` (10 million) pose map, run in a fresh
  process, against the target of 1 GB;
* the same map serially and on a LocalCluster of 2 single-threaded worker
  processes: wall times, the speed-up, the cluster's start-up apart, and that
  the maps are equal bit for bit.

The machine may be shared: the load average is printed with each figure (a
speed-up needs 2 idle cores to be read against the target of 1.7x).
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import fmt_time, header, table, verdict

import kinematica as km
from kinematica.reach import compute
from kinematica.robot.velocity import manipulability, selected_rows

TARGET_RATE = 400_000
TARGET_MEMORY_MB = 1024.0
TARGET_SPEEDUP = 1.7
ORIENTATIONS = 64


def _warm_up() -> None:
    """What a worker process does once: import kinematica and solve one pose."""
    import kinematica as km
    import kinematica.design
    import kinematica.reach

    robot = km.load("puma560")
    robot.ik(robot.fk(np.zeros(6)))


def _load() -> str:
    return ", ".join(f"{v:.1f}" for v in os.getloadavg())


def _resolution_for(robot: km.Robot, poses: int) -> float:
    """A voxel side giving about ``poses`` poses (voxels in the reach ball × 64)."""
    m = km.reachability(robot, resolution=0.2, orientations=1, manipulability=False)
    volume = 4.0 / 3.0 * np.pi * m.radius**3
    return float((volume * ORIENTATIONS / poses) ** (1.0 / 3.0))


def _asked(m: km.reach.ReachabilityMap) -> int:
    inside = np.linalg.norm(m.centres() - m.centre, axis=-1) <= m.radius
    return int(np.count_nonzero(inside)) * m.count


def one_core(poses: int) -> None:
    print(f"\nOne core (threads=1): maps of about {poses:,} poses, {ORIENTATIONS} orientations")
    rows = []
    for name in ("puma560", "ur5"):
        robot = km.load(name)
        h = _resolution_for(robot, poses)
        for manip in (False, True):
            c0, t0 = time.process_time(), time.perf_counter()
            m = km.reachability(
                robot, resolution=h, orientations=ORIENTATIONS, manipulability=manip, threads=1
            )
            cpu, wall = time.process_time() - c0, time.perf_counter() - t0
            n = _asked(m)
            rows.append(
                (
                    f"{robot.name} ({km.classify(robot).kind})",
                    "yes" if manip else "no",
                    f"{n:,}",
                    fmt_time(cpu),
                    f"{n / cpu:,.0f}",
                    f"{n / wall:,.0f}",
                    fmt_time(cpu * 1e6 / n),
                    verdict(n / cpu >= TARGET_RATE, f"{n / cpu / TARGET_RATE:.2f}x")
                    if not manip
                    else "-",
                )
            )
    print(
        table(
            rows,
            ("arm", "manip.", "poses", "CPU", "poses/s CPU", "poses/s wall", "per 1M", "400k/s"),
        )
    )
    print(f"load average during the run: {_load()}")


def where_time_goes() -> None:
    """One block of CHUNK_QUERIES poses, by stage (CPU time of this process)."""
    print(f"\nWhere the time goes: one block of {compute.CHUNK_QUERIES:,} poses (CPU time)")
    rows = []
    for name in ("puma560", "ur5"):
        robot = km.load(name)
        rot = km.reach.so3_set(ORIENTATIONS)
        v = compute.CHUNK_QUERIES // ORIENTATIONS
        rng = np.random.default_rng(0)
        centres = rng.uniform(-0.6, 0.6, (v, 3))
        c = time.process_time()
        targets = np.zeros((v, ORIENTATIONS, 4, 4))
        targets[:, :, :3, :3] = rot
        targets[:, :, :3, 3] = centres[:, None, :]
        targets[:, :, 3, 3] = 1.0
        targets = targets.reshape(-1, 4, 4)
        t_targets = time.process_time() - c
        c = time.process_time()
        res = robot.ik(targets, workers=1)
        count = res.count
        t_ik = time.process_time() - c
        c = time.process_time()
        count.reshape(v, -1).sum(axis=1)
        np.count_nonzero(count.reshape(v, -1) > 0, axis=1)
        t_reduce = time.process_time() - c
        c = time.process_time()
        sol = res.solutions
        valid = np.isfinite(sol[..., 0])
        t_sol = time.process_time() - c
        c = time.process_time()
        task_rows = selected_rows(robot, "task")
        robot.chain.volumes(sol.reshape(-1, robot.dof), task_rows, workers=1)
        t_manip = time.process_time() - c  # as the map computes it: |det J| by the core's LU
        c = time.process_time()
        manipulability(robot, sol[valid], axes="task")  # numpy's LU of robot.jacobian's
        t_numpy = time.process_time() - c
        n = targets.shape[0]
        rows.append(
            (
                robot.name,
                *(fmt_time(t / n) for t in (t_targets, t_ik, t_reduce, t_sol, t_manip, t_numpy)),
                f"{valid.sum() / n:.2f}",
            )
        )
    print(
        table(
            rows,
            (
                "arm (per pose)",
                "targets",
                "robot.ik",
                "reduce",
                "solutions",
                "manip. (core)",
                "numpy's",
                "sol./pose",
            ),
        )
    )


_MEMORY_CHILD = """
import resource, sys, time
import numpy as np
import kinematica as km
poses = int(sys.argv[1])
robot = km.load("puma560")
m0 = km.reachability(robot, resolution=0.2, orientations=1, manipulability=False)
h = float((4 / 3 * np.pi * m0.radius**3 * 64 / poses) ** (1 / 3))
t0 = time.perf_counter()
m = km.reachability(robot, resolution=h, orientations=64, manipulability=True, threads=1)
inside = np.linalg.norm(m.centres() - m.centre, axis=-1) <= m.radius
print(int(np.count_nonzero(inside)) * 64, time.perf_counter() - t0,
      resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0)
"""


def memory(poses: int) -> None:
    print(f"\nMemory: a map of about {poses:,} poses with the manipulability, in a fresh process")
    out = subprocess.run(
        [sys.executable, "-c", _MEMORY_CHILD, str(poses)],
        capture_output=True,
        text=True,
        check=True,
    ).stdout.split()
    n, wall, rss = int(out[0]), float(out[1]), float(out[2])
    print(
        table(
            [(f"{n:,}", fmt_time(wall), f"{rss:.0f} MB", verdict(rss <= TARGET_MEMORY_MB))],
            ("poses", "wall time", "peak RSS", "<= 1 GB"),
        )
    )
    print(f"load average: {_load()}")


def dask(poses: int, workers: int) -> None:
    import dask as dask_config
    from dask.distributed import Client, LocalCluster

    from kinematica.reach.cluster import worker_config

    robot = km.load("ur5")
    h = _resolution_for(robot, poses)
    print(f"\nDask: a UR5 map of about {poses:,} poses with the manipulability, {workers} workers")
    load_before = _load()
    t0, c0 = time.perf_counter(), time.process_time()
    serial = km.reachability(robot, resolution=h, orientations=ORIENTATIONS, threads=1)
    t_serial, c_serial = time.perf_counter() - t0, time.process_time() - c0
    t0 = time.perf_counter()
    with (
        dask_config.config.set(worker_config()),  # as kinematica's own "local" cluster
        LocalCluster(n_workers=workers, threads_per_worker=1, dashboard_address=None) as cluster,
        Client(cluster) as client,
    ):
        client.wait_for_workers(workers)
        client.run(_warm_up)  # each worker imports kinematica: start-up, not the run
        t_start = time.perf_counter() - t0
        cpu0 = client.run(time.process_time)
        t0 = time.perf_counter()
        parallel = km.reachability(robot, resolution=h, orientations=ORIENTATIONS, scheduler=client)
        t_dask = time.perf_counter() - t0
        cpu1 = client.run(time.process_time)
        per_worker = [cpu1[w] - cpu0[w] for w in cpu1]
        c_dask = sum(per_worker)
    same = all(
        np.array_equal(getattr(serial, a), getattr(parallel, a), equal_nan=True)
        for a in ("reached", "solutions", "manipulability")
    )
    n = _asked(serial)
    rows = [
        (
            "serial (this process, 1 thread)",
            fmt_time(t_serial),
            fmt_time(c_serial),
            f"{n / t_serial:,.0f}",
            "1.00x",
        ),
        (
            f"LocalCluster, {workers} workers",
            fmt_time(t_dask),
            fmt_time(c_dask),
            f"{n / t_dask:,.0f}",
            f"{t_serial / t_dask:.2f}x",
        ),
    ]
    print(table(rows, ("run", "wall time", "CPU (workers')", "poses/s", "speed-up")))
    print(
        "CPU time the cluster spent against the serial run's: "
        f"{c_dask / c_serial:.2f}x (1.00x: no work lost to the cluster; the wall-time "
        "speed-up then depends on idle cores)"
    )
    print(f"cluster start-up (not in the run's time): {fmt_time(t_start)}")
    print(f"maps equal bit for bit: {same}")
    print(f"load average before: {load_before}; after: {_load()} (2 cores)")
    projected = c_serial / max(per_worker)
    print(
        f"CPU per worker: {' + '.join(fmt_time(c) for c in per_worker)}; projected speed-up on "
        f"{workers} idle cores (serial CPU / busiest worker's CPU): {projected:.2f}x"
    )
    print(
        f"speed-up >= {TARGET_SPEEDUP}x: measured wall "
        + verdict(t_serial / t_dask >= TARGET_SPEEDUP, "on a shared machine: see the load")
        + ", projected "
        + verdict(projected >= TARGET_SPEEDUP)
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--poses", type=int, default=1_000_000)
    parser.add_argument("--big", type=int, default=10_000_000)
    parser.add_argument("--dask", type=int, default=6_000_000)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--skip-memory", action="store_true")
    parser.add_argument("--skip-dask", action="store_true")
    args = parser.parse_args()
    print(header("Reachability maps by exact IK: poses per second, memory, Dask"))
    one_core(args.poses)
    where_time_goes()
    if not args.skip_memory:
        memory(args.big)
    if not args.skip_dask:
        dask(args.dask, args.workers)


if __name__ == "__main__":
    main()
