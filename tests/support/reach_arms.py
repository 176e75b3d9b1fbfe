"""Arms whose reachable orientations are worked out by hand (tests/reach)."""

from __future__ import annotations

import numpy as np

import kinematica as km
from kinematica.dh import Revolute

L1, L2, L3 = 0.5, 0.4, 0.3  # planar links (m)
UPPER, FORE = 0.5, 0.3  # the elbow arm's upper arm and forearm (m)
R_IN, R_OUT = UPPER - FORE, UPPER + FORE  # its wrist-centre shell about the shoulder


def planar(n: int) -> km.Robot:
    """A planar nR arm in the base xy plane, joints unlimited."""
    rows = [Revolute(a=a) for a in (L1, L2, L3)[:n]]
    return km.Robot.from_dh(rows, name=f"planar {n}R", convention="standard")


def elbow_wrist(tool: float = 0.0) -> km.Robot:
    """A 6R elbow arm with a spherical wrist, every joint unlimited, shoulder at the origin.

    The wrist centre reaches exactly the shell R_IN <= |p| <= R_OUT (q1 about z,
    q2 and q3 a 2R arm in the vertical plane), and the wrist turns the tool to
    any orientation there. ``tool``: an offset d (m) along the tool's z axis.
    """
    rows = [
        Revolute(alpha=np.pi / 2),
        Revolute(a=UPPER),
        Revolute(alpha=np.pi / 2),
        Revolute(d=FORE, alpha=-np.pi / 2),
        Revolute(alpha=np.pi / 2),
        Revolute(),
    ]
    return km.Robot.from_dh(
        rows, name="elbow arm", tool=km.transl(0.0, 0.0, tool), convention="standard"
    )
