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

Then, for the built-in 7R arms and the makers' GEN72, Gen3 and RM75 (``tests/data/makers``),
issue 33's budgets: ``fixed={6: v}`` (and ``fixed={0: v}``) with the pose's own new v on
every call (one pose at a time) against one pose of the 6R arm its lock leaves (the arm
locked at 0, its family's closed form, on the same poses moved: the 3x budget), and
``auto`` on random poses within the limits (per pose: each pose's shortest CPU time of 3 passes;
median, mean and max over the poses; and batched per pose, CPU time), with the share of
poses answered at the default value, at the nearest value of the sweep, and by the search
over every joint, and the share of the sweep's values the reach bounds prove out of
reach (``kinematica.ik.reach_bounds``: not screened), and the verdict of ``auto``'s budget
(:data:`BUDGET_AUTO_PUMAS` of PUMA 560's one pose, measured just before and after each arm's
``auto``, the lesser); the load average is printed beside them.

Columns: the method results name; µs per pose one pose at a time (median over
``--singles`` poses of each pose's shortest of 3 passes, wall time), and the same
given as ``options=`` (``robot.ik(T, options=IKOptions(...))``: the same path as the
keywords since issue 33, so the same cost), and
batched (one call on ``--poses`` poses, best of 3, CPU time of the process: the
machine may be shared); solutions per pose (mean); the share of poses
whose every solution our own FK puts within 1e-10 m and 1e-10 rad of the target
and holds the locked joint at its value exactly; the share with at least one.

``--bounds-poses N`` runs the reach bounds' check instead (:func:`bounds_pairs`): N poses
of the GEN72, Gen3, RM75 and 7 random 7R arms, every value of the sweep each, screened by
the elimination with the limits kept and without; no pair with a solution may be dropped.

When EAIK imports (``pip install eaik``), its joint-locked Panda (``HPRobot`` from the
Panda's axes, q7 locked by its ``fixed_axes``; its FK checked against ours) is timed on
the same poses, one pose at a time and batched on one thread. No assertions.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
import warnings
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import fmt_time, header, shortest_per_item, table, verdict

import kinematica as km
from kinematica.ik import IKBatchResult, IKOptions
from kinematica.ik.moved import end_arm, move_parts, moved_targets
from kinematica.ik.nearest_value import screen
from kinematica.ik.parameter import JointParameter
from kinematica.ik.reach_bounds import may_reach, reach_bounds
from kinematica.ik.redundancy import PARAMETER_SWEEP, choose
from kinematica.ik.request import IKRequest
from kinematica.ik.solve import solve_ik
from kinematica.ik.structure import features
from kinematica.ik.tolerance import Tolerance
from kinematica.spatial import rotation_angle

DATA = Path(__file__).resolve().parent.parent / "tests" / "data"
#: A solution is exact when our FK puts the tool this close to the target (m and rad).
TOL = 1e-10
#: The joints locked per arm (0-based): the first and the last, both cheap to lock.
LOCKS = (0, 6)
#: The value each locked joint is held at (rad), within every joint's limits.
VALUE = 0.3


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


def eaik_panda(robot: km.Robot) -> tuple[Any, np.ndarray] | str:
    """EAIK's Panda with q7 locked at VALUE and the rotation its tool leaves out, or why not.

    Built as the pose audit builds EAIK's models (``tests/support/ik_pose_audit.py``):
    ``eaik.IK_HP.HPRobot`` from the base-frame axes at q = 0 (the URDF's model holds
    the gripper's finger joints too: 9 joints, which EAIK does not take), q7 locked by
    its ``fixed_axes``. EAIK's tool has the base's orientation at q = 0, ours
    ``R0 = fk(0)``'s: a target R of ours is EAIK's ``R R0ᵀ``. Its FK is checked against
    ours at a random configuration.
    """
    try:
        from eaik.IK_HP import HPRobot
    except ImportError:
        return "EAIK is not importable (pip install eaik): its row is skipped"
    f = features(robot.chain)
    with warnings.catch_warnings():  # q = 0 is outside the Panda's q4 limits: FK still holds
        warnings.simplefilter("ignore", km.KinematicaWarning)
        M = robot.fk(np.zeros(robot.dof))
    points = np.vstack([np.zeros(3), f.points, M[:3, 3]])
    try:
        bot = HPRobot(f.directions.copy(), np.diff(points, axis=0), [(6, VALUE)])
    except Exception as exc:  # its API differs between releases: say why, go on
        return f"EAIK could not build the locked Panda ({exc}): skipped"
    R0 = M[:3, :3].copy()
    q = np.random.default_rng(0).uniform(robot.qlim[:, 0], robot.qlim[:, 1])
    q[6] = VALUE
    T = np.asarray(bot.fwdKin(q), dtype=float)
    T[:3, :3] = T[:3, :3] @ R0
    if np.abs(T - robot.fk(q)).max() > 1e-9:
        return "EAIK's locked Panda does not reproduce our FK: skipped"
    return bot, R0


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
            built = eaik_panda(robot)
            if isinstance(built, str):
                print(built)
            else:
                bot, R0 = built
                theirs = [t.copy() for t in one]
                for t in theirs:
                    t[:3, :3] = t[:3, :3] @ R0.T
                single = shortest_per_item(bot.IK, theirs)  # timed as ours are
                batch_list = [t.copy() for t in T]
                for t in batch_list:
                    t[:3, :3] = t[:3, :3] @ R0.T
                batched = cpu_best_of(lambda b=batch_list, e=bot: e.IK_batched(b, 1))
                batch = batched / len(batch_list)
                rows.append(
                    [f"EAIK locked q7 = {VALUE} (1 thread)", "eaik", fmt_time(single), "",
                     fmt_time(batch), "", "", ""]
                )  # fmt: skip
    head = ["call", "method", "single", "single (options=)", "batched", "sols/pose", "all exact",
            "found"]  # fmt: skip
    print(table(rows, head))


def per_pose(fn: Any, items: list[np.ndarray], passes: int = 3) -> np.ndarray:
    """Each item's shortest CPU time of this thread (s) over ``passes`` passes.

    CPU time, not wall time: on this shared machine a neighbour's burst preempts a call,
    which wall time would count (the budgets' ratios moved by 1.5x between runs so).
    """
    fn(items[0])
    best = np.full(len(items), np.inf)
    for _ in range(passes):
        for i, item in enumerate(items):
            t0 = time.thread_time()
            fn(item)
            best[i] = min(best[i], time.thread_time() - t0)
    return best


#: Issue 33's budget of ``auto`` on a 7R arm: 100 µs a pose on average over random poses,
#: on a machine where PUMA 560's one pose took 3.2 µs: so many PUMA poses, measured in the
#: same run (this machine's speed changes by a factor of 2-3 between runs).
BUDGET_AUTO_PUMAS = 100.0 / 3.2


def held_and_auto(robots: list[tuple[str, km.Robot]], poses: int, seed: int, puma: Any) -> None:
    """Issue 33's budgets: a last joint held at a new value per call, and ``auto``.

    ``puma()``: PUMA 560's one pose (s), the unit of ``auto``'s budget, measured again
    beside each arm's ``auto`` (the two timed alike, within a few seconds).
    """
    rows = []
    for name, robot in robots:
        chain = robot.chain
        rng = np.random.default_rng(seed)
        Q = rng.uniform(*robot.qlim.T, size=(poses, robot.dof))
        T = np.ascontiguousarray(robot.fk(Q))
        ends = []
        for k in (6, 0):  # the last joint, then the first
            values = Q[:, k].tolist()  # the pose's own: a new value on every call
            held = per_pose(
                lambda i, r=robot, T=T, v=values, k=k: r.ik(T[int(i)], fixed={k: v[int(i)]}),
                list(np.arange(poses)),
            )
            arm = end_arm(chain, k)
            moved = list(moved_targets(chain, k, T, Q[:, k]))
            six = per_pose(lambda t, a=arm: solve_ik(a, t, IKOptions()), moved)
            family = solve_ik(arm, moved[0], IKOptions()).method
            ratio = np.median(held) / np.median(six)
            ends += [family, fmt_time(float(np.median(six))),
                     f"{fmt_time(float(np.median(held)))} ({ratio:.1f}x)"]  # fmt: skip
        unit = puma()
        auto = per_pose(lambda t, r=robot: r.ik(t), list(T))
        unit = min(unit, puma())
        batch = cpu_best_of(lambda r=robot, T=T: r.ik(T, workers=1)) / poses
        res = robot.ik(T, workers=1)
        assert isinstance(res, IKBatchResult)
        notes = [" ".join(res[i].notes) for i in range(poses)]
        swept = np.mean(["the nearest of" in n for n in notes])
        searched = np.mean([res[i].parameter is None for i in range(poses)])
        dropped = bounds_drop(robot, T)
        rows.append(
            [
                name,
                *ends,
                f"{fmt_time(float(np.median(auto)))} / {fmt_time(float(auto.mean()))} / "
                f"{fmt_time(float(auto.max()))}",
                fmt_time(batch),
                f"{1 - swept - searched:.0%} / {swept:.0%} / {searched:.0%}",
                dropped,
                f"{auto.mean() / unit:.1f}: "
                + verdict(auto.mean() <= BUDGET_AUTO_PUMAS * unit),
            ]
        )  # fmt: skip
    head = ["arm", "q7 lock's family", "6R one pose", "fixed q7 new v (ratio)",
            "q1 lock's family", "6R one pose", "fixed q1 new v (ratio)",
            "auto median / mean / max", "auto batched", "default / swept / searched",
            "sweep values proved out",
            f"auto mean, PUMA poses: <= {BUDGET_AUTO_PUMAS:.1f}"]  # fmt: skip
    print(f"load average (1 min) {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    print(table(rows, head))


def bounds_drop(robot: km.Robot, T: np.ndarray) -> str:
    """The share of the sweep's values (per pose) the reach bounds prove out of reach."""
    joint = choose(robot.chain)
    if not isinstance(joint, JointParameter) or joint.index not in (0, robot.dof - 1):
        return "-"
    k = joint.index
    bounds = reach_bounds(end_arm(robot.chain, k))
    if bounds is None:
        return "-"
    grid = np.linspace(*joint.span(robot.chain), PARAMETER_SWEEP)
    move = move_parts(robot.chain, k)
    return f"{1 - may_reach(bounds, T, Tolerance(), grid, move).mean():.0%}"


def random_7r(seed: int) -> km.Robot:
    """A 7R arm of no maker: standard DH, lengths and twists drawn at random, no limits."""
    rng = np.random.default_rng(seed)
    rows = [km.Revolute(d=float(rng.uniform(-0.4, 0.4)), a=float(rng.uniform(-0.4, 0.4)),
                        alpha=float(rng.uniform(-np.pi, np.pi))) for _ in range(7)]  # fmt: skip
    return km.Robot.from_dh(rows, name=f"random 7R ({seed})", convention="standard")


def bounds_pairs(robots: list[tuple[str, km.Robot]], poses: int, seed: int) -> None:
    """The reach bounds against the elimination: no pair of pose and value with one dropped.

    For each arm whose ``auto`` holds an end joint: ``poses`` random configurations (within
    the limits), the :data:`PARAMETER_SWEEP` values of the held joint; each pair's target
    moved onto the arm locked at 0 and screened by its closed form alone
    (:func:`kinematica.ik.nearest_value.screen`, as the sweep tries a value), with the
    limits kept and without. Prints the pairs, those with a solution (all kept, asserted),
    and the share of those without that the bounds drop.
    """
    rows = []
    for name, robot in robots:
        joint = choose(robot.chain)
        if not isinstance(joint, JointParameter) or joint.index not in (0, robot.dof - 1):
            continue
        k = joint.index
        arm = end_arm(robot.chain, k)
        lo, hi = np.nan_to_num(joint.span(robot.chain), posinf=np.pi, neginf=-np.pi)
        grid = np.linspace(lo, hi, PARAMETER_SWEEP)
        qlo, qhi = np.nan_to_num(robot.qlim, posinf=np.pi, neginf=-np.pi).T
        Q = np.random.default_rng(seed).uniform(qlo, qhi, size=(poses, robot.dof))
        T = np.ascontiguousarray(robot.fk(Q))
        moved = moved_targets(robot.chain, k, np.repeat(T, grid.size, axis=0), np.tile(grid, poses))
        for limits in (True, False):
            bounds = reach_bounds(arm, limits)
            if bounds is None:
                continue
            kept = may_reach(bounds, T, Tolerance(), grid, move_parts(robot.chain, k), limits)
            request = IKRequest.parse(workers=1, respect_limits=limits)
            has = screen(arm, moved, request).reshape(kept.shape)  # type: ignore[arg-type]
            lost = int((has & ~kept).sum())
            assert not lost, f"{name}: {lost} pairs with a solution dropped"
            rows.append([name, "kept" if limits else "ignored", str(has.size), str(int(has.sum())),
                         f"{(~kept).sum() / max((~has).sum(), 1):.1%}"])  # fmt: skip
    print(table(rows, ["arm", "limits", "pairs", "with a solution (all kept)",
                       "without one: dropped"]))  # fmt: skip


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--poses", type=int, default=2000)
    parser.add_argument("--singles", type=int, default=200)
    parser.add_argument("--seed", type=int, default=7)
    parser.add_argument("--auto-poses", type=int, default=200)
    parser.add_argument(
        "--bounds-poses",
        type=int,
        default=0,
        help="poses per arm of the reach bounds' check (bounds_pairs; 0: none)",
    )
    args = parser.parse_args()
    makers = DATA / "makers"
    if args.bounds_poses:
        arms = [
            (n, km.load(str(makers / f"{n}.urdf")))
            for n in ("realman_gen72", "kinova_gen3", "realman_rm75")
        ]
        arms += [(f"random 7R ({s})", random_7r(s)) for s in range(7)]  # fmt: skip
        bounds_pairs(arms, args.bounds_poses, args.seed)
        return
    print(header("7R arms at a fixed joint (one core)"))
    for name in ("panda", "iiwa14"):
        run(name, args.poses, args.singles, args.seed)
    # the 6R one pose in the same run: what one pose of a 7R arm at a value is held to
    puma = km.load("puma560")
    rng = np.random.default_rng(args.seed)
    Tp = list(puma.fk(rng.uniform(*puma.qlim.T, size=(args.singles, 6))))
    single = shortest_per_item(lambda t: puma.ik(t), Tp)
    print(f"\nreference: PUMA 560 robot.ik(T), one pose (6R, spherical wrist): {fmt_time(single)}")
    print("\nq7 held at a new value each call; auto on random poses (one core)")
    robots = [(n, km.load(n)) for n in ("panda", "iiwa14")] + [
        (n, km.load(str(makers / f"{n}.urdf")))
        for n in ("realman_gen72", "kinova_gen3", "realman_rm75")
        if (makers / f"{n}.urdf").exists()
    ]
    one_pose = lambda: float(np.median(per_pose(lambda t: puma.ik(t), Tp)))  # noqa: E731
    held_and_auto(robots, args.auto_poses, args.seed, one_pose)


if __name__ == "__main__":
    main()
