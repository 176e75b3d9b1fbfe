"""The arm in motion: manipulability, named singularities, workspace, trajectories.

Seed 000 names what the kinematic model is for: simulating motion, kinematic
control and trajectory planning, robot design. This tour runs each piece on
the lecture notes' arms and the PUMA 560, and draws three pictures when
matplotlib is installed (``pip install 'kinematica[viz]'``): the workspace map,
a trajectory plot and trajectories through waypoints, written to the current
directory.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

import kinematica as km
from kinematica.motion import cartesian_path, write_csv


def velocity() -> None:
    puma = km.load("puma560")
    q = np.radians([20, -30, 40, 10, 50, 0])
    print("PUMA 560 at", np.degrees(q).round(1).tolist(), "deg")
    print(
        f"  manipulability {km.manipulability(puma, q):.5f}, "
        f"condition number {km.condition_number(puma, q):.1f}"
    )
    Ja = puma.jacobian(q, euler="ZYZ")  # d(x, y, z, a, b, c)/dq
    print("  analytic Jacobian (ZYZ), last row:", Ja[5].round(4).tolist())
    wrist = np.radians([20, -30, 40, 10, 0, 0])  # q5 = 0: axes 4 and 6 in line
    # q3 with a3 and d4 in line with a2 (PUMA: a3 = 0.0203, d4 = 0.4318): arm stretched
    elbow = np.r_[q[:2], np.arctan2(0.0203, 0.4318) - np.pi / 2, q[3:]]
    for name, qs in [("wrist", wrist), ("elbow", elbow)]:
        found = puma.singularities(qs, detail=True)
        print(f"  built for a {name} singularity ->", [str(s) for s in found])
    print("  a regular sample:", puma.singularities(puma.random_q(1, seed=0)[0]))


def workspace() -> None:
    arm = km.load("anthropomorphic-3r")
    ws = km.workspace(arm, samples=200_000, seed=0)
    shell = 4 / 3 * np.pi * (0.7**3 - 0.1**3)  # radii |L2 - L3| and L2 + L3
    print(
        f"\nanthropomorphic 3R workspace: volume {ws.volume:.4f} m3 "
        f"(closed form {shell:.4f}), voxel {ws.voxel:.3f} m"
    )
    sl = ws.slice("xz", at=0.0)
    print(f"  xz slice: area {sl.area:.4f} m2 (annulus {np.pi * (0.49 - 0.01):.4f})")
    try:
        from kinematica.motion.plot import plot_workspace_slice

        plot_workspace_slice(sl, "workspace_map.png", title=arm.name)
        print("  map written to workspace_map.png")
    except km.KinematicaError as exc:  # matplotlib missing
        print(f"  (no picture: {exc})")


def trajectories() -> None:
    q0, q1 = np.radians([0, -30, 20, 0, 40, 0]), np.radians([60, -10, 40, 30, 20, 45])
    quintic = km.joint_trajectory(q0, q1, 2.0, "quintic", dt=0.01)
    trap = km.joint_trajectory(q0, q1, None, "trapezoid", dt=0.01, vmax=0.8, amax=2.0)
    print(
        f"\nquintic: {quintic.t.size} samples over {quintic.t[-1]} s; "
        f"trapezoid (vmax 0.8 rad/s, amax 2 rad/s2): {trap.t[-1]:.3f} s, "
        f"peak speed {np.abs(trap.qd).max():.3f} rad/s"
    )
    puma = km.load("puma560")
    q_sing = np.radians([20, -30, 40, 10, 0, 0])  # wrist aligned at the middle of the line
    T = puma.fk(q_sing)
    T0, T1 = T.copy(), T.copy()
    T0[:3, 3] -= [0.0, 0.1, 0.05]
    T1[:3, 3] += [0.0, 0.1, 0.05]
    path = cartesian_path(puma, T0, T1, steps=41, q0=q_sing)
    print("Cartesian line through the wrist singularity:")
    for e in path.events:
        print("  event:", e.message)
    away = cartesian_path(
        puma,
        puma.fk(np.radians([20, -30, 40, 10, 50, 0])),
        puma.fk(np.radians([30, -20, 30, 10, 50, 0])),
        steps=50,
    )
    print(
        f"a line away from it: events {list(away.events)}, "
        f"largest joint step {away.max_step:.4f} rad"
    )
    print("CSV for `kinematica animate`:", write_csv(Path("quintic.csv"), *quintic[:2]))
    try:
        from kinematica.motion.plot import require_matplotlib

        plt = require_matplotlib()
    except km.KinematicaError as exc:
        print(f"  (no picture: {exc})")
        return
    fig, axes = plt.subplots(2, 1, figsize=(7, 5.5), sharex=True)
    for i in range(6):
        axes[0].plot(quintic.t, np.degrees(quintic.q[:, i]), label=f"q{i + 1}")
        axes[1].plot(trap.t, np.degrees(trap.qd[:, i]))
    axes[0].set_ylabel("quintic q (deg)")
    axes[1].set_ylabel("trapezoid q' (deg/s)")
    axes[1].set_xlabel("t (s)")
    axes[0].legend(ncol=6, fontsize=8)
    axes[0].set_title("PUMA 560: synchronised joint trajectories")
    fig.savefig("trajectory.png", bbox_inches="tight", dpi=100)
    print("  plot written to trajectory.png")


def waypoints() -> None:
    W = np.radians([[0, -30, 20], [30, -20, 30], [45, -10, 40], [60, -10, 20]])
    times = [0.0, 1.0, 2.0, 3.0]
    runs = {
        "cubic spline (C2)": km.via_trajectory(W, "cubic", times),
        "quintic spline (C4)": km.via_trajectory(W, "quintic", times),
        "mstraj, tacc 0.4 s": km.via_trajectory(W, "mstraj", times, tacc=0.4),
    }
    print("\nthrough 4 waypoints in 3 s:")
    for name, tr in runs.items():
        at = np.searchsorted(tr.t, times)
        miss = np.degrees(np.abs(tr.q[at] - W).max())
        print(
            f"  {name}: peak speed {np.abs(tr.qd).max():.3f} rad/s, "
            f"off the waypoints {miss:.3f} deg"
        )
    a, b = [-0.0681, -0.448, 1.79, -0.5028], [1.5185, -0.3257, -0.5059, -0.5543]
    lim = {"vmax": [0.402, 0.7714, 0.6901, 0.406], "amax": [2.3955, 2.0477, 0.5879, 1.0457]}
    fast = km.joint_trajectory(a, b, None, "trapezoid", **lim)
    line = km.joint_trajectory(a, b, None, "trapezoid", sync="shared", **lim)
    print(f"minimum-time trapezoid {fast.t[-1]:.3f} s; one shared profile {line.t[-1]:.3f} s")
    try:
        from kinematica.motion.plot import require_matplotlib

        plt = require_matplotlib()
    except km.KinematicaError as exc:
        print(f"  (no picture: {exc})")
        return
    fig, ax = plt.subplots(figsize=(7, 3.5))
    for name, tr in runs.items():
        ax.plot(tr.t, np.degrees(tr.q[:, 2]), label=name)
    ax.plot(times, np.degrees(W[:, 2]), "ko", label="waypoints")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("q3 (deg)")
    ax.legend(fontsize=8)
    ax.set_title("Through waypoints: splines pass them, mstraj cuts the corners")
    fig.savefig("via.png", bbox_inches="tight", dpi=100)
    print("  plot written to via.png")


if __name__ == "__main__":
    velocity()
    workspace()
    trajectories()
    waypoints()
