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
from kinematica import _core, _core_testing

#: Seconds from SIGINT to KeyboardInterrupt accepted here. The core looks every 0.01 s
#: and a block of 64 numeric targets takes about 2 ms, so an idle machine answers in
#: 3-30 ms (benchmarks/robustness.py); this bound leaves a loaded test machine, or the
#: sanitizer build (2.3 s once, under a load of 20 on 2 cores), its delays, and is still
#: less than half of what the batch takes uninterrupted (10 s idle, minutes sanitized).
LATENCY = 4.0

#: Each child's first lines. A shell's background job (``cmd &`` without job control)
#: starts with SIGINT ignored, and Python then installs no KeyboardInterrupt handler, so
#: a child of a suite run that way would never see the signal; it takes Python's own.
SIGINT_HANDLED = """
import signal
signal.signal(signal.SIGINT, signal.default_int_handler)
"""

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
        [sys.executable, "-c", SIGINT_HANDLED + CHILD],
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
    releasing it, one per 0.5 ms of its 10-50 ms. The spatial batches (wrap, so3_log,
    rotation_angles, pose_errors) are among them: 15-30 ns a row, where one block of
    256 rows or fewer keeps the GIL (a few µs).
    """
    rng = np.random.default_rng(1)
    arm = km.Robot.from_dh(
        [km.Revolute(a=0.01, alpha=0.3) for _ in range(40)], name="40R", convention="standard"
    )
    core = arm.chain.core
    Q = rng.uniform(-1.0, 1.0, (20_000, 40))
    T = km.load("puma560").fk(rng.uniform(-1.0, 1.0, (100_000, 6)))
    Tb = np.tile(T, (5, 1, 1))  # 500_000 poses: 10-20 ms of each spatial batch and the check
    Tb2 = Tb[::-1].copy()
    R, R2 = np.ascontiguousarray(Tb[:, :3, :3]), np.ascontiguousarray(Tb2[:, :3, :3])
    angles = rng.uniform(-100.0, 100.0, 2_000_000)
    J6 = rng.standard_normal((40_000, 6, 6))  # 20-40 ms of singular values
    calls = {
        "joint_axes": lambda: core.joint_axes(Q, 1),
        "point_rank_ratios": lambda: _core_testing.internals.point_rank_ratios(
            core, Q[:4000], np.zeros(3), 1
        ),
        "pose_defects_batch": lambda: _core.pose_defects_batch(Tb, 1),  # 10-20 ms
        "fk_batch": lambda: core.fk_batch(Q, True, 1),
        "wrap": lambda: _core.wrap(angles),
        "so3_log": lambda: _core.so3_log(R),
        "rotation_angles": lambda: _core.rotation_angles(R, R2),
        "pose_errors": lambda: _core.pose_errors(Tb, Tb2),
        "jacobian_singular_values": lambda: core.jacobian_singular_values(Q[:4000], 63, 1, 1),
        "singular_values": lambda: _core.singular_values(J6, 1),
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


SPATIAL_CHILD = r"""
import os, signal, sys, threading
import numpy as np
import kinematica as km
from kinematica import _core

# No forced switch: the second thread runs only when this one lets go of the GIL, which
# a batch holding it never does.
sys.setswitchinterval(100.0)
rng = np.random.default_rng(2)
T = km.load("iiwa14").fk(rng.uniform(-1.0, 1.0, (1000, 7)))
R = np.ascontiguousarray(np.tile(T[:, :3, :3], (3000, 1, 1)))  # 3e6 rotations, 30-90 ms
go = threading.Event()

def ctrl_c():
    go.wait()
    os.kill(os.getpid(), signal.SIGINT)  # runs once the batch has released the GIL

threading.Thread(target=ctrl_c).start()
go.set()
result = None
try:
    result = _core.rotation_angles(R, R)
    print("finished", flush=True)
except KeyboardInterrupt:
    print("interrupted", result is None, flush=True)
# still usable: the angles of a batch, against the trace formula
Ra, Rb = R[:300], R[300:600]
got = _core.rotation_angles(Ra, Rb)
cos = (np.einsum("nij,nij->n", Ra, Rb) - 1.0) / 2.0
err = float(np.abs(got - np.arccos(np.clip(cos, -1.0, 1.0))).max())
print("after", err, flush=True)
"""


def test_sigint_stops_a_spatial_batch_inside_the_call() -> None:
    """A SIGINT that arrives while rotation_angles runs stops it before its end.

    The signal is sent by a second thread of the child that can run only once the batch
    has released the GIL (the switch interval is 100 s): a batch holding the GIL would
    finish first, its result assigned, and the KeyboardInterrupt raised after it.
    """
    child = subprocess.run(
        [sys.executable, "-c", SIGINT_HANDLED + SPATIAL_CHILD],
        capture_output=True,
        text=True,
        timeout=60,
        env={**os.environ, "KINEMATICA_WORKERS": "2"},
    )
    assert child.returncode == 0, child.stderr
    lines = [line.split() for line in child.stdout.splitlines()]
    assert lines[0] == ["interrupted", "True"]
    word, err = lines[1]
    assert word == "after" and float(err) < 1e-9


TOPP_CHILD = r"""
import os, signal, sys, threading
import numpy as np
from kinematica.core.topp import time_optimal_grid

sys.setswitchinterval(100.0)  # the second thread runs only once the core lets go of the GIL


def problem(n, N):
    rng = np.random.default_rng(3)
    s = np.linspace(0.0, 1.0, N + 1)
    coef = np.zeros((N, 4, n))
    coef[:, 1] = rng.uniform(0.5, 1.0, n)
    coef[:, 2] = 0.01 * rng.uniform(-1.0, 1.0, (N, n))
    coef[:, 0] = np.cumsum(coef[:, 1] / N, axis=0)
    one = np.ones(n)
    return s, coef, (-one, one), (-5.0 * one, 5.0 * one), np.full(N, np.inf), 0.0, 0.0, 1e12


small = time_optimal_grid(*problem(3, 50))
long_path = problem(20, 20_000)  # one path of 20 joints on 20,000 intervals: 0.1-0.5 s
go = threading.Event()

def ctrl_c():
    go.wait()
    os.kill(os.getpid(), signal.SIGINT)

threading.Thread(target=ctrl_c).start()
go.set()
result = None
try:
    result = time_optimal_grid(*long_path)
    print("finished", flush=True)
except KeyboardInterrupt:
    print("interrupted", result is None, flush=True)
again = time_optimal_grid(*problem(3, 50))
same = again.status == small.status == "ok" and np.array_equal(again.x, small.x)
print("after", same, flush=True)
"""


def test_sigint_stops_one_long_time_optimal_path_inside_the_call() -> None:
    """One path's timing (the core's topp.hpp) reads Ctrl-C between its stages.

    As above: the SIGINT comes from a thread that runs only once the call has released
    the GIL; a call that did not look at the signals would finish first and return. The
    core then times a small path exactly as before the interruption.
    """
    child = subprocess.run(
        [sys.executable, "-c", SIGINT_HANDLED + TOPP_CHILD],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert child.returncode == 0, child.stderr
    lines = [line.split() for line in child.stdout.splitlines()]
    assert lines == [["interrupted", "True"], ["after", "True"]]
