"""The checks of rotations (``spatial/checks.py``): orthonormality, both sides."""

from __future__ import annotations

import numpy as np
import pytest

import kinematica as km


@pytest.mark.parametrize(("error", "accepted"), [(2e-7, True), (2e-5, False)])
def test_orthonormal_tol_of_a_tool_is_1e_6(error: float, accepted: bool) -> None:
    tool = np.eye(4)
    tool[0, 1] = error  # max |RᵀR - I| = error
    if accepted:
        robot = km.Robot.from_dh([km.Revolute(a=1.0)], tool=tool, convention="standard")
        R = robot.tool[:3, :3]
        assert np.abs(R.T @ R - np.eye(3)).max() < 1e-15
    else:
        with pytest.raises(km.DimensionError, match="not orthonormal"):
            km.Robot.from_dh([km.Revolute(a=1.0)], tool=tool, convention="standard")
