"""A guided tour of kinematica on the 6-DOF arm of the course slides (seed 000).

Run with ``make demo``. It prints the DH table, the link matrices i-1Ai at a
configuration, the matrix T, the pose (position and Euler angles), and then
every inverse-kinematics solution of that pose, each checked by forward
kinematics.
"""

from __future__ import annotations

import numpy as np

import kinematica as km
from kinematica.cli.format import fmt, matrix


def section(title: str) -> None:
    print(f"\n{'=' * 72}\n{title}\n{'=' * 72}")


def main() -> None:
    robot = km.load("arm6-dh")
    section(f"1. The robot: {robot.name} ({km.classify(robot).summary})")
    print("Its Denavit-Hartenberg table, as on the slide (theta, d, a, alpha):")
    names = ("theta", "d", "a", "alpha")
    print("   i   " + "".join(f"{n:>12}" for n in names))
    for i, (link, row) in enumerate(zip(robot.links, robot.dh_table(), strict=True), start=1):
        offset = np.degrees(link.offset)
        theta = f"q{i}" if offset == 0 else f"q{i} {'+' if offset > 0 else '-'} {abs(offset):g}°"
        cells = [theta, fmt(row[1]), fmt(row[2]), f"{np.degrees(row[3]):g}°"]
        print(f"   {i}   " + "".join(f"{c:>12}" for c in cells))

    q_deg = np.array([30.0, 40.0, -30.0, 10.0, 60.0, -20.0])
    q = np.radians(q_deg)
    section(f"2. Forward kinematics at q = {q_deg.tolist()} degrees")
    for i, A in enumerate(robot.link_matrices(q), start=1):
        print(f"{i - 1}A{i}:\n{matrix(A)}")
    T = robot.fk(q)
    print(f"T = 0A1 · 1A2 · ... · 5A6:\n{matrix(T)}")
    pose = km.to_pose(T, euler="ZYZ")
    print("\nPose p = (x, y, z, α, β, γ), Euler ZYZ:")
    print(f"  position (m):       {fmt(pose[0])}, {fmt(pose[1])}, {fmt(pose[2])}")
    print(f"  Euler ZYZ (deg):    {', '.join(fmt(v, 4) for v in np.degrees(pose[3:]))}")
    assert np.allclose(km.from_pose(pose, euler="ZYZ"), T, atol=1e-12)

    section("3. Inverse kinematics: every configuration that reaches this pose")
    res = robot.ik(T)
    print(f"status: {res.status}  method: {res.method}  ({res.message})")
    for k, (sol, branch) in enumerate(zip(res.solutions, res.branches, strict=True), start=1):
        err = km.rotation_angle(robot.fk(sol)[:3, :3], T[:3, :3])
        dp = np.linalg.norm(robot.fk(sol)[:3, 3] - T[:3, 3])
        cells = "  ".join(f"{v:8.3f}" for v in np.degrees(sol))
        print(f"  {k}: {cells}   {branch:<40} FK check: {dp:.1e} m, {err:.1e} rad")
    found = any(np.allclose(km.wrap_angle(s - q), 0, atol=1e-9) for s in res.solutions)
    print(f"\nThe configuration we started from is among them: {found}")

    section("4. Infinitely many solutions: the wrist centre on axis 1")
    # With l2 = l3 and q3 = -2 q2 the wrist centre lies on the first axis: any q1
    # works (the shoulder singularity). kinematica says so and names the free joint.
    T_sing = robot.fk(np.radians([30.0, 20.0, -40.0, 10.0, 60.0, -20.0]))
    res = robot.ik(T_sing)
    print(f"status: {res.status}; free joints: {list(res.free_names)}")
    print(f"{res.message}")

    section("5. An honest answer when there is none")
    far = T.copy()
    far[:3, 3] *= 10
    print(f"10x further away: {robot.ik(far).message}")
    print(f"status: {robot.ik(far).status} (the command line exits with code 1)")


if __name__ == "__main__":
    main()
