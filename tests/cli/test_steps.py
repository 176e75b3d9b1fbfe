"""``kinematica ik ROBOT --pose ... --steps``: seed 002's decoupling as the command prints it."""

from __future__ import annotations

import json

import numpy as np
import pytest
from support.cli import run

import kinematica as km


def test_steps_print_p_m_each_arm_solution_and_its_wrist(
    capsys: pytest.CaptureFixture[str],
) -> None:
    robot = km.load("arm6-dh")
    T = robot.fk(np.radians([-150, -10, -30, 20, 40, 60]))
    pose = km.to_pose(T, euler="ZYZ")
    args = [f"{v:.12g}" for v in (*pose[:3], *np.degrees(pose[3:]))]
    code, out, err = run(capsys, "ik", "arm6-dh", "--pose", *args, "--steps")
    assert code == 0, err
    p_m = T[:3, 3] - 0.1 * T[:3, 2]  # seed 002: p_m = p - d6·R·z
    line = next(x for x in out.splitlines() if x.strip().startswith("p_m = ("))
    shown = [float(v) for v in line.split("(")[1].split(")")[0].split(",")]
    assert np.allclose(shown, p_m, atol=1e-8)
    for step in ("1. wrist centre", "2. joints 1-3", "3. R03", "R36 = R03ᵀ·R06", "4. the wrist"):
        assert step in out
    assert out.count("arm ") >= 4 and "shoulder right, elbow up" in out and "wrist flip" in out
    code, out, err = run(capsys, "ik", "arm6-dh", "--pose", *args, "--steps", "--json")
    data = json.loads(out)
    assert code == 0 and np.allclose(data["wrist_center"], p_m, atol=1e-9)
    arms = np.array([a["q123"] for a in data["arms"]])
    assert np.any(np.all(np.abs(arms - [-150, -10, -30]) < 1e-6, axis=1))  # issue 35's numbers
    assert sum(len(a["q456"]) for a in data["arms"]) == 8


def test_steps_on_an_arm_without_a_spherical_wrist_is_one_line(
    capsys: pytest.CaptureFixture[str],
) -> None:
    code, _, err = run(
        capsys, "ik", "ur5", "--pose", "0.4", "0.1", "0.3", "0", "90", "0", "--steps"
    )
    assert code == 2 and "no spherical wrist" in err and "Traceback" not in err
