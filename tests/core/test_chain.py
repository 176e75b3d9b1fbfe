"""The core's chain (``chain.hpp``): exact twists snapped, both sides of the tolerance."""

from __future__ import annotations

import math

import pytest

import kinematica as km


@pytest.mark.parametrize(("eps", "exact"), [(1e-17, True), (1e-13, False)])
def test_snap_tol_is_1e_15(eps: float, exact: bool) -> None:
    # A twist within 1e-15 of 90 degrees has its cosine snapped to exactly 0:
    # then the frame of a joint at q = 0 has exact zeros; 1e-13 off it does not.
    robot = km.Robot.from_dh([km.Revolute(alpha=math.pi / 2 + eps)])
    T = robot.fk([0.0])
    assert bool(T[1, 1] == 0.0) == exact
