"""Pictures of arms: matplotlib figures, animations and a self-contained HTML page.

Needs the ``viz`` extra (``pip install 'kinematica[viz]'``: matplotlib and
pillow) for pictures and animations; the HTML page and its server need
nothing beyond the standard library. matplotlib is imported only when a
picture is drawn, on the headless ``Agg`` backend when there is no display::

    import kinematica as km
    from kinematica import viz

    robot = km.load("puma560")
    ax = viz.plot(robot, [0, 0.4, -0.3, 0, 0.5, 0])     # 3-D, frames S0..S6
    fig = viz.plot_solutions(robot, robot.fk([0, 0.4, -0.3, 0, 0.5, 0]))
"""

from kinematica.io.trajectory_csv import TrajectoryFileError, read_trajectory, write_trajectory
from kinematica.viz._mpl import VizError
from kinematica.viz.animate import Animation, animate, mp4_available
from kinematica.viz.geometry import ArmPose, arm_pose, drawing_plane, robot_scale
from kinematica.viz.limits import plot_limits, save_limits
from kinematica.viz.notebook import PageView, page_view
from kinematica.viz.page import page_data, page_html, robot_units, write_page
from kinematica.viz.page_reach import coarse_map, page_map
from kinematica.viz.plot import plot, save_figure, save_plot
from kinematica.viz.server import PageServer, serve
from kinematica.viz.solutions import plot_solutions, save_solutions
from kinematica.viz.trajectory import plot_trajectory
from kinematica.viz.workspace import plot_workspace

__all__ = [
    "Animation",
    "ArmPose",
    "PageServer",
    "PageView",
    "TrajectoryFileError",
    "VizError",
    "animate",
    "arm_pose",
    "coarse_map",
    "drawing_plane",
    "mp4_available",
    "page_data",
    "page_html",
    "page_map",
    "page_view",
    "plot",
    "plot_limits",
    "plot_solutions",
    "plot_trajectory",
    "plot_workspace",
    "read_trajectory",
    "robot_scale",
    "robot_units",
    "save_figure",
    "save_limits",
    "save_plot",
    "save_solutions",
    "serve",
    "write_page",
    "write_trajectory",
]
