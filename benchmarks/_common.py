"""Timing helpers shared by the benchmark scripts: median per call, best of N, a table."""

from __future__ import annotations

import math
import os
import platform
import statistics
import sys
import time
from collections.abc import Callable, Sequence

import numpy as np


def per_call(fn: Callable[[], object], calls: int = 20_000, repeats: int = 25) -> float:
    """Median seconds per call of ``fn()`` over ``repeats`` loops of ``calls // repeats`` calls."""
    fn()  # warm up
    k = max(1, calls // repeats)
    samples = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        for _ in range(k):
            fn()
        samples.append((time.perf_counter() - t0) / k)
    return statistics.median(samples)


def best_of(
    fn: Callable[[], object], repeats: int = 3, clock: Callable[[], float] = time.perf_counter
) -> float:
    """Shortest time (s) of ``repeats`` calls of ``fn()``: wall, or ``clock``'s
    (``time.process_time``: the CPU time of the process, on a shared machine)."""
    times = []
    for _ in range(repeats):
        t0 = clock()
        fn()
        times.append(clock() - t0)
    return min(times)


def median_of(fn: Callable[[], object], repeats: int = 15) -> float:
    """Median wall time (s) of ``repeats`` calls of ``fn()``, after one warm-up call."""
    fn()
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def shortest_per_item(
    fn: Callable[[np.ndarray], object], items: Sequence[np.ndarray], passes: int = 3
) -> float:
    """Median over ``items`` of ``fn(item)``'s wall time (s), each call timed on its own.

    Each item's time is the shortest of ``passes`` passes over all the items: a
    neighbour's burst on a shared machine slows one pass, not all of them.
    """
    return shortest_per_item_together([(fn, items)], passes)[0]


def shortest_per_item_together(
    calls: Sequence[tuple[Callable[[np.ndarray], object], Sequence[np.ndarray]]], passes: int = 3
) -> list[float]:
    """:func:`shortest_per_item` of several ``(fn, items)``, their passes taken in turn.

    Pass k of each call runs right after pass k of the one before it, so that the
    calls compared (ours and a peer's) meet the same state of a shared machine: a
    burst that slows one of them in a pass slows the next one too, or neither.
    """
    for fn, items in calls:
        fn(items[0])
    best = [[math.inf] * len(items) for _, items in calls]
    for _ in range(passes):
        for (fn, items), times in zip(calls, best, strict=True):
            for i, item in enumerate(items):
                t0 = time.perf_counter()
                fn(item)
                times[i] = min(times[i], time.perf_counter() - t0)
    return [statistics.median(times) for times in best]


def cores() -> tuple[int, int]:
    """(cores this process may run on, logical cores of the machine)."""
    try:
        usable = len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        usable = os.cpu_count() or 1
    return usable, os.cpu_count() or 1


def header(title: str) -> str:
    usable, total = cores()
    return (
        f"{title}\n"
        f"Python {sys.version.split()[0]}, numpy {np.__version__}, "
        f"{platform.system()} {platform.machine()}; "
        f"cores: {usable} usable of {total}; load average "
        + ", ".join(f"{v:.1f}" for v in os.getloadavg())
    )


def table(rows: Sequence[Sequence[str]], head: Sequence[str]) -> str:
    """Rows of strings as a fixed-width text table: first column left, others right."""
    widths = [max(len(r[i]) for r in [head, *rows]) for i in range(len(head))]

    def line(r: Sequence[str]) -> str:
        cells = [r[0].ljust(widths[0])] + [
            c.rjust(w) for c, w in zip(r[1:], widths[1:], strict=True)
        ]
        return "  " + "  ".join(cells).rstrip()

    rule = "  " + "  ".join("-" * w for w in widths)
    return "\n".join([line(head), rule, *(line(r) for r in rows)])


def verdict(ok: bool, by: str = "") -> str:
    """``"met"``, or ``"NOT met"`` and by how much (``by``)."""
    return "met" if ok else f"NOT met ({by})" if by else "NOT met"


def fmt_time(seconds: float) -> str:
    """A duration with a unit that keeps 3-4 significant digits."""
    if seconds < 1e-3:
        return f"{seconds * 1e6:.2f} µs"
    if seconds < 1.0:
        return f"{seconds * 1e3:.2f} ms"
    return f"{seconds:.2f} s"
