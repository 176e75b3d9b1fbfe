"""7-joint arms at a fixed joint: every solution per pose, and how long it takes.

Run with ``.venv/bin/python benchmarks/ik_redundant.py`` (``--poses``,
``--singles``, ``--seed`` change the sample). For the built-in Franka Panda and
KUKA iiwa14 it draws random configurations within the joint limits, sets the
locked joint to one value (so every pose is reachable with it there), and
prints, on one core (``workers=1``), for each way of solving:

* ``fixed qK``: ``robot.ik(T, fixed={K-1: v})``, the locked arm solved by
  whatever the registry gives it (closed form: ``analytic:...``; else the
  numeric search on the 6 joints left);
* ``auto``: ``robot.ik(T)``, which holds a joint chosen for a closed form (or
  searches every joint when no lock has one), for the same poses;
* ``numeric (7 joints)``: ``robot.ik(T, method="numeric")``, one answer a pose.

Columns: the method results name; µs per pose one pose at a time (median over
``--singles`` poses of each pose's shortest of 3 passes, wall time) and batched
(one call on ``--poses`` poses, best of 3, CPU time of the process: the machine
may be shared); solutions per pose (mean); the share of poses
whose every solution our own FK puts within 1e-10 m and 1e-10 rad of the target
and holds the locked joint at its value exactly; the share with at least one.

When EAIK imports (``pip install eaik``), its joint-locked Panda (the URDF of
``tests/data/urdf``, q7 locked) is timed on the same poses. No assertions.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import fmt_time, header, shortest_per_item, table

import kinematica as km
from kinematica.ik import IKBatchResult
from kinematica.ik.redundancy import choose
from kinematica.spatial import rotation_angle

#: A solution is exact when our FK puts the tool this close to the target (m and rad).
TOL = 1e-10
#: The joints locked per arm (0-based): the first and the last, both cheap to lock.
LOCKS = (0, 6)
#: The value each locked joint is held at (rad), within every joint's limits.
VALUE = 0.3
PANDA_URDF = Path(__file__).resolve().parents[1] / "tests" / "data" / "urdf" / "franka_panda.urdf"


def judge(
    robot: km.Robot, res: IKBatchResult, targets: np.ndarray, k: int | None
) -> tuple[float, float, float]:
    """(mean solutions, share all exact (and q_k = VALUE), share with one or more)."""
    sols = res.solutions
    count = res.count.astype(int)
    exact = np.ones(len(targets), dtype=bool)
    for i in range(len(targets)):
        Q = sols[i, : count[i]]
        if not len(Q):
            continue
        T = robot.fk(Q)
        pos = np.linalg.norm(T[:, :3, 3] - targets[i, :3, 3], axis=1)
        rot = rotation_angle(T[:, :3, :3], np.broadcast_to(targets[i, :3, :3], T[:, :3, :3].shape))
        ok = (pos <= TOL) & (rot <= TOL)
        if k is not None:
            ok &= Q[:, k] == VALUE
        exact[i] = bool(ok.all())
    return float(count.mean()), float(exact.mean()), float((count > 0).mean())


def cpu_best_of(fn: Any, repeats: int = 3) -> float:
    """Shortest CPU time (s) of this process over ``repeats`` calls: a shared machine's
    other jobs do not count (one worker thread: CPU time is its time)."""
    times = []
    for _ in range(repeats):
        t0 = time.process_time()
        fn()
        times.append(time.process_time() - t0)
    return min(times)


def eaik_panda() -> Any:
    """EAIK's Panda with q7 locked at VALUE, or why there is none (a string)."""
    try:
        from eaik.IK_URDF import UrdfRobot
    except ImportError:
        return "EAIK is not importable (pip install eaik): its row is skipped"
    try:
        return UrdfRobot(str(PANDA_URDF), [(6, VALUE)])
    except Exception as exc:  # its API differs between releases: say why, go on
        return f"EAIK could not build the locked Panda ({exc}): skipped"


def run(name: str, poses: int, singles: int, seed: int) -> None:
    robot = km.load(name)
    rng = np.random.default_rng(seed)
    Q = rng.uniform(*robot.qlim.T, size=(poses, robot.dof))
    auto = choose(robot.chain)
    print(f"\n{robot.name}: auto holds {'nothing' if auto is None else auto.name}")
    rows = []
    for k in LOCKS:
        Qk = Q.copy()
        Qk[:, k] = VALUE
        T = robot.fk(Qk)
        one = list(T[:singles])
        cases: list[tuple[str, dict[str, Any], int | None]] = [
            (f"fixed q{k + 1} = {VALUE}", {"fixed": {k: VALUE}}, k),
        ]
        if k == LOCKS[0]:
            cases += [("auto", {}, None), ("numeric (7 joints)", {"method": "numeric"}, None)]
        for label, kwargs, held in cases:
            single = shortest_per_item(lambda t, kw=kwargs: robot.ik(t, **kw), one)
            batch = cpu_best_of(lambda kw=kwargs, T=T: robot.ik(T, workers=1, **kw)) / poses
            res = robot.ik(T, workers=1, **kwargs)
            assert isinstance(res, IKBatchResult)
            mean, exact, found = judge(robot, res, T, held)
            rows.append(
                [
                    f"{label} (poses made with q{k + 1} = {VALUE})",
                    res.method,
                    fmt_time(single),
                    fmt_time(batch),
                    f"{mean:.2f}",
                    f"{exact:.0%}",
                    f"{found:.0%}",
                ]
            )
        if name == "panda" and k == 6:
            bot = eaik_panda()
            if isinstance(bot, str):
                print(bot)
            else:
                t0 = time.perf_counter()
                for t in one:
                    bot.IK(t)
                single = (time.perf_counter() - t0) / len(one)
                rows.append([f"EAIK locked q7 = {VALUE}", "eaik", fmt_time(single), "", "", "", ""])
    head = ["call", "method", "single", "batched", "sols/pose", "all exact", "found"]
    print(table(rows, head))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--poses", type=int, default=2000)
    parser.add_argument("--singles", type=int, default=200)
    parser.add_argument("--seed", type=int, default=7)
    args = parser.parse_args()
    print(header("7R arms at a fixed joint (one core)"))
    for name in ("panda", "iiwa14"):
        run(name, args.poses, args.singles, args.seed)


if __name__ == "__main__":
    main()
