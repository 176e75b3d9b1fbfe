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
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from support.ik_audit import COUNTS, run


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--arms", type=int, default=160, help="arms per family and kind")
    parser.add_argument("--targets", type=int, default=35, help="targets per arm")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--show", type=int, default=10, help="failures to print")
    args = parser.parse_args()
    t0 = time.perf_counter()
    counts, cases = run(args.arms, args.targets, args.seed, keep=args.show)
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
