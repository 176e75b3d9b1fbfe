"""Motion speed: Jacobian throughput, workspace samples per second, IK steps along a path.

Run with ``make bench`` (or ``.venv/bin/python benchmarks/motion.py``). Each
figure has a baseline measured in the same run:

* Jacobian: ``robot.jacobian(q)`` on a batch, against ``robot.fk(q)`` on the same
  batch (a Jacobian needs every frame, so FK throughput is its natural floor)
  and against a central-difference Jacobian from ``robot.fk`` (2n FK calls);
* workspace: ``km.workspace`` samples per second with and without the
  manipulability map, against the bare ``robot.fk`` of the same samples;
* Cartesian path: IK steps per second of ``cartesian_path`` (IK, continuity,
  singularity checks per step), against bare ``robot.ik`` calls on the same poses.

No assertions: figures only.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parent))

from _common import best_of, fmt_time, header, table

import kinematica as km
from kinematica.motion import cartesian_path


def fd_jacobian(robot: km.Robot, q: np.ndarray, h: float = 1e-6) -> np.ndarray:
    """Baseline: linear rows by central differences of FK positions (2n batched FK calls)."""
    cols = []
    for i in range(robot.dof):
        dq = np.zeros(robot.dof)
        dq[i] = h
        cols.append((robot.fk(q + dq)[..., :3, 3] - robot.fk(q - dq)[..., :3, 3]) / (2 * h))
    return np.stack(cols, axis=-1)


def main() -> None:
    print(header("kinematica motion benchmarks"))
    rows = []
    for name in ("puma560", "panda"):
        robot = km.load(name)
        q = robot.random_q(100_000, seed=0)
        n = q.shape[0]
        tj = best_of(lambda r=robot, x=q: r.jacobian(x))
        tf = best_of(lambda r=robot, x=q: r.fk(x))
        td = best_of(lambda r=robot, x=q: fd_jacobian(r, x), repeats=1)
        rows.append(
            (
                f"Jacobian, {robot.name}, N = 1e5",
                f"{n / tj / 1e6:.2f} M/s",
                f"FK {n / tf / 1e6:.2f} M/s; finite differences {n / td / 1e6:.3f} M/s",
            )
        )
    for name in ("puma560", "anthropomorphic-3r"):
        robot = km.load(name)
        n = 500_000
        tw = best_of(lambda r=robot, m=n: km.workspace(r, samples=m, seed=0), repeats=1)
        tn = best_of(
            lambda r=robot, m=n: km.workspace(r, samples=m, seed=0, manipulability=False), repeats=1
        )
        q = robot.random_q(n, seed=0)
        tf = best_of(lambda r=robot, x=q: r.fk(x), repeats=1)
        rows.append(
            (
                f"workspace, {robot.name}, N = 5e5",
                f"{n / tw / 1e6:.2f} M/s (map) / {n / tn / 1e6:.2f} M/s",
                f"bare FK {n / tf / 1e6:.2f} M/s",
            )
        )
    puma = km.load("puma560")
    q0 = np.array([0.2, -0.5, 0.3, 0.4, 0.9, -0.1])
    T0 = puma.fk(q0)
    T1 = T0.copy()
    T1[:3, 3] += [0.05, 0.1, -0.05]
    steps = 200
    tp = best_of(lambda: cartesian_path(puma, T0, T1, steps=steps, q0=q0))
    poses = cartesian_path(puma, T0, T1, steps=steps, q0=q0).poses
    ti = best_of(lambda: [puma.ik(T) for T in poses])
    rows.append(
        (
            f"Cartesian line, {puma.name}, {steps} steps",
            f"{steps / tp:.0f} steps/s ({fmt_time(tp / steps)} each)",
            f"bare robot.ik {steps / ti:.0f} poses/s ({fmt_time(ti / steps)} each)",
        )
    )
    print(table(rows, ("what", "kinematica", "baseline (same run)")))


if __name__ == "__main__":
    main()
