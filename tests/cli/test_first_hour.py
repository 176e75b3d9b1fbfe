"""The command line as a first-time user meets it (issue 35, item 9).

Every option explains itself in --help, a command offers no option that does
nothing there, and the mistakes of a first robot file are said in its words.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import pytest
from support.helpers import run_cli as run

import kinematica as km
from kinematica.cli.main import build_parser


def _commands() -> dict[str, argparse.ArgumentParser]:
    sub = next(a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction))
    return dict(sub.choices)


def test_every_option_of_every_command_has_a_help_text() -> None:
    missing = [
        f"{name} {'/'.join(action.option_strings)}"
        for name, parser in _commands().items()
        for action in parser._actions
        if action.option_strings and action.help is None
    ]
    assert missing == []


def test_robots_help_offers_no_option_that_does_nothing_there() -> None:
    text = _commands()["robots"].format_help()
    assert "--euler" not in text and "--rad" not in text and "--units" not in text
    assert "--json" in text


def test_reversed_limits_say_the_values(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    path = tmp_path / "rev.yaml"
    path.write_text(
        "name: rev\nconvention: standard\nunits: {angle: deg, length: m}\njoints:\n"
        "  - {theta: q1, d: 0.3, a: 0.2, alpha: 0, limits: [90, -90]}\n"
    )
    code, _, err = run(capsys, "show", str(path))
    assert code == 2 and "found [90, -90] (lower > upper" in err


def test_a_yaml_tab_is_named_as_such(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    path = tmp_path / "tab.yaml"
    path.write_text(
        "name: tab\nconvention: standard\njoints:\n\t- {theta: q1, d: 0, a: 1, alpha: 0}\n"
    )
    code, _, err = run(capsys, "show", str(path))
    assert code == 2 and "line 4 is indented with a tab" in err


def test_ur10_is_a_built_in_robot() -> None:
    assert km.load("ur10").name == "UR10"
