"""The named singularities' tolerances (``robot/singularities.py``), both sides.

Each case sits a factor 10 inside or outside the documented value, written here as
a literal: a test that read the constant would move with it.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import kinematica as km

#: A case a factor 10 inside a tolerance, and one a factor 10 outside it.
FACTORS = [(0.1, True), (10.0, False)]


WRIST_TOL = 1e-6  # robot/singularities.py


ELBOW_TOL = 1e-6  # robot/singularities.py


SHOULDER_TOL = 1e-6  # robot/singularities.py


RANK_TOL = 1e-8  # robot/singularities.py


L2, L3 = 0.4, 0.3  # the link lengths of the built-in anthropomorphic-3r


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_wrist_tol_is_the_sine_between_axes_4_and_6(factor: float, inside: bool) -> None:
    """WRIST_TOL: the wrist is singular when the sine of the angle between axes
    4 and 6 is below it; on a PUMA that sine is |sin q5|.
    """
    puma = km.load("puma560")
    q = np.array([0.3, -0.7, 0.9, 0.5, factor * WRIST_TOL, -0.4])
    assert puma.singularities(q) == (["wrist"] if inside else [])


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_elbow_tol_is_the_rate_of_the_reach(factor: float, inside: bool) -> None:
    """ELBOW_TOL: the elbow is singular when the distance r of the wrist from
    the shoulder changes with q3 slower than this (m/rad).

    r(q3)² = L2² + L3² + 2 L2 L3 cos q3, so |dr/dq3| = L2 L3 sin q3 / r: q3 is
    solved for a given rate by fixed-point iteration.
    """
    rate = factor * ELBOW_TOL
    q3 = rate * (L2 + L3) / (L2 * L3)
    for _ in range(5):
        r = math.sqrt(L2**2 + L3**2 + 2 * L2 * L3 * math.cos(q3))
        q3 = math.asin(rate * r / (L2 * L3))
    arm = km.load("anthropomorphic-3r")
    assert arm.singularities(np.array([0.3, 0.5, q3])) == (["elbow"] if inside else [])


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_shoulder_tol_is_the_distance_from_axis_1(factor: float, inside: bool) -> None:
    """SHOULDER_TOL: the shoulder is singular when the wrist centre is closer
    than this (m) to axis 1: L2 cos q2 + L3 cos(q2 + q3) = dist.
    """
    dist, q2 = factor * SHOULDER_TOL, 1.2
    q = np.array([0.3, q2, math.acos((dist - L2 * math.cos(q2)) / L3) - q2])
    arm = km.load("anthropomorphic-3r")
    assert arm.singularities(q) == (["shoulder"] if inside else [])


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_rank_tol_is_the_relative_singular_value(factor: float, inside: bool) -> None:
    """RANK_TOL: a singular value of the Jacobian below it times the largest one
    is lost ("rank" on an arm with no named singularities).

    A revolute joint then a prismatic one along the radius: the singular
    values of the position rows are 1 (the slide) and the extension q2 (m, the
    turn), so their ratio is q2.
    """
    arm = km.Robot.from_dh(
        [km.Revolute(alpha=-math.pi / 2), km.Prismatic(qlim=(0.0, 1.0))], convention="standard"
    )
    s = np.linalg.svd(arm.jacobian([0.2, 0.5])[:3], compute_uv=False)
    assert s == pytest.approx([1.0, 0.5])
    assert arm.singularities([0.2, factor * RANK_TOL]) == (["rank"] if inside else [])
