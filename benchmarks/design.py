"""Robot design: candidate evaluations per second, in this process and on a local Dask cluster.

Run with ``.venv/bin/python benchmarks/design.py`` (``--poses``, ``--budget``,
``--workers``). The problem is the one of ``tests/design/test_runner.py``, made
bigger: the seed 6-DOF arm with ``l2`` and ``l3`` free in [0.2, 0.7] m, a task
of ``--poses`` poses it reaches, maximise the mean manipulability. Each
candidate is one ``robot.ik`` on the whole batch (closed form, spherical
wrist), the Jacobian SVD of every solution, and the rebuild of the robot from
the template.

Printed, each measured in the same run:

* one evaluation alone (``evaluate_design``), median;
* a whole run of ``--budget`` evaluations: serial (the baseline), then on a
  LocalCluster of ``--workers`` processes (start-up timed apart), as
  evaluations per second and speed-up over serial;
* that the cluster's result is identical to the serial one.

No assertions; the figures go in the README.
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

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


def cost_of_ik(tmpl: DesignTemplate, task: Task) -> None:
    """One evaluation against the batched IK of its poses (one thread, CPU time), by stage."""
    x = np.array([0.45, 0.5])
    robot = tmpl.robot_at(tmpl.params(x))
    stages = {
        "evaluation (all of it)": lambda: evaluate_design(tmpl, task, x),
        "rebuild the arm from the template": lambda: tmpl.robot_at(tmpl.params(x)),
        "batched IK of the poses (1 thread)": lambda: robot.ik(task.targets, workers=1).count,
    }
    res = robot.ik(task.targets, workers=1)
    sol = res.solutions[np.isfinite(res.solutions[..., 0])]
    J = robot.jacobian(sol)
    stages["Jacobians of every solution"] = lambda: robot.jacobian(sol)
    stages["their singular values (numpy SVD)"] = lambda: np.linalg.svd(J, compute_uv=False)
    times = {k: best_of(f, repeats=15, clock=time.process_time) for k, f in stages.items()}
    ik = times["batched IK of the poses (1 thread)"]
    rows = [(k, fmt_time(t), f"{t / ik:.2f}x") for k, t in times.items()]
    print(f"\nwhere an evaluation's time goes ({sol.shape[0]} solutions of {len(task)} poses):")
    print(table(rows, ("stage (CPU time)", "time", "x the IK")))
    ratio = times["evaluation (all of it)"] / ik
    print(f"evaluation / its IK: {ratio:.1f}x (target 3x: {verdict(ratio <= 3.0)})")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--poses", type=int, default=300)
    parser.add_argument("--budget", type=int, default=120)
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args()
    print(header("Robot design: candidate evaluations per second"))
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "arm6.yaml"
        path.write_text(TEMPLATE)
        tmpl = load_template(path)
        robot = tmpl.robot_at({})
        lim = robot.qlim
        rng = np.random.default_rng(0)
        q = rng.uniform(0.6 * lim[:, 0], 0.6 * lim[:, 1], (args.poses, 6))
        task = Task.from_poses(robot.fk(q))
        one = median_of(lambda: evaluate_design(tmpl, task, [0.45, 0.5]), repeats=9)
        print(f"\n6R, {args.poses} poses, mean manipulability, budget {args.budget}")
        print(f"one evaluation: {fmt_time(one)} ({fmt_time(one / args.poses)} per pose)")
        cost_of_ik(tmpl, task)
        print()

        t0 = time.perf_counter()
        serial = optimize(path, task, "mean_manipulability", budget=args.budget, seed=1)
        t_serial = time.perf_counter() - t0

        from dask.distributed import Client, LocalCluster

        t0 = time.perf_counter()
        with (
            LocalCluster(
                n_workers=args.workers, threads_per_worker=1, dashboard_address=None
            ) as cluster,
            Client(cluster) as client,
        ):
            client.wait_for_workers(args.workers)
            t_start = time.perf_counter() - t0
            t0 = time.perf_counter()
            dask = optimize(
                path, task, "mean_manipulability", budget=args.budget, seed=1, scheduler=client
            )
            t_dask = time.perf_counter() - t0
        same = [e.x for e in serial.history] == [e.x for e in dask.history] and (
            serial.best_value == dask.best_value
        )
        rows = [
            ("serial (this process)", fmt_time(t_serial), f"{serial.evaluated / t_serial:.1f}",
             "1.00x"),
            (f"LocalCluster, {args.workers} workers", fmt_time(t_dask),
             f"{dask.evaluated / t_dask:.1f}", f"{t_serial / t_dask:.2f}x"),
        ]  # fmt: skip
        print(table(rows, ("run", "wall time", "evaluations/s", "speed-up")))
        print(f"\ncluster start-up (not in the run's time): {fmt_time(t_start)}")
        print(f"evaluations computed: {serial.evaluated} of {len(serial.history)} asked")
        print(f"cluster result identical to the serial one: {same}")


if __name__ == "__main__":
    main()
