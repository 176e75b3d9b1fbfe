"""Linear segments with parabolic blends through via points (the Toolbox's ``mstraj``).

Waypoints ``w_0 .. w_{k-1}`` have nominal times ``τ_0 = 0 < τ_1 < ... <
τ_{k-1} = T``. Between them the joints move along straight lines at constant
velocity; every corner is a blend of duration ``tacc`` at constant
acceleration that joins one line to the next tangentially (continuous
velocity). The rule, Craig's linear-parabolic blends with a fixed blend time:

- the line of an interior segment passes through ``(τ_i, w_i)`` and
  ``(τ_{i+1}, w_{i+1})``; the blend at via ``i`` is centred on ``τ_i``
  (``[τ_i - tacc/2, τ_i + tacc/2]``) with acceleration ``(v_i - v_{i-1}) /
  tacc``. The via point itself is not passed: at ``τ_i`` the joints are at
  ``w_i + (v_i - v_{i-1})·tacc/8``, as ``mstraj`` cuts its corners;
- the first blend starts at rest at ``w_0`` at ``t = 0`` and lasts ``tacc``;
  the first line passes ``w_0`` at ``tacc/2`` (so its velocity is ``(w_1 -
  w_0) / (τ_1 - tacc/2)``), and the last likewise ends at rest exactly at
  ``w_{k-1}`` at ``T``. Start and end are reached exactly;
- with speed limits and no times, each segment lasts the time its slowest
  joint needs at its limit (plus ``tacc/2`` for the first and the last
  segment), so one joint cruises at its limit; and never less than the
  blends need (``tacc``, and ``1.5·tacc`` for the first and last).

Differences from the Toolbox's ``mstraj``, which works on a sample grid: its
times are rounded up to multiples of ``dt``, its segment time adds the whole
blend time to the cruise time, and its blends are quintic polynomials
(``jtraj``) rather than parabolas. The rule above is its continuous-time
form: constant acceleration in the blends, exact times.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from kinematica.errors import KinematicaError
from kinematica.motion.piecewise import PiecewisePolynomial
from kinematica.motion.trajectory import DURATION_RTOL

__all__ = ["blend_pieces", "blend_times"]

FloatArray = NDArray[np.float64]


def _end_share(k: int, tacc: float) -> FloatArray:
    """``(k-1,)`` the part of each segment taken by the start and end blends' halves."""
    e = np.zeros(k - 1)
    e[0] += 0.5 * tacc
    e[-1] += 0.5 * tacc
    return e


def blend_times(w: FloatArray, vmax: FloatArray, tacc: float) -> FloatArray:
    """``(k,)`` waypoint times from per-segment, per-joint speed limits.

    Args:
        w: ``(k, n)`` waypoints.
        vmax: ``(k - 1, n)`` speed limits (> 0) of each segment and joint.
        tacc: Blend time (s).
    """
    k = w.shape[0]
    e = _end_share(k, tacc)
    cruise = (np.abs(np.diff(w, axis=0)) / vmax).max(axis=1)
    seg = np.maximum(cruise + e, tacc + e)
    return np.concatenate([[0.0], np.cumsum(seg)])


def blend_pieces(w: FloatArray, times: FloatArray, tacc: float) -> PiecewisePolynomial:
    """Lines and parabolic blends through ``w`` at nominal ``times``.

    Args:
        w: ``(k, n)`` waypoints, k >= 2.
        times: ``(k,)`` increasing nominal times (s), from 0.
        tacc: Blend time (s) > 0.

    Returns:
        Quadratic pieces; ``knots`` are the nominal ``times``.

    Raises:
        KinematicaError: Two waypoints too close in time for their blends.
    """
    k, n = w.shape
    e = _end_share(k, tacc)
    span = np.diff(times)
    need = tacc + e
    short = span < need * (1.0 - DURATION_RTOL)
    if short.any():
        i = int(np.flatnonzero(short)[0])
        raise KinematicaError(
            f"waypoints {i + 1} and {i + 2} are {span[i]:.6g} s apart: blends of tacc "
            f"{tacc:g} s need at least {need[i]:.6g} s"
        )
    v = np.diff(w, axis=0) / (span - e)[:, None]  # (k-1, n) line velocities
    # Line i passes w_i at its anchor time (τ_i, or tacc/2 for the first line).
    anchor = times[:-1].copy()
    anchor[0] += 0.5 * tacc

    def line(i: int, t: float) -> FloatArray:
        out: FloatArray = w[i] + v[i] * (t - anchor[i])
        return out

    breaks: list[float] = [0.0]
    coef: list[FloatArray] = []
    zero = np.zeros(n)

    def piece(t_end: float, q: FloatArray, qd: FloatArray, qdd: FloatArray) -> None:
        if t_end > breaks[-1]:  # a line of zero length between two blends is left out
            coef.append(np.stack([q, qd, 0.5 * qdd]))
            breaks.append(t_end)

    piece(tacc, w[0], zero, v[0] / tacc)  # start blend, from rest
    for i in range(k - 1):
        start = tacc if i == 0 else times[i] + 0.5 * tacc
        stop = times[-1] - tacc if i == k - 2 else times[i + 1] - 0.5 * tacc
        piece(stop, line(i, start), v[i], zero)
        if i < k - 2:
            piece(times[i + 1] + 0.5 * tacc, line(i, stop), v[i], (v[i + 1] - v[i]) / tacc)
    piece(times[-1], line(k - 2, times[-1] - tacc), v[-1], -v[-1] / tacc)  # to rest
    return PiecewisePolynomial(np.array(breaks), np.stack(coef), np.asarray(times, dtype=float))
