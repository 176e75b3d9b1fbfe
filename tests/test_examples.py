"""Every example script, and every Python block and command of the README and the docs, runs."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = sorted((ROOT / "examples").glob("*.py"))
#: The pages whose examples run: the README and every page of the docs site.
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]


def _name(page: Path) -> str:
    return str(page.relative_to(ROOT))


@pytest.mark.parametrize("script", EXAMPLES, ids=[p.name for p in EXAMPLES])
def test_example_runs(script: Path, tmp_path: Path) -> None:
    proc = subprocess.run(
        [sys.executable, str(script)], capture_output=True, text=True, cwd=tmp_path, check=False
    )
    assert proc.returncode == 0, proc.stderr[-3000:]
    assert proc.stdout.strip()


def _python_blocks() -> list[tuple[str, int, str]]:
    found = []
    for page in PAGES:
        blocks = re.findall(r"```python\n(.*?)```", page.read_text(), flags=re.S)
        found += [(_name(page), k, code) for k, code in enumerate(blocks)]
    return found


def _shell_commands() -> list[tuple[str, str]]:
    found = []
    for page in PAGES:
        blocks = re.findall(r"```(?:sh|bash|console)\n(.*?)```", page.read_text(), flags=re.S)
        found += [
            (_name(page), line.removeprefix("$ ").strip())
            for block in blocks
            for line in block.splitlines()
            if line.startswith("$ kinematica")
        ]
    return found


def test_the_readme_and_the_tours_have_python_examples() -> None:
    pages = {page for page, _, _ in _python_blocks()}
    assert "README.md" in pages
    assert {"docs/forward-kinematics.md", "docs/inverse-kinematics.md", "docs/motion.md"} <= pages


@pytest.mark.parametrize(
    ("page", "index", "code"), _python_blocks(), ids=[f"{p}#{k}" for p, k, _ in _python_blocks()]
)
def test_python_block_runs(page: str, index: int, code: str, tmp_path: Path) -> None:
    proc = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path, check=False
    )
    assert proc.returncode == 0, f"{page}, block {index}:\n{proc.stderr[-3000:]}"


@pytest.mark.parametrize(("page", "command"), _shell_commands())
def test_cli_command_runs(page: str, command: str, tmp_path: Path) -> None:
    args = command.split()[1:]
    proc = subprocess.run(
        [sys.executable, "-m", "kinematica.cli.main", *args],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        check=False,
    )
    assert proc.returncode in (0, 1), f"{page}: {command}\n{proc.stderr}"
    assert "Traceback" not in proc.stderr
