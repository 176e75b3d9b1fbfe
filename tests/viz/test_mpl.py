"""Picture sizes and resolutions (``viz/_mpl.py``): their ranges, both sides of each bound."""

from __future__ import annotations

import math

import pytest

from kinematica.errors import ArgumentError
from kinematica.viz._mpl import (
    MAX_DPI,
    MAX_PIXELS,
    MAX_SIDE,
    MIN_DPI,
    MIN_SIDE,
    check_picture,
)


def test_picture_sizes_and_dpi() -> None:
    assert check_picture((MIN_SIDE, MAX_SIDE), MIN_DPI) == ((MIN_SIDE, MAX_SIDE), MIN_DPI)
    tallest = MAX_PIXELS // MAX_SIDE
    assert check_picture((MAX_SIDE, tallest), MAX_DPI)[0] == (MAX_SIDE, tallest)
    for size, match in [
        ((MIN_SIDE - 1, 100), r"^size must be a whole number from 16 to 20,000, got 15"),
        ((100, MAX_SIDE + 1), r"^size must be a whole number from 16 to 20,000, got 20001"),
        ((MAX_SIDE, tallest + 1), r"^size gives 4e\+07 pixels; at most 40,000,000"),
        ((100.0, 100), r"^size must be a whole number"),
        ((100,), r"^size must be \(width, height\) in pixels"),
    ]:
        with pytest.raises(ArgumentError, match=match):
            check_picture(size, 100.0)
    for dpi in (MIN_DPI * 0.99, MAX_DPI * 1.01, math.nan, "100"):
        with pytest.raises(ArgumentError, match=r"^dpi must be a number of dots per inch from 10"):
            check_picture(None, dpi)
