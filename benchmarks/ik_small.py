"""Closed-form IK of the small arms (planar, SCARA, 3R elbow arms): speed, exactness, vs EAIK.

Run with ``make bench`` (or ``.venv/bin/python benchmarks/ik_small.py``;
``--poses``, ``--singles``, ``--seed`` change the sample). On the built-in
planar PR, planar 3R, planar PRR, SCARA, anthropomorphic 3R and RRR arms and a
planar 2R arm, for pose targets and position targets (forward kinematics of
configurations uniform within the joint limits, seeded), one thread
(``workers=1``), it prints:

* ``robot.ik`` (solver, check by FK, dedupe, limits): one target per call
  (a loop of ``--singles`` calls) and batched (one call on all ``--poses``
  targets), CPU time per target, best of 3; the solver alone (the core's raw
  candidates of one target, ``params.candidates``; it has no batched entry)
  the same way;
* the statuses, and the share of targets whose every solution our FK puts
  within 1e-10 m / 1e-10 rad and among whose solutions is the configuration
  that made the target (modulo 2π; for a continuum, ``singular``, the joints
  that are not free);
* baselines measured in the same run: ``robot.fk`` of one configuration, and
  EAIK's ``IK`` / ``IK_batched`` (one thread) on the same poses where EAIK has
  the arm (its 3R arms, standard DH, all revolute), judged by our FK.

The development machine is shared: figures are CPU time (``time.process_time``,
best of 3), which other processes disturb less than wall time. No assertions.
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import fmt_time, header, table

import kinematica as km
from kinematica.ik import IKBatchResult, closed_form
from kinematica.robot import Robot
from kinematica.spatial import inv_transform, rotation_angle, wrap_angle

#: A solution is exact when our FK puts the tool this close to the target (m and rad).
TOL = 1e-10
#: The configuration that made a target is among its solutions when one is this close.
MATCH_TOL = 1e-7
#: Targets of the brief, per target on one core: one call, batched.
TARGET_SINGLE, TARGET_BATCHED = 15e-6, 3e-6


def arms() -> list[Robot]:
    two_r = km.Robot.from_dh(
        [km.Revolute(a=0.5), km.Revolute(a=0.4)], name="planar 2R", convention="standard"
    )
    names = ("planar-pr", "planar-3r", "planar-prr", "scara", "anthropomorphic-3r", "rrr-geometric")
    return [two_r, *(km.load(name) for name in names)]


def cpu_per_call(fn: Callable[[np.ndarray], object], targets: np.ndarray) -> float:
    """CPU seconds per call of ``fn(t)``, one call per target (best of 3 loops)."""
    fn(targets[0])
    best = float("inf")
    for _ in range(3):
        t0 = time.process_time()
        for t in targets:
            fn(t)
        best = min(best, time.process_time() - t0)
    return best / len(targets)


def cpu_batch(fn: Callable[[], object], n: int) -> float:
    """CPU seconds per target of one batch call ``fn()`` on ``n`` targets (best of 3)."""
    fn()
    best = float("inf")
    for _ in range(3):
        t0 = time.process_time()
        fn()
        best = min(best, time.process_time() - t0)
    return best / n


def judge(robot: Robot, res: IKBatchResult, targets: np.ndarray, q: np.ndarray) -> list[str]:
    """Statuses, share of targets with every solution exact, share with ``q`` among them."""
    n = robot.dof
    sols = res.solutions
    real = np.isfinite(sols).all(axis=-1)
    T = robot.fk(np.where(real[..., None], sols, 0.0).reshape(-1, n)).reshape(*sols.shape[:2], 4, 4)
    want = targets if targets.shape[-1] == 4 else None
    pos = np.linalg.norm(
        T[..., :3, 3] - (targets[:, None, :3, 3] if want is not None else targets[:, None]), axis=-1
    )
    rot = (
        rotation_angle(
            T[..., :3, :3], np.broadcast_to(targets[:, None, :3, :3], T[..., :3, :3].shape)
        )
        if want is not None
        else 0 * pos
    )
    exact = (~real | ((pos <= TOL) & (rot <= TOL))).all(axis=1)
    d = sols - q[:, None]
    d[..., ~robot.is_prismatic] = wrap_angle(d[..., ~robot.is_prismatic])
    d = np.where(res.free[:, None, :], 0.0, np.abs(d))  # free joints: representatives
    found = (np.nan_to_num(d, nan=np.inf).max(axis=-1) < MATCH_TOL).any(axis=1)
    names, counts = np.unique(res.status, return_counts=True)
    statuses = ", ".join(f"{k} {v:,}" for k, v in zip(names, counts, strict=True))
    return [statuses, f"{100 * exact.mean():.2f} %", f"{100 * found.mean():.2f} %"]


def eaik_rows(robot: Robot, T: np.ndarray, q: np.ndarray, singles: int) -> list[str] | None:
    """EAIK's times and exactness on poses ``T`` of a standard-DH revolute arm, or None."""
    try:
        from eaik.IK_DH import DhRobot
    except ImportError:
        return None
    if robot.convention != "standard" or robot.is_prismatic.any():
        return None
    L = robot.links
    model: Any = DhRobot(
        np.array([j.alpha for j in L]), np.array([j.a for j in L]), np.array([j.d for j in L])
    )
    if not model.hasKnownDecomposition():
        return None
    offsets = np.array([j.offset for j in L])
    Te = inv_transform(robot.base) @ T @ inv_transform(robot.tool)
    poses = list(Te)
    single = cpu_per_call(model.IK, Te[:singles])
    batched = cpu_batch(lambda: model.IK_batched(poses, 1), len(poses))
    sols = model.IK_batched(poses, 1)
    exact = found = 0
    for i, s in enumerate(sols):
        qs = wrap_angle(np.asarray(s.Q).reshape(-1, robot.dof) - offsets)
        if len(qs) == 0:
            continue
        F = robot.fk(qs)
        ok = (np.linalg.norm(F[:, :3, 3] - T[i, :3, 3], axis=-1) <= TOL) & (
            rotation_angle(F[:, :3, :3], np.broadcast_to(T[i, :3, :3], F[:, :3, :3].shape)) <= TOL
        )
        exact += bool(ok.all())
        found += bool((np.abs(wrap_angle(qs[ok] - q[i])).max(axis=-1, initial=0) < MATCH_TOL).any())
    n = len(poses)
    return [
        fmt_time(single),
        fmt_time(batched),
        f"{100 * exact / n:.2f} %",
        f"{100 * found / n:.2f} %",
    ]


def bench_targets(
    robot: Robot, kind: str, targets: np.ndarray, singles: int
) -> tuple[float, float, float] | None:
    """Seconds per target: robot.ik single and batched, the solver alone single."""
    closed = closed_form(robot.chain, kind)  # type: ignore[arg-type]
    if closed is None:
        return None
    poses = np.ascontiguousarray(targets if kind == "pose" else _as_poses(targets))
    core = robot.chain.core
    solver_single = cpu_per_call(lambda t: closed.params.candidates(core, t), poses[:singles])
    ik_single = cpu_per_call(robot.ik, targets[:singles])
    ik_batched = cpu_batch(lambda: robot.ik(targets, workers=1), len(targets))
    return ik_single, ik_batched, solver_single


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--poses", type=int, default=20_000, help="targets per arm (20,000)")
    parser.add_argument("--singles", type=int, default=2_000, help="targets timed one by one")
    parser.add_argument("--seed", type=int, default=0, help="seed of the targets (0)")
    args = parser.parse_args()
    print(header("kinematica IK benchmark: planar arms, SCARA, 3R elbow arms (one thread)"))
    rows: list[list[str]] = []
    judged: list[list[str]] = []
    eaik: list[list[str]] = []
    for robot in arms():
        lo, hi = np.nan_to_num(robot.qlim, posinf=1.0, neginf=-1.0).T
        q = np.random.default_rng(args.seed).uniform(lo, hi, (args.poses, robot.dof))
        T = robot.fk(q)
        fk_one = cpu_per_call(robot.fk, q[: args.singles])
        for kind in ("pose", "position"):
            targets = T if kind == "pose" else np.ascontiguousarray(T[:, :3, 3])
            times = bench_targets(robot, kind, targets, args.singles)
            if times is None:
                continue
            label = f"{robot.name} ({kind})"
            rows.append([label, *(fmt_time(t) for t in times), fmt_time(fk_one)])
            res = robot.ik(targets, workers=1)
            assert isinstance(res, IKBatchResult)
            judged.append([label, *judge(robot, res, targets, q)])
            if kind == "pose":
                e = eaik_rows(robot, T, q, args.singles)
                if e is not None:
                    eaik.append([robot.name, fmt_time(times[0]), fmt_time(times[1]), *e])
    print(
        f"\n  CPU time per target, one thread; robot.ik = solver + check + dedupe + limits "
        f"(targets: single <= {fmt_time(TARGET_SINGLE)}, batched <= {fmt_time(TARGET_BATCHED)})"
    )
    head = ["", "robot.ik single", "batched", "solver alone, single", "fk one call"]
    print(table(rows, head))
    print(
        f"\n  {args.poses:,} targets per row: statuses; every solution exact; its q found (a "
        "continuum's free joints aside:\n  the others then follow the representative, unless the "
        "free joint moves nothing else, as the SCARA's q4)"
    )
    print(table(judged, ["", "statuses", "all exact", "q found"]))
    if eaik:
        print("\n  EAIK on the same poses (IK / IK_batched, one thread), judged by our FK")
        head = ["", "robot.ik single", "batched", "EAIK single", "batched", "all exact", "q found"]
        print(table(eaik, head))
    else:
        print("\n  EAIK is not importable (pip install eaik): its rows are skipped.")


def _as_poses(positions: np.ndarray) -> np.ndarray:
    T = np.broadcast_to(np.eye(4), (len(positions), 4, 4)).copy()
    T[:, :3, 3] = positions
    return T


if __name__ == "__main__":
    main()
