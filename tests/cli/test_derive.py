"""Subcommand ``derive`` (``cli/derive.py``): the report on stdout, in a file, as JSON."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from support.helpers import run_cli as run

pytest.importorskip("sympy")  # the report is derived with sympy


def test_cli_derive_stdout_file_json(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    code, out, _ = run(capsys, "derive", "planar-pr", "--lang", "en")
    assert code == 0 and out.startswith("# Kinematics of Planar PR")
    # a 3-joint arm: the command's plumbing is the same for any (a 6-joint report is
    # tests/symbolic/test_report.py's, and the docs' `derive arm6-dh` runs in test_examples)
    target = tmp_path / "arm.tex"
    code, out, _ = run(
        capsys, "derive", "anthropomorphic-3r", "--format", "latex", "-o", str(target)
    )
    assert code == 0 and target.read_text().startswith("\\documentclass")
    code, out, _ = run(capsys, "derive", "planar-3r", "--format", "html", "--json")
    data = json.loads(out)
    assert code == 0 and data["report"].startswith("<!DOCTYPE html>") and data["lang"] == "es"


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["derive", "nope"], "no built-in robot named 'nope'"),
        (["derive", "planar-pr", "--format", "pdf"], "invalid choice: 'pdf'"),
        (["derive", "planar-pr", "-o", "/nonexistent-dir/x.md"], "cannot write"),
    ],
)
def test_cli_derive_bad_input(
    capsys: pytest.CaptureFixture[str], argv: list[str], message: str
) -> None:
    code, _, err = run(capsys, *argv)
    assert code == 2 and message in err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err
