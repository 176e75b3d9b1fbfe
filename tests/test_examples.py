"""Every example script, and every Python block and command of the README and the docs, runs."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest
from support import ROOT
from support.cli import run

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
def test_python_block_runs(
    page: str, index: int, code: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # In-process, in a namespace of its own (it imports what it uses, as a reader's
    # session would): a Python start per block would cost more than most blocks.
    monkeypatch.chdir(tmp_path)
    try:
        exec(compile(code, f"{page}, block {index}", "exec"), {"__name__": "__main__"})
    finally:
        if "matplotlib.pyplot" in sys.modules:
            sys.modules["matplotlib.pyplot"].close("all")


@pytest.mark.parametrize(("page", "command"), _shell_commands())
def test_cli_command_runs(
    page: str,
    command: str,
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    capsys: pytest.CaptureFixture[str],
) -> None:
    # In-process: the same main() the console script calls, without a Python start per
    # command (tests/cli/test_main.py runs the installed script itself).
    monkeypatch.chdir(tmp_path)
    code, _, err = run(capsys, *command.split()[1:])
    assert code in (0, 1), f"{page}: {command}\n{err}"
    assert "internal error" not in err


def _prose_calls(page: Path) -> list[str]:
    """Names called in a page's sentences (tables left out): `write_csv(path, t, q)`."""
    text = page.read_text()
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


@pytest.mark.parametrize("page", PAGES, ids=_name)
def test_prose_names_what_exists(page: Path) -> None:
    # `km.X(...)` and `kinematica.a.X(...)` must resolve. A function of a subpackage
    # called bare in a sentence (`write_csv(path, t, q)` beside `km.joint_trajectory`)
    # must be a name of `km` or one the page's examples import or call through
    # their module: `km.write_csv` is an AttributeError.
    import importlib

    subpackages = ("motion", "viz", "symbolic", "design", "spatial", "io", "dh", "ik", "robot")
    public = set()
    for sub in subpackages:
        try:
            public |= set(importlib.import_module(f"kinematica.{sub}").__all__)
        except ImportError:  # an optional extra not installed
            continue
    code = "\n".join(re.findall(r"```python\n(.*?)```", page.read_text(), flags=re.S))
    imports = re.findall(r"^from kinematica[\w.]* import \(?([^)\n]*)", code, flags=re.M)
    imported = {name.strip() for line in imports for name in line.split(",")}
    missing = []
    for call in _prose_calls(page):
        head, *rest = call.split(".")
        if head in ("km", "kinematica"):
            if not _resolves(call):
                missing.append(call)
        elif not rest and head in public:
            known = _resolves(f"km.{head}") or head in imported
            if not known and not re.search(rf"\.{head}\(", code):
                missing.append(call)
    assert not missing, f"{_name(page)}: names that do not exist as written: {missing}"
