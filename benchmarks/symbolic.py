"""Symbolic derivation speed: a whole 6-DOF report must take under 10 s.

Run with ``make bench`` (or ``.venv/bin/python benchmarks/symbolic.py``). For
seed 000's 6-DOF arm (parameters as symbols) and the PUMA 560 (numbers) it
times each stage once, cold (sympy caches cleared): the DH table in sympy, the
link matrices and T in textbook form, the checked inverse-kinematics
derivation, and the full report in each format. Baseline measured in the same
run: ``sympy.simplify`` of the six position/orientation entries of T, the
general-purpose route a hand-written script would take. No assertions.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))

import sympy as sp
from _common import fmt_time, header, table

from kinematica import symbolic
from kinematica.symbolic.inverse import derive_inverse
from kinematica.symbolic.kinematics import _product_frames

#: The issue's budget for a whole 6-DOF derivation, report included (s).
BUDGET = 10.0


def cold(fn: Callable[[], Any]) -> float:
    sp.core.cache.clear_cache()
    t0 = time.perf_counter()
    fn()
    return time.perf_counter() - t0


def measure(name: str) -> list[list[str]]:
    """Rows of the table for one robot."""
    model = symbolic.symbolic_robot(name)
    stages: list[tuple[str, Callable[[], Any]]] = [
        ("DH table -> sympy", lambda: symbolic.symbolic_robot(name)),
        ("link matrices + T, textbook form", lambda: symbolic.frames(model)),
        ("IK derivation, checked", lambda: derive_inverse(model)),
        ("report markdown", lambda: symbolic.report(model, format="markdown")),
        ("report latex", lambda: symbolic.report(model, format="latex")),
        ("report html", lambda: symbolic.report(model, format="html")),
    ]
    rows = [[name, label, fmt_time(cold(fn))] for label, fn in stages]
    whole = cold(lambda: symbolic.report(name, format="html", lang="es"))
    verdict = "under" if whole < BUDGET else "OVER"
    rows.append([name, f"whole derivation + report ({verdict} {BUDGET:g} s)", fmt_time(whole)])
    T = _product_frames(model)[-1]
    cells = [(0, 3), (1, 3), (2, 3), (0, 0), (1, 2), (2, 2)]
    baseline = cold(lambda: [sp.simplify(T[i, j]) for i, j in cells])
    rows.append([name, "baseline: sympy.simplify on 6 entries of T", fmt_time(baseline)])
    return rows


def main() -> None:
    print(header("Symbolic derivations (kinematica.symbolic, sympy " + sp.__version__ + ")"))
    rows = []
    for name in ("arm6-dh", "puma560"):
        rows += measure(name)
    print(table(rows, ["robot", "stage (cold caches)", "time"]))


if __name__ == "__main__":
    main()
