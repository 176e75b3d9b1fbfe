"""Forward kinematics of four published arms against figures computed by other tools.

``data/reference/fk_reference.json`` (see the README beside it) holds, for the
PUMA 560, UR5 (standard DH), Franka Panda (modified DH, flange tool) and the
Stanford arm (prismatic joint 3), 25-26 configurations each with the
base-to-flange transform computed by Pinocchio or the Robotics Toolbox.
"""

from __future__ import annotations

import json
from typing import Any

import numpy as np
import pytest
from support import DATA as TESTS_DATA
from support.helpers import assert_transform_close

from kinematica.dh import Prismatic, Revolute
from kinematica.robot import Robot

DATA = TESTS_DATA / "reference" / "fk_reference.json"
ARMS: dict[str, dict[str, Any]] = {arm["name"]: arm for arm in json.loads(DATA.read_text())["arms"]}

#: The other tools agree with an exact DH product to about 1e-15; 1e-12 leaves room.
ATOL = 1e-12


def build(arm: dict[str, Any]) -> Robot:
    """A Robot from the file's rows: theta of an R row and d of a P row are offsets."""
    rows: list[Revolute | Prismatic] = []
    for j in arm["joints"]:
        if j["type"] == "R":
            rows.append(Revolute(d=j["d"], a=j["a"], alpha=j["alpha"], offset=j["theta"]))
        else:
            assert j["type"] == "P"
            rows.append(Prismatic(theta=j["theta"], a=j["a"], alpha=j["alpha"], offset=j["d"]))
    return Robot.from_dh(rows, convention=arm["convention"], name=arm["name"], tool=arm["tool"])


def samples(arm: dict[str, Any]) -> tuple[np.ndarray, np.ndarray]:
    q = np.array([s["q"] for s in arm["samples"]], dtype=float)
    T = np.array([s["T"] for s in arm["samples"]], dtype=float)
    return q, T


def test_file_holds_the_four_arms() -> None:
    assert set(ARMS) == {"puma560", "ur5", "panda", "stanford"}
    assert ARMS["panda"]["convention"] == "modified"
    assert [j["type"] for j in ARMS["stanford"]["joints"]].count("P") == 1
    for arm in ARMS.values():
        q, T = samples(arm)
        assert len(q) >= 25
        assert q.shape[1] == len(arm["joints"])
        assert T.shape == (len(q), 4, 4)


@pytest.mark.parametrize("name", ["puma560", "ur5", "panda", "stanford"])
def test_fk_matches_reference_batched(name: str) -> None:
    robot = build(ARMS[name])
    q, T = samples(ARMS[name])
    assert_transform_close(robot.fk(q), T, atol=ATOL, err_msg=name)
    assert_transform_close(robot.fk(q, all_frames=True)[:, -1], T, atol=ATOL, err_msg=name)


@pytest.mark.parametrize("name", ["puma560", "ur5", "panda", "stanford"])
def test_fk_matches_reference_one_by_one(name: str) -> None:
    robot = build(ARMS[name])
    q, T = samples(ARMS[name])
    for k, (qk, Tk) in enumerate(zip(q, T, strict=True)):
        assert_transform_close(robot.fk(qk.tolist()), Tk, atol=ATOL, err_msg=f"{name} sample {k}")


@pytest.mark.parametrize("name", ["puma560", "ur5", "panda", "stanford"])
def test_fk_matches_reference_in_the_other_convention(name: str) -> None:
    # Seed 001: the other convention moves the intermediate frames, not the tool.
    robot = build(ARMS[name])
    other = robot.to_convention("standard" if robot.convention == "modified" else "modified")
    q, T = samples(ARMS[name])
    assert_transform_close(other.fk(q), T, atol=ATOL, err_msg=name)
