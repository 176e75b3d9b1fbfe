"""Start-up costs: ``import kinematica``, first-call compilation, the warm command line.

Everything here runs in subprocesses (numba's compiled code lives per process
and on disk), timed by wall clock and by CPU time (``getrusage`` of the
children): on a machine shared with other jobs the CPU time is the steadier
figure. ``PYTHONDONTWRITEBYTECODE`` is removed from the children's
environment, so that they import from ``.pyc`` files as an installed package
does. Each numba cache used here is a fresh temporary directory
(``NUMBA_CACHE_DIR``): "cold" is an empty cache, "warm" the same cache after
one run.
"""

from __future__ import annotations

import json
import os
import re
import resource
import subprocess
import sys
import tempfile
import textwrap
import time
from dataclasses import dataclass
from pathlib import Path

from _common import table

#: Runs of each warm measurement (best of them is reported).
RUNS = 5


@dataclass(frozen=True)
class Run:
    """One child process: wall time (s), CPU time (s, user + system), its stdout."""

    wall: float
    cpu: float
    out: str


def child(args: list[str], cache: Path | None = None) -> Run:
    """Run ``args``; ``cache`` is its ``NUMBA_CACHE_DIR`` (None: numba's default)."""
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONDONTWRITEBYTECODE",)}
    env.pop("NUMBA_CACHE_DIR", None)
    if cache is not None:
        env["NUMBA_CACHE_DIR"] = str(cache)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    done = subprocess.run(args, capture_output=True, text=True, env=env, check=False)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode not in (0, 1):
        raise RuntimeError(f"{' '.join(args[:4])} ...: {done.stderr.strip()[-500:]}")
    cpu = after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime
    return Run(wall, cpu, done.stdout)


def best(args: list[str], cache: Path | None = None, runs: int = RUNS) -> Run:
    """The shortest wall and the shortest CPU time of ``runs`` runs."""
    done = [child(args, cache) for _ in range(runs)]
    return Run(min(r.wall for r in done), min(r.cpu for r in done), done[-1].out)


def python(code: str) -> list[str]:
    return [sys.executable, "-c", textwrap.dedent(code)]


def seconds(t: float) -> str:
    return f"{t:.2f} s" if t >= 0.995 else f"{t * 1e3:.0f} ms"


# --------------------------------------------------------------------- import
def import_breakdown(runs: int = RUNS) -> dict[str, float]:
    """Seconds of ``import kinematica`` by owner (``-X importtime``, best self time per module)."""
    best_self: dict[str, int] = {}
    for _ in range(runs):
        err = subprocess.run(
            [sys.executable, "-X", "importtime", "-c", "import kinematica"],
            capture_output=True,
            text=True,
            env={k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"},
            check=True,
        ).stderr
        for m in re.finditer(r"import time:\s+(\d+) \|\s+\d+ \| +(\S+)", err):
            us, name = int(m.group(1)), m.group(2)
            best_self[name] = min(best_self.get(name, us), us)
    groups = {"kinematica (ours)": 0, "numba + llvmlite": 0, "numpy": 0, "everything else": 0}
    for name, us in best_self.items():
        top = name.split(".")[0]
        key = {
            "kinematica": "kinematica (ours)",
            "numba": "numba + llvmlite",
            "llvmlite": "numba + llvmlite",
            "numpy": "numpy",
        }.get(top, "everything else")
        groups[key] += us
    ours = sorted(
        ((us, n) for n, us in best_self.items() if n.startswith("kinematica")), reverse=True
    )
    print("    heaviest of ours: " + ", ".join(f"{n} {us / 1e3:.1f} ms" for us, n in ours[:4]))
    return {k: v / 1e6 for k, v in groups.items()}


def bench_import() -> None:
    print("\n== import ==")
    rows = []
    for label, stmt in (
        ("python -c pass (the interpreter)", "pass"),
        ("import numpy", "import numpy"),
        ("import numpy, numba", "import numpy, numba"),
        ("import kinematica", "import kinematica"),
        ("import kinematica.cli.main (the command line)", "import kinematica.cli.main"),
    ):
        r = best(python(stmt), runs=RUNS + 2)
        rows.append([label, seconds(r.wall), seconds(r.cpu)])
    print(f"  best of {RUNS + 2} runs")
    print(table(rows, ["", "wall", "CPU"]))
    print("  -X importtime of `import kinematica`, self time by owner (best of 5 per module):")
    parts = import_breakdown()
    print("    " + "; ".join(f"{k} {v * 1e3:.0f} ms" for k, v in parts.items()))


# ------------------------------------------------------------ compile, per family
FAMILIES = """
import json, time, warnings
import numpy as np
import kinematica as km
warnings.simplefilter("ignore")
rows = []

def first(label, fn):
    c, w = time.process_time(), time.perf_counter()
    fn()
    rows.append((label, time.process_time() - c, time.perf_counter() - w))

puma, panda = km.load("puma560"), km.load("panda")
q = np.radians([10.0, 20.0, -30.0, 40.0, 50.0, 60.0])
Q = np.tile(q, (4, 1))
first("FK, one configuration", lambda: puma.fk(q))
first("FK, every frame", lambda: puma.fk(q, all_frames=True))
first("FK, batch", lambda: puma.fk(Q))
first("Jacobian, one configuration", lambda: puma.jacobian(q))
first("Jacobian, batch", lambda: puma.jacobian(Q))
for name in ("puma560", "ur5", "stanford", "anthropomorphic-3r", "planar-3r", "scara"):
    robot = km.load(name)
    qq = np.clip(np.full(robot.dof, 0.3), robot.qlim[:, 0], robot.qlim[:, 1])
    T = robot.fk(qq)
    res = []
    first(name, lambda: res.append(robot.ik(T)))
    rows[-1] = (f"IK {name} ({res[0].method}), one pose", *rows[-1][1:])
    first(f"IK {name}, batch", lambda: robot.ik(np.stack([T, T])))
T7 = panda.fk(np.full(7, 0.3))
first("numeric IK panda, one target", lambda: panda.ik(T7, method="numeric"))
first("numeric IK panda, batch", lambda: panda.ik(np.stack([T7, T7]), method="numeric"))
print(json.dumps(rows))
"""


def cache_size(path: Path) -> tuple[int, float]:
    files = [p for p in path.rglob("*") if p.is_file()]
    return len(files), sum(p.stat().st_size for p in files) / 1e6


def bench_compile() -> None:
    print("\n== first-call compilation, per kernel family (one process, fresh cache) ==")
    print("  Each row is the first call of its kind in the process, in this order: what")
    print("  it compiles (cold) or loads from the on-disk cache (warm) beyond the rows above.")
    with tempfile.TemporaryDirectory() as tmp:
        cache = Path(tmp)
        cold = child(python(FAMILIES), cache)
        warm = child(python(FAMILIES), cache)
        rows = []
        for (label, c_cpu, c_wall), (_, w_cpu, _) in zip(
            json.loads(cold.out), json.loads(warm.out), strict=True
        ):
            rows.append([label, seconds(c_cpu), seconds(c_wall), seconds(w_cpu)])
        print(table(rows, ["", "cold CPU", "cold wall", "warm CPU (cache load)"]))
        files, mb = cache_size(cache)
        print(f"  whole process: cold {seconds(cold.wall)} wall / {seconds(cold.cpu)} CPU,")
        print(f"  warm {seconds(warm.wall)} / {seconds(warm.cpu)}; the cache holds every")
        print(f"  kernel above: {files} files, {mb:.1f} MB")


# -------------------------------------------------------------- the command line
USED_KERNELS = """
import contextlib, io, json, sys
from numba.core.dispatcher import Dispatcher
from kinematica.cli.main import main
with contextlib.redirect_stdout(io.StringIO()):
    main(sys.argv[1:])
used = sorted({
    f"{d.py_func.__module__}.{d.py_func.__name__}"
    for name, m in list(sys.modules.items()) if name.startswith("kinematica")
    for d in vars(m).values() if isinstance(d, Dispatcher) and d.overloads
})
print(json.dumps(used))
"""

FLOOR = """
import numba
@numba.njit(cache=True)
def f(x):
    return x + 1.0
"""


def cli() -> list[str]:
    script = Path(sys.executable).with_name("kinematica")
    return [str(script)] if script.exists() else [sys.executable, "-m", "kinematica"]


#: Runs the command line in a process where ``import scipy`` fails, as on a
#: core install (numpy + numba): numba imports scipy.linalg when it is there.
NO_SCIPY = """
import sys
sys.modules["scipy"] = None
from kinematica.cli.main import main
sys.exit(main(sys.argv[1:]))
"""


def bench_cli(q_deg: list[float], pose: list[float]) -> dict[str, tuple[float, float]]:
    """Cold and warm ``kinematica fk`` / ``ik``; returns their warm (wall, CPU) times."""
    print("\n== the command line (subprocess wall time and CPU time) ==")
    fk = ["fk", "puma560", "--q", *map(str, q_deg)]
    ik = ["ik", "puma560", "--pose", *(f"{v:.9g}" for v in pose)]
    rows = []
    out: dict[str, tuple[float, float]] = {}
    with tempfile.TemporaryDirectory() as tmp:
        for label, args in (("kinematica fk puma560 --q ...", fk), ("kinematica ik ...", ik)):
            cache = Path(tmp) / args[0]
            cold = child([*cli(), *args], cache)
            warm = best([*cli(), *args], cache)
            rows.append([label, seconds(cold.wall), seconds(cold.cpu), seconds(warm.wall)])
            rows[-1].append(seconds(warm.cpu))
            out[args[0]] = (warm.wall, warm.cpu)
            bare = best([*python(NO_SCIPY), *args], cache)
            rows.append(["  the same without scipy installed", "", "", seconds(bare.wall)])
            rows[-1].append(seconds(bare.cpu))
        module = Path(tmp) / "floor"
        module.mkdir()
        (module / "floor.py").write_text(textwrap.dedent(FLOOR))
        for label, block in (("", ""), (", no scipy", "sys.modules['scipy'] = None; ")):
            floor = python(f"import sys; {block}sys.path.insert(0, {str(module)!r})")
            floor[-1] += "\nimport numpy, floor; floor.f(1.0)"
            child(floor, Path(tmp) / "floor-cache")
            r = best(floor, Path(tmp) / "floor-cache")
            rows.append([f"floor{label}: numpy, numba, one cached trivial kernel", "", ""])
            rows[-1] += [seconds(r.wall), seconds(r.cpu)]
        used = json.loads(child([*python(USED_KERNELS), *fk], Path(tmp) / "fk").out)
    print(f"  cold: empty numba cache; warm: best of {RUNS} runs after it. The floor is")
    print("  numba's own start-up (import, then its first load of a cached kernel)")
    print(table(rows, ["", "cold wall", "cold CPU", "warm wall", "warm CPU"]))
    print(f"  kernels `kinematica fk` compiled or loaded: {', '.join(used)}")
    return out
