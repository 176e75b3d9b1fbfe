"""Robot design: an evaluation against its IK, and candidates per second serially and on Dask.

Run with ``.venv/bin/python benchmarks/design.py`` (``--poses``, ``--budget``,
``--dask-poses``, ``--workers``, ``--skip-dask``). The problem is the one of
``tests/design/test_runner.py``, made bigger: the seed 6-DOF arm with ``l2``
and ``l3`` free in [0.2, 0.7] m, a task of poses it reaches, maximise the mean
manipulability. Each candidate is the rebuild of the robot from the template,
one ``robot.ik`` on the whole batch (closed form, spherical wrist), and the
manipulability of every solution (``|det J|``, the core's LU: the objective
reads nothing else); an evaluation of every measure adds the singular values
(the core's one-sided Jacobi, a wrist flip's values copied from its twin).
Everything runs on one core (``KINEMATICA_WORKERS=1``, set here).

Printed, each measured in the same run:

* one evaluation (``evaluate_design`` with the search's objective, and with
  every measure) against the batched IK of its poses, stage by stage (CPU
  time), and the ratio against the issue's target of 3x, for ``--poses`` and
  ten times as many (the arm built from the compiled template and its IK
  solver built, about 0.45 ms, are paid once a candidate; the template read
  again from its file, as before the compiled template, beside them); numpy's
  batched SVD of the same Jacobians beside the core's;
* a whole run of ``--budget`` evaluations on a task of ``--dask-poses`` poses:
  serial (the baseline), then on a LocalCluster of ``--workers`` processes
  (start-up timed apart): wall time, CPU time (this process, the workers), the
  speed-up, the speed-up projected for idle cores (the serial CPU time over
  the busiest worker's) and the load average;
* that the cluster's result is identical to the serial one.

No assertions; the figures go in the README.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from pathlib import Path

os.environ["KINEMATICA_WORKERS"] = "1"  # one core, here and in the cluster's workers

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import best_of, fmt_time, header, median_of, table, verdict

from kinematica.design import DesignTemplate, Task, evaluate_design, load_template, optimize

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


#: What the search's objective reads (``mean_manipulability``).
NEEDS = ("mean_manipulability",)


def cost_of_ik(tmpl: DesignTemplate, task: Task) -> None:
    """One evaluation against the batched IK of its poses (one thread, CPU time), by stage."""
    x = np.array([0.45, 0.5])
    robot = tmpl.robot_at(tmpl.params(x))
    res = robot.ik(task.targets, workers=1)
    k = res.solutions.shape[1]
    padded = res.solutions.reshape(-1, 6)
    sol = padded[np.isfinite(padded[:, 0])]
    J = robot.jacobian(sol)
    stages = {
        "evaluation (mean manipulability)": lambda: evaluate_design(tmpl, task, x, needs=NEEDS),
        "evaluation (every measure)": lambda: evaluate_design(tmpl, task, x),
        "the arm from the compiled template": lambda: tmpl.compiled.robot(x),
        "  the same, the file read again": lambda: tmpl.robot_at(tmpl.params(x)),
        "the arm and its IK solver built": lambda: tmpl.compiled.robot(x).ik(task.targets[:1]),
        "batched IK of the poses (1 thread)": lambda: robot.ik(task.targets, workers=1).count,
        "|det J| of every solution, core": lambda: robot.chain.volumes(padded),
        "singular values, core (every measure)": lambda: robot.chain.singular_values(
            padded, group=k
        ),
        "  the same, each solution's computed": lambda: robot.chain.singular_values(sol),
        "  numpy: Jacobians, then batched SVD": lambda: np.linalg.svd(
            robot.jacobian(sol), compute_uv=False
        ),
    }
    times = {name: best_of(f, repeats=15, clock=time.process_time) for name, f in stages.items()}
    ik = times["batched IK of the poses (1 thread)"]
    rows = [(name, fmt_time(t), f"{t / ik:.2f}x") for name, t in times.items()]
    print(f"\nwhere an evaluation's time goes ({sol.shape[0]} solutions of {len(task)} poses):")
    print(table(rows, ("stage (CPU time)", "time", "x the IK")))
    worst = float(
        np.max(np.abs(robot.chain.singular_values(sol) - np.linalg.svd(J, compute_uv=False)))
    )
    print(f"core against numpy's singular values here: largest difference {worst:.1e}")
    ratio = times["evaluation (mean manipulability)"] / ik
    every = times["evaluation (every measure)"] / ik
    print(
        f"evaluation / its IK: {ratio:.2f}x (target 3x: {verdict(ratio <= 3.0)}); "
        f"with every measure {every:.2f}x"
    )


def _warm_up() -> None:
    """What a worker process does once: import kinematica and solve one pose."""
    import kinematica as km
    import kinematica.design
    import kinematica.reach

    robot = km.load("puma560")
    robot.ik(robot.fk(np.zeros(6)))


def _load() -> str:
    return ", ".join(f"{v:.1f}" for v in os.getloadavg())


def _task(robot: object, poses: int) -> Task:
    lim = robot.qlim  # type: ignore[attr-defined]
    rng = np.random.default_rng(0)
    q = rng.uniform(0.6 * lim[:, 0], 0.6 * lim[:, 1], (poses, 6))
    return Task.from_poses(robot.fk(q))  # type: ignore[attr-defined]


def on_dask(path: Path, task: Task, budget: int, workers: int) -> None:
    """The whole search serially and on a LocalCluster: wall, CPU, projected speed-up."""
    import dask
    from dask.distributed import Client, LocalCluster

    from kinematica.reach.cluster import worker_config

    print(f"\nsearch of {budget} evaluations, {len(task)} poses, {workers} Dask workers")
    load_before = _load()
    c0, t0 = time.process_time(), time.perf_counter()
    serial = optimize(path, task, "mean_manipulability", budget=budget, seed=1)
    t_serial, c_serial = time.perf_counter() - t0, time.process_time() - c0
    t0 = time.perf_counter()
    with (
        dask.config.set(worker_config()),  # as kinematica's own "local" cluster
        LocalCluster(n_workers=workers, threads_per_worker=1, dashboard_address=None) as cluster,
        Client(cluster) as client,
    ):
        client.wait_for_workers(workers)
        client.run(_warm_up)  # each worker imports kinematica: start-up, not the run
        t_start = time.perf_counter() - t0
        cpu0 = client.run(time.process_time)
        c0, t0 = time.process_time(), time.perf_counter()
        dask = optimize(path, task, "mean_manipulability", budget=budget, seed=1, scheduler=client)
        t_dask, c_here = time.perf_counter() - t0, time.process_time() - c0
        cpu1 = client.run(time.process_time)
    per_worker = [cpu1[w] - cpu0[w] for w in cpu1]
    same = [e.x for e in serial.history] == [e.x for e in dask.history] and (
        serial.best_value == dask.best_value
    )
    projected = c_serial / max(per_worker)
    rows = [
        ("serial (this process, 1 thread)", fmt_time(t_serial), fmt_time(c_serial), "-",
         f"{serial.evaluated / t_serial:.1f}", "1.00x"),
        (f"LocalCluster, {workers} workers", fmt_time(t_dask), fmt_time(c_here),
         " + ".join(fmt_time(c) for c in per_worker), f"{dask.evaluated / t_dask:.1f}",
         f"{t_serial / t_dask:.2f}x"),
    ]  # fmt: skip
    print(table(rows, ("run", "wall", "CPU here", "CPU workers", "evaluations/s", "speed-up")))
    print(f"cluster start-up (not in the run's time): {fmt_time(t_start)}")
    print(
        f"projected speed-up on {workers} idle cores (serial CPU / busiest worker's CPU): "
        f"{projected:.2f}x (target 1.7x: {verdict(projected >= 1.7)}); measured wall: "
        f"{t_serial / t_dask:.2f}x"
    )
    print(f"load average before: {load_before}; after: {_load()} (2 cores)")
    print(f"evaluations computed: {serial.evaluated} of {len(serial.history)} asked")
    print(f"cluster result identical to the serial one: {same}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--poses", type=int, default=300)
    parser.add_argument("--budget", type=int, default=100)
    parser.add_argument("--dask-poses", type=int, default=3000)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--skip-dask", action="store_true")
    args = parser.parse_args()
    print(header("Robot design: an evaluation against its IK; Dask"))
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "arm6.yaml"
        path.write_text(TEMPLATE)
        tmpl = load_template(path)
        robot = tmpl.robot_at({})
        for poses in (args.poses, 10 * args.poses):
            task = _task(robot, poses)
            one = median_of(
                lambda t=task: evaluate_design(tmpl, t, [0.45, 0.5], needs=NEEDS), repeats=9
            )
            print(f"\n6R, {poses} poses, mean manipulability")
            print(f"one evaluation: {fmt_time(one)} ({fmt_time(one / poses)} per pose)")
            cost_of_ik(tmpl, task)
            print(f"load average: {_load()}")
        if not args.skip_dask:
            on_dask(path, _task(robot, args.dask_poses), args.budget, args.workers)


if __name__ == "__main__":
    main()
