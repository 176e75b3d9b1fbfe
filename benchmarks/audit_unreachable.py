"""Are the general 6R's proofs of unreachability true? An audit against a multi-start search.

Run with ``.venv/bin/python benchmarks/audit_unreachable.py`` (``--arms``, ``--targets``,
``--edges``, ``--starts``, ``--seed``). Where none of the elimination's candidates closes
the loop and every eigenvalue of its pencil lies ``CERTIFY_MARGIN`` times its error bound
from the real axis, ``robot.ik`` answers "unreachable" without a reach gap
(``general_6r.hpp``). Two ways of looking for a target so answered that an arm reaches:

* **far**: random arms of the general family (every other one on an edge of it:
  ``general_6r.sample_arm(degenerate=True)``), targets of random orientation at 0.7-1.5
  times an FK pose's distance from the base; each proved one searched from
  ``--starts`` random configurations (``robot.ik(method="numeric")`` in one batch);
* **edge**: from an FK pose along a random line (position and orientation moved
  together) to where the solver's answer turns, then 40 bisections toward the
  workspace's boundary; each target said unreachable on the way searched from the last
  solutions found inside and 20 random starts. Printed: how far from the boundary the
  proofs reach (the bracket's width where the answer is left to the search).

A proof contradicted (the search reaches the target to the default tolerance) is a
failure, printed with its arm.
"""

from __future__ import annotations

import argparse
import collections
import time

import numpy as np
from scipy.spatial.transform import Rotation

import kinematica as km
from kinematica.ik.analytic import general_6r

FloatArray = np.ndarray


def _arm(rng: np.random.Generator, degenerate: bool) -> tuple[km.Robot, str]:
    s = general_6r.sample_arm(rng, degenerate)
    robot = km.Robot.from_dh(list(s.links), convention=s.convention, base=s.base, tool=s.tool)
    return robot, s.note or "generic"


def _reached(robot: km.Robot, T: FloatArray, q0: FloatArray) -> bool:
    """Whether a search from any of the starts ``q0`` (k, 6) reaches T."""
    many = robot.ik(np.repeat(T[None], len(q0), 0), q0=q0, method="numeric", workers=1)
    return any(str(s) in ("ok", "singular") for s in many.status)


def _proved(res: km.IKResult) -> bool:
    return str(res.status) == "unreachable" and res.gap is None


def far(arms: int, targets: int, starts: int, rng: np.random.Generator) -> None:
    counts: collections.Counter[str] = collections.Counter()
    failures = []
    t0 = time.perf_counter()
    for a in range(arms):
        robot, note = _arm(rng, bool(a % 2))
        base = robot.base[:3, 3]
        for _ in range(targets):
            T = robot.fk(rng.uniform(-np.pi, np.pi, 6))
            T[:3, 3] = base + (T[:3, 3] - base) * rng.uniform(0.7, 1.5)
            T[:3, :3] = Rotation.random(random_state=int(rng.integers(1 << 30))).as_matrix()
            res = robot.ik(T)
            counts[f"{res.method.split(':')[0]} {res.status}"] += 1
            if _proved(res):
                counts["proved"] += 1
                if _reached(robot, T, rng.uniform(-np.pi, np.pi, (starts, 6))):
                    failures.append((a, note, T.tolist()))
    print(f"far: {arms} arms, {arms * targets} targets, {time.perf_counter() - t0:.0f} s")
    for key, n in sorted(counts.items()):
        print(f"  {key}: {n}")
    print(f"  proofs contradicted by the search: {len(failures)}")
    for f in failures[:5]:
        print("   ", f)


def edge(arms: int, rng: np.random.Generator) -> None:
    counts: collections.Counter[str] = collections.Counter()
    failures, widths = [], []
    t0 = time.perf_counter()
    for a in range(arms):
        robot, note = _arm(rng, bool(a % 2))
        for _ in range(3):
            T0 = robot.fk(rng.uniform(-np.pi, np.pi, 6))
            d = rng.normal(size=3)
            d /= np.linalg.norm(d)
            w = rng.normal(size=3)
            w /= np.linalg.norm(w)

            def target(
                t: float, T0: FloatArray = T0, d: FloatArray = d, w: FloatArray = w
            ) -> FloatArray:
                T = T0.copy()
                T[:3, 3] += t * d
                T[:3, :3] = Rotation.from_rotvec(w * t).as_matrix() @ T0[:3, :3]
                return T

            lo, hi, sols, t = 0.0, None, robot.ik(T0).solutions, 0.05
            while t < 3.0:
                res = robot.ik(target(t))
                if str(res.status) == "unreachable":
                    hi = t
                    break
                if str(res.status) in ("ok", "singular") and res.count:
                    lo, sols = t, res.solutions
                t *= 1.5
            if hi is None:
                counts["no boundary met"] += 1
                continue
            for _ in range(40):
                mid = 0.5 * (lo + hi)
                res = robot.ik(target(mid))
                if str(res.status) == "unreachable":
                    hi = mid
                    counts["proved" if res.gap is None else "reach gap"] += 1
                    starts = np.vstack([sols, rng.uniform(-np.pi, np.pi, (20, 6))])
                    if _proved(res) and _reached(robot, target(mid), starts):
                        failures.append((a, note, mid - lo))
                elif str(res.status) in ("ok", "singular") and res.count:
                    lo, sols = mid, res.solutions
                else:
                    counts[f"left to {res.method}"] += 1
                    widths.append(hi - lo)
                    break
    print(f"edge: {arms} arms, {time.perf_counter() - t0:.0f} s")
    for key, n in sorted(counts.items()):
        print(f"  {key}: {n}")
    if widths:
        pct = np.percentile(widths, [10, 50, 90, 100])
        print("  bracket where the search answers (m and rad), 10/50/90/100 %:", pct.tolist())
    print(f"  proofs contradicted by the search: {len(failures)}")
    for f in failures[:5]:
        print("   ", f)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--arms", type=int, default=100)
    parser.add_argument("--targets", type=int, default=10)
    parser.add_argument("--edges", type=int, default=50, help="arms of the edge audit")
    parser.add_argument("--starts", type=int, default=100)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    rng = np.random.default_rng(args.seed)
    far(args.arms, args.targets, args.starts, rng)
    edge(args.edges, rng)


if __name__ == "__main__":
    main()
