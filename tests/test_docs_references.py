"""Every name and cross-reference the documents give resolves to something the repository has.

A student follows the docs literally: ``km.euler_rate_matrix`` must be a name of the
package, "the README's arm6-dh example" an example the README shows, a file a comment
cites (``DESIGN.md``) a file of the repository, a path in backticks a path that exists.
"""

from __future__ import annotations

import importlib
import re
import subprocess
from pathlib import Path

import pytest
from support import ROOT

PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]
#: The repository's own text files that may cite documents: sources, tests, docs, build.
TRACKED = subprocess.run(
    ["git", "ls-files"], cwd=ROOT, capture_output=True, text=True, check=True
).stdout.split()
#: Top-level folders a path in backticks may start with (a path of the repository).
TOP = {p.split("/", 1)[0] for p in TRACKED if "/" in p}
#: The files whose text is searched for cited documents.
TEXT_SUFFIXES = {".py", ".md", ".toml", ".hpp", ".cpp", ".txt", ".cfg", ".yaml", ".yml"}
#: This file, which names missing documents on purpose.
THIS = "tests/test_docs_references.py"
_KM_NAME = re.compile(r"(?<![\w.])km\.([A-Za-z_]\w*(?:\.[A-Za-z_]\w*)*)")


def _resolve(dotted: str) -> bool:
    """Whether ``kinematica.<dotted>`` names something (a module, class, function...)."""
    obj: object = importlib.import_module("kinematica")
    parts = dotted.split(".")
    for i, part in enumerate(parts):
        if hasattr(obj, part):
            obj = getattr(obj, part)
            continue
        try:  # a submodule not yet imported
            obj = importlib.import_module("kinematica." + ".".join(parts[: i + 1]))
        except ImportError:
            return False
    return True


def km_names(text: str) -> set[str]:
    """Every ``km.name(.attr)*`` of a text, without a trailing method call's result."""
    return set(_KM_NAME.findall(text))


@pytest.mark.parametrize("page", PAGES, ids=lambda p: str(p.relative_to(ROOT)))
def test_every_km_name_of_a_page_resolves(page: Path) -> None:
    missing = sorted(n for n in km_names(page.read_text()) if not _resolve(n))
    assert missing == [], f"{page.name}: km.{', km.'.join(missing)} do not exist"


def test_every_km_name_of_the_examples_resolves() -> None:
    missing = []
    for path in sorted((ROOT / "examples").glob("*.py")):
        missing += [f"{path.name}: km.{n}" for n in km_names(path.read_text()) if not _resolve(n)]
    assert missing == []


def test_the_resolver_tells_a_name_from_a_missing_one() -> None:
    assert km_names("x = km.euler_rate_matrix(a) + km.spatial.euler_rate_matrix(b)") == {
        "euler_rate_matrix",
        "spatial.euler_rate_matrix",
    }
    assert _resolve("spatial.euler_rate_matrix") and _resolve("Robot.fk")
    assert not _resolve("euler_rate_matrix") and not _resolve("Robot.nothing_here")


def _backticked_paths(text: str) -> set[str]:
    """Paths in backticks that start with a folder of the repository (``docs/x.md``)."""
    found = set()
    for token in re.findall(r"`([^`\s]+)`", text):
        path = token.split("#", 1)[0].split(":", 1)[0].rstrip(".,;")
        if "/" in path and path.split("/", 1)[0] in TOP and "*" not in path and "<" not in path:
            found.add(path)
    return found


@pytest.mark.parametrize("page", PAGES, ids=lambda p: str(p.relative_to(ROOT)))
def test_every_repository_path_a_page_names_exists(page: Path) -> None:
    missing = sorted(p for p in _backticked_paths(page.read_text()) if not (ROOT / p).exists())
    assert missing == [], f"{page.name}: {missing}"


def test_every_document_a_file_cites_is_in_the_repository() -> None:
    """A ``NAME.md`` cited in a source, a test, a doc or the build is a file of the repository."""
    held = {Path(p).name for p in TRACKED}
    cited: list[str] = []
    for rel in TRACKED:
        path = ROOT / rel
        data = rel.startswith("tests/data/") and path.suffix != ".md"  # data, not text
        if path.suffix not in TEXT_SUFFIXES or data or rel == THIS or not path.is_file():
            continue
        for name in set(
            re.findall(r"\b([A-Z][A-Za-z_-]*\.md)\b", path.read_text(errors="replace"))
        ):
            if name not in held:
                cited.append(f"{rel}: {name}")
    assert cited == []


def _readme_examples() -> str:
    """The README's code blocks, one text."""
    return "\n".join(re.findall(r"```\w*\n(.*?)```", (ROOT / "README.md").read_text(), flags=re.S))


def test_every_readme_example_a_page_cites_is_in_the_readme() -> None:
    """Each "the README's X example" of a page names an example the README shows."""
    examples = _readme_examples()
    wrong = []
    for page in PAGES:
        text = re.sub(r"\s+", " ", page.read_text())
        for name in re.findall(r"README's ([\w-]+) example", text):
            if not re.search(rf"\b{re.escape(name)}\b", examples):
                wrong.append(f"{page.name}: the README's {name} example")
    assert wrong == []
