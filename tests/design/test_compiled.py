"""The compiled template: a candidate's arm equal, bit for bit, to the file read again.

The reference is :meth:`DesignTemplate.robot_at` (the robot-file reader, with the
candidate's values): the DH table, limits, base and tool of the compiled arm must be
identical to its, for templates with parameters that follow the design variables,
degrees, millimetres, prismatic joints and divisions; a template whose variables reach
something else than the DH table is not compiled, and says why.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from kinematica.design import evaluate_design, load_template
from kinematica.design.measures import TASK_MEASURES
from kinematica.design.task import Task
from kinematica.errors import RobotFileError

ARM = """
name: compiled arm
convention: modified
units: {angle: deg, length: mm}
parameters:
  l1: {value: 300, min: 200, max: 400}
  l2: 1000 - l1
  h: {value: 90, min: 60, max: 120}
  k: l2 / 3 + h * 0.1
  ofs: {value: 10, min: -20, max: 20}
joints:
  - {theta: q1, d: l1 / 2, a: 0, alpha: 0, limits: [-170, 170]}
  - {theta: q2 + ofs, d: 0, a: 0, alpha: -h, limits: [-120, 120]}
  - {theta: -90 + q3, d: 0, a: l2 - 2 * k / 7, alpha: 0}
  - {theta: 0, d: q4 + k, a: 25, alpha: 90, limits: [0, 300]}
  - {theta: q5, d: l1 * 0.3, a: 0, alpha: -(h - 90)}
tool: {xyz: [0, 0, 50]}
"""


def _template(tmp_path: Path, text: str = ARM) -> object:
    path = tmp_path / "arm.yaml"
    path.write_text(text)
    return load_template(path)


def _same(a: object, b: object) -> None:
    for name in ("qlim", "base", "tool"):
        assert np.array_equal(getattr(a, name), getattr(b, name)), name
    assert np.array_equal(a.dh_table(), b.dh_table())  # type: ignore[attr-defined]
    assert a.joint_types == b.joint_types  # type: ignore[attr-defined]
    assert a.convention == b.convention  # type: ignore[attr-defined]


def test_compiled_arm_equals_the_file_read_again(tmp_path: Path) -> None:
    tmpl = _template(tmp_path)
    compiled = tmpl.compiled  # type: ignore[attr-defined]
    assert compiled.reason is None
    # the cells that follow a variable, and only they, are recomputed
    assert {(r, c) for r, c, _, _ in compiled.cells} == {
        (0, 1),
        (1, 0),
        (1, 3),
        (2, 2),
        (3, 1),
        (4, 1),
        (4, 3),
    }
    rng = np.random.default_rng(0)
    X = rng.uniform(tmpl.lower, tmpl.upper, (25, 3))  # type: ignore[attr-defined]
    X[0] = tmpl.lower  # type: ignore[attr-defined]
    X[1] = tmpl.upper  # type: ignore[attr-defined]
    for x in X:
        _same(compiled.robot(x), tmpl.robot_at(x))  # type: ignore[attr-defined]
    # vectorised over candidates: each row as the one candidate's table
    table = compiled.table(X)
    assert table.shape == (25, 5, 4)
    for x, t in zip(X, table, strict=True):
        assert np.array_equal(t, compiled.table(x))


def test_outside_the_bounds_says_so_as_the_reader_does(tmp_path: Path) -> None:
    tmpl = _template(tmp_path)
    with pytest.raises(RobotFileError, match="l1"):
        tmpl.compiled.robot(np.array([450.0, 90.0, 0.0]))  # type: ignore[attr-defined]


@pytest.mark.parametrize(
    ("change", "why"),
    [
        (("limits: [-170, 170]", "limits: [-l1, 170]"), "limits of joint 1"),
        (("tool: {xyz: [0, 0, 50]}", "tool: {xyz: [0, 0, k]}"), "tool"),
        (("tool: {xyz: [0, 0, 50]}", "tool: {xyz: [0, 0, 50]}\nbase: {xyz: [ofs, 0, 0]}"), "base"),
    ],
)
def test_variables_reaching_more_than_the_table_are_read_from_the_file(
    tmp_path: Path, change: tuple[str, str], why: str
) -> None:
    tmpl = _template(tmp_path, ARM.replace(*change))
    compiled = tmpl.compiled  # type: ignore[attr-defined]
    assert compiled.reason is not None and why in compiled.reason
    x = np.array([250.0, 100.0, 5.0])
    _same(compiled.robot(x), tmpl.robot_at(x))  # type: ignore[attr-defined]


def test_a_compiled_template_pickles_without_its_compiled_form(tmp_path: Path) -> None:
    import pickle

    tmpl = _template(tmp_path)
    before = tmpl.compiled  # type: ignore[attr-defined]
    back = pickle.loads(pickle.dumps(tmpl))
    assert "compiled" not in back.__dict__
    x = np.array([250.0, 100.0, 5.0])
    _same(back.compiled.robot(x), before.robot(x))


def test_evaluation_measures_what_is_asked(tmp_path: Path) -> None:
    path = tmp_path / "arm6.yaml"
    path.write_text(
        ARM6 := """
name: seed
convention: standard
units: {angle: deg, length: m}
parameters:
  l2: {value: 0.4, min: 0.2, max: 0.7}
  l3: {value: 0.4, min: 0.2, max: 0.7}
joints:
  - {theta: q1,      d: 0.5, a: 0,  alpha: 90}
  - {theta: q2 + 90, d: 0,   a: l2, alpha: 0}
  - {theta: q3 - 90, d: 0,   a: 0,  alpha: -90}
  - {theta: q4 - 90, d: l3,  a: 0,  alpha: -90}
  - {theta: q5,      d: 0,   a: 0,  alpha: 90}
  - {theta: q6,      d: 0.1, a: 0,  alpha: 0}
"""
    )
    assert ARM6
    tmpl = load_template(path)
    robot = tmpl.robot_at({})
    q = np.random.default_rng(1).uniform(-1.0, 1.0, (40, 6))
    task = Task.from_poses(robot.fk(q))
    every = evaluate_design(tmpl, task, [0.45, 0.5])
    manip = evaluate_design(tmpl, task, [0.45, 0.5], needs=["mean_manipulability"])
    assert set(every.measures) == {*TASK_MEASURES, "reached", "total_length"}
    assert set(manip.measures) == {
        "min_manipulability",
        "mean_manipulability",
        "reached",
        "total_length",
    }
    for name, value in manip.measures.items():  # the same numbers, bit for bit
        assert every.measures[name] == value
