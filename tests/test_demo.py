"""``make demo`` installs what the demo uses and nothing else (issue 35, item 1).

On a fresh clone the demo installed the test tools (``.[test]``: Dask, MkDocs,
Jupyter, linters: 726 MB, 78 s on an idle machine) to print a tour that needs numpy
and the compiled core. The demo's own install is kinematica alone, and the tour runs
with every optional dependency out of reach.
"""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from support import ROOT

#: The optional dependencies (pyproject's extras) and the test tools: the demo needs none.
OPTIONAL = (
    "yaml",
    "xacro",
    "matplotlib",
    "PIL",
    "scipy",
    "sympy",
    "dask",
    "distributed",
    "mkdocs",
    "playwright",
    "hypothesis",
    "nbclient",
    "ipykernel",
    "pytest",
)

_BLOCK = """
import importlib.abc, sys
class Block(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] in {names!r}:
            raise ImportError(f"{{name}} is not installed (blocked by the test)")
        return None
sys.meta_path.insert(0, Block())
import runpy
runpy.run_path({script!r}, run_name="__main__")
"""


def test_the_demo_runs_on_numpy_and_the_core_alone() -> None:
    script = str(ROOT / "examples" / "01_demo.py")
    code = _BLOCK.format(names=set(OPTIONAL), script=script)
    proc = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=False, timeout=120
    )
    assert proc.returncode == 0, proc.stderr[-2000:]
    assert "Inverse kinematics" in proc.stdout


@pytest.mark.skipif(shutil.which("make") is None, reason="make is not installed")
def test_make_demo_on_a_fresh_clone_installs_kinematica_alone(tmp_path: Path) -> None:
    venv = tmp_path / "venv"  # a fresh clone: no venv yet (make -n runs nothing but $(MAKE))
    proc = subprocess.run(
        ["make", "-n", "demo", f"VENV={venv}"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=False,
        timeout=60,
    )
    assert proc.returncode == 0, proc.stderr
    installs = [line for line in proc.stdout.splitlines() if "pip install" in line]
    assert installs, proc.stdout
    assert all("[" not in line for line in installs), installs  # no extra: no test tools
    assert any(line.rstrip().endswith("-e .") for line in installs), installs
    assert "examples/01_demo.py" in proc.stdout


@pytest.mark.skipif(shutil.which("make") is None, reason="make is not installed")
def test_make_test_after_the_demo_adds_the_test_tools_without_a_second_build(
    tmp_path: Path,
) -> None:
    # the demo's venv (its stamp newer than every source): `make test` installs the test
    # extra's requirements, read from pyproject.toml, and does not build kinematica again
    venv = tmp_path / "venv"
    venv.mkdir()
    (venv / ".installed-core").touch()
    proc = subprocess.run(["make", "-n", "test", f"VENV={venv}"], cwd=ROOT, capture_output=True,
                          text=True, check=False, timeout=60)  # fmt: skip
    assert proc.returncode == 0, proc.stderr
    assert '["optional-dependencies"]["test"]' in proc.stdout
    assert f"-newer {venv}/.installed-core" in proc.stdout
