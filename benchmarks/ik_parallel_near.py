"""Near-degenerate UR-type arms near their aligned wrist: completeness, and the price of it.

Run with ``nice -n 19 .venv/bin/python benchmarks/ik_parallel_near.py`` (``--arms``,
``--poses``, ``--seed``, ``--timing-only``). Issue 32 item 4(b): a three-parallel 6R
whose axes 2 and 3 are parallel only within the line geometry's tolerance (α2 moved by
5e-10 rad) loses solutions near its aligned wrist when the family's closed form (on the
exact arm beside it) is repaired alone. ``solvers/near_6r.hpp`` adds the general 6R's
candidates where the family's lie within ``watch`` = WATCH_FACTOR √(slack / size) of its
singular sets.

Part 1, completeness: the near UR5 and random arms of the family (axes 5 and 6 meeting
and apart, ±90° twists so that the wrist aligns), 16 poses each made by FK with q5
10^U(-12, -2) rad from aligned. Per setting of ``watch`` in units of √(slack / size)
(0: the general 6R only where the family says near or singular or finds nothing; 1;
10; WATCH_FACTOR, the default; ∞: at every target, as before this trigger) it counts
the poses whose generating configuration is missing (to the conditioning's allowance,
``support.ik_search.found_tolerance``), the poses where a 200-start search finds a
solution we miss (``support.ik_pose_audit.check_complete``), and the poses at which
the general 6R ran: WATCH_FACTOR must lie where the counts have reached ∞'s.

Part 2, speed (one core; ``--timing-only``, run by ``make bench``): µs per pose of the
UR5 URDFs (example-robot-data's and ssik's catalogue's, near-degenerate to 3e-11 m),
one pose at a time and batched, with the default watch and with ∞, beside the exact
built-in UR5 (the last column: batched, over the exact UR5's).
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import sys
import time
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from support.ik_pose_audit import check_complete
from support.ik_search import dls_solutions, found_tolerance, joint_distance
from support.parallel_arms import UR5_ROWS, random_arm

import kinematica as km
from kinematica import _core, _core_testing
from kinematica.ik import closed_form
from kinematica.ik.structure import features

ROOT = Path(__file__).resolve().parents[1]
PI = math.pi
ALPHA2 = 5e-10
URDFS = (
    ROOT / "tests/data/urdf/ur5_robot.urdf",
    ROOT / "tests/data/makers/universal_robots_ur5.urdf",
)


def tilted(robot: km.Robot) -> km.Robot:
    links = list(robot.links)
    links[1] = dataclasses.replace(links[1], alpha=links[1].alpha + ALPHA2)
    return km.Robot.from_dh(links, convention=robot.convention, base=robot.base, tool=robot.tool)


def aligned_q5(robot: km.Robot) -> float:
    P = _core_testing.parallel.values(robot.chain.core)  # the built arm's values
    q5 = math.atan2(P["E1"], P["D1"])
    return q5 if abs(math.hypot(P["D1"], P["E1"]) + P["F1"] - 1.0) < 1e-9 else q5 + PI


def completeness(arms: int, poses: int, seed: int) -> None:
    rng = np.random.default_rng(seed)
    robots = [tilted(km.Robot.from_dh(UR5_ROWS, convention="standard"))]
    while len(robots) < arms:
        robots.append(tilted(random_arm(rng, ("meet", "apart")[len(robots) % 2], square=True)))
    # watch in units of sqrt(slack / size): 0 (the general 6R only where the family says
    # near or singular or finds nothing), then 1, 10, WATCH_FACTOR (the default), inf
    factor = _core_testing.general6r.WATCH_FACTOR
    settings = {"0": 0.0, "1": 1.0, "10": 10.0, f"{factor:g}": factor, "inf": math.inf}
    counts = {k: [0, 0, 0] for k in settings}  # q missing, search's missed, general ran
    total = 0
    t0 = time.perf_counter()
    for robot in robots:
        f = features(robot.chain)
        closed = closed_form(robot.chain, "pose")
        assert isinstance(closed.params, _core.general6r.NearParallelParams)  # type: ignore[union-attr]
        default = closed.params.watch
        root = math.sqrt(f.slack / f.size)
        assert default == factor * root
        q = rng.uniform(-PI, PI, (poses, 6))
        off = rng.choice([-1.0, 1.0], poses) * 10 ** rng.uniform(-12, -2, poses)
        q[:, 4] = aligned_q5(robot) + off
        T = robot.fk(q)
        for i in range(poses):
            total += 1
            ref = dls_solutions(robot, T[i], rng)
            for name, watch in settings.items():
                _core_testing.general6r.set_watch(closed.params, watch * root)
                res = robot.ik(T[i], respect_limits=False)
                raw = closed.params.candidates(robot.chain.core, T[i])[0]
                near = joint_distance(robot, res.solutions, q[i]).min(initial=math.inf)
                c = counts[name]
                c[0] += float(near) > found_tolerance(robot, q[i])
                c[1] += bool(check_complete(robot, res.solutions, ref, f.size)[0])
                c[2] += bool(np.isfinite(raw[8:, 0]).any())
            _core_testing.general6r.set_watch(closed.params, default)
    print(
        f"{len(robots)} arms, {total} poses, q5 10^U(-12, -2) rad from aligned "
        f"({time.perf_counter() - t0:.0f} s)"
    )
    head = ("watch / sqrt(slack/size)", "q missing", "search missed", "general ran")
    print(f"{head[0]:<26} {head[1]:>10} {head[2]:>14} {head[3]:>12}")
    for name, (a, b, c) in counts.items():
        print(f"{name:<26} {a:>10} {b:>14} {c:>12}")


def per_pose(robot: km.Robot, T: np.ndarray, repeat: int = 3) -> tuple[float, float]:
    """µs per pose, one at a time and batched (best of ``repeat``)."""
    n = len(T)
    one = batch = math.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        for i in range(n):
            robot.ik(T[i], respect_limits=False)
        one = min(one, (time.perf_counter() - t0) / n * 1e6)
        t0 = time.perf_counter()
        robot.ik(T, respect_limits=False, workers=1)
        batch = min(batch, (time.perf_counter() - t0) / n * 1e6)
    return one, batch


def speed(poses: int, seed: int) -> None:
    rng = np.random.default_rng(seed)
    print(f"\n{'arm':<40} {'slack (m)':>10} {'one (us)':>9} {'batch (us)':>10} {'x exact':>8}")
    exact = km.load("ur5")
    T = exact.fk(rng.uniform(-PI, PI, (poses, 6)))
    one, base = per_pose(exact, T)
    print(f"{'UR5 (built in, exact)':<40} {0.0:>10.2g} {one:>9.1f} {base:>10.1f} {1.0:>8.2f}")
    for path in URDFS:
        robot = km.load(path)
        f = features(robot.chain)
        closed = closed_form(robot.chain, "pose")
        T = robot.fk(rng.uniform(-PI, PI, (poses, 6)))
        cases = [("", None)]
        if hasattr(closed.params, "watch"):  # the general 6R at every target, as before
            cases.append((", general 6R always", math.inf))
        for label, watch in cases:
            if watch is not None:
                _core_testing.general6r.set_watch(closed.params, watch)
            one, batch = per_pose(robot, T)
            name = f"{path.stem}{label}"
            ratio = batch / base
            print(f"{name:<40} {f.slack:>10.2g} {one:>9.1f} {batch:>10.1f} {ratio:>8.2f}")
        if hasattr(closed.params, "watch"):
            _core_testing.general6r.set_watch(
                closed.params, _core_testing.general6r.WATCH_FACTOR * math.sqrt(f.slack / f.size)
            )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--arms", type=int, default=40)
    parser.add_argument("--poses", type=int, default=16, help="poses per arm")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--timing-only", action="store_true")
    args = parser.parse_args()
    warnings.simplefilter("ignore", km.KinematicaWarning)
    if not args.timing_only:
        completeness(args.arms, args.poses, args.seed)
    speed(2000, args.seed)


if __name__ == "__main__":
    main()
