"""The Robotics Toolbox's ``mstraj``: lines through via points, quintic blends, on a dt grid.

Peter Corke's multi-segment trajectory (Robotics Toolbox for Python 1.5,
``roboticstoolbox.tools.trajectory.mstraj``; *Robotics, Vision and Control*,
3rd ed., ch. 3), reproduced sample for sample (the tests hold it to the
Toolbox's own output to 1e-12, ``tests/data/rtb_mstraj.json``). Waypoints
``w_0 .. w_{k-1}``; segment ``i`` runs from ``w_i`` to ``w_{i+1}``:

- **Its time** ``T_i``: given (the Toolbox's ``tsegment``, here the differences
  of ``times``), or from the speed limits (``qdmax``, here ``vmax``): the blend
  time before it plus its slowest joint's ``|Δq| / vmax``, each rounded up to
  a whole number of steps ``dt``, and at least two blend times. The blend time
  ``tacc_i`` (one for all segments or one each) is rounded up to whole steps,
  and so is its half ``h_i``; the first segment's blend is that half alone.
- **Its line**: ``q = w_i + (t / T_i)·(w_{i+1} - w_i)`` in the segment's own time
  ``t``, sampled at whole steps from ``h_i + dt`` to ``T_i - h_i``, at the
  velocity ``(w_{i+1} - w_i) / T_i``.
- **Its blend**: the quintic (``jtraj``) from the last sample of the line before
  (the start ``w_0`` for the first) to its own line at ``t = h_i``, from the
  velocity before (``qd0`` at the start) to its line's, with zero acceleration
  at both ends; it lasts ``tacc_i`` (``h_0`` for the first). The via point is
  not passed: the blend cuts the corner. A last blend of ``h`` brings the arm
  from the last line's last sample to ``w_{k-1}`` at the velocity ``qdf`` (here
  ``qd1``), zero by default.

Speed limits bound the lines, not the blends: the first line passes ``w_0`` at
``t = 0`` and its blend, starting there at rest, must catch up with it (``Δ =
T·v`` in ``T``), so the quintic peaks at 1.512 times the line's speed (``v·(15s⁴
- 32s³ + 18s²)`` at ``s = 0.6``), and the last blend likewise; as in the Toolbox.

The steps are counted as the Toolbox counts them, in floating point:
``ceil(tacc / dt)`` steps, then ``ceil(that·dt / 2 / dt)`` for the half, so a
blend of 0.6 s at ``dt = 0.1`` s has a half of 4 steps, not 3 (0.6000000000000001
/ 0.2 is just above 3), as in the Toolbox. A segment of ``k`` blend steps with
``k`` odd runs its blend ``dt`` short of two halves: the Toolbox's timing too.

Where this differs from the Toolbox, on purpose:

- **The start is a sample.** The Toolbox leaves ``w_0`` (its ``q0``) out of
  its output and stamps its first sample, taken one step after the start,
  ``t = 0``; here ``t = 0`` is ``w_0`` and every sample is one step later than
  the Toolbox's stamp: one more sample, the duration one ``dt`` longer.
- **A segment too short for its line** (given times shorter than its blends:
  no line sample between ``h_i + dt`` and ``T_i - h_i``): the Toolbox starts
  the next blend from the last line sample of an earlier segment (its start
  point is only updated on a line), so its samples jump; here the next blend
  starts where the arm is, the end of the last blend.
- **The last sample is the last waypoint** exactly (the Toolbox's is the
  quintic's value there, equal to round-off; without blends and with times
  that are no whole number of steps, its last line sample).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from kinematica.errors import KinematicaError
from kinematica.motion.piecewise import PiecewisePolynomial

__all__ = ["mstraj_pieces"]

FloatArray = NDArray[np.float64]


def _steps(x: float, dt: float) -> int:
    """The number of steps of ``dt`` in ``x``, as the Toolbox's ``round(x / dt)``."""
    return round(x / dt)


class _Pieces:
    """Pieces on the grid of steps: each starts at a whole step, lowest power first."""

    def __init__(self, n: int) -> None:
        self.n = n
        self.steps: list[int] = [0]  # break indices
        self.coef: list[FloatArray] = []

    @property
    def at(self) -> int:
        return self.steps[-1]

    def blend(
        self, steps: int, dt: float, q0: FloatArray, q1: FloatArray, v0: FloatArray, v1: FloatArray
    ) -> None:
        """The Toolbox's ``jtraj`` quintic from ``(q0, v0)`` to ``(q1, v1)`` over ``steps``.

        Zero acceleration at both ends; in the normalised time ``s = τ / T``:
        ``q = A s⁵ + B s⁴ + C s³ + T·v0·s + q0``.
        """
        T = steps * dt
        d = q1 - q0
        A = 6 * d - 3 * (v1 + v0) * T
        B = -15 * d + (8 * v0 + 7 * v1) * T
        C = 10 * d - (6 * v0 + 4 * v1) * T
        zero = np.zeros(self.n)
        c = np.stack([q0, v0, zero, C / T**3, B / T**4, A / T**5])
        self.coef.append(c)
        self.steps.append(self.at + steps)

    def line(self, steps: int, q: FloatArray, v: FloatArray) -> None:
        """``q + v·τ`` for ``steps`` steps."""
        c = np.zeros((6, self.n))
        c[0], c[1] = q, v
        self.coef.append(c)
        self.steps.append(self.at + steps)


def _segment_time(
    dq: FloatArray, dt: float, taccx: float, tacc_seg: float, vmax: FloatArray
) -> float:
    """The Toolbox's segment time from speed limits, each part rounded up to dt."""
    tl = np.ceil((np.abs(dq) / vmax) / dt) * dt
    tseg = float((taccx + tl).max())
    return 2 * tacc_seg if tseg <= 2 * tacc_seg else tseg


def mstraj_pieces(
    w: FloatArray,
    dt: float,
    tacc: FloatArray,
    *,
    vmax: FloatArray | None = None,
    times: FloatArray | None = None,
    qd0: FloatArray,
    qd1: FloatArray,
) -> PiecewisePolynomial:
    """The Toolbox's ``mstraj`` through ``w`` as pieces on the grid of ``dt`` (module docstring).

    Args:
        w: ``(k, n)`` waypoints (rad, m), k >= 2, the start first.
        dt: Step (s) > 0.
        tacc: ``(k - 1,)`` blend time (s) >= 0 at the start of each segment.
        vmax: ``(k - 1, n)`` speed limits (> 0) timing each segment, or None.
        times: ``(k,)`` waypoint times (s) from 0, increasing, when ``vmax`` is None.
        qd0: ``(n,)`` start velocity.
        qd1: ``(n,)`` end velocity.

    Returns:
        Pieces whose breaks (and ``knots``) are whole steps: sampled at
        ``t = j·dt`` with ``left=True`` they are the Toolbox's samples.

    Raises:
        KinematicaError: The waypoints all equal and no blend: nothing to sample.
    """
    k, n = w.shape
    out = _Pieces(n)
    here = w[0]  # the last sample's position
    v_prev = qd0
    tacc2 = 0.0
    for i in range(k - 1):
        tacc_seg = math.ceil(tacc[i] / dt) * dt
        tacc2 = math.ceil(tacc_seg / 2 / dt) * dt
        taccx = tacc2 if i == 0 else tacc_seg
        dq = w[i + 1] - w[i]
        if vmax is not None:
            tseg = _segment_time(dq, dt, taccx, tacc_seg, vmax[i])
        else:
            assert times is not None
            tseg = float(times[i + 1] - times[i])
        v = dq / tseg if tseg > 0 else np.zeros(n)
        blend_steps = _steps(taccx, dt)
        if blend_steps > 0:
            end = w[i] + tacc2 * v
            out.blend(blend_steps, dt, here, end, v_prev, v)
            here = end
        first, last = _steps(tacc2 + dt, dt), _steps(tseg - tacc2, dt)
        if last >= first:
            h = first - 1  # the line's own time at the start of its piece, in steps
            out.line(last - h, w[i] + (h * dt) * v, v)
            s = last * dt / tseg
            here = (1 - s) * w[i] + s * w[i + 1]
        v_prev = v
    final_steps = _steps(tacc2, dt)
    if final_steps > 0:
        out.blend(final_steps, dt, here, w[-1], v_prev, qd1)
    if out.at == 0:
        raise KinematicaError("mstraj: the waypoints are all equal and tacc is 0: nothing moves")
    breaks = np.asarray(out.steps, dtype=float) * dt
    return PiecewisePolynomial(breaks, np.stack(out.coef), breaks.copy())
