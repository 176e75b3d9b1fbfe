"""Describe a robot by its DH table as written on a slide, then compute T and the pose.

The table is seed 000's 6-DOF arm, written as a robot file (YAML here; JSON and
TOML carry the same keys) with named lengths and offsets like ``q2 + 90``.
"""

from __future__ import annotations

import tempfile
from pathlib import Path

import numpy as np

import kinematica as km

ROBOT_FILE = """\
name: Seed 6-DOF arm
convention: standard
units: {angle: deg, length: m}
parameters: {l1: 0.5, l2: 0.4, l3: 0.4, l4: 0.1}
joints:
  - {theta: q1,      d: l1, a: 0,  alpha: 90,  limits: [-160, 160]}
  - {theta: q2 + 90, d: 0,  a: l2, alpha: 0}
  - {theta: q3 - 90, d: 0,  a: 0,  alpha: -90}
  - {theta: q4 - 90, d: l3, a: 0,  alpha: -90}
  - {theta: q5,      d: 0,  a: 0,  alpha: 90}
  - {theta: q6,      d: l4, a: 0,  alpha: 0}
tool: {xyz: [0, 0, 0.05]}
"""


def main() -> None:
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "arm.yaml"
        path.write_text(ROBOT_FILE)
        robot = km.load(path)
    print(robot, "-", km.classify(robot).summary)

    # The same table in Python: offsets in radians, lengths in metres.
    rows = [
        km.Revolute(d=0.5, alpha=np.pi / 2, qlim=np.radians([-160, 160])),
        km.Revolute(a=0.4, offset=np.pi / 2),
        km.Revolute(offset=-np.pi / 2, alpha=-np.pi / 2),
        km.Revolute(d=0.4, offset=-np.pi / 2, alpha=-np.pi / 2),
        km.Revolute(alpha=np.pi / 2),
        km.Revolute(d=0.1),
    ]
    same = km.Robot.from_dh(
        rows, tool=km.transl(0, 0, 0.05), name="from code", convention="standard"
    )

    q = np.radians([10, -20, 30, 40, -50, 60])
    T = robot.fk(q)
    assert np.allclose(T, same.fk(q), atol=1e-15)
    print("T =\n", np.array2string(T, precision=4, suppress_small=True))
    x, y, z, a, b, g = km.to_pose(T, euler="ZYZ", degrees=True)
    print(f"position: ({x:.4f}, {y:.4f}, {z:.4f}) m;  ZYZ: ({a:.2f}, {b:.2f}, {g:.2f}) deg")

    # Every frame 0Ti, and a batch of configurations in one call.
    frames = robot.fk(q, all_frames=True)
    print("origins of frames 0..6 (m):\n", np.array2string(frames[:, :3, 3], precision=3))
    batch = np.random.default_rng(0).uniform(-np.pi, np.pi, (100_000, 6))
    print("batch of", len(batch), "configurations ->", robot.fk(batch).shape)


if __name__ == "__main__":
    main()
