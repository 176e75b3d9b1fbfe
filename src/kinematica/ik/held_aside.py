"""A batch held at its values with the targets proved out of reach there left unsolved.

``auto`` holds a 7R arm's joint at one value per target (:mod:`kinematica.ik.redundancy`);
a target the reach bounds prove has no solution at its value
(:mod:`kinematica.ik.reach_bounds`) is answered at the nearest value with one, or by the
search over every joint, as its single call is. Solving it at its value first would
find nothing (the elimination, then the numeric search, in vain): its row is left
unsolved (not found, no solution) and the others are solved together.
"""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

import kinematica._core as _core
from kinematica.core import Chain
from kinematica.ik.parameter import Parameter
from kinematica.ik.result import IKBatchResult

if TYPE_CHECKING:
    from kinematica.ik.options import IKOptions

__all__ = ["solved_except"]

FloatArray = NDArray[np.float64]

_NOT_FOUND = _core.STATUS["not_found"]


def solved_except(
    chain: Chain,
    joint: Parameter,
    poses: FloatArray,
    shape: tuple[int, ...],
    values: FloatArray,
    options: IKOptions,
    q0s: FloatArray | None,
    aside: NDArray[np.bool_],
) -> IKBatchResult:
    """The targets held at ``values``, those ``aside`` not solved (not found, no solution).

    Args:
        chain: The whole arm.
        joint: The joint held.
        poses: ``(N, 4, 4)`` the targets (flat, C order), each valid, none of them noted.
        shape: The batch's shape.
        values: ``(N,)`` each target's value.
        options: The IK settings.
        q0s: ``(N, n)`` q0 per target, or None.
        aside: ``(N,)`` the targets not solved.
    """
    keep = np.flatnonzero(~aside)
    # with every target aside, the first is solved for the batch's method and labels alone
    solve = keep if keep.size else np.arange(1)
    opts = options if q0s is None else dataclasses.replace(options, q0=q0s[solve])
    sub = joint.solve(chain, np.ascontiguousarray(poses[solve]), values[solve], opts)
    assert isinstance(sub, IKBatchResult)
    a, N = sub.raw, aside.size

    def full(x: NDArray[Any], fill: Any) -> NDArray[Any]:
        out = np.full((N, *x.shape[1:]), fill, dtype=x.dtype)
        out[keep] = x[: keep.size]
        return out

    raw = _core.BatchAnswer(
        full(a.q, np.nan), full(a.slot, -1), full(a.res, np.nan), full(a.status, _NOT_FOUND),
        full(a.count, 0), full(a.out_count, 0), full(a.gap, np.nan), full(a.nearest, np.nan),
        full(a.near, False), full(a.free, False),
    )  # fmt: skip

    def placed(d: dict[tuple[int, ...], Any]) -> dict[tuple[int, ...], Any]:
        at = [j for (j,) in d if j < keep.size]
        return {tuple(int(c) for c in np.unravel_index(int(keep[j]), shape)): d[(j,)] for j in at}

    held = None if sub.parameter is None else (sub.parameter[0], values.reshape(shape))
    return dataclasses.replace(
        sub, raw=raw, shape=shape, errors=placed(dict(sub.errors)), notes=placed(dict(sub.notes)),
        methods=placed(dict(sub.methods)), parameter=held,
    )  # fmt: skip
