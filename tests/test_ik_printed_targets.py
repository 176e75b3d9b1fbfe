"""Targets pasted from printed numbers: rotations copied with a few decimals.

Reference: the bound by hand. A rotation whose entries are each off by at most
5e-5 (4 decimals) has max |RᵀR − I| <= 2·√3·5e-5 + 3·(5e-5)² ≈ 1.73e-4.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import kinematica as km
from kinematica.ik import PROJECTION_TOL
from kinematica.spatial.checks import shown_above


def test_every_four_decimal_copy_is_within_the_projection_tolerance():
    assert 2 * math.sqrt(3) * 5e-5 + 3 * 5e-5**2 < PROJECTION_TOL < 2 * math.sqrt(3) * 5e-4


@pytest.mark.parametrize("name", ["ur5", "panda", "puma560"])
def test_a_rotation_copied_with_4_decimals_is_accepted_with_a_note(name):
    robot = km.load(name)
    rng = np.random.default_rng(5)
    worst = 0.0
    for q in robot.random_q(40, seed=rng):
        T = np.round(robot.fk(q), 4)
        R = T[:3, :3]
        worst = max(worst, float(np.abs(R.T @ R - np.eye(3)).max()))
        res = robot.ik(T, tol=1e-3)  # the copied position is off by up to 5e-5 m too
        assert any("projected onto SO(3)" in n for n in res.notes), res.message
    assert worst > 1e-4  # copies the old 1e-4 refused were among them


def test_a_refusal_never_reads_as_within_its_limit():
    T = km.load("ur5").fk(np.zeros(6))
    T[:3, :3] = T[:3, :3] @ np.diag([1.0 + 1.02 * PROJECTION_TOL / 2, 1.0, 1.0])
    with pytest.raises(km.DimensionError) as info:
        km.load("ur5").ik(T)
    message = str(info.value)
    shown = float(message.split("= ")[1].split(",")[0])
    assert shown > PROJECTION_TOL, message


@pytest.mark.parametrize(
    ("value", "limit", "text"),
    [(1.04e-4, 1e-4, "1.04e-04"), (2.5e-4, 2e-4, "2.5e-04"), (2.0000001e-4, 2e-4, "2.0000001e-04")],
)
def test_shown_above_uses_the_digits_that_show_the_excess(value, limit, text):
    assert shown_above(value, limit) == text
