"""The geometric path a time-optimal timing follows, and its grid.

A path is ``q(s)`` for ``s`` in [0, 1], a polynomial between knots
(:class:`~kinematica.motion.piecewise.PiecewisePolynomial` in ``s`` instead of
time):

- ``(k, n)`` waypoints: the natural cubic spline (C2, zero ``q''`` at both
  ends) through them, the knots at their normalised cumulative joint-space chord
  length (``s_k = Σ|ΔW| / total``), so that ``|q'(s)|`` stays near the path's
  length and ``ṡ`` is a speed along it;
- a :class:`~kinematica.motion.trajectory.JointTrajectory`: the quintic
  Hermite pieces through its samples with their velocities and accelerations,
  ``s = t / T`` (the path it traces, C2, exactly as sampled);
- a :class:`~kinematica.motion.cartesian.CartesianPath`: the natural cubic
  spline through its configurations at its own ``s``.

The grid puts every knot on it and splits each knot interval evenly, so that
every grid interval lies within one polynomial piece (the core bounds the
limits over whole intervals from the piece's coefficients).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from kinematica.errors import DimensionError, KinematicaError
from kinematica.motion.piecewise import PiecewisePolynomial
from kinematica.motion.splines import hermite_pieces, spline_derivatives
from kinematica.motion.trajectory import JointTrajectory

__all__ = ["grid_for", "spline_path", "taylor_coefficients", "trajectory_path", "waypoint_path"]

FloatArray = NDArray[np.float64]


def spline_path(knots: FloatArray, q: FloatArray) -> PiecewisePolynomial:
    """The natural cubic spline through ``q`` ``(k, n)`` at increasing ``knots`` ``(k,)``."""
    zero = np.zeros((1, q.shape[1]))
    derivs = spline_derivatives(knots, q, 2, "natural", zero, zero)
    return hermite_pieces(knots, q, derivs)


def waypoint_path(W: FloatArray) -> PiecewisePolynomial:
    """The natural cubic spline through waypoints ``W`` ``(k, n)`` at chord-length knots.

    Raises:
        KinematicaError: Two consecutive waypoints equal (no chord to measure).
    """
    chord = np.linalg.norm(np.diff(W, axis=0), axis=1)
    if np.any(chord == 0.0):
        i = int(np.flatnonzero(chord == 0.0)[0])
        raise KinematicaError(f"waypoints {i + 1} and {i + 2} are equal: drop the repeat")
    knots = np.concatenate([[0.0], np.cumsum(chord)]) / chord.sum()
    knots[-1] = 1.0
    return spline_path(knots, W)


def trajectory_path(traj: JointTrajectory) -> PiecewisePolynomial:
    """The quintic Hermite path in ``s = t / T`` through a trajectory's samples.

    Raises:
        DimensionError: Fewer than two samples, or shapes that differ.
        KinematicaError: Times not increasing.
    """
    t, q, qd, qdd = (np.asarray(a, dtype=float) for a in traj)
    if t.ndim != 1 or t.size < 2 or q.shape != (t.size, q.shape[-1]) or q.ndim != 2:
        raise DimensionError("the trajectory must hold >= 2 samples: t (m,), q, qd, qdd (m, n)")
    if qd.shape != q.shape or qdd.shape != q.shape:
        raise DimensionError("the trajectory's q, qd and qdd must have one shape")
    T = float(t[-1] - t[0])
    if not np.all(np.diff(t) > 0) or not np.isfinite(T):
        raise KinematicaError("the trajectory's times must increase")
    s = (t - t[0]) / T
    s[-1] = 1.0
    derivs = np.stack([qd * T, qdd * (T * T)], axis=1)
    return hermite_pieces(s, q, derivs)


def grid_for(knots: FloatArray, grid: int) -> tuple[FloatArray, FloatArray]:
    """``(s (N+1,), piece (N,))``: about ``grid`` intervals, every knot on the grid.

    Each knot interval of width ``w`` gets ``max(1, ceil(grid·w))`` equal
    intervals; ``piece[i]`` is the polynomial piece holding interval ``i``.
    """
    parts = [knots[:1]]
    pieces = []
    for j in range(knots.size - 1):
        a, b = float(knots[j]), float(knots[j + 1])
        m = max(1, math.ceil(grid * (b - a) - 1e-9))
        seg = np.linspace(a, b, m + 1)[1:]
        seg[-1] = b
        parts.append(seg)
        pieces.append(np.full(m, j))
    return np.concatenate(parts), np.concatenate(pieces)


def taylor_coefficients(pp: PiecewisePolynomial, s: FloatArray, piece: FloatArray) -> FloatArray:
    """``(N, d + 1, n)``: each grid interval's polynomial in ``τ = s - s_i``.

    ``c_m = q⁽ᵐ⁾(s_i) / m!``, shifted from the piece's own coefficients
    (``c_m = Σ_{j>=m} C(j, m)·a_j·δ^(j-m)``, ``δ = s_i - breaks[piece]``).
    """
    a = pp.coef[piece]  # (N, d + 1, n)
    d1 = a.shape[1]
    delta = (s[:-1] - pp.breaks[piece])[:, None]
    out = np.zeros_like(a)
    for m in range(d1):
        for j in range(m, d1):
            out[:, m, :] += math.comb(j, m) * a[:, j, :] * delta ** (j - m)
    return out
