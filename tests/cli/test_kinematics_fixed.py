"""``kinematica ik --fixed JOINT=VALUE``: a joint held at a value, in the command line's units."""

from __future__ import annotations

import numpy as np
import pytest
from support.cli import one_line, run, strict_json

import kinematica as km

Q = np.array([0.3, 0.5, -0.2, -1.2, 0.4, 0.9, 0.2])


def matrix() -> list[str]:
    return [repr(float(v)) for v in km.load("iiwa14").fk(Q).ravel()]


def test_fixed_in_degrees_every_solution_holds_it(capsys: pytest.CaptureFixture[str]) -> None:
    robot = km.load("iiwa14")
    q1 = float(np.degrees(Q[0]))
    code, out, _ = run(
        capsys, "ik", "iiwa14", "--matrix", *matrix(), "--fixed", f"q1={q1!r}", "--json"
    )
    assert code == 0
    data = strict_json(out)
    assert data["parameter"] == {
        "name": "q1",
        "joint": "q1",
        "value": pytest.approx(q1),
        "unit": "deg",
    }
    sols = np.radians(np.array(data["solutions"]))
    assert len(sols)
    np.testing.assert_allclose(sols[:, 0], Q[0], atol=1e-12)
    np.testing.assert_allclose(
        robot.fk(sols), np.broadcast_to(robot.fk(Q), (len(sols), 4, 4)), atol=1e-9
    )
    code, out, _ = run(capsys, "ik", "iiwa14", "--matrix", *matrix(), "--fixed", "q1=0.3", "--rad")
    assert code == 0
    assert "parameter: q1 = 0.3 rad" in out


def test_a_7r_without_fixed_says_the_joint_it_held(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = run(capsys, "ik", "iiwa14", "--matrix", *matrix(), "--json")
    data = strict_json(out)
    assert code == 0
    if data["parameter"] is not None:
        assert "redundancy parameter" in err
        assert data["parameter"]["name"] in data["message"]


def test_no_solution_at_the_lock_is_exit_1(capsys: pytest.CaptureFixture[str]) -> None:
    # q1 = 0: a pose to the side of the iiwa is beyond the elbow's circle
    T = km.load("iiwa14").fk(np.array([1.4, 0.9, 0.3, -1.0, 0.2, 0.6, 0.1]))
    cells = [repr(float(v)) for v in T.ravel()]
    code, out, _ = run(capsys, "ik", "iiwa14", "--matrix", *cells, "--fixed", "q1=0")
    assert code == 1
    assert "unreachable with q1 = 0:" in out and "other values of q1" in out


@pytest.mark.parametrize(
    ("fixed", "words"),
    [
        ("7=10", "--fixed: name a joint as q1..q7"),
        ("q8=10", "--fixed: name a joint as q1..q7"),
        ("q7", "--fixed takes JOINT=VALUE"),
        ("q7=abc", "--fixed: the value of q7 must be a finite number"),
        ("q7=nan", "--fixed: the value of q7 must be a finite number"),
        ("q1=175", "--fixed: q1 = 3.05433 rad is outside its limits"),
    ],
)
def test_bad_fixed_is_exit_2_in_one_line(
    capsys: pytest.CaptureFixture[str], fixed: str, words: str
) -> None:
    code, _, err = run(capsys, "ik", "iiwa14", "--matrix", *matrix(), "--fixed", fixed)
    assert code == 2
    assert words in one_line(err)


def test_help_says_how_joints_are_named(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run(capsys, "ik", "--help")
    assert code == 0
    assert "q1..qN" in out and "1-based" in out
