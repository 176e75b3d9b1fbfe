"""Time-optimal timing: the core's TOPP-RA on a 7-joint path, against toppra in the same run.

Run with ``make bench`` (or ``.venv/bin/python benchmarks/optimal.py``). A random
7-joint path through 12 waypoints (the natural cubic spline at chord-length s) on a
1,000-interval grid, with joint velocity and acceleration limits:

* the core alone (``kinematica.core.topp.time_optimal_grid``: backward controllable
  sets and the forward pass; then with the limit curve and the reachable sets too) —
  the target is <= 1 ms on one core;
* ``km.time_optimal`` whole (the path's grid coefficients, the core, the trajectory
  sampled every 10 ms);
* toppra 0.6.10 (``TOPPRA(...).compute_parameters`` on the same spline and grid,
  ``seidel`` solver), when installed; the ratio is taken in the same run, pass by pass.

Durations of the two timings are printed too (ours holds the limits between grid
points, toppra's at them). Times are CPU times of this process (best of several
calls), steadier than wall time on a shared machine. No assertions: figures only.
"""

from __future__ import annotations

import sys
import time
from importlib.metadata import version
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parent))

from _common import best_of, fmt_time, header, table, verdict

import kinematica as km
from kinematica.core.topp import time_optimal_grid
from kinematica.motion.optimal_path import grid_for, taylor_coefficients, waypoint_path

#: The target of issue 36 for the core on a 7-joint, 1,000-interval grid (s).
TARGET = 1e-3


def main() -> None:
    print(header("kinematica time-optimal timing benchmark"))
    rng = np.random.default_rng(7)
    n, k = 7, 12
    W = np.cumsum(rng.uniform(-0.8, 0.8, (k, n)), axis=0)
    v = rng.uniform(0.5, 3.0, n)
    a = rng.uniform(1.0, 10.0, n)
    vel = np.stack([-v, v], axis=1)
    acc = np.stack([-a, a], axis=1)
    pp = waypoint_path(W)
    s, piece = grid_for(pp.knots, 1000)
    coef = taylor_coefficients(pp, s, piece)
    cap = np.full(s.size - 1, np.inf)

    def core() -> object:
        return time_optimal_grid(s, coef, (-v, v), (-a, a), cap, 0.0, 0.0, 1e12, sets=False)

    def core_sets() -> object:
        return time_optimal_grid(s, coef, (-v, v), (-a, a), cap, 0.0, 0.0, 1e12, sets=True)

    def whole() -> object:
        return km.time_optimal(W, vel, acc, grid=1000)

    tc = best_of(core, repeats=30, clock=time.process_time)
    ts = best_of(core_sets, repeats=30, clock=time.process_time)
    tw = best_of(whole, repeats=10, clock=time.process_time)
    ours = km.time_optimal(W, vel, acc, grid=1000)
    rows = [
        (
            f"core TOPP-RA, {n} joints, {s.size - 1} intervals",
            fmt_time(tc),
            f"target <= 1 ms: {verdict(tc <= TARGET, fmt_time(tc))}",
        ),
        ("core, with the limit curve and the reachable sets", fmt_time(ts), ""),
        (
            "km.time_optimal (path, core, 10 ms samples)",
            fmt_time(tw),
            f"duration {ours.duration:.6f} s",
        ),
    ]
    try:
        import toppra
        import toppra.algorithm as algo
        import toppra.constraint as constraint
    except ImportError:
        rows.append(("toppra", "not installed", "pip install toppra to compare"))
    else:
        toppra.setup_logging("WARNING")
        path = toppra.SplineInterpolator(pp.knots, W, bc_type="natural")
        cons = [
            constraint.JointVelocityConstraint(vel),
            constraint.JointAccelerationConstraint(acc),
        ]
        inst = algo.TOPPRA(cons, path, gridpoints=s, parametrizer="ParametrizeConstAccel")
        tt = best_of(
            lambda: inst.compute_parameterization(0.0, 0.0), repeats=10, clock=time.process_time
        )
        traj = inst.compute_trajectory(0.0, 0.0)
        rows.append(
            (
                f"toppra {version('toppra')}, same path and grid",
                fmt_time(tt),
                f"core {tt / tc:.1f}x faster (with the sets {tt / ts:.1f}x); "
                f"its duration {traj.duration:.6f} s "
                f"(ours {100 * (ours.duration / traj.duration - 1):+.3f} %)",
            )
        )
    print(table(rows, ("what", "time (best)", "against")))


if __name__ == "__main__":
    main()
