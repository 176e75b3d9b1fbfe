"""Arms as they are (the nominal one with its DH values off) and their measurements."""

from __future__ import annotations

import dataclasses
import math

import numpy as np

import kinematica as km

#: The issue's synthetic set-up: each DH value off by up to 1 mm / 0.1 degree, a tracker
#: with 10 µm / 0.001 degree of noise.
OFF_LENGTH, OFF_ANGLE = 1e-3, math.radians(0.1)
NOISE = (1e-5, math.radians(1e-3))


def perturbed(robot: km.Robot, seed: int) -> km.Robot:
    """The robot with every DH value (offset, d, a, alpha) off by up to 1 mm / 0.1 degree.

    Written as a new DH table (Robot.from_dh): independent of the calibration's own model.
    """
    rng = np.random.default_rng(seed)
    rows = []
    for link in robot.links:
        da, dd = rng.uniform(-OFF_LENGTH, OFF_LENGTH, 2)
        dalpha, doff = rng.uniform(-OFF_ANGLE, OFF_ANGLE, 2)
        if link.type == "R":
            rows.append(
                dataclasses.replace(
                    link, a=link.a + da, d=link.d + dd, alpha=link.alpha + dalpha,
                    offset=link.offset + doff,
                )
            )  # fmt: skip
        else:
            rows.append(
                dataclasses.replace(
                    link, a=link.a + da, theta=link.theta + doff, alpha=link.alpha + dalpha,
                    offset=link.offset + dd,
                )
            )  # fmt: skip
    return km.Robot.from_dh(
        rows, convention=robot.convention, name=robot.name, base=robot.base, tool=robot.tool
    )
