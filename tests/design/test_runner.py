"""A 6R design on a few hundred poses: Dask clusters give the serial result, and a
killed run resumes from its checkpoint to the same end."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import textwrap
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from kinematica.design import CheckpointError, DesignResult, Task, load_template, optimize
from kinematica.errors import KinematicaError

distributed = pytest.importorskip("distributed")

TEMPLATE = """
name: Seed 6-DOF arm, design
convention: standard
units: {angle: deg, length: m}
parameters:
  l1: 0.5
  l2: {value: 0.4, min: 0.2, max: 0.7}
  l3: {value: 0.4, min: 0.2, max: 0.7}
  l4: 0.1
joints:
  - {theta: q1,      d: l1, a: 0,  alpha: 90,  limits: [-160, 160]}
  - {theta: q2 + 90, d: 0,  a: l2, alpha: 0,   limits: [-110, 110]}
  - {theta: q3 - 90, d: 0,  a: 0,  alpha: -90, limits: [-135, 135]}
  - {theta: q4 - 90, d: l3, a: 0,  alpha: -90}
  - {theta: q5,      d: 0,  a: 0,  alpha: 90,  limits: [-120, 120]}
  - {theta: q6,      d: l4, a: 0,  alpha: 0}
"""
POSES = 200
BUDGET = 30
SEED = 11
OBJECTIVE = "mean_manipulability"


@pytest.fixture(scope="module")
def problem(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Task]:
    folder = tmp_path_factory.mktemp("design6r")
    path = folder / "arm6.yaml"
    path.write_text(TEMPLATE)
    tmpl = load_template(path)
    robot = tmpl.robot_at(tmpl.nominal)
    lim = robot.qlim
    q = np.random.default_rng(5).uniform(0.6 * lim[:, 0], 0.6 * lim[:, 1], (POSES, 6))
    task = Task.from_poses(robot.fk(q), name="poses")
    np.save(folder / "poses.npy", task.targets)
    return path, task


@pytest.fixture(scope="module")
def serial(problem: tuple[Path, Task]) -> DesignResult:
    path, task = problem
    return optimize(path, task, OBJECTIVE, budget=BUDGET, seed=SEED)


@pytest.fixture(scope="module")
def cluster() -> Iterator[Any]:
    from dask.distributed import LocalCluster

    with LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as c:
        yield c


def assert_same_run(a: DesignResult, b: DesignResult) -> None:
    """Bit-identical: every candidate, every measure, the best."""
    assert [ev.x for ev in a.history] == [ev.x for ev in b.history]
    for name in a.history[0].measures:
        np.testing.assert_array_equal(
            [ev.measures[name] for ev in a.history], [ev.measures[name] for ev in b.history]
        )
    assert [ev.violation for ev in a.history] == [ev.violation for ev in b.history]
    assert a.best_params == b.best_params
    assert a.best_value == b.best_value


def test_the_serial_run_is_a_real_design(serial: DesignResult) -> None:
    assert len(serial.task) == POSES and serial.task.kind == "pose"
    assert serial.feasible and serial.history[0].feasible  # the template reaches every pose
    assert serial.best_value > serial.history[0].measures[OBJECTIVE]
    assert serial.best_robot.dof == 6
    assert len({ev.x for ev in serial.history}) > 20


def test_local_cluster_of_two_workers_gives_the_serial_result(
    problem: tuple[Path, Task], serial: DesignResult
) -> None:
    path, task = problem
    res = optimize(path, task, OBJECTIVE, budget=BUDGET, seed=SEED, scheduler="local", workers=2)
    assert_same_run(serial, res)


def test_existing_cluster_by_address_or_client(
    problem: tuple[Path, Task], serial: DesignResult, cluster: Any
) -> None:
    path, task = problem
    by_address = optimize(
        path, task, OBJECTIVE, budget=BUDGET, seed=SEED, scheduler=cluster.scheduler_address
    )
    assert_same_run(serial, by_address)
    with distributed.Client(cluster) as client:
        by_client = optimize(path, task, OBJECTIVE, budget=BUDGET, seed=SEED, scheduler=client)
        assert client.status == "running"  # a client we were given is left open
    assert_same_run(serial, by_client)


def test_unreachable_scheduler_is_a_clear_error(
    problem: tuple[Path, Task], monkeypatch: pytest.MonkeyPatch
) -> None:
    from kinematica.reach import cluster

    monkeypatch.setattr(cluster, "CONNECT_TIMEOUT", "1s")
    path, task = problem
    with pytest.raises(
        KinematicaError, match=r"cannot reach the Dask scheduler at 'tcp://127\.0\.0\.1"
    ):
        optimize(path, task, budget=10, scheduler="tcp://127.0.0.1:9")


def _lines(path: Path) -> list[str]:
    return path.read_text().splitlines() if path.exists() else []


def test_checkpoint_cut_after_k_evaluations_resumes_to_the_same_end(
    problem: tuple[Path, Task], serial: DesignResult, tmp_path: Path
) -> None:
    path, task = problem
    ck = tmp_path / "run.ckpt"
    full = optimize(path, task, OBJECTIVE, budget=BUDGET, seed=SEED, checkpoint=ck)
    assert_same_run(serial, full)
    lines = _lines(ck)
    assert len(lines) == 1 + full.evaluated
    # simulate a kill after k finished evaluations, in the middle of writing the next one
    k = 12
    ck.write_text("\n".join(lines[: 1 + k]) + "\n" + lines[1 + k][:25])
    resumed = optimize(path, task, OBJECTIVE, budget=BUDGET, seed=SEED, checkpoint=ck)
    assert_same_run(serial, resumed)
    assert resumed.reused == k and resumed.evaluated == full.evaluated - k
    assert len(_lines(ck)) == 1 + full.evaluated  # the cut line was dropped, none lost
    # the same checkpoint serves a run with another objective that reads what was measured
    # (the manipulability): the first generation is shared
    other = optimize(path, task, "min_manipulability", budget=BUDGET, seed=SEED, checkpoint=ck)
    assert other.reused >= 10
    # an objective reading a measure the run did not take (the singular values) computes
    # those evaluations again, and the checkpoint then serves it too
    clear = optimize(path, task, "singularity_clearance", budget=BUDGET, seed=SEED, checkpoint=ck)
    assert clear.reused == 0 and clear.evaluated > 0
    assert all("singularity_clearance" in ev.measures for ev in clear.history)
    again = optimize(path, task, "singularity_clearance", budget=BUDGET, seed=SEED, checkpoint=ck)
    assert again.evaluated == 0 and again.best_value == clear.best_value


def test_killed_subprocess_resumes_on_a_cluster(
    problem: tuple[Path, Task], serial: DesignResult, tmp_path: Path, cluster: Any
) -> None:
    path, _ = problem
    ck = tmp_path / "killed.ckpt"
    poses = path.parent / "poses.npy"
    script = textwrap.dedent(
        f"""
        from kinematica.design import optimize
        optimize({str(path)!r}, {str(poses)!r}, {OBJECTIVE!r}, budget={BUDGET * 2},
                 seed={SEED}, checkpoint={str(ck)!r})
        """
    )
    proc = subprocess.Popen([sys.executable, "-c", script], cwd=tmp_path)
    try:
        deadline = time.monotonic() + 60
        while len(_lines(ck)) < 1 + 10 and time.monotonic() < deadline:
            assert proc.poll() is None, "the run ended before it could be killed"
            time.sleep(0.005)
        assert proc.poll() is None
        os.kill(proc.pid, signal.SIGKILL)
    finally:
        proc.wait()
    assert proc.returncode == -signal.SIGKILL
    done = len(_lines(ck)) - 1
    assert 10 <= done < BUDGET * 2
    task = Task(np.load(poses), name=str(poses))
    uninterrupted = optimize(path, task, OBJECTIVE, budget=BUDGET * 2, seed=SEED)
    resumed = optimize(
        path,
        task,
        OBJECTIVE,
        budget=BUDGET * 2,
        seed=SEED,
        checkpoint=ck,
        scheduler=cluster.scheduler_address,
    )
    assert_same_run(uninterrupted, resumed)
    assert resumed.reused >= done - 1  # at most the line being written was lost
    assert resumed.reused + resumed.evaluated == uninterrupted.evaluated


def test_checkpoint_of_another_problem_or_not_a_checkpoint(
    problem: tuple[Path, Task], tmp_path: Path
) -> None:
    path, task = problem
    ck = tmp_path / "a.ckpt"
    optimize(path, Task.ring(0.5, 4), budget=10, seed=0, checkpoint=ck)
    with pytest.raises(CheckpointError, match=r"a\.ckpt: this checkpoint belongs to another"):
        optimize(path, task, budget=10, seed=0, checkpoint=ck)
    bad = tmp_path / "b.ckpt"
    bad.write_text('{"hello": 1}\n')
    with pytest.raises(CheckpointError, match=r"b\.ckpt: not a kinematica design checkpoint"):
        optimize(path, task, budget=10, checkpoint=bad)
    lines = _lines(ck)
    broken = tmp_path / "c.ckpt"
    broken.write_text("\n".join([lines[0], "{oops", *lines[1:3]]) + "\n")
    with pytest.raises(CheckpointError, match=r"c\.ckpt, line 2: not a checkpoint line"):
        optimize(path, Task.ring(0.5, 4), budget=10, checkpoint=broken)
    short = json.loads(lines[1])
    short["x"] = [0.3]
    broken.write_text("\n".join([lines[0], json.dumps(short)]) + "\n")
    with pytest.raises(CheckpointError, match=r"line 2: 1 values for 2 parameters"):
        optimize(path, Task.ring(0.5, 4), budget=10, checkpoint=broken)
    with pytest.raises(CheckpointError, match="cannot write the checkpoint"):
        optimize(path, task, budget=10, checkpoint=tmp_path / "no" / "such.ckpt")


def test_balanced_runs_split_a_generation_evenly() -> None:
    """Sizes within one of each other, larger first, order kept, at most 16 a run."""
    from kinematica.design.runner import CANDIDATES_PER_TASK, balanced_runs

    keys = [(float(i),) for i in range(10)]
    runs = balanced_runs(keys, 2)
    assert [len(r) for r in runs] == [3, 3, 2, 2]
    assert [k for r in runs for k in r] == keys
    assert [len(r) for r in balanced_runs(keys[:3], 2)] == [1, 1, 1]
    big = [(float(i),) for i in range(100)]
    sizes = [len(r) for r in balanced_runs(big, 2)]
    assert max(sizes) <= CANDIDATES_PER_TASK and max(sizes) - min(sizes) <= 1
    assert sum(sizes) == 100 and len(sizes) == 7
    assert balanced_runs([], 4) == []
