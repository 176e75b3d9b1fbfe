"""What a Cartesian path is: its samples, configurations, events and (when timed) times."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

__all__ = ["CartesianPath", "PathEvent"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class PathEvent:
    """Something met along a Cartesian path.

    Attributes:
        kind: ``"singularity"``, ``"unreachable"``, ``"joint_limit"``,
            ``"branch_change"``, ``"near_singularity"``, ``"speed_jump"``,
            ``"end_branch"``; on a timed path also ``"slowed"`` and ``"stopped"``.
        index: First sample where it is met (for a crossing or a jump
            between samples ``i-1`` and ``i``: ``i``).
        stop: Last sample of a run of consecutive samples with this event.
        s: Path parameter in [0, 1] where it is met (the crossing itself
            when located between samples).
        names: Singularity names, or the joints (``"q3"``) over their limits,
            jumping, or differing from the end asked for.
        message: One sentence for people.
    """

    kind: str
    index: int
    stop: int
    s: float
    names: tuple[str, ...]
    message: str


@dataclass(frozen=True)
class CartesianPath:
    """Samples of a Cartesian path and the configurations that follow it.

    Attributes:
        s: ``(m,)`` path parameter, 0 to 1.
        poses: ``(m, 4, 4)`` tool poses (base frame).
        q: ``(m, n)`` joint values (rad, m); NaN where the pose has no
            solution within the limits.
        events: What was met along the way, in path order (a timed path adds
            ``"slowed"``: where a limit slows it down, and ``"stopped"``: where
            it cannot go on).
        t: ``(m,)`` times (s) of the samples when the path is timed by the
            robot's limits (``cartesian_path(..., vmax=...)``), else None.
        qd: ``(m, n)`` joint velocities of a timed path, else None.
        qdd: ``(m, n)`` joint accelerations of a timed path, else None.
    """

    s: FloatArray
    poses: FloatArray
    q: FloatArray
    events: tuple[PathEvent, ...]
    t: FloatArray | None = None
    qd: FloatArray | None = None
    qdd: FloatArray | None = None

    @property
    def ok(self) -> bool:
        """True when the path was followed on one branch to its end (slowing down is fine)."""
        return all(e.kind == "slowed" for e in self.events)

    @property
    def max_step(self) -> float:
        """Largest joint change between consecutive samples (rad or m)."""
        d = np.abs(np.diff(self.q, axis=0))
        return float(np.nanmax(d)) if np.isfinite(d).any() else float("nan")

    def _repr_html_(self) -> str:
        """A few samples' joint values and every event, as HTML (Jupyter)."""
        from kinematica.motion.display import samples_html

        k = len(self.events)
        met = "no event" if k == 0 else f"{k} event" + ("s" if k > 1 else "")
        caption = f"{len(self.s)} samples along the path, {met} (q in rad, m)"
        footer = tuple(e.message for e in self.events)
        return samples_html(self.s, self.q, time_name="s", caption=caption, footer=footer)
