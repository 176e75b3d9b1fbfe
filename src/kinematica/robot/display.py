"""A robot as an HTML table, for notebooks: its DH table with units and limits."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from kinematica.io.html_table import html_table, number

if TYPE_CHECKING:
    from kinematica.robot.description import RobotDescription

__all__ = ["robot_html"]


def _angle(rad: float) -> str:
    """Degrees with their sign; a zero angle as the slides write it, ``0``."""
    text = number(math.degrees(rad))
    return text if text == "0" else f"{text}°"


def _plus(var: str, offset: str, zero: bool) -> str:
    if zero:
        return var
    sign = "−" if offset.startswith("−") else "+"
    return f"{var} {sign} {offset.removeprefix('−')}"


def robot_html(robot: RobotDescription) -> str:
    """The DH table as the lecture notes write it (``q2 + 90°``), degrees and metres.

    One row per joint: its name, type, θ, d, a, α in the robot's own convention
    (the modified convention's a and α are a(i-1), α(i-1)), and its limits.
    """
    modified = robot.convention == "modified"
    header = ["joint", "type", "θ", "d (m)", "a(i−1) (m)" if modified else "a (m)",
              "α(i−1)" if modified else "α", "limits"]  # fmt: skip
    rows = []
    for i, link in enumerate(robot.links, start=1):
        var = f"q{i}"
        if link.type == "R":
            theta = _plus(var, _angle(link.offset), link.offset == 0.0)
            d = number(link.d)
        else:
            theta = _angle(link.theta)
            d = _plus(var, number(link.offset), link.offset == 0.0)
        if link.qlim is None:
            limits = "none"
        elif link.type == "R":
            limits = f"[{_angle(link.qlim[0])}, {_angle(link.qlim[1])}]"
        else:
            limits = f"[{number(link.qlim[0])}, {number(link.qlim[1])}] m"
        name = link.name or var
        rows.append([name, link.type, theta, d, number(link.a), _angle(link.alpha), limits])
    footer = []
    if not np.allclose(robot.base, np.eye(4)):
        footer.append(f"base: position {_vector(robot.base[:3, 3])} m")
    if not np.allclose(robot.tool, np.eye(4)):
        footer.append(f"tool: position {_vector(robot.tool[:3, 3])} m in frame {robot.dof}")
    caption = f"{robot.name}: {robot.dof} joints ({robot.joint_types}), {robot.convention} DH"
    return html_table(header, rows, caption=caption, footer=footer)


def _vector(v: np.ndarray) -> str:
    return "(" + ", ".join(number(float(x)) for x in v) + ")"
