"""Numeric IK: success at 1e-10 and speed, kinematica's LM against the Robotics Toolbox.

Run with ``.venv/bin/python benchmarks/ik_numeric.py`` (``--targets``,
``--singles``, ``--seed`` to change the sample). For two 7-DOF arms within
their joint limits, the Franka Panda (modified DH, flange tool) and the KUKA
iiwa14 (standard DH), it draws random reachable poses (forward kinematics of
configurations uniform within the limits) and prints:

* success: the share of targets with a returned configuration that our own
  ``robot.fk`` puts within 1e-10 m and 1e-10 rad of the target (rotation angle
  of ``R_targetᵀ R``), with every joint within its limits; the solver's own
  flag is not used;
* batched: wall time per target of one ``solve_numeric`` call on all targets
  (best of 3);
* single: median wall time of ``solve_numeric`` on one pose, over ``--singles``
  of them;
* LM evaluations per target (mean and median, restarts included) and attempts
  (99th percentile and maximum).

When ``roboticstoolbox`` imports, the same poses go to its ``ETS.ik_LM``
(Levenberg-Marquardt with random restarts, C++), one call per pose, with its
tolerance on ``E = ½ eᵀe`` set to 1e-20 so that it may reach 1e-10 in our
terms, and are judged by our FK the same way. No assertions.
"""

from __future__ import annotations

import argparse
import math
import statistics
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import best_of, fmt_time, header, table

from kinematica.dh import Revolute
from kinematica.ik.numeric import solve_numeric, solve_numeric_detailed
from kinematica.robot import Robot
from kinematica.spatial import rotation_angle

TOL = 1e-10
PI = math.pi
PANDA_ROWS = [  # modified DH: a, d, alpha
    (0.0, 0.333, 0.0),
    (0.0, 0.0, -PI / 2),
    (0.0, 0.316, PI / 2),
    (0.0825, 0.0, PI / 2),
    (-0.0825, 0.384, -PI / 2),
    (0.0, 0.0, PI / 2),
    (0.088, 0.0, PI / 2),
]
PANDA_LIMITS = [
    (-2.8973, 2.8973),
    (-1.7628, 1.7628),
    (-2.8973, 2.8973),
    (-3.0718, -0.0698),
    (-2.8973, 2.8973),
    (-0.0175, 3.7525),
    (-2.8973, 2.8973),
]
PANDA_FLANGE = 0.107
IIWA_D = [0.36, 0.0, 0.42, 0.0, 0.4, 0.0, 0.126]  # standard DH, a = 0
IIWA_ALPHA = [-PI / 2, PI / 2, PI / 2, -PI / 2, -PI / 2, PI / 2, 0.0]
IIWA_LIMITS = [(-math.radians(v), math.radians(v)) for v in (170, 120, 170, 120, 170, 120, 175)]


def panda() -> Robot:
    tool = np.eye(4)
    tool[2, 3] = PANDA_FLANGE
    rows = [
        Revolute(a=a, d=d, alpha=al, qlim=lim)
        for (a, d, al), lim in zip(PANDA_ROWS, PANDA_LIMITS, strict=True)
    ]
    return Robot.from_dh(rows, convention="modified", tool=tool, name="Panda")


def iiwa14() -> Robot:
    rows = [
        Revolute(d=d, alpha=al, qlim=lim)
        for d, al, lim in zip(IIWA_D, IIWA_ALPHA, IIWA_LIMITS, strict=True)
    ]
    return Robot.from_dh(rows, convention="standard", name="iiwa14")


def judge(robot: Robot, q: np.ndarray, targets: np.ndarray) -> np.ndarray:
    """``(N,)`` True where ``q (N, n)`` reaches its target by our FK, within limits."""
    ok = np.all(np.isfinite(q), axis=1)
    qs = np.where(ok[:, None], q, 0.0)
    T = robot.fk(qs)
    dist = np.linalg.norm(T[:, :3, 3] - targets[:, :3, 3], axis=1)
    angle = rotation_angle(T[:, :3, :3], targets[:, :3, :3])
    lo, hi = robot.qlim.T
    inside = np.all((qs >= lo) & (qs <= hi), axis=1)
    return ok & (dist <= TOL) & (angle <= TOL) & inside


def ours(robot: Robot, targets: np.ndarray, singles: int) -> list[str]:
    N = len(targets)
    batch_time = best_of(lambda: solve_numeric(robot, targets), repeats=3)
    d = solve_numeric_detailed(robot, targets)
    success = judge(robot, d.candidates.q[:, 0], targets)
    times = []
    for i in range(singles):
        t0 = time.perf_counter()
        solve_numeric(robot, targets[i : i + 1])
        times.append(time.perf_counter() - t0)
    return [
        f"{robot.name}",
        "kinematica LM",
        f"{100 * success.mean():.2f} %",
        fmt_time(batch_time / N),
        fmt_time(statistics.median(times)),
        f"{d.iterations.mean():.1f} / {np.median(d.iterations):.0f}",
        f"{np.percentile(d.attempts, 99):.0f} / {d.attempts.max()}",
    ]


def rtb_robot(robot: Robot) -> Any:
    """The same arm as a Robotics Toolbox ``ETS``, or None if it does not import."""
    try:
        import roboticstoolbox as rtb
        from spatialmath import SE3
    except ImportError:
        return None
    if robot.name == "Panda":
        links = [
            rtb.RevoluteMDH(a=a, d=d, alpha=al, qlim=list(lim))
            for (a, d, al), lim in zip(PANDA_ROWS, PANDA_LIMITS, strict=True)
        ]
        arm = rtb.DHRobot(links, tool=SE3.Tz(PANDA_FLANGE))
    else:
        links = [
            rtb.RevoluteDH(d=d, alpha=al, qlim=list(lim))
            for d, al, lim in zip(IIWA_D, IIWA_ALPHA, IIWA_LIMITS, strict=True)
        ]
        arm = rtb.DHRobot(links)
    return arm.ets()


def theirs(robot: Robot, targets: np.ndarray, singles: int) -> list[str] | None:
    ets = rtb_robot(robot)
    if ets is None:
        return None
    q_check = np.random.default_rng(1).uniform(*robot.qlim.T, size=(5, robot.dof))
    fk_gap = max(np.abs(np.asarray(ets.eval(q)) - robot.fk(q)).max() for q in q_check)
    if fk_gap > 1e-12:
        print(f"  (Robotics Toolbox FK differs from ours by {fk_gap:.1e}: its row is skipped)")
        return None
    N = len(targets)
    q = np.full((N, robot.dof), np.nan)
    its = np.zeros(N)
    searches = np.zeros(N)
    times = []
    for i in range(N):
        t0 = time.perf_counter()
        sol = ets.ik_LM(targets[i], tol=1e-20, joint_limits=True)
        times.append(time.perf_counter() - t0)
        its[i], searches[i] = sol.iterations, sol.searches
        if sol.success:
            q[i] = sol.q
    success = judge(robot, q, targets)
    return [
        f"{robot.name}",
        "RTB ETS.ik_LM",
        f"{100 * success.mean():.2f} %",
        "(one call each)",
        fmt_time(statistics.median(times[:singles] or times)),
        f"{its.mean():.1f} / {np.median(its):.0f}",
        f"{np.percentile(searches, 99):.0f} / {searches.max():.0f}",
    ]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--targets", type=int, default=1000, help="poses per arm (1000)")
    parser.add_argument("--singles", type=int, default=200, help="poses timed one by one (200)")
    parser.add_argument("--seed", type=int, default=0, help="seed of the poses (0)")
    args = parser.parse_args()
    print(header("Numeric IK on 7-DOF arms within limits: success at 1e-10 by our FK, speed"))
    print(f"{args.targets} random reachable poses per arm (seed {args.seed})\n")
    rows = []
    for make in (panda, iiwa14):
        robot = make()
        lo, hi = robot.qlim.T
        q = np.random.default_rng(args.seed).uniform(lo, hi, (args.targets, robot.dof))
        targets = robot.fk(q)
        rows.append(ours(robot, targets, args.singles))
        other = theirs(robot, targets, args.singles)
        if other is not None:
            rows.append(other)
    head = ["arm", "solver", "success", "batched/target", "single (median)", "evals mean/med"]
    print(table(rows, [*head, "attempts p99/max"]))
    if not any(r[1].startswith("RTB") for r in rows):
        print("\nroboticstoolbox not importable: its column is skipped.")


if __name__ == "__main__":
    main()
