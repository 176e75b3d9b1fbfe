"""Cartesian paths timed by the robot: the fastest timing within its limits.

:func:`~kinematica.motion.cartesian.cartesian_path` and
:func:`~kinematica.motion.cartesian_via.cartesian_via_path` follow their path at
``steps`` samples; given joint or tool-speed limits they then time the spline
through those configurations with :func:`~kinematica.motion.optimal.time_optimal`
and return the path sampled in time. Where the Jacobian degenerates the joint
rates per unit of path grow, so the timing slows there instead of exceeding a
joint rate; the events say where (``"slowed"``, with the limit that binds) and,
when a blocking event (a singular crossing, an unreachable pose, a joint limit, a
branch change) or a limit ends the path early, where it stops (``"stopped"``).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.motion.cartesian_types import CartesianPath, PathEvent
from kinematica.motion.optimal import DEFAULT_GRID, time_optimal

if TYPE_CHECKING:
    from kinematica.robot import Robot

__all__ = ["Timing", "time_cartesian"]

FloatArray = NDArray[np.float64]
#: The timing options of a Cartesian path: vmax, amax, tcp_speed, tcp_angular_speed, dt.
Timing = tuple[ArrayLike | None, ArrayLike | None, float | None, float | None, float]


def time_cartesian(
    robot: Robot,
    geometry: Callable[[FloatArray], FloatArray],
    path: CartesianPath,
    timing: Timing,
    grid: int = DEFAULT_GRID,
) -> CartesianPath:
    """``path`` timed within the limits ``timing`` and sampled every ``dt``.

    Args:
        robot: The robot.
        geometry: Path parameter ``(m,)`` to the poses ``(m, 4, 4)`` asked for.
        path: The path followed at its samples (IK), with its events.
        timing: ``(vmax, amax, tcp_speed, tcp_angular_speed, dt)`` as for
            :func:`~kinematica.motion.optimal.time_optimal`.
        grid: Grid intervals of the timing.

    Returns:
        The timed :class:`CartesianPath`: ``t``, ``qd``, ``qdd`` set, ``s`` the
        path parameter at each time, ``q`` the joint path at it, ``poses`` the
        poses asked for there, and the events with ``"slowed"`` and ``"stopped"``.
    """
    vmax, amax, tcp_speed, tcp_angular_speed, dt = timing
    res = time_optimal(
        path,
        vmax,
        amax,
        robot,
        tcp_speed=tcp_speed,
        tcp_angular_speed=tcp_angular_speed,
        dt=dt,
        grid=grid,
    )
    tr, ss = res.trajectory, res.s_samples
    m = ss.size

    def at(s: float) -> int:
        return min(int(np.searchsorted(ss, s)), m - 1)

    events = [PathEvent(e.kind, at(e.s), at(e.s), e.s, e.names, e.message) for e in path.events]
    for w in res.slowdowns:
        i = at(w.s)
        events.append(
            PathEvent(
                "slowed",
                i,
                i,
                w.s,
                (w.limit,),
                f"slowed to ṡ = {w.sd:.4g}/s at s = {w.s:.6g} (t = {tr.t[i]:.4g} s) by the "
                f"{w.limit}",
            )
        )
    if res.s_stop is not None:
        events.append(
            PathEvent("stopped", m - 1, m - 1, res.s_stop, (str(res.limit),), res.message)
        )
    events.sort(key=lambda e: (e.index, e.s))
    return CartesianPath(ss, geometry(ss), tr.q, tuple(events), tr.t, tr.qd, tr.qdd)
