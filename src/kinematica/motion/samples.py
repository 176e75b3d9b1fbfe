"""Samples of a joint trajectory, and the spacing and tolerances every timing shares.

Below :mod:`~kinematica.motion.trajectory`, :mod:`~kinematica.motion.piecewise`
and :mod:`~kinematica.motion.scurve`, which all make or check them.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numpy.typing import NDArray

__all__ = ["DURATION_RTOL", "LIMIT_RTOL", "MAX_SAMPLES", "JointTrajectory", "sample_times"]

FloatArray = NDArray[np.float64]

#: Relative shortfall of a given duration (or waypoint spacing) below the
#: shortest one accepted as round-off of the times' arithmetic.
DURATION_RTOL = 1e-12
#: Relative excess over ``vmax``/``amax`` accepted as round-off when checking given times.
LIMIT_RTOL = 1e-9
#: Most samples a trajectory has (duration / dt + 1): ~50 MB of q, qd, qdd for 6 joints.
MAX_SAMPLES = 1_000_000


class JointTrajectory(NamedTuple):
    """Samples of a joint trajectory (unpacks as ``t, q, qd, qdd``).

    Attributes:
        t: ``(m,)`` times (s), from 0 to the duration.
        q: ``(m, n)`` joint values (rad, m).
        qd: ``(m, n)`` joint velocities (rad/s, m/s).
        qdd: ``(m, n)`` joint accelerations (rad/s², m/s²).
    """

    t: FloatArray
    q: FloatArray
    qd: FloatArray
    qdd: FloatArray

    def _repr_html_(self) -> str:
        """A few samples' joint values as an HTML table (Jupyter)."""
        from kinematica.motion.display import samples_html

        m, n = self.q.shape
        duration = float(self.t[-1]) if m else 0.0
        caption = f"{n} joints, {m} samples over {duration:g} s (q in rad, m)"
        return samples_html(self.t, self.q, time_name="t (s)", caption=caption)


def sample_times(T: float, dt: float) -> FloatArray:
    """``(m,)`` uniform times from 0 to ``T`` (the last exactly ``T``), spacing <= ``dt``."""
    m = max(2, math.ceil(T / dt - 1e-9) + 1)
    t = np.linspace(0.0, T, m)
    t[-1] = T
    return t
