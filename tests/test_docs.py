"""The README fits on a page and its links resolve; the docs site builds and covers the API."""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from support import ROOT

import kinematica as km

README_MAX_LINES = 150


def _links(page: Path) -> list[str]:
    text = re.sub(r"```.*?```", "", page.read_text(), flags=re.S)
    return re.findall(r"\]\(([^)\s]+)\)", text)


def test_the_readme_fits_on_a_page() -> None:
    assert len((ROOT / "README.md").read_text().splitlines()) <= README_MAX_LINES


@pytest.mark.parametrize("page", [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))],
                         ids=lambda p: p.name)  # fmt: skip
def test_every_relative_link_resolves(page: Path) -> None:
    for link in _links(page):
        if re.match(r"[a-z]+:", link) or link.startswith("#"):
            continue
        target = link.split("#", 1)[0]
        assert (page.parent / target).exists(), f"{page.name}: {link}"


def test_every_public_name_has_a_reference_entry() -> None:
    reference = "\n".join(p.read_text() for p in (ROOT / "docs" / "reference").glob("*.md"))
    entries = set(re.findall(r"^::: kinematica(?:\.\w+)*\.(\w+)$", reference, flags=re.M))
    missing = [n for n in km.__all__ if not n.startswith("_") and n not in entries]
    assert missing == []


def test_no_page_narrates_an_earlier_version() -> None:
    pattern = re.compile(r"release before|earlier version|previous release|used to be|numba")
    for page in [ROOT / "README.md", *(ROOT / "docs").rglob("*.md")]:
        assert not pattern.search(page.read_text()), page.name


@pytest.mark.skipif(shutil.which("mkdocs", path=str(Path(sys.executable).parent)) is None,
                    reason="mkdocs is not installed (the docs extra)")  # fmt: skip
def test_the_site_builds_strictly(tmp_path: Path) -> None:
    mkdocs = Path(sys.executable).parent / "mkdocs"
    proc = subprocess.run(
        [str(mkdocs), "build", "--strict", "--quiet", "--site-dir", str(tmp_path / "site")],
        cwd=ROOT, capture_output=True, text=True, check=False,
    )  # fmt: skip
    assert proc.returncode == 0, proc.stderr[-3000:]
    index = (tmp_path / "site" / "index.html").read_text()
    assert "kinematica" in index
    reference = (tmp_path / "site" / "reference" / "kinematica" / "index.html").read_text()
    assert "to_pose" in reference and "Robot" in reference
