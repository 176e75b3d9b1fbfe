"""Pictures of the seed 6-DOF arm: its DH frames, every IK solution, workspace, trajectory.

Writes into the folder given as the first argument (default: the current one):

* ``arm.png``         the arm at one configuration with its frames S0..S6 and the tool;
* ``planar.png``      the planar 3R arm of seed 001, drawn in its plane;
* ``solutions.png``   every IK solution of one pose, each titled with its branch;
* ``workspace.png``   positions the wrist flange reaches, coloured by manipulability;
* ``trajectory.png``  joint curves of a quintic move and the tool path;
* ``arm.gif``         the same move, animated;
* ``arm.html``        the interactive page (sliders, frames, live T), and with a
  Chromium and playwright installed, ``page.png``, a screenshot of it.

The pictures of the docs site are made by ``python examples/07_pictures.py docs``.
"""

from __future__ import annotations

import shutil
import sys
from pathlib import Path

import numpy as np

import kinematica as km
from kinematica import viz


def quintic(q0: np.ndarray, q1: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Rest-to-rest joint move: q0 + (q1 - q0)(10s³ - 15s⁴ + 6s⁵), s = t / t_end."""
    s = (t / t[-1])[:, None]
    return q0 + (q1 - q0) * (10 * s**3 - 15 * s**4 + 6 * s**5)


def screenshot(page: Path, out: Path) -> bool:
    """A headless-Chromium screenshot of the page, when a browser and playwright exist."""
    browser = shutil.which("chromium") or shutil.which("chromium-browser")
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        return False
    if browser is None:
        return False
    args = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking"]
    with sync_playwright() as p:
        b = p.chromium.launch(executable_path=browser, args=args)
        tab = b.new_page(viewport={"width": 1000, "height": 560})
        tab.goto(page.resolve().as_uri() + "#q=30,40,-30,10,60,-20")
        tab.screenshot(path=str(out))
        b.close()
    return True


def main() -> None:
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path.cwd()
    out.mkdir(parents=True, exist_ok=True)
    robot = km.load("arm6-dh").with_tool(km.transl(0.0, 0.0, 0.05))
    q = np.radians([30, 40, -30, 10, 60, -20])
    small = (560, 500)

    viz.save_plot(robot, q, out / "arm.png", size=small, title="seed 000 arm, frames S0..S6")
    print(f"arm.png: {robot.name} at q = {np.degrees(q).round(1).tolist()} deg")

    planar = km.load("planar-3r")
    viz.save_plot(planar, np.radians([30, 45, -60]), out / "planar.png", size=(460, 420))
    print(f"planar.png: {planar.name}, a 2-D view (x, y)")

    puma = km.load("puma560")  # a shoulder offset: the eight branches look different
    T = puma.fk([0.2, -0.5, 0.3, 0.4, 0.8, -0.1])
    _, k, _ = viz.save_solutions(
        puma, T, out / "solutions.png", respect_limits=False, size=(1040, 600)
    )
    print(f"solutions.png: {k} IK solutions of one {puma.name} pose, joint limits ignored")

    rng = np.random.default_rng(0)
    Q = rng.uniform(robot.qlim[:, 0], robot.qlim[:, 1], size=(4000, 6))
    J = robot.jacobian(Q)
    manip = np.sqrt(np.abs(np.linalg.det(J @ np.swapaxes(J, -1, -2))))
    points = robot.fk(Q)[:, :3, 3]
    ax = viz.plot_workspace(robot, points, q=q, values=manip, size=1.0)
    ax.figure.savefig(out / "workspace.png", dpi=80)
    print(f"workspace.png: {len(points)} tool positions, manipulability {manip.max():.3f} at most")

    t = np.linspace(0.0, 2.0, 41)
    traj = quintic(np.zeros(6), q, t)
    viz.write_trajectory(out / "path.csv", t, traj)
    fig = viz.plot_trajectory(robot, t, traj)
    fig.savefig(out / "trajectory.png", dpi=80)
    print(f"trajectory.png and path.csv: a quintic move over {t[-1]:g} s")

    anim = viz.animate(robot, traj[::2], out / "arm.gif", t=t[::2], frames=True, size=(420, 380))
    print(f"arm.gif: {anim.frames} frames at {anim.fps:g} fps, {anim.size[0]} x {anim.size[1]} px")

    page = viz.write_page(robot, out / "arm.html", q=q)
    print(f"arm.html: the interactive page; open {page.name}#q=30,40,-30,10,60,-20")
    if screenshot(page, out / "page.png"):
        print("page.png: the page in headless Chromium")


if __name__ == "__main__":
    main()
