"""The command's entry (``cli/main.py``): messages, warnings, version, exit codes, no traceback.

Most tests run ``main([...])`` in-process; the ones marked "console script"
run the installed ``kinematica`` executable (or ``python -m kinematica``) as
a user would. Expected numbers come from the library called directly (the
CLI is a printing layer over it) and, for the round trips, from FK of the
solutions the CLI prints.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import warnings
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from support import ROOT
from support.cli import SCRIPT, one_line, run, script, strict_json
from support.urdf import broken, write

import kinematica as km
from kinematica.cli import options
from kinematica.cli.main import COMMANDS, build_parser, cli_error, cli_words
from kinematica.errors import KinematicaError

# --- version, python -m, help ---------------------------------------------------


def test_version_from_the_console_script_and_python_m() -> None:
    proc = script("--version")
    assert proc.returncode == 0 and proc.stdout.strip() == f"kinematica {km.__version__}"
    proc = subprocess.run(
        [sys.executable, "-m", "kinematica", "--version"],
        capture_output=True,
        text=True,
        check=False,
        timeout=60,
    )
    assert proc.returncode == 0 and proc.stdout.strip() == f"kinematica {km.__version__}"


def _commands(parser: argparse.ArgumentParser) -> set[str]:
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return set(sub.choices)


def test_commands_name_the_module_that_registers_each() -> None:
    # a command line naming a command registers its module alone: the table must say
    # which module that is, for every command the modules register
    assert _commands(build_parser()) == set(COMMANDS)
    for command, module in COMMANDS.items():
        alone = {c for c, m in COMMANDS.items() if m == module}
        assert _commands(build_parser(command)) == alone, command
    assert _commands(build_parser("no-such-command")) == set(COMMANDS)


def test_python_m_kinematica_runs_commands() -> None:
    proc = subprocess.run(
        [sys.executable, "-m", "kinematica", "fk", "planar-3r", "--q", "0", "0", "0", "--json"],
        capture_output=True,
        text=True,
        check=False,
        timeout=60,
    )
    assert proc.returncode == 0, proc.stderr
    assert strict_json(proc.stdout)["robot"] == km.load("planar-3r").name


# --- numbers that are not numbers name their option -------------------------------


def test_messages_speak_options_not_python(capsys: pytest.CaptureFixture[str]) -> None:
    code, _, err = run(capsys, "ik", "panda", "--pose", "0.3", "0", "0.5", "0", "180", "0",
                       "--method", "analytic")  # fmt: skip
    assert code == 2
    line = one_line(err)
    assert "use --method numeric" in line
    assert "method=" not in line and "'numeric'" not in line


@pytest.mark.parametrize(
    ("message", "expected"),
    [
        ("target holds NaN", "--pose holds NaN"),
        ("target: bad", "--pose: bad"),
        ("targets are fine", "targets are fine"),  # a word, not the argument
        ("a\nb\x1b[2J", "a\\nb\\x1b[2J"),
    ],
)
def test_cli_words(message: str, expected: str) -> None:
    assert cli_words(message, {"target": "--pose"}) == expected


@pytest.mark.parametrize(
    ("error", "expected"),
    [
        (
            KinematicaError("no closed-form solver", arg="method", suggest=("method", "numeric")),
            "no closed-form solver; use --method numeric",
        ),
        (
            KinematicaError("tol (position) must be positive", arg="tol"),
            "--tol (position) must be positive",
        ),
        (
            KinematicaError("seed must be a whole number", arg="seed"),
            "--seed must be a whole number",
        ),
        (KinematicaError("target holds NaN or inf", arg="target"), "--pose holds NaN or inf"),
        (KinematicaError("plain words, no argument"), "plain words, no argument"),
    ],
)
def test_errors_in_command_line_words(error: KinematicaError, expected: str) -> None:
    # from the error's fields (arg, suggest), not from its text
    assert cli_error(error, {"target": "--pose"}) == expected
    assert "=" not in cli_error(error, {"target": "--pose"})


@pytest.mark.parametrize(
    ("argv", "fragment"),
    [
        (("ik", "puma560", "--pose", *["0"] * 6, "--seed", "-1"), "--seed: expected a whole"),
        (("ik", "puma560", "--pose", *["0"] * 6, "--seed", "x"), "--seed: expected a whole"),
        (("fk", "puma560", "--q", *["0"] * 6, "--precision", "0"), "--precision: expected"),
        (("fk", "puma560", "--q", *["0"] * 6, "--precision", "18"), "--precision: expected"),
        (("fk", "puma560", "--q", *["0"] * 6, "--units", "km"), "invalid choice: 'km'"),
    ],
)
def test_bad_options_are_one_line(
    capsys: pytest.CaptureFixture[str], argv: tuple[str, ...], fragment: str
) -> None:
    code, _, err = run(capsys, *argv)
    assert code == 2
    assert fragment in one_line(err)


# --- precision ------------------------------------------------------------------------


# --- units of length --------------------------------------------------------------------


# --- warnings, RuntimeWarnings, internal errors -----------------------------------------


def test_a_warning_is_one_line_on_stderr(tmp_path: Path) -> None:
    path = tmp_path / "arm.yaml"
    path.write_text(
        "convention: standard\nunits: {angle: rad, length: m}\n"
        "joints:\n  - {theta: q1, d: 0, a: 1, alpha: 90}\n"
    )
    proc = script("fk", str(path), "--q", "0", "--json")  # console script
    assert proc.returncode == 0
    assert strict_json(proc.stdout)["T"]
    line = one_line(proc.stderr)
    assert line.startswith(f"kinematica: warning: {path}, joint 1, key 'alpha': 90 rad is more")
    assert "KinematicaWarning" not in line and "warnings.warn" not in proc.stderr


def test_a_library_warning_during_a_command_is_one_line(
    capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    fk = km.Robot.fk

    def fk_with_a_bad_row(self: km.Robot, q: Any, all_frames: bool = False) -> np.ndarray:
        fk(self, np.stack([np.asarray(q, dtype=float), np.full(self.dof, np.nan)]))  # warns
        return fk(self, q, all_frames)

    monkeypatch.setattr(km.Robot, "fk", fk_with_a_bad_row)
    code, out, err = run(capsys, "fk", "planar-3r", "--q", "1", "2", "3")
    assert code == 0 and "T:" in out
    assert one_line(err) == (
        "kinematica: warning: q: 1 row(s) hold NaN or inf, their results are NaN: (1,)"
    )


def test_runtime_warnings_print_nothing() -> None:
    proc = script("ik", "ur5", "--pose", "1e300", "0", "0", "0", "0", "0")  # console script
    assert proc.returncode == 1
    assert proc.stderr == ""
    assert "unreachable" in proc.stdout


def test_warnings_filters_are_restored(capsys: pytest.CaptureFixture[str]) -> None:
    before = warnings.filters[:]
    run(capsys, "fk", "planar-3r", "--q", "1", "2", "3")
    assert warnings.filters == before


def test_an_internal_error_is_one_line_with_exit_2(
    capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    def broken(name: str, **kwargs: object) -> km.Robot:
        raise ZeroDivisionError("float division by zero")

    monkeypatch.setattr(options, "load", broken)
    code, out, err = run(capsys, "fk", "puma560", "--q", *["0"] * 6)
    assert code == 2 and out == ""
    line = one_line(err)
    assert line.startswith("kinematica: internal error: ZeroDivisionError: float division by zero")
    assert "please report" in line


# --- hostile robot files and names ----------------------------------------------------------


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs on this system")
def test_a_fifo_robot_file_is_refused_at_once(tmp_path: Path) -> None:
    fifo = tmp_path / "x.yaml"
    os.mkfifo(fifo)
    proc = script("show", str(fifo), timeout=30)  # console script; would hang if opened
    assert proc.returncode == 2
    assert "is a named pipe (FIFO), not a robot file" in one_line(proc.stderr)


# --- the README round trip -------------------------------------------------------------------


def test_the_command_line_page_round_trip_is_true(capsys: pytest.CaptureFixture[str]) -> None:
    text = (ROOT / "docs" / "command-line.md").read_text()
    block = text.split("so that\nwhat `fk` prints can be pasted back into `ik`:", 1)[1]
    block = block.split("```console\n", 1)[1].split("```", 1)[0]
    fk_line, rest = block.split("\n", 1)
    shown, ik_line = rest.rsplit("$ kinematica ik", 1)
    code, out, _ = run(capsys, *fk_line.removeprefix("$ kinematica ").split())
    assert code == 0
    assert out == shown  # the page shows exactly what fk prints
    code, out, _ = run(capsys, "ik", *ik_line.split(), "--json")
    assert code == 0
    data = strict_json(out)
    q = np.array([10, 20, 30, 40, 50, 60])
    assert np.abs(np.array(data["solutions"]) - q).max(axis=1).min() < 1e-6


def test_the_docs_name_the_builtin_robots_in_millimetres(
    capsys: pytest.CaptureFixture[str],
) -> None:
    in_mm = set()
    for name in km.builtin_names():
        code, out, _ = run(capsys, "show", name, "--json")
        assert code == 0
        if strict_json(out)["units"]["length"] == "mm":
            in_mm.add(name)
    assert in_mm == {"irb120", "kr6"}  # as the command-line page says
    page = (ROOT / "docs" / "command-line.md").read_text()
    assert "for `irb120`, `kr6` and any file with" in page


def test_the_all_extra_lists_every_optional_dependency() -> None:
    import tomllib

    extras = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"][
        "optional-dependencies"
    ]
    # docs and bench are tools for working on kinematica, not parts of it
    tools = ("all", "test", "bench", "docs")
    optional = {dep for name, deps in extras.items() if name not in tools
                for dep in deps}  # fmt: skip
    assert optional <= set(extras["all"])
    assert set(extras["docs"]) <= set(extras["test"])  # the tests build the site
    assert set(extras["all"]) <= set(extras["test"])  # CI runs the tests of every part


def test_a_terminal_that_cannot_show_degrees_gets_escapes() -> None:
    if not SCRIPT.exists():  # pragma: no cover - the venv always has it
        pytest.skip("the kinematica console script is not installed next to this python")
    env = dict(os.environ, PYTHONIOENCODING="ascii")
    proc = subprocess.run(
        [str(SCRIPT), "show", "puma560"], capture_output=True, text=True, env=env, timeout=60,
        check=False,
    )  # fmt: skip
    assert proc.returncode == 0 and proc.stderr == ""
    assert "90\\xb0" in proc.stdout  # 90° as an escape, not a crash


# ------------------------------------------------------------------ command line
@pytest.mark.parametrize("command", ["show", "convert"])
def test_cli_reports_a_broken_urdf_in_one_line(tmp_path, command):
    path = write(tmp_path, broken('xyz="0.1 0 0"', 'xyz="nan 0 0"'))
    extra = ["--to", "urdf"] if command == "convert" else []
    proc = subprocess.run(
        [sys.executable, "-m", "kinematica.cli.main", command, str(path), *extra],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        check=False,
    )
    assert proc.returncode == 2
    assert proc.stdout == ""
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1
    assert "joint 'j2'" in lines[0]
    assert "NaN" in lines[0]
