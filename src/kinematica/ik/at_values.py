"""A redundant arm's closed form solved at given values of its parameter.

``robot.ik(T, arm_angle=psi)`` solves an SRS 7R arm at the arm angle ``psi``
(:mod:`kinematica.ik.analytic.srs`): one value for every target, or one per
target. :class:`AtValues` stands in for the closed form's ``Params``
(``ik``, ``ik_batch``): one target is solved with a
copy set to its value (``Params.at(value)``), a batch by the core with each
target's value (``Params.ik_batch_at``), so that the solver built once per arm is
never changed.
"""

from __future__ import annotations

import math
import numbers
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.errors import ArgumentError, DimensionError

__all__ = ["AtValues", "parameter_values"]

FloatArray = NDArray[np.float64]


def parameter_values(name: str, value: ArrayLike, shape: tuple[int, ...]) -> FloatArray:
    """``(N,)`` the parameter's value for each of the targets of batch shape ``shape``.

    Args:
        name: The keyword (``"arm_angle"``), for messages.
        value: One number (every target), or an array of the targets' batch shape.
        shape: The targets' batch shape (``()`` for one target).

    Raises:
        ArgumentError: Not numbers, or NaN/inf among them.
        DimensionError: An array whose shape is not the targets' batch shape.
    """
    n = math.prod(shape)
    if isinstance(value, bool):
        raise ArgumentError(_not_numbers(name, value), arg=name)
    if isinstance(value, numbers.Real):  # one number: no array to build
        one = float(value)
        if not math.isfinite(one):
            raise ArgumentError(f"{name} must be finite, got {value!r}", arg=name)
        return np.full(n, one)
    try:
        v = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ArgumentError(_not_numbers(name, value), arg=name) from None
    if not np.all(np.isfinite(v)):
        raise ArgumentError(f"{name} must be finite, got {value!r}", arg=name)
    if v.ndim and v.shape != shape:
        raise DimensionError(
            f"{name} must be one number or one per target (shape {shape}), got shape {v.shape}",
            arg=name,
        )
    return np.ascontiguousarray(np.broadcast_to(v, shape).reshape(n))


def _not_numbers(name: str, value: object) -> str:
    """The message of a value that is not numbers, made only when it is raised.

    An array's repr costs more than the whole check: ``auto``'s arm-angle sweep spent
    half its time on it.
    """
    return f"{name} must be a number (rad) or an array of them, got {value!r}"


class AtValues:
    """A parametrised closed form's ``Params``, solving target i at ``values[i]``.

    Args:
        params: The closed form's ``Params``, with ``at(value)`` (a copy at it) and
            ``ik_batch_at`` (``ik_batch`` with a value per target, in the core).
        values: ``(N,)`` one value per target (the single-target methods take the first).
    """

    def __init__(self, params: Any, values: FloatArray) -> None:
        self._params = params
        self._values = values
        self._first = params.at(float(values[0])) if values.size else params

    def ik(self, chain: Any, T: Any, options: Any, q0: Any, labels: Any) -> Any:
        """``Params.ik`` at the first value."""
        return self._first.ik(chain, T, options, q0, labels)

    def ik_batch(
        self, chain: Any, T: FloatArray, options: Any, q0: Any, invalid: Any, workers: int
    ) -> Any:
        """``Params.ik_batch`` at one value, else ``Params.ik_batch_at`` (one per target)."""
        values = self._values
        if values.size and np.all(values == values[0]):
            return self._first.ik_batch(chain, T, options, q0, invalid, workers)
        return self._params.ik_batch_at(chain, T, values, options, q0, invalid, workers)
