"""The three drifts the first release let users see: each path now shares one definition.

1. Convention names: a robot file and ``Robot.from_dh`` accept the same aliases.
2. A base/tool matrix written with 7 digits: accepted by the file reader and by
   ``Robot`` alike (one tolerance), the robot keeping an exactly rigid transform.
3. Unreachable targets: one target and the same target in a batch get the same
   answer and the same message (one check in the core).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import kinematica as km
from kinematica.io.spec import CONVENTION_ALIASES

ROW = "  - {theta: q1, d: 0.3, a: 0.2, alpha: 90}\n  - {theta: q2, d: 0, a: 0.4, alpha: 0}\n"


@pytest.mark.parametrize("alias", sorted(CONVENTION_ALIASES))
def test_every_convention_alias_works_in_files_and_in_code(alias: str, tmp_path: Path) -> None:
    path = tmp_path / "arm.yaml"
    path.write_text(f"name: arm\nconvention: {alias.upper()}\njoints:\n{ROW}")
    from_file = km.load(path)
    rows = [km.Revolute(d=0.3, a=0.2, alpha=np.pi / 2), km.Revolute(a=0.4)]
    in_code = km.Robot.from_dh(rows, convention=alias)
    assert from_file.convention == in_code.convention == CONVENTION_ALIASES[alias]
    q = [0.3, -0.7]
    np.testing.assert_allclose(from_file.fk(q), in_code.fk(q), atol=1e-15)


def test_a_tool_written_with_seven_digits_loads_rigid(tmp_path: Path) -> None:
    c, s = float(np.cos(0.3)), float(np.sin(0.3))
    R = [[round(c, 7), round(-s, 7), 0.0], [round(s, 7), round(c, 7), 0.0], [0.0, 0.0, 1.0]]
    matrix = [[*R[0], 0.0], [*R[1], 0.0], [*R[2], 0.05], [0.0, 0.0, 0.0, 1.0]]
    path = tmp_path / "arm.yaml"
    path.write_text(f"name: arm\nconvention: standard\njoints:\n{ROW}tool: {{matrix: {matrix}}}\n")
    robot = km.load(path)
    Rt = robot.tool[:3, :3]
    assert np.abs(Rt.T @ Rt - np.eye(3)).max() < 1e-15
    assert np.abs(robot.tool - np.array(matrix)).max() < 1e-7
    # in code, the same matrix is accepted the same way
    assert np.array_equal(km.Robot.from_dh(robot.links, tool=matrix).tool, robot.tool)


def test_unreachable_targets_get_the_same_answer_alone_and_in_a_batch() -> None:
    arm = km.load("anthropomorphic-3r")
    rng = np.random.default_rng(3)
    q = rng.uniform(-np.pi, np.pi, (200, 3))
    T = arm.fk(q)
    # turn every target's orientation away from what the arm can reach there
    turn = km.rotx(0.4) @ km.roty(0.3)
    T[:, :3, :3] = T[:, :3, :3] @ turn
    many = arm.ik(T)
    for i in range(len(T)):
        one = arm.ik(T[i])
        assert one.status == many.status[i] == "unreachable"
        assert one.message == many.message[i] == many[i].message
        np.testing.assert_array_equal(one.solutions, many[i].solutions)
