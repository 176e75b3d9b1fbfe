"""IK of the makers' 6R arms (tests/data/makers, from ssik 8.2.0): ours against ssik's.

Run with ``.venv/bin/python benchmarks/ik_makers.py`` (``--poses``, ``--seed``,
``--arms`` a substring of the arms' names). The arms are the 53 six-joint arms whose
URDFs ``tests/data/makers/make_makers.py`` wrote from ssik's prebuilt modules. For
each: µs per pose of ``robot.ik`` one pose at a time (median over the poses, each
the shortest of three passes) and batched on one thread (best of three), on poses
of random configurations within the limits, with the method and mean solution
count. ssik is an optional peer: when ``import ssik`` works (e.g.
``PYTHONPATH=/tmp/ssikvenv/lib/python3.11/site-packages``, a venv holding
``ssik==8.2.0``), its ``solve(T)`` on the same poses, one at a time, by default
(within the limits, every 2 pi copy that stays within them) and with
``respect_limits=False``, timed in the same passes as ours, and the ratio of its
default time to our one-pose time.
"""

from __future__ import annotations

import argparse
import importlib
import json
import sys
from collections.abc import Callable, Sequence
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import best_of, fmt_time, header, shortest_per_item_together, table

import kinematica as km

MAKERS = Path(__file__).resolve().parents[1] / "tests" / "data" / "makers"


def six_r_arms(pattern: str) -> list[dict[str, Any]]:
    """The reference's 6-joint arms whose names hold ``pattern``."""
    arms = json.loads((MAKERS / "ssik_reference.json").read_text())["arms"]
    return [a for a in arms if a["dof"] == 6 and pattern in a["arm"]]


def ssik_module(arm: dict[str, Any]) -> ModuleType | None:
    """ssik's module of the arm, or None when ssik does not import."""
    try:
        return importlib.import_module(arm["module"])
    except ImportError:
        return None


def poses(robot: km.Robot, n: int, rng: np.random.Generator) -> np.ndarray:
    """``(n, 4, 4)`` poses of configurations uniform within the limits (continuous: ±pi)."""
    return robot.fk(rng.uniform(robot.qlim[:, 0], robot.qlim[:, 1], (n, robot.dof)))


def timing(arms: Sequence[dict[str, Any]], n: int, seed: int) -> None:
    rows = []
    have_ssik = False
    ratios = []
    for arm in arms:
        robot = km.load(MAKERS / arm["urdf"])
        rng = np.random.default_rng([seed, len(rows)])
        Ts = poses(robot, n, rng)
        items = list(Ts)
        mod = ssik_module(arm)
        calls: list[tuple[Callable[[np.ndarray], object], Sequence[np.ndarray]]] = [
            (robot.ik, items)
        ]
        if mod is not None:
            have_ssik = True
            calls += [
                (mod.solve, items),
                (lambda T, m=mod: m.solve(T, respect_limits=False), items),
            ]
        times = shortest_per_item_together(calls)
        batch = best_of(lambda r=robot, p=Ts: r.ik(p, workers=1)) / n
        ours = robot.ik(Ts)
        methods = sorted({robot.ik(T).method for T in items})
        row = [
            arm["arm"],
            ", ".join(m.removeprefix("analytic:") for m in methods),
            fmt_time(times[0]),
            fmt_time(batch),
            f"{ours.count.mean():.2f}",
        ]
        if mod is not None:
            counts = np.mean([len(mod.solve(T)) for T in items])
            ratios.append(times[1] / times[0])
            row += [
                arm["solver"].removeprefix("ikgeo."),
                fmt_time(times[1]),
                fmt_time(times[2]),
                f"{counts:.1f}",
                f"{times[1] / times[0]:.0f}x",
                f"{times[1] / batch:.0f}x",
            ]
        rows.append(row)
        print(f"  {arm['arm']} done", file=sys.stderr, flush=True)
    head = ["arm", "our method", "one", "batched", "solutions"]
    if have_ssik:
        head += ["ssik solver", "ssik", "ssik no limits", "ssik sols", "ssik/one", "ssik/batched"]
    else:
        head += ["ssik"]
        rows = [[*r, "not installed"] for r in rows]
    print(table(rows, head))
    if ratios:
        print(
            f"ssik's default solve over our one-pose robot.ik: median {np.median(ratios):.0f}x, "
            f"range {min(ratios):.0f}x-{max(ratios):.0f}x over {len(ratios)} arms"
        )
    else:
        print(
            "ssik not importable: pip install ssik==8.2.0 in a venv and put its "
            "site-packages on PYTHONPATH"
        )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--poses", type=int, default=100, help="poses per arm")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--arms", default="", help="only arms whose names hold this")
    args = parser.parse_args()
    try:
        import ssik

        peer = f"ssik {ssik.__version__}"
    except ImportError:
        peer = "ssik not installed"
    print(header(f"IK of the makers' 6R arms: robot.ik against {peer}"))
    timing(six_r_arms(args.arms), args.poses, args.seed)


if __name__ == "__main__":
    main()
