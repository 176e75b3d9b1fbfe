"""Running the command line in tests (in-process, or as the installed script) and reading it."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from kinematica.cli.main import main

SCRIPT = Path(sys.executable).with_name("kinematica")


def run(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    """Run the CLI in-process; argparse's SystemExit becomes an exit code."""
    try:
        code = main(list(argv))
    except SystemExit as exc:
        code = int(exc.code or 0)
    out, err = capsys.readouterr()
    return code, out, err


def script(*argv: str, timeout: float = 60) -> subprocess.CompletedProcess[str]:
    """Run the installed console script, as a user would."""
    if not SCRIPT.exists():  # pragma: no cover - the venv always has it
        pytest.skip("the kinematica console script is not installed next to this python")
    return subprocess.run(
        [str(SCRIPT), *argv], capture_output=True, text=True, timeout=timeout, check=False
    )


def strict_json(text: str) -> Any:
    """JSON as the standard defines it: NaN and Infinity are not JSON."""

    def refuse(token: str) -> None:
        raise AssertionError(f"not valid JSON: {token}")

    return json.loads(text, parse_constant=refuse)


def one_line(err: str) -> str:
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert len(lines) == 1, err
    assert "Traceback" not in err
    return lines[0]
