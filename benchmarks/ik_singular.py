"""IK statuses at targets within round-off of a singular set: every family, 200,000 targets.

Run with ``nice -n 19 .venv/bin/python benchmarks/ik_singular.py`` (``--arms``,
``--targets``, ``--seed`` change the sample; the defaults make 201,600 targets, about
two minutes). The audit is ``tests/support/ik_singular_audit.py``'s (its docstring says
what is counted): UR-type, spherical-wrist and SRS arms, random and named, each
configuration placed on a singular set (a root of the Jacobian's determinant along
the shoulder, elbow or wrist joint; the iiwa's q2, q4, q6) and moved off it by
10^U(-13, -6) rad or not at all; targets by forward kinematics. It prints per family
the targets, the counts held to 0 (false "unreachable" and "not_found", "ok" without
``near_singular`` and without the generating configuration, "singular" whose
representatives do not reach it along the free joints, solutions given twice, FK
misses), then what is only reported (q farther than 1e-6 rad from an unflagged ``ok``,
pairs of solutions within 1e-6, the flagged and singular answers), then the first
failures. ``tests/ik/test_singular_audit.py`` runs it on a small sample and asserts.
"""

from __future__ import annotations

import argparse
import sys
import time
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from support.ik_singular_audit import COUNTS, run

import kinematica as km


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--arms", type=int, default=240, help="arms per family")
    parser.add_argument("--targets", type=int, default=280, help="targets per arm")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--show", type=int, default=10, help="failures to print")
    args = parser.parse_args()
    warnings.simplefilter("ignore", km.KinematicaWarning)
    t0 = time.perf_counter()
    counts, findings = run(args.arms, args.targets, args.seed, keep=args.show)
    print(f"{'family':<16} " + " ".join(f"{c:>16}" for c in COUNTS))
    total = dict.fromkeys(COUNTS, 0)
    for family, c in counts.items():
        print(f"{family:<16} " + " ".join(f"{c[k]:>16}" for k in COUNTS))
        for k in COUNTS:
            total[k] += c[k]
    print(f"{'all':<16} " + " ".join(f"{total[k]:>16}" for k in COUNTS))
    print(f"{time.perf_counter() - t0:.0f} s")
    np.set_printoptions(precision=17)
    for f in findings:
        print(f"\n{f.family} ({f.robot.name}): {f.what}: {f.detail}; {f.status}: {f.message}")
        print(f"  q = {f.q.tolist()}")
        print(f"  links = {f.robot.links!r}, convention = {f.robot.convention!r}")
        print(f"  base = {np.asarray(f.robot.base).tolist()}")
        print(f"  tool = {np.asarray(f.robot.tool).tolist()}")


if __name__ == "__main__":
    main()
