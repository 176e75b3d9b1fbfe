"""The core's edges (issue 34): Ctrl-C latency, NaN rows, arrays the core copies, long URDFs.

Run with ``make bench`` (or ``.venv/bin/python benchmarks/robustness.py``). It prints:

* Ctrl-C: a child process runs a numeric IK batch of 400,000 iiwa targets (about 10 s
  uninterrupted); SIGINT is sent 0.3 s in, and the time to its KeyboardInterrupt is
  measured on the machine's monotonic clock, over ``--trials`` runs (the median and
  the largest); the core looks at signals every ``POLL_INTERVAL`` (0.01 s);
* FK and Jacobian batches of 1,000,000 PUMA configurations, every row NaN against
  every row finite (CPU time, best of 3): the ratio was 14 before the warning stopped
  making a Python object per bad row;
* FK of misaligned float64 configurations (copied once by the core) against aligned
  ones, batch and single call;
* loading URDFs of 25,000, 50,000 and 100,000 fixed joints (CPU time): per joint, to
  show the growth is linear.

The development machine is shared: figures move by 30 % or more from run to run.
No assertions.
"""

from __future__ import annotations

import argparse
import signal
import statistics
import subprocess
import sys
import tempfile
import time
import warnings
from collections.abc import Callable
from pathlib import Path

import numpy as np

import kinematica as km

CHILD = r"""
import time
import numpy as np
import kinematica as km

iiwa = km.load("iiwa14")
T = iiwa.fk(np.random.default_rng(0).uniform(-1.0, 1.0, (400_000, 7)))
print("ready", flush=True)
try:
    iiwa.ik(T, method="numeric", seed=0)
    print("finished", flush=True)
except KeyboardInterrupt:
    print("interrupted", time.monotonic(), flush=True)
"""


def interrupt_latency(trials: int) -> list[float]:
    """Seconds from SIGINT to KeyboardInterrupt, one per trial."""
    out = []
    for _ in range(trials):
        child = subprocess.Popen([sys.executable, "-c", CHILD], stdout=subprocess.PIPE, text=True)
        assert child.stdout is not None
        child.stdout.readline()
        time.sleep(0.3)
        sent = time.monotonic()
        child.send_signal(signal.SIGINT)
        words = child.stdout.readline().split()
        child.wait()
        if words and words[0] == "interrupted":
            out.append(float(words[1]) - sent)
    return out


def cpu(fn: Callable[[], object], repeats: int = 3) -> float:
    best = float("inf")
    for _ in range(repeats):
        start = time.process_time()
        fn()
        best = min(best, time.process_time() - start)
    return best


def unaligned(a: np.ndarray) -> np.ndarray:
    buf = bytearray(a.nbytes + 1)
    out = np.frombuffer(buf, dtype=np.float64, count=a.size, offset=1).reshape(a.shape)
    out[...] = a
    return out


def fixed_joint_urdf(n: int, path: Path) -> None:
    parts = ['<robot name="fixed">', '<link name="l0"/>']
    for i in range(n):
        parts.append(f'<link name="l{i + 1}"/>')
        parts.append(
            f'<joint name="j{i}" type="fixed"><parent link="l{i}"/><child link="l{i + 1}"/>'
            '<origin xyz="0 0 0.001"/></joint>'
        )
    parts.append(
        f'<link name="tip"/><joint name="r" type="revolute"><parent link="l{n}"/>'
        '<child link="tip"/><axis xyz="0 0 1"/>'
        '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>'
    )
    path.write_text("\n".join(parts))


def main() -> None:
    warnings.simplefilter("ignore")  # the random configurations leave the PUMA's limits
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--trials", type=int, default=5)
    args = parser.parse_args()
    print("Ctrl-C during a numeric IK batch of 400,000 targets (about 10 s uninterrupted)")
    lat = interrupt_latency(args.trials)
    if lat:
        print(f"  SIGINT -> KeyboardInterrupt: median {statistics.median(lat) * 1e3:.0f} ms, "
              f"largest {max(lat) * 1e3:.0f} ms over {len(lat)} trials")  # fmt: skip
    puma = km.load("puma560")
    n = 1_000_000
    finite = np.random.default_rng(0).uniform(-1.0, 1.0, (n, 6))
    nan = np.full((n, 6), np.nan)
    print("1,000,000 PUMA configurations, CPU s (best of 3)")
    for name, f in (("fk", puma.fk), ("jacobian", puma.jacobian)):
        a, b = cpu(lambda f=f: f(finite)), cpu(lambda f=f: f(nan))
        print(f"  {name:9s} finite {a:.3f}  NaN rows {b:.3f}  ratio {b / a:.2f}")
    q = finite[:100_000]
    qm = unaligned(q)
    a, b = cpu(lambda: puma.fk(q)), cpu(lambda: puma.fk(qm))
    print(f"FK of 100,000 misaligned rows / aligned: {b / a:.2f} ({a:.4f} s aligned)")
    one, onem = q[0].copy(), unaligned(q[0])
    a = cpu(lambda: [puma.fk(one) for _ in range(20_000)])
    b = cpu(lambda: [puma.fk(onem) for _ in range(20_000)])
    print(f"one FK call, misaligned / aligned: {b / a:.2f} ({a / 20_000 * 1e6:.2f} us aligned)")
    print("URDF of n fixed joints, load CPU s")
    with tempfile.TemporaryDirectory() as folder:
        for count in (25_000, 50_000, 100_000):
            path = Path(folder) / f"fixed{count}.urdf"
            fixed_joint_urdf(count, path)
            t = cpu(lambda path=path: km.load(path), repeats=1)
            print(f"  n = {count:7,d}: {t:.2f} s, {t / count * 1e6:.1f} us a joint")


if __name__ == "__main__":
    main()
