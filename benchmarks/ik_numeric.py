"""Numeric IK: success at 1e-10 and speed, kinematica's LM against the Robotics Toolbox.

Run with ``.venv/bin/python benchmarks/ik_numeric.py`` (``--targets``,
``--singles``, ``--seed`` to change the sample); ``benchmarks/ik.py`` runs it
too. For the built-in Franka Panda (modified DH, flange tool) and KUKA iiwa14
(standard DH), within their joint limits, it draws random reachable poses
(forward kinematics of configurations uniform within the limits, seeded) and
prints, on one core (``workers=1``):

* success: the share of targets with a returned configuration that our own
  ``robot.fk`` puts within 1e-10 m and 1e-10 rad of the target (angle of
  ``R_targetᵀ R``), every joint within its limits; the solver's flag is not used;
* batched: time per target of one ``robot.ik(targets, method="numeric",
  workers=1)`` call on all targets (solve, check, limits), best of 3, as CPU
  time of the process (wall time in brackets: the machine is shared);
* single: ``robot.ik(T, method="numeric")``, the median over ``--singles``
  poses of each pose's shortest of 3 passes (wall), and the same for the
  core's call alone (``solver.ik``: the search and the check, no Python
  around it).

Where the batched time goes: the search's own counts per target
(``kinematica._core_testing.internals.lm_stats``: configurations evaluated, attempts),
their median, mean and tail, the share of targets that needed restarts and of
the evaluations spent on them, and the batched time per evaluation.

When ``roboticstoolbox`` imports (``make bench`` installs it when it can), the
same poses go to its ``ETS.ik_LM`` (Levenberg-Marquardt with random
restarts, C++), one call per pose, with its tolerance on ``E = ½ eᵀe`` set to
1e-20 so that it may reach 1e-10 in our terms, and its answers are judged by
our FK the same way; its single figure is timed as ours, and the last column
gives it over ours. No assertions.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import fmt_time, header, shortest_per_item, table, verdict
from kinematica._core_testing import internals

import kinematica as km
from kinematica import _core
from kinematica.ik.numeric import LABEL, NumericSetup, numeric_setup
from kinematica.ik.result import IKBatchResult
from kinematica.spatial import rotation_angle

#: A returned configuration counts when our FK puts the tool this close (m and rad).
TOL = 1e-10
#: Issue 19's targets, on one core: success, single median, batched per target.
TARGET_SUCCESS, TARGET_SINGLE, TARGET_BATCHED = 1.0, 15e-6, 10e-6


def judge(robot: km.Robot, q: np.ndarray, targets: np.ndarray) -> np.ndarray:
    """``(N,)`` True where ``q (N, n)`` reaches its target by our FK, within limits."""
    ok = np.all(np.isfinite(q), axis=1)
    qs = np.where(ok[:, None], q, robot.qlim.mean(axis=1))
    T = robot.fk(qs)
    dist = np.linalg.norm(T[:, :3, 3] - targets[:, :3, 3], axis=1)
    angle = rotation_angle(T[:, :3, :3], targets[:, :3, :3])
    lo, hi = robot.qlim.T
    inside = np.all((qs >= lo) & (qs <= hi), axis=1)
    return ok & (dist <= TOL) & (angle <= TOL) & inside


def default_setup(robot: km.Robot) -> NumericSetup:
    """The numeric set-up ``robot.ik(T, method="numeric")`` uses (every default)."""
    return numeric_setup(
        robot.chain,
        respect_limits=True,
        tol_position=TOL,
        tol_rotation=TOL,
        seed=None,
        weights=(1.0,) * 6,
    )


def core_call(robot: km.Robot) -> Any:
    """``T -> setup.ik(...)``: the core's search and check of one target, as robot.ik calls it.

    (The first guess alone, then the restarts where it did not settle: two core calls for
    the few targets that need restarts, one for the rest.)
    """
    default = robot.ik(robot.fk(robot.qlim.mean(axis=1)), method="numeric")
    assert default.method == "numeric:lm"
    setup = default_setup(robot)
    opts = _core.CheckOptions()
    opts.tol = _core.Tolerance(1e-10, 1e-10)
    opts.respect_limits, opts.complete, opts.weights = True, False, (1.0,) * 6
    core = robot.chain.core
    return lambda T: setup.ik(core, T, opts, None, (LABEL,))


def account(robot: km.Robot, targets: np.ndarray, batched: float) -> list[str]:
    """A row of where the batched time goes: evaluations and attempts per target."""
    setup = default_setup(robot)
    evaluations, attempts, _ = internals.lm_stats(setup.solver, robot.chain.core, targets)
    restarted = attempts > 1
    p90, p99 = np.percentile(evaluations, [90, 99])
    return [
        robot.name,
        f"{np.median(evaluations):.0f} / {evaluations.mean():.1f}",
        f"{p90:.0f} / {p99:.0f} / {evaluations.max()}",
        f"{100 * restarted.mean():.1f} %",
        f"{100 * evaluations[restarted].sum() / evaluations.sum():.0f} %",
        f"{attempts.max()}",
        fmt_time(batched / evaluations.mean()),
    ]


def ours(robot: km.Robot, targets: np.ndarray, singles: int) -> tuple[list[str], list[float]]:
    N = len(targets)
    robot.ik(targets[:2], method="numeric", workers=1)
    cpu, wall = [], []
    res: IKBatchResult | None = None
    for _ in range(3):
        t0, c0 = time.perf_counter(), time.process_time()
        out = robot.ik(targets, method="numeric", workers=1)
        wall.append(time.perf_counter() - t0)
        cpu.append(time.process_time() - c0)
        assert isinstance(out, IKBatchResult)
        res = out
    assert res is not None
    q = np.full((N, robot.dof), np.nan)
    if res.solutions.shape[1]:
        q = np.where(res.count[:, None] > 0, res.solutions[:, 0], np.nan)
    success = float(judge(robot, q, targets).mean())
    few = list(targets[:singles])
    single = shortest_per_item(lambda T: robot.ik(T, method="numeric"), few)
    core = shortest_per_item(core_call(robot), few)
    batched = min(min(cpu), min(wall)) / N
    row = [
        robot.name,
        "kinematica LM",
        f"{100 * success:.2f} %",
        f"{fmt_time(min(cpu) / N)} ({fmt_time(min(wall) / N)})",
        fmt_time(single),
        fmt_time(core),
        "1",
    ]
    return row, [success, single, batched]


def rtb_robot(robot: km.Robot) -> Any:
    """The same arm as a Robotics Toolbox ``ETS`` (from our DH table), or None."""
    try:
        import roboticstoolbox as rtb
        from spatialmath import SE3
    except ImportError:
        return None
    make = rtb.RevoluteMDH if robot.convention == "modified" else rtb.RevoluteDH
    links = [
        make(d=d, a=a, alpha=alpha, offset=theta, qlim=list(lim))
        for (theta, d, a, alpha), lim in zip(robot.dh_table(), robot.qlim, strict=True)
    ]
    arm = rtb.DHRobot(links, base=SE3(robot.base, check=False), tool=SE3(robot.tool, check=False))
    return arm.ets()


def theirs(robot: km.Robot, targets: np.ndarray, singles: int, ours_single: float) -> list[str]:
    ets = rtb_robot(robot)
    if ets is None:
        return []
    q_check = np.random.default_rng(1).uniform(*robot.qlim.T, size=(5, robot.dof))
    fk_gap = max(np.abs(np.asarray(ets.eval(q)) - robot.fk(q)).max() for q in q_check)
    if fk_gap > 1e-12:
        print(f"  (Robotics Toolbox FK differs from ours by {fk_gap:.1e}: its row is skipped)")
        return []
    N = len(targets)
    q = np.full((N, robot.dof), np.nan)
    wall, cpu = time.perf_counter(), time.process_time()
    for i in range(N):
        sol = ets.ik_LM(targets[i], tol=1e-20, joint_limits=True)
        if sol.success:
            q[i] = sol.q
    wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
    success = judge(robot, q, targets)
    single = shortest_per_item(
        lambda T: ets.ik_LM(T, tol=1e-20, joint_limits=True), list(targets[:singles])
    )
    return [
        robot.name,
        "RTB ETS.ik_LM",
        f"{100 * success.mean():.2f} %",
        f"{fmt_time(cpu / N)} ({fmt_time(wall / N)}), a loop",
        fmt_time(single),
        "-",
        f"{single / ours_single:.2f}",
    ]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--targets", type=int, default=1000, help="poses per arm (1000)")
    parser.add_argument("--singles", type=int, default=200, help="poses timed one by one (200)")
    parser.add_argument("--seed", type=int, default=0, help="seed of the poses (0)")
    args = parser.parse_args()
    print(header("Numeric IK on 7-DOF arms within limits: success at 1e-10 by our FK, speed"))
    print(
        f"{args.targets} random reachable poses per arm (seed {args.seed}); one core "
        "(workers=1); batched: CPU time (wall in brackets); single: median over "
        f"{args.singles} poses of each one's shortest of 3 passes (wall)\n"
    )
    rows, figures, spent = [], {}, []
    for name in ("panda", "iiwa14"):
        robot = km.load(name)
        lo, hi = robot.qlim.T
        q = np.random.default_rng(args.seed).uniform(lo, hi, (args.targets, robot.dof))
        targets = robot.fk(q)
        row, figures[robot.name] = ours(robot, targets, args.singles)
        rows.append(row)
        spent.append(account(robot, targets, figures[robot.name][2]))
        other = theirs(robot, targets, args.singles, figures[robot.name][1])
        if other:
            rows.append(other)
    head = ["arm", "solver", "success", "batched/target", "single (median)", "its core call"]
    print(table(rows, [*head, "single vs ours"]))
    if not any(r[1].startswith("RTB") for r in rows):
        print("\nroboticstoolbox not importable: its rows are skipped.")

    print("\n  where the batched time goes: configurations evaluated per target")
    head = ["arm", "median / mean", "p90 / p99 / max", "restarted", "their share", "most attempts"]
    print(table(spent, [*head, "time per evaluation"]))

    print("\n  issue 19 targets (one core)")
    out = []
    for arm, (success, single, batched) in figures.items():
        out += [
            [f"{arm}: success at 1e-10 = 100 %", f"{100 * success:.2f} %"],
            [f"{arm}: single median <= {fmt_time(TARGET_SINGLE)}", fmt_time(single)],
            [f"{arm}: batched <= {fmt_time(TARGET_BATCHED)} per target", fmt_time(batched)],
        ]
        out[-3].append(verdict(success >= TARGET_SUCCESS))
        out[-2].append(verdict(single <= TARGET_SINGLE, f"{single / TARGET_SINGLE:.2f}x"))
        out[-1].append(verdict(batched <= TARGET_BATCHED, f"{batched / TARGET_BATCHED:.2f}x"))
    print(table(out, ["", "measured", ""]))


if __name__ == "__main__":
    main()
