"""Robot design (seed 000's "dimensiones óptimas de los eslabones"): link lengths for a task.

A planar 2R arm of total length 1 m (``l2 = 1 - l1``) must reach every point of
a ring of radius 0.6 m. Which split of the length makes its worst
manipulability largest? By hand: on the ring ``w² = 0.64·l1·l2 - 0.1024``, so
``l1 = l2 = 0.5`` and ``w = 0.24``. Then the same arm on a ring of radius
0.3 m that the template (``l1 = 0.3``) cannot reach at all: reaching every
target is a hard constraint. Last, the command line on the same files: best
robot file, Markdown report with pictures, evaluation log.
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
from pathlib import Path

import kinematica as km
from kinematica import design

TEMPLATE = """\
name: planar 2R, total length 1 m
convention: standard
parameters:
  l1: {value: 0.3, min: 0.1, max: 0.9}   # the design variable
  l2: 1 - l1                             # follows it
joints:
  - {theta: q1, d: 0, a: l1, alpha: 0}
  - {theta: q2, d: 0, a: l2, alpha: 0}
"""


def main() -> None:
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        template = folder / "arm2r.yaml"
        template.write_text(TEMPLATE)

        print("1. Worst manipulability on a ring of radius 0.6 m (closed form: l1 = 0.5, w = 0.24)")
        res = design.optimize(template, design.Task.ring(0.6, 32), budget=150, seed=1)
        print(f"   {res.message}")
        print(f"   l1 = {res.best_params['l1']:.5f} m, worst manipulability = {res.best_value:.6f}")
        print(f"   the template (l1 = 0.3): {res.history[0].measures['min_manipulability']:.6f}")

        print("\n2. A ring of radius 0.3 m: |l1 - l2| <= 0.3 is needed, the template has 0.4")
        inner = design.optimize(template, design.Task.ring(0.3, 32), budget=100, seed=1)
        print(f"   template reaches {inner.history[0].measures['reached']:.0%} of the targets")
        print(f"   best: l1 = {inner.best_params['l1']:.5f} m, reaches 100%: {inner.feasible}")
        # by hand: w² = 0.91·l1·l2 - 0.455², largest at l1 = l2 = 0.5
        print(f"   worst manipulability {inner.best_value:.6f} (closed form 0.143091)")

        print("\n3. The command line, with a task file")
        (folder / "ring.json").write_text('{"region": "ring", "radius": 0.6, "count": 32}')
        cmd = [
            sys.executable, "-m", "kinematica.cli.main", "design", str(template),
            "--task", str(folder / "ring.json"), "--objective", "min_manipulability",
            "--budget", "60", "--seed", "2", "-o", str(folder / "best.yaml"),
        ]  # fmt: skip
        print("   $ kinematica design arm2r.yaml --task ring.json --objective min_manipulability "
              "--budget 60 --seed 2 -o best.yaml")  # fmt: skip
        out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
        print("   " + out.strip().replace("\n", "\n   ").replace(str(folder) + "/", ""))
        best = km.load(folder / "best.yaml")
        print(f"   km.load('best.yaml'): {best}, a = {[round(lk.a, 5) for lk in best.links]}")


if __name__ == "__main__":
    main()
