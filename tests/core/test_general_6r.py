"""The general 6R solver's header (cpp/include/kinematica/solvers/general_6r.hpp) as bound.

Its Params refuse fields the solver cannot run with (a ValueError naming the field),
and its tolerances are exported under the names the header gives them.
"""

from __future__ import annotations

import kinematica._core as _core
import numpy as np
import pytest

import kinematica as km
from kinematica.ik.analytic import general_6r as g6


def _chain() -> km.core.Chain:
    arm = g6.sample_arm(np.random.default_rng(2), False)
    return km.Robot.from_dh(arm.links, convention=arm.convention).chain


def test_params_fields_are_checked() -> None:
    p = _core.general6r.General6RParams()
    T = np.eye(4)
    chain = _chain()
    p.t_link = 1
    with pytest.raises(ValueError, match="t_link"):
        p.candidates(chain.core, T)
    p.t_link = 5
    p.order = np.array([0, 0, 1, 2, 3, 4])
    with pytest.raises(ValueError, match="permutation"):
        p.candidates(chain.core, T)
    with pytest.raises(ValueError, match=r"N must have shape \(6, 14\)"):
        p.N = np.zeros((14, 6))


def test_the_header_s_constants_are_exported() -> None:
    g = _core.general6r
    assert g.SLOTS == g.CLASSES * g.PER_CLASS + g.FURTHER == len(g6.LABELS)
    assert (g.EQUATIONS, g.PRODUCTS, g.REDUCED) == (14, 8, 6)
    assert 0 < g.DOUBLE_ROOT_TOL < g.LEADING_RCOND_TOL < g.CLOSURE_TOL < 1
