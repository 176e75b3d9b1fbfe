"""Ctrl-C stops a batch in the core, and the batches let other Python threads run.

The core runs a batch with the GIL released; its caller's thread looks at Python's
signals between blocks (``cpp/python/interrupt.hpp``, every ``POLL_INTERVAL`` s at
most). A SIGINT sent to a process in the middle of a long IK batch raises
KeyboardInterrupt there within a fraction of a second, where it once waited for the
whole batch (6.5-8 s for 2e6 poses); the interpreter and the core's threads then
work as before. How fast, on an idle machine: ``benchmarks/interrupt.py``.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import threading
import time

import numpy as np

import kinematica as km
from kinematica import _core

#: Seconds from SIGINT to KeyboardInterrupt accepted here. The core looks every 0.01 s
#: and a block of 64 numeric targets takes about 2 ms, so an idle machine answers in
#: 3-30 ms (benchmarks/robustness.py); this bound leaves a loaded test machine, or the
#: sanitizer build (2.3 s once, under a load of 20 on 2 cores), its delays, and is still
#: less than half of what the batch takes uninterrupted (10 s idle, minutes sanitized).
LATENCY = 4.0

CHILD = r"""
import sys, time
import numpy as np
import kinematica as km
from kinematica import _core

iiwa = km.load("iiwa14")
rng = np.random.default_rng(0)
T = iiwa.fk(rng.uniform(-1.0, 1.0, (400_000, 7)))  # about 10 s of numeric IK
for attempt in range(2):
    print("ready", flush=True)
    start = time.monotonic()
    try:
        iiwa.ik(T, method="numeric", seed=0)
        print("finished", time.monotonic() - start, flush=True)
    except KeyboardInterrupt:
        print("interrupted", time.monotonic(), time.monotonic() - start, flush=True)
# still usable: a batch, its FK checked, and a single call
q = rng.uniform(-1.0, 1.0, (300, 7))
res = iiwa.ik(iiwa.fk(q), method="numeric", seed=0)
ok = bool((res.status == "ok").all())
err = float(np.abs(iiwa.fk(res.solutions[:, 0]) - iiwa.fk(q)).max())
one = iiwa.ik(iiwa.fk(q[0]))
print("after", ok, err, one.status, flush=True)
"""


def test_sigint_stops_a_long_ik_batch_and_the_interpreter_goes_on() -> None:
    child = subprocess.Popen(
        [sys.executable, "-c", CHILD],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env={**os.environ, "KINEMATICA_WORKERS": "2"},
    )
    try:
        assert child.stdout is not None
        for _ in range(2):
            assert child.stdout.readline().split() == ["ready"]
            time.sleep(0.3)  # into the batch
            sent = time.monotonic()
            child.send_signal(signal.SIGINT)
            word, caught, ran = child.stdout.readline().split()
            assert word == "interrupted"
            assert float(caught) - sent < LATENCY
            assert float(ran) < 0.3 + LATENCY
        word, ok, err, status = child.stdout.readline().split()
        assert word == "after" and ok == "True" and status == "ok"
        assert float(err) < 1e-9
        assert child.wait(timeout=60) == 0
    finally:
        child.kill()
        child.wait()


def test_batches_release_the_gil() -> None:
    """While the core runs a batch in one thread, another thread runs Python.

    Each call is timed in the first thread; the second notes the time every 0.5 ms,
    and can do so only while it holds the GIL. A call holding the GIL lets at most one
    such note fall inside it (taken just before the call entered the core); one
    releasing it, one per 0.5 ms of its 10-30 ms.
    """
    rng = np.random.default_rng(1)
    arm = km.Robot.from_dh([km.Revolute(a=0.01, alpha=0.3) for _ in range(40)], name="40R")
    core = arm.chain.core
    Q = rng.uniform(-1.0, 1.0, (20_000, 40))
    T = km.load("puma560").fk(rng.uniform(-1.0, 1.0, (100_000, 6)))
    T2 = T[::-1].copy()
    R, R2 = np.ascontiguousarray(T[:, :3, :3]), np.ascontiguousarray(T2[:, :3, :3])
    angles = rng.uniform(-100.0, 100.0, 2_000_000)
    calls = {
        "joint_axes": lambda: core.joint_axes(Q, 1),
        "point_rank_ratios": lambda: core.point_rank_ratios(Q[:4000], np.zeros(3), 1),
        "pose_defects_batch": lambda: _core.pose_defects_batch(T, 1),
        "fk_batch": lambda: core.fk_batch(Q, True, 1),
        "wrap": lambda: _core.wrap(angles),
        "so3_log": lambda: _core.so3_log(R),
        "rotation_angles": lambda: _core.rotation_angles(R, R2),
        "pose_errors": lambda: _core.pose_errors(T, T2),
    }
    repeats = 5
    windows: dict[str, list[tuple[float, float]]] = {name: [] for name in calls}

    def run() -> None:
        for name, call in calls.items():
            for _ in range(repeats):
                start = time.monotonic()
                call()
                windows[name].append((start, time.monotonic()))

    ticks: list[float] = []
    worker = threading.Thread(target=run)
    worker.start()
    while worker.is_alive():
        ticks.append(time.monotonic())
        time.sleep(0.0005)
    worker.join()
    for name, spans in windows.items():
        inside = sum(1 for t in ticks for a, b in spans if a < t < b)
        assert inside > 2 * repeats, f"{name}: {inside} notes inside {repeats} calls"
