"""Robot files written as users read them: round-off within the line tolerances rounded away."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest
from support import DATA
from support.helpers import run_cli as run

import kinematica as km
from kinematica.dh.lines import AXIS_ANGLE_TOL, AXIS_LENGTH_TOL
from kinematica.robot.rounding import rounded_spec, shortest_within
from kinematica.robot.save import spec_from_robot

DEG = lambda v: v * (math.pi / 180.0)  # noqa: E731  (the reader's conversion)


def test_shortest_within_the_angle_tolerance_boundary() -> None:
    right = math.pi / 2
    assert shortest_within(right + 0.9 * AXIS_ANGLE_TOL, AXIS_ANGLE_TOL, DEG) == DEG(90)
    beyond = right + 1.1 * AXIS_ANGLE_TOL
    assert shortest_within(beyond, AXIS_ANGLE_TOL, DEG) != DEG(90)
    assert abs(shortest_within(beyond, AXIS_ANGLE_TOL, DEG) - beyond) <= AXIS_ANGLE_TOL


def test_rounded_spec_length_tolerance_boundary() -> None:
    arm = km.load("puma560")
    spec = dataclasses.replace(spec_from_robot(arm), units={"angle": "deg", "length": "m"})
    j = spec.joints[2]
    for factor, rounds in ((0.9, True), (1.1, False)):
        moved = dataclasses.replace(j, a=0.4318 + factor * AXIS_LENGTH_TOL)
        out = rounded_spec(
            dataclasses.replace(spec, joints=(*spec.joints[:2], moved, *spec.joints[3:]))
        )
        assert (out.joints[2].a == 0.4318) is rounds


def test_convert_of_a_urdf_writes_round_numbers_and_the_same_arm(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    # Issue 35, item 8: `q1 + 1.1850091143197455e-11` and limits of `360.0000000000237`
    urdf = DATA / "urdf" / "ur5_robot.urdf"
    out = tmp_path / "ur5.yaml"
    code, _, err = run(capsys, "convert", str(urdf), "--to", "dh-modified", "-o", str(out))
    assert code == 0, err
    text = out.read_text()
    assert "e-1" not in text and "360.0000" not in text
    assert "theta: q1," in text and "limits: [-360, 360]" in text
    written, original = km.load(out), km.load(urdf)
    q = np.random.default_rng(3).uniform(-3, 3, (50, 6))
    gap = np.abs(written.fk(q) - original.fk(q)).max()
    assert gap < 1e-8  # moved by no more than the line tolerances (1e-9 rad and m) allow
