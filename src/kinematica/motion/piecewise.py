"""Piecewise polynomials in time: the joint trajectories through waypoints.

Each piece is a polynomial in the local time ``τ = t - breaks[i]`` (lowest
power first), one per joint, so the value at the start of a piece is its
constant coefficient exactly: a waypoint set at a break is hit to the bit.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.motion.samples import JointTrajectory, sample_times

__all__ = ["PiecewisePolynomial"]

FloatArray = NDArray[np.float64]


def _times_between(knots: FloatArray, dt: float) -> FloatArray:
    """Samples uniform within each knot interval (spacing <= dt), every knot among them."""
    parts = [knots[:1]]
    for a, b in itertools.pairwise(knots):
        seg = a + sample_times(b - a, dt)[1:]
        seg[-1] = b
        parts.append(seg)
    return np.concatenate(parts)


def _real_parts_of_roots(polys: FloatArray) -> FloatArray:
    """``(N, d)`` real parts of the roots of each row's polynomial (lowest power first).

    Rows are grouped by their degree (highest non-zero coefficient); each
    group's roots are the eigenvalues of its companion matrices. Missing roots
    (a lower degree) are NaN; complex roots give their real part, which is
    only an extra candidate point for the caller.
    """
    N, d1 = polys.shape
    out = np.full((N, d1 - 1), np.nan)
    nonzero = polys != 0.0
    degree = np.where(nonzero.any(axis=1), d1 - 1 - np.argmax(nonzero[:, ::-1], axis=1), 0)
    for deg in range(1, d1):
        rows = np.flatnonzero(degree == deg)
        if rows.size == 0:
            continue
        c = polys[rows, : deg + 1]
        if deg == 1:  # a line: its root directly (a 1 x 1 eigenproblem per row is slow)
            out[rows, 0] = -c[:, 0] / c[:, 1]
            continue
        comp = np.zeros((rows.size, deg, deg))
        comp[:, 1:, :-1] = np.eye(deg - 1)
        comp[:, :, -1] = -c[:, :deg] / c[:, deg : deg + 1]
        out[rows, :deg] = np.real(np.linalg.eigvals(comp))
    return out


@dataclass(frozen=True)
class PiecewisePolynomial:
    """Joint values ``q(t)``, one polynomial per piece and joint.

    Attributes:
        breaks: ``(p + 1,)`` increasing times (s) where the pieces meet;
            ``breaks[0]`` is 0, ``breaks[-1]`` the duration.
        coef: ``(p, d + 1, n)`` coefficients of piece ``i`` in ``τ = t -
            breaks[i]`` (lowest power first; rad or m, per second powers).
        knots: ``(k,)`` the waypoints' times (s): the breaks of a spline;
            for ``"mstraj"`` every break (whole steps of its ``dt``).
    """

    breaks: FloatArray
    coef: FloatArray
    knots: FloatArray

    @property
    def duration(self) -> float:
        """The last break (s)."""
        return float(self.breaks[-1])

    def _derivative(self, order: int) -> FloatArray:
        d = self.coef.shape[1] - 1
        if order > d:
            return np.zeros((self.coef.shape[0], 1, self.coef.shape[2]))
        k = np.arange(order, d + 1)
        fall = np.array([math.perm(int(j), order) for j in k], dtype=float)
        out: FloatArray = self.coef[:, order:, :] * fall[None, :, None]
        return out

    def __call__(self, t: ArrayLike, order: int = 0, left: bool = False) -> FloatArray:
        """The ``order``-th time derivative at ``t``.

        Args:
            t: ``(m,)`` times (s); outside ``[0, duration]`` the end pieces extend.
            order: 0 for q, 1 for qd, 2 for qdd, ...
            left: At a break, use the piece that ends there (the left limit)
                instead of the one that starts there.

        Returns:
            ``(m, n)`` values.
        """
        ta = np.atleast_1d(np.asarray(t, dtype=float))
        side: Literal["left", "right"] = "left" if left else "right"
        i = np.clip(np.searchsorted(self.breaks, ta, side=side) - 1, 0, self.coef.shape[0] - 1)
        tau = (ta - self.breaks[i])[:, None]
        c = self._derivative(order)[i]  # (m, d + 1 - order, n)
        out = c[:, -1, :].copy()
        for j in range(c.shape[1] - 2, -1, -1):
            out = out * tau + c[:, j, :]
        return out

    def peak(self, order: int) -> FloatArray:
        """``(n,)`` largest ``|q^(order)(t)|`` over the whole trajectory.

        Exact to round-off: each piece's extremes are at its ends or at the
        real roots of the next derivative within it.
        """
        c = self._derivative(order)  # (p, d + 1, n)
        h = np.diff(self.breaks)
        p, d1, n = c.shape
        polys = np.moveaxis(c, 1, -1).reshape(p * n, d1)  # one row per piece and joint
        span = np.repeat(h, n)
        cand = [np.zeros(p * n), span]
        if d1 > 1:
            dpoly = polys[:, 1:] * np.arange(1, d1)  # the next derivative
            roots = _real_parts_of_roots(dpoly)
            cand.extend(np.clip(np.nan_to_num(r, nan=0.0), 0.0, span) for r in roots.T)
        x = np.stack(cand, axis=1)  # (p*n, candidates)
        val = np.zeros_like(x)
        for j in range(d1 - 1, -1, -1):
            val = val * x + polys[:, j : j + 1]
        out: FloatArray = np.abs(val).max(axis=1).reshape(p, n).max(axis=0)
        return out

    def sample(self, dt: float) -> JointTrajectory:
        """Samples every ``dt`` or closer, with every knot time among them.

        The last sample is the end value of the last piece, the final waypoint
        to round-off.
        """
        t = _times_between(self.knots, dt)
        return JointTrajectory(t, self(t), self(t, 1), self(t, 2))
