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
* ``auto (poses at its value)``: ``robot.ik(T)`` on poses that have a solution
  at the value ``auto`` holds (the Panda: q7 made at it; the iiwa: poses with a
  solution at arm angle 0), so no pose falls back to the numeric search;
* ``numeric (7 joints)``: ``robot.ik(T, method="numeric")``, one answer a pose;

and, for reference, one pose of the PUMA 560 (a 6R arm, every default) in the same run.

Columns: the method results name; µs per pose one pose at a time (median over
``--singles`` poses of each pose's shortest of 3 passes, wall time), and the same
through the general path (``robot.ik(T, options=IKOptions(...))``: what one pose
cost before it went straight to the core, :mod:`kinematica.ik.direct`), and
batched (one call on ``--poses`` poses, best of 3, CPU time of the process: the
machine may be shared); solutions per pose (mean); the share of poses
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
from kinematica.ik import IKBatchResult, IKOptions
from kinematica.ik.parameter import JointParameter
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


def at_auto_value(robot: km.Robot, Q: np.ndarray) -> np.ndarray:
    """``(N, 4, 4)`` poses with a solution at the value ``auto`` holds (no fallback)."""
    auto = choose(robot.chain, robot.joint_names)
    if isinstance(auto, JointParameter):
        Q = Q.copy()
        Q[:, auto.index] = auto.default(robot.chain)
        return np.ascontiguousarray(robot.fk(Q))
    T = np.ascontiguousarray(robot.fk(Q))
    res = robot.ik(T, arm_angle=0.0 if auto is None else auto.default(robot.chain), workers=1)
    return np.ascontiguousarray(T[np.asarray(res.count) > 0])


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
        made = f"poses made with q{k + 1} = {VALUE}"
        cases: list[tuple[str, dict[str, Any], int | None, np.ndarray]] = [
            (f"fixed q{k + 1} = {VALUE} ({made})", {"fixed": {k: VALUE}}, k, robot.fk(Qk)),
        ]
        if k == LOCKS[0]:
            cases += [
                (f"auto ({made})", {}, None, robot.fk(Qk)),
                ("auto (poses at its value)", {}, None, at_auto_value(robot, Q)),
                (f"numeric (7 joints) ({made})", {"method": "numeric"}, None, robot.fk(Qk)),
            ]
        for label, kwargs, held, T in cases:
            one = list(T[:singles])
            single = shortest_per_item(lambda t, kw=kwargs: robot.ik(t, **kw), one)
            general = IKOptions(**kwargs)
            slow = shortest_per_item(lambda t, o=general: robot.ik(t, options=o), one)
            batch = cpu_best_of(lambda kw=kwargs, T=T: robot.ik(T, workers=1, **kw)) / len(T)
            res = robot.ik(T, workers=1, **kwargs)
            assert isinstance(res, IKBatchResult)
            mean, exact, found = judge(robot, res, T, held)
            rows.append(
                [
                    label,
                    res.method,
                    fmt_time(single),
                    fmt_time(slow),
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
                rows.append(
                    [f"EAIK locked q7 = {VALUE}", "eaik", fmt_time(single), "", "", "", "", ""]
                )
    head = ["call", "method", "single", "single (general)", "batched", "sols/pose", "all exact",
            "found"]  # fmt: skip
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
    # the 6R one pose in the same run: what one pose of a 7R arm at a value is held to
    puma = km.load("puma560")
    rng = np.random.default_rng(args.seed)
    Tp = list(puma.fk(rng.uniform(*puma.qlim.T, size=(args.singles, 6))))
    single = shortest_per_item(lambda t: puma.ik(t), Tp)
    print(f"\nreference: PUMA 560 robot.ik(T), one pose (6R, spherical wrist): {fmt_time(single)}")


if __name__ == "__main__":
    main()
