"""7R arms held where the arm left is nearly a continuum: every solution, how fast, how exact.

Run with ``.venv/bin/python benchmarks/ik_held.py`` (``--poses``, ``--sweeps``, ``--seed``
change the sample). rtb-data's iiwa 14 URDF (its shoulder 0.44 mm off an SRS arm's) and
the Realman RM75 (micrometres off), q4 held (``robot.ik(T, fixed={3: v})``), on poses
made by forward kinematics from random configurations within the limits with q4 = v:

* ``iiwa URDF, q4 = 0.05`` (and ``-0.03``): the arm left has no closed form; the SRS
  neighbour's sweep answers (:mod:`kinematica.ik.held_neighbour`);
* ``iiwa URDF, q4 = 0``: axes 3 and 5 parallel 0.44 mm apart; the coaxial neighbour's
  sweep (:mod:`kinematica.ik.held_coaxial`);
* ``iiwa URDF, q4 new per pose in [-0.1, 0.1]``: each pose's held arm is new, so its
  time includes the registry's look for a closed form of that arm (built once per arm);
* ``RM75, q4 = -1.0`` and ``RM75, q4 = 0``: the same two sweeps on the RM75.

Columns: the methods the answers name (share of poses); ms per pose, one pose at a time
(median over the poses of each pose's shortest of 3 passes, wall time; the held arms are
built by the first pass); solutions per pose (mean); the share of poses whose every row
our own FK puts within 1e-10 m and rad of the target with q4 at v; the share whose
generating configuration is among the rows (every joint within 1e-6 rad; 1e-5 on the
iiwa URDF at q4 = 0, σ6/σ1 2e-11 there; 2e-3 on the RM75 at q4 = 0, whose solutions move
by 1e-4..1e-3 rad along its circles for a change of the pose at round-off); the share
answered by the numeric search.

In the same run, on the first ``--sweeps`` poses of each case, for reference: the
numeric search on the held arm (``method="numeric"``: one solution) and the sweep over
a joint of the real arm that answered before (:func:`kinematica.ik.held_sweep.held_sweep`,
every value a closed form of an arm built for it), with our time's ratio to each.
No assertions.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
import warnings
from collections import Counter
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import fmt_time, header, shortest_per_item, table

import kinematica as km
from kinematica.ik import IKOptions
from kinematica.ik.held_sweep import held_sweep
from kinematica.ik.parameter import JointParameter

DATA = Path(__file__).resolve().parent.parent / "tests" / "data"
#: A row is exact when our FK puts the tool this close to the target (m and rad).
TOL = 1e-10


def wrapped(d: np.ndarray) -> np.ndarray:
    return np.abs(np.remainder(d + math.pi, 2.0 * math.pi) - math.pi)


def cases(seed: int, poses: int) -> list[tuple[str, km.Robot, np.ndarray, float]]:
    """``(label, robot, configurations (poses, 7), generating tolerance)``."""
    iiwa = km.load(str(DATA / "urdf" / "kuka_lbr_iiwa_14_r820.urdf"))
    rm75 = km.load(str(DATA / "makers" / "realman_rm75.urdf"))
    out = []
    for label, robot, v, near in (
        ("iiwa URDF, q4 = 0.05", iiwa, 0.05, 1e-6),
        ("iiwa URDF, q4 = -0.03", iiwa, -0.03, 1e-6),
        ("iiwa URDF, q4 = 0", iiwa, 0.0, 1e-5),
        ("iiwa URDF, q4 new per pose", iiwa, math.nan, 1e-6),
        ("RM75, q4 = -1.0", rm75, -1.0, 1e-6),
        ("RM75, q4 = 0", rm75, 0.0, 2e-3),
    ):
        rng = np.random.default_rng(seed)
        Q = rng.uniform(robot.qlim[:, 0], robot.qlim[:, 1], (poses, 7))
        Q[:, 3] = rng.uniform(-0.1, 0.1, poses) if math.isnan(v) else v
        out.append((label, robot, Q, near))
    return out


def old_sweep(robot: km.Robot, T: np.ndarray, v: float) -> object:
    """The sweep over a joint of the real arm (the answer before the neighbours')."""
    chain = robot.chain

    def hold(s: int, target: np.ndarray, values: object, o: IKOptions) -> object:
        return JointParameter(s, f"q{s + 1}").solve(chain, target, values, o)  # type: ignore[arg-type]

    opts = IKOptions(respect_limits=False)
    return held_sweep(chain, 3, v, T, opts, hold)  # type: ignore[arg-type]


def run(poses: int, sweeps: int, seed: int) -> None:
    rows = []
    for label, robot, Q, near in cases(seed, poses):
        T = robot.fk(Q)
        held = [{3: float(q[3])} for q in Q]
        items = list(range(poses))
        ours = shortest_per_item(
            lambda i, r=robot, T=T, h=held: r.ik(T[int(i)], fixed=h[int(i)], respect_limits=False),
            items,  # type: ignore[arg-type]
        )
        methods: Counter[str] = Counter()
        count, exact, found, numeric = 0, 0, 0, 0
        for i in range(poses):
            res = robot.ik(T[i], fixed=held[i], respect_limits=False)
            methods[res.method] += 1
            R = np.concatenate([res.solutions, res.out_of_limits])
            count += len(R)
            numeric += res.method.startswith("numeric")
            if not len(R):
                continue
            F = robot.fk(R)
            pos = np.linalg.norm(F[:, :3, 3] - T[i, :3, 3], axis=1)
            rot = np.array([km.rotation_angle(f[:3, :3], T[i, :3, :3]) for f in F])
            exact += bool(np.all((pos <= TOL) & (rot <= TOL) & (R[:, 3] == Q[i, 3])))
            found += bool(wrapped(R - Q[i]).max(axis=1).min() <= near)
        said = ", ".join(f"{m} {k / poses:.0%}" for m, k in methods.most_common())
        some = list(range(min(sweeps, poses)))
        search = shortest_per_item(
            lambda i, r=robot, T=T, h=held: r.ik(T[int(i)], fixed=h[int(i)], method="numeric",
                                                 respect_limits=False),
            some,  # type: ignore[arg-type]
            passes=1,
        )  # fmt: skip
        t0 = time.perf_counter()
        for i in some:
            old_sweep(robot, T[i], float(Q[i, 3]))
        before = (time.perf_counter() - t0) / len(some)
        rows.append(
            [
                label,
                said,
                fmt_time(ours),
                f"{count / poses:.2f}",
                f"{exact / poses:.0%}",
                f"{found / poses:.0%}",
                f"{numeric / poses:.0%}",
                f"{fmt_time(search)} ({search / ours:.2f}x)",
                f"{fmt_time(before)} ({before / ours:.0f}x)",
            ]
        )
    head = ["case", "method", "per pose", "sols/pose", "all exact", "gen found", "numeric",
            "search (ratio)", "joint sweep (ratio)"]  # fmt: skip
    print(table(rows, head))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--poses", type=int, default=40)
    parser.add_argument("--sweeps", type=int, default=4)
    parser.add_argument("--seed", type=int, default=7)
    args = parser.parse_args()
    print(header("7R arms held nearly a continuum (one core)"))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", km.KinematicaWarning)
        run(args.poses, args.sweeps, args.seed)


if __name__ == "__main__":
    main()
