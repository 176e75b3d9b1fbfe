"""Picture speed: drawing an arm with its frames, the `kinematica plot` command, animation frames.

Run with ``make bench`` (or ``.venv/bin/python benchmarks/viz.py``). Targets from
issue 10: a 6-DOF arm with frames drawn in under 0.5 s, ``kinematica plot`` in
under 2 s. Baselines measured in the same run: an empty 3-D Axes rendered by
matplotlib (the floor for any 3-D picture), and ``kinematica fk`` (the command
line's own start-up: Python, numpy, kinematica). No assertions.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parent))
from _common import fmt_time, header, median_of, table

import kinematica as km
from kinematica import viz


def _figure() -> object:
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(8, 7), dpi=100)
    FigureCanvasAgg(fig)  # a bare Figure's canvas would not render anything
    return fig


def render_arm(robot: km.Robot, q: np.ndarray, frames: bool) -> None:
    fig = _figure()
    plane = viz.drawing_plane(robot)
    ax = fig.add_subplot(projection="3d") if plane is None else fig.add_subplot()  # type: ignore[attr-defined]
    viz.plot(robot, q, ax=ax, frames=frames)
    fig.canvas.draw()  # type: ignore[attr-defined]


def render_empty() -> None:
    fig = _figure()
    fig.add_subplot(projection="3d").plot([0, 1], [0, 1], [0, 1])  # type: ignore[attr-defined]
    fig.canvas.draw()  # type: ignore[attr-defined]


def command(args: list[str], cwd: str) -> None:
    subprocess.run(
        [sys.executable, "-m", "kinematica.cli.main", *args],
        cwd=cwd,
        check=True,
        capture_output=True,
    )


def main() -> None:
    print(header("kinematica.viz: drawing speed"))
    puma = km.load("puma560")
    q = np.array([0.3, -0.6, 0.4, 0.2, 0.7, -0.1])
    rows = []
    empty = median_of(render_empty, 7)
    rows.append(("empty 3-D Axes with one line, rendered (baseline)", fmt_time(empty), "1.0x"))
    for frames in (True, False):
        t = median_of(lambda f=frames: render_arm(puma, q, f), 7)
        what = "with frames S0..S6 and labels" if frames else "without frames"
        rows.append((f"PUMA 560 drawn and rendered, {what}", fmt_time(t), f"{t / empty:.1f}x"))
    p3 = km.load("planar-3r")
    t = median_of(lambda: render_arm(p3, np.array([0.3, 0.5, -0.4]), True), 7)
    rows.append(("planar 3R (2-D view) with frames", fmt_time(t), f"{t / empty:.1f}x"))
    print(
        table(rows, ("drawing (target < 0.5 s for a 6-DOF arm with frames)", "median", "vs empty"))
    )

    with tempfile.TemporaryDirectory() as tmp:
        fk_cmd = ["fk", "puma560", "--q", "0", "45", "-30", "0", "0", "0"]
        base = median_of(lambda: command(fk_cmd, tmp), 3)
        rows = [("kinematica fk puma560 --q ... (baseline: start-up)", fmt_time(base), "1.0x")]
        imp = median_of(
            lambda: subprocess.run(
                [sys.executable, "-c", "import matplotlib.figure, mpl_toolkits.mplot3d"],
                check=True,
            ),
            3,
        )
        rows.append(("python -c 'import matplotlib.figure, mplot3d' alone", fmt_time(imp), ""))
        plot_cmd = ["plot", "puma560", "--q", "0", "45", "-30", "0", "0", "0", "--frames"]
        for args, what in (
            (plot_cmd, "kinematica plot puma560 --q ... --frames"),
            (
                [*plot_cmd, "--solutions", "-o", "s.png"],
                "kinematica plot ... --solutions (2 panels)",
            ),
            (["view", "puma560"], "kinematica view puma560 (HTML page)"),
        ):
            t = median_of(lambda a=args: command(a, tmp), 3)
            rows.append((what, fmt_time(t), f"{t / base:.1f}x"))
        print()
        print(table(rows, ("command (target < 2 s for plot)", "median", "vs fk")))

        t_samples = np.linspace(0, 2, 41)
        traj = np.outer(np.sin(t_samples), q)
        t = median_of(lambda: viz.animate(puma, traj, Path(tmp) / "a.gif", t=t_samples), 3)
        print()
        print(
            table(
                [("41-frame GIF, 640 x 560 px, frames drawn", fmt_time(t), fmt_time(t / 41))],
                ("animation", "total", "per frame"),
            )
        )
    print(f"\nload average at the end: {', '.join(f'{v:.1f}' for v in os.getloadavg())}")


if __name__ == "__main__":
    main()
