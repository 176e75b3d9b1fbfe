"""A joint held where the arm left is nearly a continuum: which neighbour answers.

Tried before the numeric search on a 7R arm whose held arm has no closed form
(:meth:`kinematica.ik.parameter.JointParameter.solve`): first the coaxial neighbour,
where the held value makes two consecutive axes nearly one line
(:mod:`kinematica.ik.held_coaxial`), then the SRS neighbour of a nearly SRS arm
(:mod:`kinematica.ik.held_neighbour`). Where neither applies or finds a solution, the
search answers and the sweep over the arm's joints (:mod:`kinematica.ik.held_sweep`)
follows it.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from kinematica.core import Chain
from kinematica.ik.result import IKResult

if TYPE_CHECKING:
    from kinematica.ik.options import IKOptions

__all__ = ["near_continuum_answer"]

FloatArray = NDArray[np.float64]


def near_continuum_answer(
    chain: Chain,
    joint: int,
    value: float,
    name: str,
    T: FloatArray,
    options: IKOptions,
    lock: Callable[[Chain, int, float], Chain],
) -> IKResult | None:
    """The held arm's solutions found beside a neighbour's continuum, or None.

    Args:
        chain: The 7R arm.
        joint: The held joint (0-based).
        value: Its value (rad).
        name: Its name, as results name the parameter.
        T: ``(4, 4)`` the target (base frame, m).
        options: The call's settings.
        lock: ``(chain, joint, value)`` -> the arm with that joint held (the kept one).

    Returns:
        The answer (``near_singular``, never complete), or None where no neighbour
        applies or none found a solution.
    """
    from kinematica.ik.held_coaxial import near_coaxial_answer
    from kinematica.ik.held_continuum import continuum_answer
    from kinematica.ik.held_neighbour import neighbour_sweep
    from kinematica.ik.held_sweep import sweep_result
    from kinematica.ik.solve import solve_ik

    if T.shape != (4, 4):
        return None
    respect = bool(options.respect_limits)
    held = lock(chain, joint, value)
    swept = near_coaxial_answer(held, joint, value, T, options)
    if swept is not None:  # isolated solutions beside a continuum's circles: not one
        return sweep_result(chain, *swept, T, respect, (name, value))
    swept = neighbour_sweep(chain, held, joint, value, T, options)
    if swept is None:
        return None
    res = sweep_result(chain, *swept, T, respect, (name, value))
    return continuum_answer(chain, joint, value, name, T, res, options, lock, solve_ik)
