"""The jerk-limited side of ``kinematica trajectory``: its options, its JSON keys, its lines."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING, Any

from kinematica.cli.format import fmt
from kinematica.cli.options import q_out
from kinematica.robot import Robot

if TYPE_CHECKING:  # kinematica.motion loads when the trajectory command runs
    from kinematica.motion import JointTrajectory

__all__ = ["add_jerk_options", "jerk_json", "jerk_text"]


def add_jerk_options(p: argparse.ArgumentParser) -> None:
    """``--jmax`` and ``--plot`` on the trajectory command's parser ``p``."""
    p.add_argument("--jmax", nargs="+", type=float, help="jerk limit of --profile scurve (deg/s³)")
    p.add_argument(
        "--plot",
        metavar="FIG.png",
        help="draw q, q̇, q̈ against their limits (and the jerk of scurve; with --optimal, the "
        "phase plane) (needs matplotlib)",
    )


def jerk_json(
    traj: JointTrajectory | None, robot: Robot, args: argparse.Namespace, safe: Any
) -> dict[str, Any]:
    """``qddd`` (and through waypoints ``waypoint_times``, ``stop_duration``, ``margin``)."""
    from kinematica.motion import JerkTrajectory

    if not isinstance(traj, JerkTrajectory):
        return {"qddd": None}
    out: dict[str, Any] = {"qddd": safe(q_out(robot, traj.qddd, args))}
    if traj.margin is not None:
        out["waypoint_times"] = safe(traj.waypoint_times)
        out["stop_duration"] = traj.stop_duration
        out["margin"] = traj.margin
    return out


def jerk_text(traj: JointTrajectory | None) -> None:
    """Print what not stopping at the waypoints saved, for a jerk-limited move through them."""
    from kinematica.motion import JerkTrajectory

    if isinstance(traj, JerkTrajectory) and traj.margin is not None:
        print(
            f"passing the waypoints without a stop: {fmt(traj.margin, 4)} s shorter than "
            f"stopping at each ({fmt(traj.stop_duration or 0.0, 4)} s)"
        )
