"""Hostile robot files (``io/robotfile.py``): the size limit, BOMs, YAML merge keys, arguments.

Each limit is pinned on both sides: the largest accepted input loads, one more
is refused with a message naming the limit (so a 1000x larger or smaller
constant fails a test). "Refused quickly" is checked by the message naming the
limit, which is only reached when the check runs before the expensive work.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

import kinematica as km
from kinematica.errors import ArgumentError, RobotFileError
from kinematica.io import load_robot_text, read_robot_file
from kinematica.io.robotfile import MAX_FILE_SIZE

ONE_JOINT = '{"convention": "standard", "joints": [{"theta": "q1", "d": 0, "a": 1, "alpha": 0}]}'


# --- file size and type -------------------------------------------------------


def _padded_json(size: int) -> bytes:
    """A valid one-joint JSON robot file of exactly ``size`` bytes (trailing spaces)."""
    text = ONE_JOINT.encode()
    return text + b" " * (size - len(text))


def test_a_file_of_max_size_loads_and_one_byte_more_is_refused(tmp_path: Path) -> None:
    ok = tmp_path / "max.json"
    ok.write_bytes(_padded_json(MAX_FILE_SIZE))
    assert read_robot_file(ok).dof == 1
    big = tmp_path / "big.json"
    big.write_bytes(_padded_json(MAX_FILE_SIZE + 1))
    with pytest.raises(RobotFileError, match=rf"big\.json: the file is {MAX_FILE_SIZE + 1:,} byte"):
        read_robot_file(big)


def test_a_50_mb_yaml_is_refused_before_it_is_read(tmp_path: Path) -> None:
    path = tmp_path / "huge.yaml"
    with path.open("wb") as f:  # sparse: no 50 MB written to disk
        f.truncate(50_000_000)
    limit = f"robot files of at most {MAX_FILE_SIZE:,} bytes are read"
    with pytest.raises(RobotFileError, match=f"the file is 50,000,000 bytes; {limit}"):
        read_robot_file(path)
    with pytest.raises(RobotFileError, match=limit):
        km.load(path)


def test_text_longer_than_the_limit_is_refused() -> None:
    with pytest.raises(RobotFileError, match=rf"{MAX_FILE_SIZE + 1:,} characters; robot files"):
        load_robot_text(ONE_JOINT + " " * (MAX_FILE_SIZE + 1 - len(ONE_JOINT)), ".json")


# --- joints, parameters, expressions ------------------------------------------


# --- byte-order marks and YAML merge keys -------------------------------------


@pytest.mark.parametrize(
    ("suffix", "text"),
    [
        (".json", ONE_JOINT),
        (".toml", 'convention = "standard"\njoints = [{theta = "q1", d = 0, a = 1, alpha = 0}]\n'),
        (".yaml", "convention: standard\njoints:\n  - {theta: q1, d: 0, a: 1, alpha: 0}\n"),
    ],
)
def test_a_utf8_bom_is_accepted_in_every_format(tmp_path: Path, suffix: str, text: str) -> None:
    path = tmp_path / f"bom{suffix}"
    path.write_bytes(b"\xef\xbb\xbf" + text.encode())
    assert read_robot_file(path).joints[0].a == 1.0
    assert load_robot_text("\ufeff" + text, suffix).joints[0].a == 1.0


def test_yaml_merge_keys_are_accepted() -> None:
    text = """
convention: standard
units: {angle: deg, length: m}
joints:
  - &wrist {theta: q1, d: 0, a: 0, alpha: 90}
  - {<<: *wrist, theta: q2, alpha: -90}
  - <<: *wrist
    theta: q3
    d: 0.1
"""
    spec = load_robot_text(text, ".yaml")
    assert [j.alpha for j in spec.joints] == [math.pi / 2, -math.pi / 2, math.pi / 2]
    assert [j.d for j in spec.joints] == [0.0, 0.0, 0.1]


def test_yaml_merge_of_a_list_of_mappings() -> None:
    text = """
convention: standard
parameters: {l1: 1, l2: 2}
joints:
  - &j1 {theta: q1, d: 0, a: l1, alpha: 0}
  - {<<: *j1, theta: q2, a: l2}
  - {<<: [{d: 0.5}, *j1], theta: q3}
"""
    spec = load_robot_text(text, ".yaml")
    # In a list of merged mappings the first to give a key wins (d = 0.5).
    assert [j.a for j in spec.joints] == [1.0, 2.0, 1.0]
    assert [j.d for j in spec.joints] == [0.0, 0.0, 0.5]


def test_duplicate_keys_are_still_refused_next_to_a_merge() -> None:
    text = """
convention: standard
joints:
  - &a {theta: q1, d: 0, a: 1, alpha: 0}
  - {<<: *a, theta: q2, a: 2, a: 3}
"""
    with pytest.raises(RobotFileError, match="the key 'a' appears twice"):
        load_robot_text(text, ".yaml")


# --- arguments of the API -----------------------------------------------------


def test_read_robot_file_of_a_non_path_is_an_argument_error() -> None:
    with pytest.raises(ArgumentError, match="expected a path"):
        read_robot_file(None)  # type: ignore[arg-type]
    with pytest.raises(ArgumentError, match="takes text and a suffix"):
        load_robot_text(b"{}", ".json")  # type: ignore[arg-type]
