"""Every example script and every Python block of the README runs."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = sorted((ROOT / "examples").glob("*.py"))


@pytest.mark.parametrize("script", EXAMPLES, ids=[p.name for p in EXAMPLES])
def test_example_runs(script: Path, tmp_path: Path) -> None:
    proc = subprocess.run(
        [sys.executable, str(script)], capture_output=True, text=True, cwd=tmp_path, check=False
    )
    assert proc.returncode == 0, proc.stderr[-3000:]
    assert proc.stdout.strip()


def _readme_blocks() -> list[str]:
    text = (ROOT / "README.md").read_text()
    return re.findall(r"```python\n(.*?)```", text, flags=re.S)


def test_readme_has_python_examples() -> None:
    assert len(_readme_blocks()) >= 2


@pytest.mark.parametrize("index", range(len(_readme_blocks())))
def test_readme_block_runs(index: int, tmp_path: Path) -> None:
    code = _readme_blocks()[index]
    proc = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path, check=False
    )
    assert proc.returncode == 0, proc.stderr[-3000:]


def _readme_shell_commands() -> list[str]:
    text = (ROOT / "README.md").read_text()
    blocks = re.findall(r"```(?:sh|bash|console)\n(.*?)```", text, flags=re.S)
    return [
        line.removeprefix("$ ").strip()
        for block in blocks
        for line in block.splitlines()
        if line.startswith("$ kinematica")
    ]


@pytest.mark.parametrize("command", _readme_shell_commands())
def test_readme_cli_command_runs(command: str, tmp_path: Path) -> None:
    args = command.split()[1:]
    proc = subprocess.run(
        [sys.executable, "-m", "kinematica.cli.main", *args],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        check=False,
    )
    assert proc.returncode in (0, 1), proc.stderr
    assert "Traceback" not in proc.stderr


def _readme_calls() -> list[str]:
    """Names called in the README's sentences (tables left out): `write_csv(path, t, q)`."""
    text = (ROOT / "README.md").read_text()
    prose = re.sub(r"```.*?```", "", text, flags=re.S)
    sentences = "\n".join(line for line in prose.splitlines() if not line.startswith("|"))
    spans = re.findall(r"`([^`\n]+)`", sentences)
    return sorted({m.group(1) for s in spans if (m := re.match(r"([A-Za-z_][\w.]*)\(", s))})


def _resolves(dotted: str) -> bool:
    """True when ``kinematica.motion.write_csv`` (or ``km.load``) names something."""
    import importlib

    parts = ["kinematica", *dotted.split(".")[1:]]
    for k in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:k]))
        except ImportError:
            continue
        for part in parts[k:]:
            if not hasattr(obj, part):
                return False
            obj = getattr(obj, part)
        return True
    return False


def test_readme_prose_names_what_exists() -> None:
    # `km.X(...)` and `kinematica.a.X(...)` must resolve. A function of a subpackage
    # called bare in a sentence (`write_csv(path, t, q)` beside `km.joint_trajectory`)
    # must be a name of `km` or one the README's examples import or call through
    # their module: `km.write_csv` is an AttributeError.
    import importlib

    subpackages = ("motion", "viz", "symbolic", "design", "spatial", "io", "dh", "ik", "robot")
    public = set()
    for sub in subpackages:
        try:
            public |= set(importlib.import_module(f"kinematica.{sub}").__all__)
        except ImportError:  # an optional extra not installed
            continue
    code = "\n".join(_readme_blocks())
    imports = re.findall(r"^from kinematica[\w.]* import \(?([^)\n]*)", code, flags=re.M)
    imported = {name.strip() for line in imports for name in line.split(",")}
    missing = []
    for call in _readme_calls():
        head, *rest = call.split(".")
        if head in ("km", "kinematica"):
            if not _resolves(call):
                missing.append(call)
        elif not rest and head in public:
            known = _resolves(f"km.{head}") or head in imported
            if not known and not re.search(rf"\.{head}\(", code):
                missing.append(call)
    assert not missing, f"README names that do not exist as written: {missing}"
