"""The core's time-optimal timing of one path on a grid (``cpp/include/kinematica/topp.hpp``).

The caller (:mod:`kinematica.motion.optimal`) builds the grid and the path's
coefficients and checks the user's input; this module only names what the core
returns.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import NDArray

import kinematica._core as _core

__all__ = ["KINDS", "MAX_DEGREE", "STATUSES", "GridTiming", "time_optimal_grid"]

FloatArray = NDArray[np.float64]

#: The core's statuses, by number.
STATUSES = ("ok", "stuck", "start_outside", "empty", "interrupted")
#: What a limit is about, by the core's number.
KINDS = ("velocity", "acceleration", "cap", "next_set", "none")
#: Highest degree of a path piece the core takes.
MAX_DEGREE: int = _core.TOPP_MAX_DEGREE


class GridTiming(NamedTuple):
    """The core's answer; every array ``(N + 1,)`` holds squared path speeds ``ṡ²``.

    Attributes:
        status: ``"ok"``, ``"stuck"`` (a limit holds the path at rest at ``stage``),
            ``"start_outside"`` (the start speed is not controllable) or ``"empty"``
            (no controllable set at ``stage``: the end speed cannot be met).
        stage: Grid index where the timing stops (-1 when ``"ok"``).
        kind: What stops it: ``"velocity"``, ``"acceleration"``, ``"cap"`` or ``"none"``.
        joint: Its joint (0-based) for a velocity or acceleration limit, else -1.
        x: The timing's ``ṡ²`` (NaN past ``stage``).
        k_lo: Lower ends of the controllable sets (NaN where empty).
        k_hi: Upper ends of the controllable sets.
        r_lo: Lower ends of the reachable sets.
        r_hi: Upper ends of the reachable sets.
        mvc: The largest ``ṡ²`` each stage's own limits allow (the limit curve).
    """

    status: str
    stage: int
    kind: str
    joint: int
    x: FloatArray
    k_lo: FloatArray
    k_hi: FloatArray
    r_lo: FloatArray
    r_hi: FloatArray
    mvc: FloatArray


def time_optimal_grid(
    s: FloatArray,
    coef: FloatArray,
    vel: tuple[FloatArray, FloatArray],
    acc: tuple[FloatArray, FloatArray],
    cap: FloatArray,
    x_start: float,
    x_end: float,
    x_max: float,
    sets: bool = True,
) -> GridTiming:
    """TOPP-RA in the core, limits held over every grid interval.

    Args:
        s: ``(N + 1,)`` increasing grid of the path parameter.
        coef: ``(N, d + 1, n)`` Taylor coefficients of ``q`` at each ``s_i``
            (in ``s - s_i``), ``d <= MAX_DEGREE``.
        vel: ``(lo, hi)``, each ``(n,)``: joint velocity limits, ``lo <= 0 <= hi``
            (``±inf``: none).
        acc: ``(lo, hi)``: joint acceleration limits likewise.
        cap: ``(N,)`` largest ``ṡ²`` within each interval (``inf``: none).
        x_start: ``ṡ²`` at ``s[0]``.
        x_end: ``ṡ²`` at ``s[-1]``.
        x_max: Largest ``ṡ²`` anywhere.
        sets: Also the limit curve and the reachable sets (else NaN): about 2x the work.

    Returns:
        The :class:`GridTiming`.
    """
    f = np.ascontiguousarray
    out = _core.time_optimal(
        f(s, dtype=float),
        f(coef, dtype=float),
        f(vel[0], dtype=float),
        f(vel[1], dtype=float),
        f(acc[0], dtype=float),
        f(acc[1], dtype=float),
        f(cap, dtype=float),
        float(x_start),
        float(x_end),
        float(x_max),
        bool(sets),
    )
    status, stage, kind, joint, rows = out  # rows (6, N + 1): x, k_lo, k_hi, r_lo, r_hi, mvc
    return GridTiming(STATUSES[status], int(stage), KINDS[kind], int(joint), *rows)
