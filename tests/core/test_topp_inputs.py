"""The core's time-optimal timing refuses a problem it does not take (``topp.hpp``'s
``Problem::invalid``), with a ValueError naming what is wrong, before any of it is read.

A valid problem is timed; each case below spoils one of its values.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from kinematica.core.topp import STATUSES, time_optimal_grid

N, DEGREE, JOINTS = 8, 3, 2


def _problem() -> dict[str, Any]:
    """A straight joint path of N intervals, cubic pieces, within symmetric limits."""
    s = np.linspace(0.0, 1.0, N + 1)
    coef = np.zeros((N, DEGREE + 1, JOINTS))
    coef[:, 0] = s[:-1, None] * [1.0, -0.5]  # q(s_i)
    coef[:, 1] = [1.0, -0.5]  # q'(s)
    ones = np.ones(JOINTS)
    return {
        "s": s, "coef": coef, "vel": (-ones, ones), "acc": (-2 * ones, 2 * ones),
        "cap": np.full(N, np.inf), "x_start": 0.0, "x_end": 0.0, "x_max": 1e12,
    }  # fmt: skip


def test_the_valid_problem_is_timed() -> None:
    out = time_optimal_grid(**_problem())
    assert out.status == "ok" and np.all(np.isfinite(out.x))


def _spoil(key: str, index: Any, value: float) -> dict[str, Any]:
    p = _problem()
    if index is None:
        p[key] = value
    elif isinstance(p[key], tuple):
        lo, hi = (a.copy() for a in p[key])
        (lo if index == 0 else hi)[0] = value
        p[key] = (lo, hi)
    else:
        p[key] = p[key].copy()
        p[key][index] = value
    return p


@pytest.mark.parametrize(
    ("key", "index", "value", "message"),
    [
        ("s", 3, 0.25, "s must be finite and strictly increasing"),  # s[3] = s[2]
        ("s", 4, np.nan, "s must be finite and strictly increasing"),
        ("s", N, np.inf, "s must be finite and strictly increasing"),
        ("cap", 2, -1e-300, "cap must be >= 0"),
        ("cap", 2, np.nan, "cap must be >= 0"),
        ("coef", (5, 2, 1), np.inf, "coef must be finite"),
        ("vel", 0, 1e-300, "limits must be lo <= 0 <= hi"),
        ("acc", 1, -1e-300, "limits must be lo <= 0 <= hi"),
        ("vel", 1, np.nan, "limits must be lo <= 0 <= hi"),
        ("x_start", None, -1e-300, "x_start and x_end must be finite"),
        ("x_end", None, np.inf, "x_start and x_end must be finite"),
        ("x_max", None, 0.0, "x_max must be a finite positive number"),
        ("x_max", None, np.inf, "x_max must be a finite positive number"),
    ],
)
def test_a_spoiled_value_is_refused_by_name(
    key: str, index: Any, value: float, message: str
) -> None:
    p = _spoil(key, index, value)
    with pytest.raises(ValueError, match=message):
        time_optimal_grid(**p)


def test_zero_caps_and_zero_limits_are_valid() -> None:
    p = _problem()
    p["cap"] = np.zeros(N)
    p["vel"] = (np.zeros(JOINTS), np.ones(JOINTS))
    assert time_optimal_grid(**p).status in STATUSES  # timed (or not), not refused
