"""Compute pinocchio_fk.json: Pinocchio's forward kinematics of the URDF files here.

Run once, with Pinocchio installed (``pip install pin``), from any directory:

    python tests/data/urdf/make_pinocchio_reference.py

For each case it records the chain (base and tip links), the names of the
movable joints on it in order, and the pose of the tip link in the base link
frame at q = 0 and at random joint values within the limits (continuous and
unlimited joints: within ±pi). Joints off the chain stay at 0. Pinocchio's
continuous joints take (cos q, sin q) in its configuration vector.
The test suite reads the JSON; it never needs Pinocchio itself.
"""

from __future__ import annotations

import json
import math
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pinocchio as pin

HERE = Path(__file__).resolve().parent

#: (file, base link or None for the root, tip link or None for the single leaf).
CASES = [
    ("abb_irb140.urdf", None, "tool0"),
    ("kuka_kr16_2.urdf", None, "tool0"),
    ("kuka_kr210l150.urdf", None, "tool0"),
    ("kuka_lbr_iiwa_14_r820.urdf", None, "tool0"),
    ("puma560_robot.urdf", None, "link7"),
    ("ur5_robot.urdf", None, "tool0"),
    ("ur10_robot.urdf", "base_link", "ee_link"),
    ("franka_panda.urdf", None, "panda_hand_tcp"),
    ("kinova_j2s6s200.urdf", "j2s6s200_link_base", "j2s6s200_end_effector"),
    ("ufactory_xarm7.urdf", None, "link_eef"),
    ("lynxmotion_al5d.urdf", None, "link4"),
]
SAMPLES = 6  # q = 0 and 5 random configurations


def chain_joints(path: Path, base: str | None, tip: str) -> tuple[str, list[ET.Element]]:
    """The root link (when base is None) and the movable joints from base to tip."""
    root = ET.parse(path).getroot()
    joints = {j.find("child").get("link"): j for j in root.findall("joint")}
    links = [link.get("name") for link in root.findall("link")]
    start = base or next(name for name in links if name not in joints)
    path_joints, link = [], tip
    while link != start:
        j = joints[link]
        path_joints.append(j)
        link = j.find("parent").get("link")
    movable = [j for j in reversed(path_joints) if j.get("type") != "fixed"]
    return start, movable


def main() -> None:
    rng = np.random.default_rng(20240611)
    out = {"pinocchio": pin.__version__, "cases": []}
    for name, base, tip in CASES:
        path = HERE / name
        model = pin.buildModelFromUrdf(str(path))
        data = model.createData()
        start, movable = chain_joints(path, base, tip)
        samples = []
        for s in range(SAMPLES):
            q_chain = []
            for j in movable:
                limit = j.find("limit")
                lo, hi = -math.pi, math.pi
                if j.get("type") != "continuous" and limit is not None and "lower" in limit.attrib:
                    lo, hi = float(limit.get("lower")), float(limit.get("upper"))
                q_chain.append(0.0 if s == 0 else float(rng.uniform(lo, hi)))
            q = pin.neutral(model)
            for j, value in zip(movable, q_chain, strict=True):
                jm = model.joints[model.getJointId(j.get("name"))]
                if jm.nq == 2:  # continuous: cos, sin
                    q[jm.idx_q : jm.idx_q + 2] = [math.cos(value), math.sin(value)]
                else:
                    q[jm.idx_q] = value
            pin.framesForwardKinematics(model, data, q)
            T_base = data.oMf[model.getFrameId(start)].homogeneous
            T_tip = data.oMf[model.getFrameId(tip)].homogeneous
            T = np.linalg.solve(T_base, T_tip)
            samples.append({"q": q_chain, "T": T.tolist()})
        out["cases"].append(
            {
                "file": name,
                "base": base,
                "tip": tip,
                "joints": [j.get("name") for j in movable],
                "samples": samples,
            }
        )
    target = HERE / "pinocchio_fk.json"
    target.write_text(json.dumps(out, indent=1) + "\n")
    print(f"wrote {target}")


if __name__ == "__main__":
    main()
