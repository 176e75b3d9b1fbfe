"""One rule for a DH table without a convention: standard, with a ConventionWarning.

The same in Python (``Robot.from_dh(rows)``), in a robot file without the key
``convention``, and on the command line (one line on stderr). Every table of the
repository names its convention: pyproject.toml turns this warning into an error
for the whole suite, so a call that leaves it out fails its test.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest

import kinematica as km
from kinematica.cli.main import main
from kinematica.io.robotfile import parse_robot_dict

ROWS = [km.Revolute(d=0.4, alpha=np.pi / 2), km.Revolute(a=0.3), km.Revolute(a=0.25)]
SAID = (
    r"no DH convention given: read as standard \(Paul, distal\); "
    r"{say} or 'modified' \(Craig, proximal\)"
)
FILE = """\
name: three
units: {angle: deg, length: m}
joints:
  - {theta: q1, d: 0.4, a: 0, alpha: 90}
  - {theta: q2, d: 0, a: 0.3, alpha: 0}
  - {theta: q3, d: 0, a: 0.25, alpha: 0}
"""


def test_from_dh_without_a_convention_reads_standard_and_says_so() -> None:
    with pytest.warns(
        km.ConventionWarning, match=SAID.format(say="say convention='standard'")
    ) as w:
        robot = km.Robot.from_dh(ROWS)
    assert len(w) == 1 and w[0].filename == __file__  # it points at the caller's line
    assert issubclass(km.ConventionWarning, km.KinematicaWarning)
    standard = km.Robot.from_dh(ROWS, convention="standard")
    modified = km.Robot.from_dh(ROWS, convention="modified")
    q = [0.3, 0.5, -0.4]
    assert robot.convention == "standard"
    np.testing.assert_array_equal(robot.fk(q), standard.fk(q))
    assert np.abs(robot.fk(q) - modified.fk(q)).max() > 0.1  # the choice matters


@pytest.mark.parametrize("word", ["standard", "modified", "dh", "craig"])
def test_no_warning_when_the_convention_is_given(word: str, tmp_path: Path) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        km.Robot.from_dh(ROWS, convention=word)
        path = tmp_path / "three.yaml"
        path.write_text(f"convention: {word}\n" + FILE)
        km.load(path)


def test_a_file_without_convention_reads_standard_naming_the_file_and_key(
    tmp_path: Path,
) -> None:
    path = tmp_path / "three.yaml"
    path.write_text(FILE)
    said = SAID.format(say="add convention: standard")
    with pytest.warns(km.ConventionWarning, match=f"three.yaml, key 'convention': {said}"):
        robot = km.load(path)
    assert robot.convention == "standard"
    path.write_text("convention: standard\n" + FILE)
    q = [0.3, 0.5, -0.4]
    np.testing.assert_array_equal(robot.fk(q), km.load(path).fk(q))
    # data parsed with no file named says so too
    with pytest.warns(km.ConventionWarning, match="the robot data, key 'convention'"):
        parse_robot_dict({"joints": [{"theta": "q1", "d": 0, "a": 1, "alpha": 0}]})


def test_the_command_line_prints_it_as_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    path = tmp_path / "three.yaml"
    path.write_text(FILE)
    assert main(["fk", str(path), "--q", "10", "20", "30"]) == 0
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 1
    assert err[0].startswith(f"kinematica: warning: {path}, key 'convention': no DH convention")
    path.write_text("convention: modified\n" + FILE)
    assert main(["fk", str(path), "--q", "10", "20", "30"]) == 0
    assert capsys.readouterr().err == ""
