"""The general 6R's test hooks (``kinematica._core_testing.general6r``) as tests call them."""

from __future__ import annotations

from typing import Any

import kinematica._core_testing as _core_testing
import numpy as np
from numpy.typing import NDArray

from kinematica.core import Chain

#: The general 6R family's internals and tolerances (the test-only module's).
G = _core_testing.general6r


def labelling(chain: Chain, start: int, reverse: bool) -> tuple[Any, float] | None:
    """The core's Params of one labelling of a 6R chain and its Q's σ8 / σ1, or None.

    None where its left side is rank-deficient (or the chain is not 6R); the ratio is
    NaN for a labelling with the target's link at L1 or L2 (its Q is the target's).
    """
    params, ratio = G.labelling(chain.core, G.LABELLINGS.index((start, reverse)))
    return None if params is None else (params, float(ratio))


def elimination(
    L1: NDArray[np.float64], L2: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """``(c0 (14,), Q (14, 8))``: the left side ``Rz(q'1) L1 Rz(q'2) L2 · z`` as c0 + Q S2.

    S2: the products of (1, cos q'1, sin q'1) ⊗ (1, cos q'2, sin q'2) but 1, in that
    order (c2, s2, c1, c1 c2, c1 s2, s1, s1 c2, s1 s2), found by the core exactly from
    their values on a 3 x 3 grid (``general_6r.hpp``, ``left_side``).
    """
    c0, Q = G.left_side(L1, L2)
    return np.asarray(c0), np.asarray(Q)


def field(params: Any, name: str) -> Any:
    """One field of a General6RParams (``general_6r.hpp``'s name), as the hooks read it."""
    return G.fields(params)[name]
