"""Random configurations (``robot/sampling.py``): the most a call makes, both sides of the bound."""

from __future__ import annotations

import pytest

import kinematica as km
from kinematica.errors import ArgumentError
from kinematica.motion import (
    random_q,
    workspace,
)
from kinematica.motion.workspace import MAX_SAMPLES as MAX_WORKSPACE_SAMPLES
from kinematica.robot.sampling import MAX_CONFIGURATIONS


def test_the_most_configurations_and_samples() -> None:
    one = km.Robot.from_dh([km.Revolute(a=1.0, qlim=(-1.0, 1.0))], convention="standard")
    assert random_q(one, (MAX_CONFIGURATIONS // 2, 0)).shape == (MAX_CONFIGURATIONS // 2, 0, 1)
    with pytest.raises(ArgumentError, match=r"^n gives 1e\+07 configurations; at most 10,000,000"):
        random_q(one, (MAX_CONFIGURATIONS // 2 + 1, 2))  # a batch shape counts all of it
    with pytest.raises(
        ArgumentError, match=r"^samples must be a whole number from 1 to 20,000,000"
    ):
        workspace(one, samples=MAX_WORKSPACE_SAMPLES + 1)
