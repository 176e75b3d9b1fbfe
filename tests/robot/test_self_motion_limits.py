"""robot.self_motion: the number of parameter values is bounded, as every other size is.

A sweep of ``10**8`` samples once allocated 22 GB before the kernel stopped it, and
``2**63`` raised an IndexError from numpy; both are refused at once, by the library
and by the command line, naming the argument and the accepted range.
"""

from __future__ import annotations

import numpy as np
import pytest
from support.cli import one_line, run

import kinematica as km
from kinematica.errors import ArgumentError
from kinematica.robot.self_motion import MAX_SAMPLES, _values

Q_IIWA = np.array([0.3, 0.5, -0.2, -1.2, 0.4, 0.9, 0.2])
POSE = ("--pose", "0.4", "0.2", "0.6", "0", "90", "0", "--parameter", "q1")


@pytest.fixture(scope="module")
def iiwa() -> km.Robot:
    return km.load("iiwa14")


@pytest.mark.parametrize("samples", [2**63, 10**8, MAX_SAMPLES + 1, 1, 2.0, True, "73"])
def test_samples_out_of_range_are_refused_at_once(iiwa: km.Robot, samples: object) -> None:
    T = iiwa.fk(Q_IIWA)
    with pytest.raises(ArgumentError, match="samples must be a whole number from 2 to 1,000,000"):
        iiwa.self_motion(T, "q1", samples=samples)  # type: ignore[arg-type]


def test_max_samples_boundary() -> None:
    """MAX_SAMPLES values are made; one more is refused (a constant 1000x off fails one side)."""
    span = (-1.0, 1.0)
    grid = _values(span, MAX_SAMPLES, None)
    assert grid.size == MAX_SAMPLES
    assert grid[0] == -1.0 and grid[-1] == 1.0
    with pytest.raises(ArgumentError, match="samples"):
        _values(span, MAX_SAMPLES + 1, None)
    assert _values(span, 2, None).tolist() == [-1.0, 1.0]


def test_values_bounded_too() -> None:
    assert _values((0.0, 1.0), 2, np.arange(MAX_SAMPLES, dtype=float)).size == MAX_SAMPLES
    with pytest.raises(ArgumentError, match="values gives 1e\\+06 parameter values"):
        _values((0.0, 1.0), 2, np.arange(MAX_SAMPLES + 1, dtype=float))


@pytest.mark.parametrize("samples", [str(2**63), str(10**8), "1"])
def test_cli_says_which_option(capsys: pytest.CaptureFixture[str], samples: str) -> None:
    code, _, err = run(capsys, "self-motion", "iiwa14", *POSE, "--samples", samples)
    assert code == 2
    line = one_line(err)
    assert "internal error" not in line
    assert line.startswith("kinematica: error: --samples must be a whole number from 2 to")
