"""``kinematica ik ROBOT --pose ... --steps``: the spherical wrist's decoupling, step by step."""

from __future__ import annotations

import argparse

import numpy as np
from numpy.typing import NDArray

from kinematica.cli.format import matrix, num, plain, table
from kinematica.cli.options import clean, dump, length_unit, lengths_out, q_out, units
from kinematica.robot import Robot

__all__ = ["print_steps"]

FloatArray = NDArray[np.float64]


def _arm_and_wrist(
    robot: Robot, qa: FloatArray, wrist: FloatArray, args: argparse.Namespace
) -> tuple[FloatArray, FloatArray]:
    """q1..q3 and each wrist row q4..q6 in the CLI's units."""
    rows = np.concatenate(
        [np.broadcast_to(qa, (max(len(wrist), 1), 3)), wrist if len(wrist) else np.zeros((1, 3))],
        axis=1,
    )
    shown = q_out(robot, rows, args)
    return shown[0, :3], shown[:, 3:] if len(wrist) else np.zeros((0, 3))


def print_steps(robot: Robot, target: FloatArray, args: argparse.Namespace) -> int:
    """Print (or dump as JSON) every step of ``robot.decouple(target)``; the exit code."""
    steps = robot.decouple(target)
    solved = steps.status in ("ok", "singular") and steps.solutions.shape[0] > 0
    metres = length_unit(robot, args)
    p_m = lengths_out(steps.wrist_center, robot, args)
    offset = lengths_out(steps.offset, robot, args)
    if args.json:
        arms = []
        for a in steps.arms:
            qa, wrist = _arm_and_wrist(robot, a.q, a.wrist, args)
            arms.append(
                {
                    "q123": clean(qa),
                    "branch": a.branch,
                    "R03": clean(a.R03),
                    "R36": clean(a.R36),
                    "q456": clean(wrist),
                    "wrist_branches": list(a.wrist_branches),
                    "within_limits": [bool(v) for v in a.within_limits],
                }
            )
        dump(
            {
                "robot": robot.name,
                "status": steps.status,
                "message": steps.message,
                "units": units(robot, args),
                "wrist_offset": clean(offset),
                "wrist_center": clean(p_m),
                "R06": clean(steps.R06),
                "arm_status": steps.arm_status,
                "arms": arms,
            }
        )
        return 0 if solved else 1
    unit = "rad" if args.rad else "deg"
    prec = args.precision
    print(f"{plain(robot.name)}: the spherical wrist's decoupling (seed 002), step by step")
    print(f"units: {unit} for angles, {metres} for lengths")
    print(
        f"\n1. wrist centre p_m = p + R·c, c = ({', '.join(num(v, prec) for v in offset)}) "
        f"{metres}, the wrist centre in the tool frame (c = (0, 0, -d6): p_m = p - d6·R·z)"
    )
    print(f"   p_m = ({', '.join(num(v, prec) for v in p_m)}) {metres}")
    print("   R06 (the target's rotation of frame 6):")
    print(matrix(steps.R06, indent="     ", precision=prec))
    count = len(steps.arms)
    print(f"\n2. joints 1-3 place p_m: {count} arm solution(s) ({steps.arm_status})")
    for k, a in enumerate(steps.arms, start=1):
        qa, wrist = _arm_and_wrist(robot, a.q, a.wrist, args)
        print(
            f"\n   arm {k}: q1, q2, q3 = {', '.join(num(v, prec) for v in qa)}   {plain(a.branch)}"
        )
        print("   3. R03 (frame 3 at these joints):")
        print(matrix(a.R03, indent="     ", precision=prec))
        print("      R36 = R03ᵀ·R06 (what the wrist turns):")
        print(matrix(a.R36, indent="     ", precision=prec))
        if not len(wrist):
            print("   4. no wrist solution for this arm solution")
            continue
        print("   4. the wrist solutions:")
        rows = [
            (str(i), *(num(v, prec) for v in w), plain(b), "" if ok else "outside the limits")
            for i, (w, b, ok) in enumerate(
                zip(wrist, a.wrist_branches, a.within_limits, strict=True), start=1
            )
        ]
        print(table(("#", "q4", "q5", "q6", "branch", ""), rows, indent="     "))
    print(f"\n{plain(steps.status)} — {plain(steps.message)}")
    return 0 if solved else 1
