"""Hostile robot files: size, type and count limits, BOMs, YAML merge keys, long expressions.

Each limit is pinned on both sides: the largest accepted input loads, one more
is refused with a message naming the limit (so a 1000x larger or smaller
constant fails a test). "Refused quickly" is checked by the message naming the
limit, which is only reached when the check runs before the expensive work.
"""

from __future__ import annotations

import json
import math
import os
import sys
from pathlib import Path
from typing import Any

import pytest

import kinematica as km
from kinematica.errors import ArgumentError, KinematicaError, RobotFileError
from kinematica.io import load_robot_text, parse_robot_dict, read_robot_file
from kinematica.io._parse import MAX_JOINTS, MAX_PARAMETERS
from kinematica.io.expr import MAX_DEPTH, MAX_LENGTH, ExpressionError, evaluate
from kinematica.io.robotfile import MAX_FILE_SIZE

ONE_JOINT = '{"convention": "standard", "joints": [{"theta": "q1", "d": 0, "a": 1, "alpha": 0}]}'


def _joints(n: int) -> dict[str, Any]:
    rows = [{"theta": f"q{i}", "d": 0, "a": 0.1, "alpha": 0} for i in range(1, n + 1)]
    return {"convention": "standard", "joints": rows}


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


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs on this system")
def test_a_fifo_is_refused_without_waiting_for_a_writer(tmp_path: Path) -> None:
    fifo = tmp_path / "pipe.yaml"
    os.mkfifo(fifo)
    with pytest.raises(RobotFileError, match=r"pipe\.yaml: is a named pipe \(FIFO\), not a robot"):
        read_robot_file(fifo)  # opening it would block until a writer came


@pytest.mark.skipif(not Path("/dev/zero").exists(), reason="no /dev/zero")
def test_a_device_is_refused_without_reading_it(tmp_path: Path) -> None:
    link = tmp_path / "zero.yaml"
    link.symlink_to("/dev/zero")
    with pytest.raises(RobotFileError, match=r"zero\.yaml: is a device, not a robot file"):
        read_robot_file(link)  # reading it would never end


def test_a_directory_is_refused_by_load_and_by_write(tmp_path: Path) -> None:
    folder = tmp_path / "x.yaml"
    folder.mkdir()
    with pytest.raises(RobotFileError, match=r"x\.yaml: is a directory, not a robot file"):
        km.load(folder)
    with pytest.raises(RobotFileError, match="is a directory, not a robot file: not written"):
        km.load("puma560").save(folder)


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs on this system")
def test_saving_to_a_fifo_is_refused_without_waiting_for_a_reader(tmp_path: Path) -> None:
    fifo = tmp_path / "pipe.json"
    os.mkfifo(fifo)
    with pytest.raises(RobotFileError, match="is a named pipe"):
        km.load("planar-3r").save(fifo)


# --- joints, parameters, expressions ------------------------------------------


def test_max_joints_load_and_one_more_is_refused() -> None:
    assert parse_robot_dict(_joints(MAX_JOINTS)).dof == MAX_JOINTS
    with pytest.raises(RobotFileError, match=rf"key 'joints': {MAX_JOINTS + 1} joints; at most"):
        parse_robot_dict(_joints(MAX_JOINTS + 1))


def test_a_20000_joint_json_is_refused_before_its_joints_are_read(tmp_path: Path) -> None:
    path = tmp_path / "snake.json"
    path.write_text(json.dumps(_joints(20_000), separators=(",", ":")))
    with pytest.raises(RobotFileError, match=f"robot files of at most {MAX_FILE_SIZE:,} bytes"):
        km.load(path)
    with pytest.raises(RobotFileError, match=r"20000 joints; at most 100 are accepted"):
        parse_robot_dict(_joints(20_000))  # the joint count is checked before any joint


def test_max_parameters_load_and_one_more_is_refused() -> None:
    data = _joints(1)
    data["parameters"] = {f"p{i}": i for i in range(MAX_PARAMETERS)}
    assert len(parse_robot_dict(data).parameters) == MAX_PARAMETERS
    data["parameters"][f"p{MAX_PARAMETERS}"] = 0
    with pytest.raises(RobotFileError, match=rf"{MAX_PARAMETERS + 1} parameters; at most"):
        parse_robot_dict(data)


def test_an_unknown_name_lists_a_few_known_names_only() -> None:
    data = _joints(1)
    data["parameters"] = {f"p{i:03d}": i for i in range(500)}
    data["joints"][0]["a"] = "nope"
    with pytest.raises(RobotFileError, match=r"unknown name 'nope'") as info:
        parse_robot_dict(data)
    assert "p000, p001" in str(info.value) and "p499" not in str(info.value)
    assert len(str(info.value)) < 400


def _sum(terms: int) -> str:
    return "q1" + " + 1" * (terms - 1)


def test_expression_of_max_length_evaluates_and_one_character_more_is_refused() -> None:
    terms = (MAX_LENGTH + 1) // 2
    text = ("1" + "+1" * (terms - 1)).ljust(MAX_LENGTH)
    assert len(text) == MAX_LENGTH
    assert evaluate(text).const == terms
    with pytest.raises(ExpressionError, match=rf"{MAX_LENGTH + 1} characters long; at most"):
        evaluate(text + "1")


def test_a_1000_term_expression_is_an_error_not_a_recursion_error() -> None:
    with pytest.raises(ExpressionError, match=f"at most {MAX_LENGTH} are accepted") as info:
        evaluate(_sum(1000))
    assert len(str(info.value)) < 300  # the text is shown cut short
    assert isinstance(info.value, KinematicaError)
    data = _joints(1)
    data["joints"][0]["theta"] = _sum(1000)
    with pytest.raises(RobotFileError, match="joint 1, key 'theta': the expression is 3998"):
        parse_robot_dict(data)


def test_long_expressions_need_no_deep_recursion() -> None:
    # A sum is one node with many terms, not a chain of nested nodes: an
    # expression of the longest accepted length evaluates with little stack.
    limit = sys.getrecursionlimit()
    depth = len(__import__("inspect").stack())
    sys.setrecursionlimit(depth + 60)
    try:
        form = evaluate(_sum(MAX_LENGTH // 4))
        product = evaluate("*".join(["1"] * (MAX_LENGTH // 2)))
    finally:
        sys.setrecursionlimit(limit)
    assert form.coeffs == {"q1": 1.0} and form.const == MAX_LENGTH // 4 - 1
    assert product.const == 1.0


def test_depth_limit_still_holds_within_the_length_limit() -> None:
    assert evaluate("(" * MAX_DEPTH + "1" + ")" * MAX_DEPTH).const == 1.0
    with pytest.raises(ExpressionError, match=f"nested deeper than {MAX_DEPTH}"):
        evaluate("(" * (MAX_DEPTH + 1) + "1" + ")" * (MAX_DEPTH + 1))


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


@pytest.mark.parametrize("bad", [None, 3, 2.5, ["puma560"], b"puma560"])
def test_load_of_a_non_path_is_an_argument_error(bad: object) -> None:
    with pytest.raises(ArgumentError, match="load takes a built-in robot name or"):
        km.load(bad)  # type: ignore[arg-type]


@pytest.mark.parametrize("bad", ["", "   "])
def test_load_of_an_empty_name_is_an_argument_error(bad: str) -> None:
    with pytest.raises(ArgumentError, match="load takes a built-in robot name or a path"):
        km.load(bad)


def test_load_of_a_name_too_long_for_the_file_system_is_unknown() -> None:
    with pytest.raises(km.UnknownRobotError):
        km.load("x" * 5000)
    with pytest.raises(KinematicaError):
        km.load("a\x00b.yaml")


def test_read_robot_file_of_a_non_path_is_an_argument_error() -> None:
    with pytest.raises(ArgumentError, match="expected a path"):
        read_robot_file(None)  # type: ignore[arg-type]
    with pytest.raises(ArgumentError, match="takes text and a suffix"):
        load_robot_text(b"{}", ".json")  # type: ignore[arg-type]
