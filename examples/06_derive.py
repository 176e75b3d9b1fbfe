"""A short symbolic derivation: the seeds' equations from the robot files themselves.

Needs the ``symbolic`` extra (sympy). The same DH table that drives the numbers
gives, in sympy, each link matrix, T, the position equations in the short
notation of the slides (c1, s23) and a step-by-step inverse kinematics; the
full report of any arm is one command: ``kinematica derive arm6-dh``.
"""

from __future__ import annotations

import numpy as np

import kinematica as km
from kinematica import symbolic


def main() -> None:
    # Seed 002's anthropomorphic arm: L1, L2, L3 stay symbols, as the file names them.
    px, py, pz = symbolic.short(symbolic.position("anthropomorphic-3r"))
    print("anthropomorphic 3R (seed 002):")
    print("  px =", px)  # c1*(L2*c2 + L3*c23)
    print("  py =", py)
    print("  pz =", pz)

    # Seed 000's 2-DOF prismatic-rotational mechanism: x = q1 + l1 + l2 cos q2.
    x, y, _ = symbolic.position("planar-pr")
    print("planar PR (seed 000):  x =", x, "   y =", y)

    # One link matrix of seed 000's 6-DOF arm, from its four elementary transforms.
    A2 = symbolic.link_matrices("arm6-dh")[1]
    print("arm6-dh 1A2 =", symbolic.short(A2).tolist())

    # The symbolic T compiled to a numeric function agrees with robot.fk.
    robot = km.load("arm6-dh")
    q = np.random.default_rng(0).uniform(-np.pi, np.pi, (1000, 6))
    err = np.abs(symbolic.lambdify("arm6-dh")(q) - robot.fk(q)).max()
    print(f"lambdify vs robot.fk on 1000 configurations: max |dT| = {err:.1e}")

    # The report (Markdown here; latex and html too, in Spanish or English).
    text = symbolic.report("anthropomorphic-3r", format="markdown", lang="en")
    ik = text[text.index("## Inverse kinematics") :]
    print(ik.splitlines()[0], f"({len(ik.splitlines())} lines, e.g.)")
    print("\n".join(line for line in ik.splitlines() if line.startswith("q_{3} &=")))


if __name__ == "__main__":
    main()
