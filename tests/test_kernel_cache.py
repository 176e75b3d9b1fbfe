"""Pay only for what is used: which kernels a command compiles, and where they are cached.

Each test runs Python in a subprocess (numba's state is per process) and reads
back, as JSON, which kernels hold a compiled or cache-loaded version
(``dispatcher.overloads``) and the dispatchers' cache statistics.
"""

from __future__ import annotations

import json
import os
import shutil
import stat
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest

import kinematica
import kinematica as km

#: Kernel modules FK may use: FK itself and the leaf helpers it inlines.
FK_FAMILY = {"kinematica.kernels.fk", "kinematica.kernels.trig", "kinematica.kernels.arrays"}

#: Prints, as JSON, the kernels (``module.name``) that hold a compiled version.
USED = """
import json, sys
from numba.core.dispatcher import Dispatcher

def used():
    seen = set()
    for name, module in list(sys.modules.items()):
        if name.startswith("kinematica"):
            for obj in vars(module).values():
                if isinstance(obj, Dispatcher) and obj.overloads:
                    seen.add(f"{obj.py_func.__module__}.{obj.py_func.__name__}")
    return sorted(seen)
"""

Q_DEG = ["0", "45", "-30", "0", "20", "0"]


def run_python(code: str, env: dict[str, str] | None = None, *argv: str) -> dict[str, object]:
    """Run ``code`` in a fresh interpreter; its last stdout line is JSON."""
    out = subprocess.run(
        [sys.executable, "-c", code, *argv],
        capture_output=True,
        text=True,
        env=env,
        timeout=600,
    )
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout.strip().splitlines()[-1])  # type: ignore[no-any-return]


def test_cli_fk_compiles_no_ik_kernel() -> None:
    code = (
        USED
        + f"""
import contextlib, io
from kinematica.cli.main import main
with contextlib.redirect_stdout(io.StringIO()):
    status = main(["fk", "puma560", "--q", *{Q_DEG!r}])
after_fk = used()
import kinematica as km
km.load("puma560").jacobian([0.1, 0.2, 0.3, 0.4, 0.5, 0.6])
print(json.dumps({{"status": status, "fk": after_fk, "then_jacobian": used()}}))
"""
    )
    got = run_python(code)
    assert got["status"] == 0
    fk = set(got["fk"])  # type: ignore[arg-type]
    assert "kinematica.kernels.fk.fk_pose" in fk
    assert {name.rsplit(".", 1)[0] for name in fk} <= FK_FAMILY, fk
    # The detector sees other kernels too: a Jacobian is one more, not an IK one.
    more = set(got["then_jacobian"]) - fk  # type: ignore[arg-type]
    assert "kinematica.kernels.jacobian.jacobian_one" in more
    assert not any(".ik_check." in n or ".lm." in n or ".solvers." in n for n in more), more


# ----------------------------------------------------------- read-only package
def _walk_dirs(root: Path) -> Iterator[Path]:
    yield root
    yield from (p for p in root.rglob("*") if p.is_dir())


def _set_writable(root: Path, writable: bool) -> None:
    for d in sorted(_walk_dirs(root), key=lambda p: len(p.parts), reverse=not writable):
        mode = d.stat().st_mode
        bits = stat.S_IWUSR | stat.S_IWGRP | stat.S_IWOTH
        d.chmod(mode | stat.S_IWUSR if writable else mode & ~bits)


@pytest.fixture
def read_only_copy(tmp_path: Path) -> Iterator[Path]:
    """A copy of the kinematica package in a directory nobody may write to."""
    site = tmp_path / "site"
    package = site / "kinematica"
    shutil.copytree(
        Path(kinematica.__file__).parent,
        package,
        ignore=shutil.ignore_patterns("__pycache__", "*.pyc", "*.nbi", "*.nbc"),
    )
    _set_writable(site, False)
    if os.access(package, os.W_OK):
        # root ignores permission bits: a regular file named __pycache__ in
        # every directory makes the package's cache directories as impossible
        # to create as a read-only directory does for everyone else.
        _set_writable(site, True)
        for d in list(_walk_dirs(package)):
            (d / "__pycache__").touch()
        _set_writable(site, False)
    try:
        yield site
    finally:
        _set_writable(site, True)  # let pytest clean up


#: FK of PUMA 560 (when argv asks for it) and a tiny kernel; prints where
#: kinematica came from, T, and the cache hits and misses of both kernels.
RUN = """
import json, sys
import numpy as np
import kinematica as km
from kinematica.kernels.arrays import copy1
from kinematica.kernels.fk import fk_pose
T = None
if "fk" in sys.argv:
    T = km.load("puma560").fk(np.radians([10.0, 20.0, -30.0, 40.0, 50.0, 60.0])).tolist()
copy1(np.empty(3), np.ones(3))
stats = {
    d.py_func.__name__: [sum(d.stats.cache_hits.values()), sum(d.stats.cache_misses.values())]
    for d in (fk_pose, copy1)
}
print(json.dumps({"file": km.__file__, "T": T, **stats}))
"""


def test_read_only_package_caches_in_the_user_cache(read_only_copy: Path, tmp_path: Path) -> None:
    cache = tmp_path / "cache"
    env = {k: v for k, v in os.environ.items() if k != "NUMBA_CACHE_DIR"}
    env.update(
        PYTHONPATH=str(read_only_copy),
        HOME=str(tmp_path / "home"),
        XDG_CACHE_HOME=str(cache),
        PYTHONDONTWRITEBYTECODE="1",
    )
    first = run_python(RUN, env, "fk")
    assert Path(str(first["file"])).is_relative_to(read_only_copy)
    want = km.load("puma560").fk(np.radians([10.0, 20.0, -30.0, 40.0, 50.0, 60.0]))
    np.testing.assert_allclose(first["T"], want, rtol=0, atol=1e-15)  # type: ignore[arg-type]
    assert first["fk_pose"] == [0, 1]  # compiled on first use...
    entries = " ".join(sorted(p.name for p in cache.rglob("*.nbi")))
    assert "fk.fk_pose-" in entries, entries  # ...into the user's cache directory
    assert not [p for p in read_only_copy.rglob("*") if p.suffix in (".nbi", ".nbc")]

    second = run_python(RUN, env, "fk")
    assert second["fk_pose"] == [1, 0]  # loaded, not compiled
    assert second["copy1"] == [1, 0]
    assert second["T"] == first["T"]

    # Another kernel file changes (an edit, an upgrade): numba alone would
    # load copy1 from its cache (its own file is unchanged); our key sees it.
    trig = read_only_copy / "kinematica" / "kernels" / "trig.py"
    _set_writable(read_only_copy, True)
    trig.write_text(trig.read_text() + "\n# an edit\n")
    _set_writable(read_only_copy, False)
    third = run_python(RUN, env)
    assert third["copy1"] == [0, 1]
