"""The statuses of IK on random arms of every closed-form family, near-degenerate ones too.

Run with ``.venv/bin/python benchmarks/ik_degenerate.py`` (``--arms``, ``--targets``,
``--seed`` change the sample; the defaults make about 100,000 targets: run it at low
priority, ``nice -n 19``). The audit is ``tests/support/ik_audit.py``'s (its docstring says
what is counted): arms from each family's ``sample_arm``, generic, degenerate and
jittered (twists within 5e-10 rad of 0, ±π/2, π, lengths of 1e-10 m), targets by
forward kinematics of random configurations, a third with a joint within 1e-9 rad of
a fold. It prints, per family and target kind, the targets and every false answer
(a solution whose FK misses, "ok" without the generating configuration where the arm
is not singular there, "unreachable", "not_found", "out_of_limits"), then the first
failures with enough to reproduce them. No assertions.

``--tables N`` runs instead the audit of random 6R DH tables
(``tests/support/random_tables.py``: twists among 0, ±π/2, π and random, lengths 0 or
random; N arms without a coaxial pair, ``--targets`` FK poses each): per class of arm
(rank 5 everywhere, those arms perturbed by 1e-12..1e-3 split at σ6/σ1 = 1e-5, the
others) the answers of ``method="auto"`` by the numeric search, the FK misses, the
generating configurations missed, the continua answered ``singular`` and the false
statuses.

``--near N`` times instead the arms near rank 5 alone (N random tables, the rank-5 ones
perturbed twice each, ``--targets`` FK poses each): ``robot.ik`` one pose at a time
(ms/pose median, mean, max; the first pose of each arm, which builds its sweep's arms,
apart) and the same poses as one batch per arm (ms/pose).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from support.ik_audit import COUNTS, run
from support.random_tables import COUNTS as TABLE_COUNTS
from support.random_tables import run as run_tables


def tables(count: int, targets: int, seed: int, show: bool) -> None:
    """Print the random-table audit's counts per class of arm (with ``show``, its failures)."""
    t0 = time.perf_counter()
    counts = run_tables(count, targets, seed, show=show)
    print(f"{'arms':<12} " + " ".join(f"{c:>12}" for c in TABLE_COUNTS) + "  ms/pose")
    for key, c in sorted(counts.items()):
        per = 1e-3 * c["us"] / max(c["targets"], 1)
        print(f"{key:<12} " + " ".join(f"{c[k]:>12}" for k in TABLE_COUNTS) + f"  {per:7.2f}")
    print(f"{time.perf_counter() - t0:.0f} s")


def near(count: int, targets: int, seed: int) -> None:
    """Print the near-rank-5 path's time per pose, one at a time and batched."""
    from support.random_tables import arms, perturbed

    import kinematica as km
    from kinematica.ik.rank_five import rank_five

    rng = np.random.default_rng(seed + 1)
    first: list[float] = []
    single: list[float] = []
    batched: list[float] = []
    for rows, robot in arms(count, seed):
        five = rank_five(robot.chain)
        if five is None or not five.exact:
            continue
        for _ in range(2):
            moved = km.Robot.from_dh(perturbed(rows, rng), convention="standard")
            if rank_five(moved.chain) is None:
                continue
            T = moved.fk(rng.uniform(-np.pi, np.pi, (targets + 1, 6)))
            t0 = time.perf_counter()
            moved.ik(T[0])
            first.append(time.perf_counter() - t0)
            for t in T[1:]:
                t0 = time.perf_counter()
                moved.ik(t)
                single.append(time.perf_counter() - t0)
            t0 = time.perf_counter()
            moved.ik(T[1:])
            batched.append((time.perf_counter() - t0) / targets)
    for name, v in (("first pose", first), ("one pose", single), ("batched", batched)):
        ms = 1e3 * np.array(v)
        print(
            f"{name:<12} {len(ms):5d}  median {np.median(ms):7.2f}  mean {ms.mean():7.2f}  "
            f"max {ms.max():7.2f} ms/pose"
        )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--arms", type=int, default=160, help="arms per family and kind")
    parser.add_argument("--targets", type=int, default=None, help="targets per arm (35; 3)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--show", type=int, default=10, help="failures to print")
    parser.add_argument("--tables", type=int, default=0, help="random DH tables to audit")
    parser.add_argument("--near", type=int, default=0, help="random DH tables: near-rank-5 times")
    args = parser.parse_args()
    if args.near:
        near(args.near, args.targets or 5, args.seed)
        return
    if args.tables:
        tables(args.tables, args.targets or 3, args.seed, args.show > 0)
        return
    t0 = time.perf_counter()
    counts, cases = run(args.arms, args.targets or 35, args.seed, keep=args.show)
    names = COUNTS
    print(f"{'family':<24} {'kind':<9} " + " ".join(f"{c:>15}" for c in names))
    total = dict.fromkeys(names, 0)
    for (family, kind), c in counts.items():
        print(f"{family:<24} {kind:<9} " + " ".join(f"{c[k]:>15}" for k in names))
        for k in names:
            total[k] += c[k]
    print(f"{'all':<34} " + " ".join(f"{total[k]:>15}" for k in names))
    print(f"{time.perf_counter() - t0:.0f} s")
    np.set_printoptions(precision=17)
    for case in cases:
        print(f"\n{case.what}: {case.spec} {case.kind} ({case.note}): {case.status}:")
        print(f"  {case.message}")
        print(f"  q = {case.q.tolist()}")
        print(f"  convention = {case.arm.convention!r}, links = {case.arm.links!r}")
        print(f"  base = {np.asarray(case.arm.base).tolist()}")
        print(f"  tool = {np.asarray(case.arm.tool).tolist()}")


if __name__ == "__main__":
    main()
