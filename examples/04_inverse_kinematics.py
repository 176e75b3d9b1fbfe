"""Inverse kinematics on the lecture notes' arms: every solution, and why there may be none.

Seed 000's prismatic-rotational arm has two solutions for a point (q2A and
q2B = π − q2A); seed 002's anthropomorphic arm has four (two q1, two q3, one q2
each); a 6R arm with a spherical wrist up to eight. Every solution is checked
by forward kinematics before it is returned.
"""

from __future__ import annotations

import numpy as np

import kinematica as km


def show(title: str, robot: km.Robot, res: km.ik.IKResult) -> None:
    print(f"\n{title}: {res.status} ({res.method}) - {res.message}")
    for q, branch in zip(res.solutions, res.branches, strict=True):
        cells = "  ".join(f"{v:9.4f}" for v in q)
        print(f"   {cells}   {branch}")


def main() -> None:
    # Seed 000: x = q1 + l1 + l2 cos q2, y = l2 sin q2.
    pr = km.load("planar-pr")
    p = pr.fk([0.15, 0.7])[:3, 3]
    res = pr.ik(p, respect_limits=False)
    show("planar PR, a point (joint limits ignored)", pr, res)
    l2 = 0.4  # the model's default length (parameters in its file)
    q2a = np.arcsin(p[1] / l2)
    print(f"   seed formulas: q2A = asin(y/l2) = {q2a:.4f}, q2B = pi - q2A = {np.pi - q2a:.4f}")

    # Seed 002: four solutions for the anthropomorphic arm.
    arm = km.load("anthropomorphic-3r")
    show("anthropomorphic 3R, a point", arm, arm.ik(arm.fk([0.5, 0.4, -0.9])[:3, 3]))

    # A 6R arm with a spherical wrist: up to eight; the limits keep some apart.
    puma = km.load("puma560")
    T = puma.fk([0.4, -0.3, 0.3, 1.0, 0.6, -0.5])
    res = puma.ik(T)
    show("PUMA 560, a pose", puma, res)
    print(f"   and {len(res.out_of_limits)} more outside the joint limits")

    # Honest answers.
    far = T.copy()
    far[:3, 3] = [2.0, 0.0, 0.5]
    print(f"\nPUMA 560, 2 m away: {puma.ik(far).message}")
    wrist_aligned = puma.fk([0.4, -0.3, 0.3, 1.0, 0.0, -0.5])
    res = puma.ik(wrist_aligned)
    print(f"PUMA 560, wrist aligned: {res.status}, free joints {list(res.free_names)}")

    # A redundant arm: numeric, within its limits, exact to 1e-10.
    panda = km.load("panda")
    res = panda.ik(panda.fk([0.3, -0.2, 0.1, -2.1, 0.2, 1.9, 0.4]), seed=0)
    show("Panda (7R), a pose", panda, res)

    # Many targets at once: arrays, one row per target.
    ur5 = km.load("ur5")
    Ts = ur5.fk(np.random.default_rng(0).uniform(-np.pi, np.pi, (2000, 6)))
    many = ur5.ik(Ts)
    counts = np.bincount(many.count, minlength=9)
    print(f"\nUR5, 2000 poses: solutions per pose {dict(enumerate(counts.tolist()))}")


if __name__ == "__main__":
    main()
