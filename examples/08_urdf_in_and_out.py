"""URDF in and out: a maker's URDF becomes a DH table by the rules of seed 000.

1. The ROS-Industrial description of the KUKA KR 16-2 (a URDF shipped on PyPI,
   see tests/data/urdf/PROVENANCE.md) is read, its chain base_link -> tool0
   turned into a standard DH table, and each frame's rule printed.
2. The closed-form IK recognises its spherical wrist; every solution is checked
   against the URDF's own forward kinematics (composed here joint by joint).
3. A DH robot goes out as URDF and comes back with the same table.
"""

from __future__ import annotations

import math
import tempfile
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

import kinematica as km

KR16 = Path(__file__).resolve().parents[1] / "tests" / "data" / "urdf" / "kuka_kr16_2.urdf"


def urdf_fk(path: Path, q: np.ndarray) -> np.ndarray:
    """The URDF's own FK: origin (xyz, rpy) then the rotation about the axis, joint by joint."""
    T = np.eye(4)
    values = iter(q)
    for joint in ET.parse(path).getroot().findall("joint"):
        if joint.find("child").get("link") == "base":  # the ROS-Industrial side frame
            continue
        origin = joint.find("origin")
        x, y, z = (float(v) for v in origin.get("xyz").split())
        r, p, w = (float(v) for v in origin.get("rpy").split())
        T = T @ km.make_transform(km.rotz(w) @ km.roty(p) @ km.rotx(r), [x, y, z])
        if joint.get("type") == "revolute":
            axis = np.array([float(v) for v in joint.find("axis").get("xyz").split()])
            M = np.eye(4)
            M[:3, :3] = km.matrix_from_axis_angle(axis, next(values))
            T = T @ M
    return T


def main() -> None:
    ext = km.urdf_to_dh(KR16)  # default tip: tool0, the single leaf at the end of the arm
    robot = ext.robot
    print(ext.report())
    print("theta offset, d, a, alpha (rad, m) at q = 0:")
    print(np.array2string(robot.dh_table(), precision=4, suppress_small=True))
    print(f"base:\n{np.array2string(robot.base, precision=4, suppress_small=True)}")
    print(f"structure: {km.classify(robot).summary}")
    print(f"the DH table alone misses the URDF's FK by {ext.fk_error:.1e} (largest entry of T)")

    q = np.radians([20, -60, 80, 30, -40, 50])
    target = urdf_fk(KR16, q)
    assert np.abs(robot.fk(q) - target).max() < 1e-12
    res = robot.ik(target)
    print(f"\nIK: {res.status}, {res.method}, {res.count} solutions within the limits")
    for sol, branch in zip(res.solutions, res.branches, strict=True):
        error = np.abs(urdf_fk(KR16, sol) - target).max()
        print(f"  {np.round(np.degrees(sol), 2)}  {branch}  (URDF FK error {error:.0e})")
        assert error < 1e-9

    puma = km.load("puma560")
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "puma560.urdf"
        puma.to_urdf(path)
        back = km.load(path)
    same = np.abs(back.dh_table() - puma.dh_table()).max()
    print(f"\nPUMA 560 -> URDF -> DH: tables differ by {same:.0e}")
    assert same < 1e-12
    craig = puma.to_dh("modified")
    print(f"the same arm by Craig's rules ({len(craig.rules)} frames):")
    print(np.array2string(craig.robot.dh_table(), precision=4, suppress_small=True))
    assert math.isclose(craig.fk_error, 0.0, abs_tol=1e-12)


if __name__ == "__main__":
    main()
