"""Static pictures: the drawing's own data against an independent DH product.

Every check reads the artists back from the Axes (the ``links`` line, the
joint shapes, the frame arrows) and compares them with the frames of
``tests/support/helpers.py``'s reference product, written from the slides.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from support.helpers import PROPERTY, RobotSpec, random_q, robot_specs, seeds

import kinematica as km

pytest.importorskip("matplotlib")
from matplotlib.figure import Figure
from PIL import Image

from kinematica import viz
from kinematica.viz.arm import SAME_PLACE, SHRINK
from kinematica.viz.geometry import ARROW, PLANAR_TOL
from kinematica.viz.solutions import fit_solutions


def _axes3d() -> object:
    return Figure().add_subplot(projection="3d")


def _artist(ax: object, gid: str) -> object:
    found = [a for a in ax.get_children() if a.get_gid() == gid]  # type: ignore[attr-defined]
    assert len(found) == 1, f"expected one artist with gid={gid!r}, found {len(found)}"
    return found[0]


def _line_points(ax: object) -> np.ndarray:
    line = _artist(ax, "links")
    if hasattr(line, "get_data_3d"):
        return np.array(line.get_data_3d()).T
    return np.array(line.get_data()).T


def _origins(spec: RobotSpec, q: np.ndarray) -> np.ndarray:
    return spec.ref_frames(q)[:, :3, 3]


@PROPERTY
@given(spec=robot_specs(), seed=seeds)
def test_links_line_passes_through_the_fk_origins(spec: RobotSpec, seed: int) -> None:
    robot = spec.build()
    q = random_q(spec, np.random.default_rng(seed))
    ax = viz.plot(robot, q, ax=_axes3d())
    np.testing.assert_allclose(_line_points(ax), _origins(spec, q), atol=1e-9)


@PROPERTY
@given(spec=robot_specs(max_dof=4), seed=seeds)
def test_automatic_view_shows_the_fk_origins(spec: RobotSpec, seed: int) -> None:
    import matplotlib.pyplot as plt

    robot = spec.build()
    q = random_q(spec, np.random.default_rng(seed))
    try:
        ax = viz.plot(robot, q)
        plane = viz.drawing_plane(robot)
        expected = _origins(spec, q)
        assert (ax.name == "3d") == (plane is None)
        shown = expected if plane is None else expected[:, list(plane)]
        np.testing.assert_allclose(_line_points(ax), shown, atol=1e-9)
    finally:
        plt.close("all")


@PROPERTY
@given(spec=robot_specs(max_dof=6), seed=seeds)
def test_joints_sit_on_the_reference_axes(spec: RobotSpec, seed: int) -> None:
    q = random_q(spec, np.random.default_rng(seed))
    pose = viz.arm_pose(spec.build(), q)
    frames = spec.ref_frames(q)
    tool = np.eye(4) if spec.tool is None else spec.tool
    frames[-1] = frames[-1] @ np.linalg.inv(tool)
    # joint i turns about / slides along z(i-1) (standard) or z(i) (modified, Craig)
    expected = frames[:-1] if spec.convention == "standard" else frames[1:]
    np.testing.assert_allclose(pose.joints, expected, atol=1e-9)
    np.testing.assert_allclose(pose.frames, frames, atol=1e-9)


def test_cylinder_and_box_by_hand() -> None:
    frame = km.make_transform(km.rotx(0.7) @ km.rotz(0.3), [0.1, -0.2, 0.3])
    faces = viz.geometry.cylinder(frame, 0.05, 0.2, segments=12)
    assert faces.shape == (14, 12, 3)
    rel = faces.reshape(-1, 3) - frame[:3, 3]
    axial = rel @ frame[:3, 2]
    radial = np.linalg.norm(rel - np.outer(axial, frame[:3, 2]), axis=1)
    np.testing.assert_allclose(radial, 0.05, atol=1e-12)
    np.testing.assert_allclose(np.abs(axial), 0.1, atol=1e-12)
    corners = viz.geometry.box(frame, (0.01, 0.02, 0.03)).reshape(-1, 3) - frame[:3, 3]
    local = np.abs(corners @ frame[:3, :3])
    np.testing.assert_allclose(local, np.broadcast_to([0.01, 0.02, 0.03], local.shape), atol=1e-12)


@PROPERTY
@given(spec=robot_specs(max_dof=5), seed=seeds)
def test_frame_arrows_follow_the_reference_axes(spec: RobotSpec, seed: int) -> None:
    robot = spec.build()
    q = random_q(spec, np.random.default_rng(seed))
    ax = viz.plot(robot, q, ax=_axes3d())
    segs = np.array(_artist(ax, "frames")._segments3d)  # type: ignore[attr-defined]
    n = spec.dof
    frames = spec.ref_frames(q)
    tool = np.eye(4) if spec.tool is None else spec.tool
    frames[n] = frames[n] @ np.linalg.inv(tool)
    assert segs.shape == ((n + 1) * 9, 2, 3)
    scale = viz.robot_scale(robot)
    # a frame in the place of k earlier ones has arrows SHRINK**k as long (S5 at S4)
    origins = frames[:, :3, 3]
    earlier = [
        sum(np.linalg.norm(origins[i] - origins[j]) < SAME_PLACE * scale for j in range(i))
        for i in range(n + 1)
    ]
    length = ARROW * scale * SHRINK ** np.array(earlier, dtype=float)
    shafts = segs.reshape(n + 1, 3, 3, 2, 3)[:, :, 0]  # frame, axis, (start, end)
    np.testing.assert_allclose(shafts[:, :, 0], np.repeat(frames[:, None, :3, 3], 3, 1), atol=1e-9)
    direction = np.swapaxes(frames[:, :3, :3], 1, 2)  # [frame, axis] -> unit vector
    np.testing.assert_allclose(
        shafts[:, :, 1] - shafts[:, :, 0], length[:, None, None] * direction, atol=1e-9
    )


def test_labels_name_every_frame_once() -> None:
    robot = km.load("puma560")
    ax = viz.plot(robot, np.zeros(6), ax=_axes3d())
    texts = " ".join(t.get_text() for t in ax.texts)
    for i in range(7):
        assert texts.count(f"S{i}") == 1, texts
    ax = viz.plot(robot, np.zeros(6), ax=_axes3d(), labels=False)
    assert not any(t.get_text().startswith("S") for t in ax.texts)


def _drawn(fig: Figure) -> object:
    """Draw ``fig`` on an Agg canvas; its renderer."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    return canvas.get_renderer()


def _overlaps(fig: Figure, texts: list[object]) -> list[tuple[str, str]]:
    """Pairs of texts whose boxes overlap once drawn (3-D labels where they are projected)."""
    from matplotlib.text import Text
    from mpl_toolkits.mplot3d import proj3d

    renderer = _drawn(fig)
    boxes = []
    for t in texts:
        if not t.get_text():  # type: ignore[attr-defined]
            continue
        if hasattr(t, "get_position_3d"):  # a Text3D measures itself unprojected
            x, y, _ = proj3d.proj_transform(*t.get_position_3d(), t.axes.get_proj())  # type: ignore[attr-defined]
            t = Text(
                x,
                y,
                t.get_text(),  # type: ignore[attr-defined]
                fontproperties=t.get_fontproperties(),  # type: ignore[attr-defined]
                va=t.get_va(),  # type: ignore[attr-defined]
                ha=t.get_ha(),  # type: ignore[attr-defined]
                transform=t.axes.transData,  # type: ignore[attr-defined]
                figure=fig,
            )
        boxes.append((t.get_text(), t.get_window_extent(renderer)))  # type: ignore[attr-defined]
    return [
        (a, b)
        for i, (a, box_a) in enumerate(boxes)
        for b, box_b in boxes[i + 1 :]
        if box_a.overlaps(box_b)
    ]


def test_single_solution_picture_keeps_its_text_inside(tmp_path: Path) -> None:
    # one narrow panel: the picture's title, the panel's and the axis labels all inside it
    for name, q in (("planar-pr", [0.2, 0.5]), ("anthropomorphic-3r", [0.2, 0.3, 0.5])):
        robot = km.load(name)
        fig = Figure(dpi=100)
        viz.plot_solutions(robot, robot.fk(q), fig=fig)
        _, count, size = viz.save_solutions(robot, robot.fk(q), tmp_path / "s.png")
        assert count == 1
        fig.set_size_inches(size[0] / 100, size[1] / 100)
        fit_solutions(fig)  # as save_solutions does after its resize
        renderer = _drawn(fig)
        texts = [fig._suptitle] + [
            t for ax in fig.axes for t in (ax.title, ax.xaxis.label, ax.yaxis.label)
        ]
        for text in texts:
            box = text.get_window_extent(renderer)
            assert box.x0 >= 0 and box.y0 >= 0, (name, text.get_text())
            assert box.x1 <= size[0] and box.y1 <= size[1], (name, text.get_text())
        assert _overlaps(fig, [fig._suptitle, *(ax.title for ax in fig.axes)]) == []


def test_tool_frame_drawn_apart_at_fk() -> None:
    robot = km.load("arm6-dh").with_tool(km.transl(0.0, 0.02, 0.05))
    q = np.radians([30, 40, -30, 10, 60, -20])
    ax = viz.plot(robot, q, ax=_axes3d())
    T = robot.fk(q)
    segs = np.array(_artist(ax, "tool-frame")._segments3d)  # type: ignore[attr-defined]
    np.testing.assert_allclose(segs[0, 0], T[:3, 3], atol=1e-12)
    tool_link = np.array(_artist(ax, "tool").get_data_3d()).T  # type: ignore[attr-defined]
    np.testing.assert_allclose(tool_link[1], T[:3, 3], atol=1e-12)
    Sn = T @ np.linalg.inv(robot.tool)
    np.testing.assert_allclose(tool_link[0], Sn[:3, 3], atol=1e-12)


def test_world_frame_drawn_when_the_base_moves() -> None:
    robot = km.load("puma560").with_base(km.transl(0.3, 0.0, 0.5))
    ax = viz.plot(robot, np.zeros(6), ax=_axes3d())
    segs = np.array(_artist(ax, "world-frame")._segments3d)  # type: ignore[attr-defined]
    np.testing.assert_allclose(segs[0], [[0, 0, 0], [ARROW * viz.robot_scale(robot), 0, 0]])
    assert "W" in [t.get_text() for t in ax.texts]
    ax = viz.plot(km.load("puma560"), np.zeros(6), ax=_axes3d())
    assert not [a for a in ax.get_children() if a.get_gid() == "world-frame"]


@pytest.mark.parametrize("q_deg", [(30.0, 40.0, -30.0), (0.0, 0.0, 0.0), (170.0, -90.0, 45.0)])
def test_planar_3r_drawn_in_2d_as_the_seed_formula(q_deg: tuple[float, float, float]) -> None:
    robot = km.load("planar-3r")
    l1, l2, l3 = 0.4, 0.3, 0.2  # the model file's lengths (seed 001)
    q1, q2, q3 = np.radians(q_deg)
    ax = viz.plot(robot, [q1, q2, q3])
    assert ax.name != "3d"
    x = [0, l1 * math.cos(q1), l1 * math.cos(q1) + l2 * math.cos(q1 + q2)]
    y = [0, l1 * math.sin(q1), l1 * math.sin(q1) + l2 * math.sin(q1 + q2)]
    x.append(x[-1] + l3 * math.cos(q1 + q2 + q3))
    y.append(y[-1] + l3 * math.sin(q1 + q2 + q3))
    np.testing.assert_allclose(_line_points(ax), np.c_[x, y], atol=1e-12)
    assert ax.get_aspect() == 1.0  # a metre is one length on both axes


def test_planar_pr_drawn_in_its_plane() -> None:
    robot = km.load("planar-pr")
    l1, l2 = 0.5, 0.4
    q1, q2 = 0.2, 0.7
    ax = viz.plot(robot, [q1, q2])
    assert ax.name != "3d"
    end = _line_points(ax)[-1]
    np.testing.assert_allclose(end, [q1 + l1 + l2 * math.cos(q2), l2 * math.sin(q2)], atol=1e-12)


def _tilted_2r(alpha: float) -> km.Robot:
    return km.Robot.from_dh(
        [km.Revolute(a=0.4, alpha=alpha), km.Revolute(a=0.3)], convention="standard"
    )


def test_planar_tolerance_both_sides() -> None:
    # the second axis tilted by ~alpha: parallel within PLANAR_TOL is planar
    assert viz.drawing_plane(_tilted_2r(PLANAR_TOL / 100)) == (0, 1)
    assert viz.drawing_plane(_tilted_2r(PLANAR_TOL * 100)) is None
    assert viz.plot(_tilted_2r(PLANAR_TOL * 100), [0.1, 0.2]).name == "3d"


def test_vertical_planar_arm_uses_x_z() -> None:
    # base turned so the joint axes lie along world y: the arm moves in x-z
    base = km.make_transform(km.rotx(-math.pi / 2), [0, 0, 0])
    robot = km.Robot.from_dh(
        [km.Revolute(a=0.4), km.Revolute(a=0.3)], base=base, convention="standard"
    )
    assert viz.drawing_plane(robot) == (0, 2)
    q = [0.3, -0.6]
    ax = viz.plot(robot, q)
    np.testing.assert_allclose(_line_points(ax), robot.fk(q, all_frames=True)[:, :3, 3][:, [0, 2]])


def test_equal_scaling_in_3d() -> None:
    ax = viz.plot(km.load("puma560"), [0.1, -0.4, 0.3, 0.2, 0.5, 0.0], ax=_axes3d())
    widths = [np.diff(lim)[0] for lim in (ax.get_xlim(), ax.get_ylim(), ax.get_zlim())]
    per_metre = np.array(ax.get_box_aspect()) / widths  # a metre is one length on every axis
    np.testing.assert_allclose(per_metre, per_metre[0], rtol=1e-12)


def test_bad_input() -> None:
    robot = km.load("puma560")
    with pytest.raises(km.DimensionError, match="one configuration"):
        viz.plot(robot, np.zeros((2, 6)), ax=_axes3d())
    with pytest.raises(km.DimensionError, match="6 joint values"):
        viz.plot(robot, np.zeros(5), ax=_axes3d())
    with pytest.raises(viz.VizError, match="not a planar arm"):
        viz.plot(robot, np.zeros(6), ax=Figure().add_subplot())
    with pytest.raises(viz.VizError, match=r"type '\.txt'"):
        viz.save_plot(robot, np.zeros(6), "/tmp/never-written.txt")


@pytest.mark.parametrize("size", [(320, 240), (801, 599)])
def test_png_has_the_requested_size(tmp_path: Path, size: tuple[int, int]) -> None:
    out = viz.save_plot(
        km.load("stanford"), [0.2, 0.4, 0.3, 0.1, 0.5, 0.2], tmp_path / "a.png", size=size
    )
    with Image.open(out) as im:
        assert im.format == "PNG"
        assert im.size == size
        pixels = np.asarray(im.convert("L"), dtype=float)
    assert pixels.std() > 5  # something was drawn


def test_solutions_each_reach_the_target_and_name_their_branch() -> None:
    puma = km.load("puma560")
    T = puma.fk([0.2, -0.5, 0.3, 0.4, 0.8, -0.1])
    fig = viz.plot_solutions(puma, T, respect_limits=False, fig=Figure())
    res = puma.ik(T, respect_limits=False)
    assert len(fig.axes) == res.count == 8
    titles = [ax.get_title().replace("\n", " ") for ax in fig.axes]
    assert [t.split(" q = ")[0] for t in titles] == [
        f"{k}: {b}" for k, b in enumerate(res.branches, start=1)
    ]
    limits = {(ax.get_xlim(), ax.get_ylim(), ax.get_zlim()) for ax in fig.axes}
    assert len(limits) == 1  # one common scale
    for ax in fig.axes:
        np.testing.assert_allclose(_line_points(ax)[-1], T[:3, 3], atol=1e-9)
        star = np.array(_artist(ax, "target").get_data_3d()).ravel()  # type: ignore[attr-defined]
        np.testing.assert_allclose(star, T[:3, 3])


def test_solutions_of_a_planar_arm_in_2d() -> None:
    robot = km.load("planar-3r")
    T = robot.fk(np.radians([20, 50, -30]))
    fig = viz.plot_solutions(robot, T, fig=Figure())
    assert len(fig.axes) == 2
    for ax in fig.axes:
        assert ax.name != "3d"
        np.testing.assert_allclose(_line_points(ax)[-1], T[:2, 3], atol=1e-9)


def test_solutions_unreachable_and_bad_target(tmp_path: Path) -> None:
    puma = km.load("puma560")
    far = km.transl(5.0, 0.0, 0.0)
    with pytest.raises(km.UnreachableError, match="unreachable"):
        viz.plot_solutions(puma, far, fig=Figure())
    with pytest.raises(km.DimensionError, match="one target"):
        viz.plot_solutions(puma, np.zeros((2, 4, 4)))
    out, k, size = viz.save_solutions(
        puma, puma.fk([0.2, -0.5, 0.3, 0.4, 0.8, -0.1]), tmp_path / "s.png"
    )
    with Image.open(out) as im:
        assert im.size == size == (330 * 2, 340 + 50)  # 2 solutions within the limits
    assert k == 2


@pytest.mark.parametrize("shape", [(), (1,), (3, 2)])
def test_arm_pose_batches(shape: tuple[int, ...]) -> None:
    robot = km.load("stanford")
    q = np.random.default_rng(1).uniform(-1, 1, (*shape, 6))
    pose = viz.arm_pose(robot, q)
    assert pose.origins.shape == (*shape, 7, 3)
    assert pose.frames.shape == (*shape, 7, 4, 4)
    np.testing.assert_allclose(pose.tool, robot.fk(q))
    h, p = robot.joint_axes(q)
    np.testing.assert_allclose(pose.joints[..., :3, 2], h, atol=1e-12)
    np.testing.assert_allclose(pose.joints[..., :3, 3], p, atol=1e-12)


def test_robot_scale_by_hand() -> None:
    robot = km.Robot.from_dh(
        [km.Revolute(d=0.3, a=0.2), km.Prismatic(a=-0.1, qlim=(-0.5, 0.25))],
        tool=km.transl(0.0, 0.3, 0.4),
        convention="standard",
    )
    assert viz.robot_scale(robot) == pytest.approx(0.3 + 0.2 + 0.1 + 0.5 + 0.5)
    assert viz.robot_scale(km.Robot.from_dh([km.Prismatic()], convention="standard")) == 1.0


def test_pyplot_figure_when_no_axes_given() -> None:
    import matplotlib.pyplot as plt

    ax = viz.plot(km.load("puma560"), np.zeros(6))
    try:
        assert ax.figure in [plt.figure(n) for n in plt.get_fignums()]
    finally:
        plt.close("all")


def test_importing_kinematica_leaves_matplotlib_alone() -> None:
    import subprocess
    import sys

    code = "import kinematica, kinematica.viz, sys; print('matplotlib' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_joint_polygons_share_one_vertex_count() -> None:
    """Boxes (prismatic) and cylinders (revolute) reach matplotlib padded to one length.

    matplotlib pads ragged 3-D polygons with uninitialised memory and autoscales
    over the padding: the Stanford arm's axis limits were then sometimes ±1e308.
    """
    ax = viz.plot(km.load("stanford"), [0.2, 0.4, 0.5, 0.1, 0.5, 0.2], ax=_axes3d())
    joints = _artist(ax, "joints")
    faces = np.asarray(joints._faces)  # type: ignore[attr-defined]
    assert faces.shape == (6 + 14 * 5, 12, 3)  # one box, five cylinders
    assert not np.any(joints._invalid_vertices)  # type: ignore[attr-defined]
    assert np.all(np.isfinite(faces)) and np.abs(faces).max() < 5.0
    for lim in (ax.get_xlim(), ax.get_ylim(), ax.get_zlim()):  # type: ignore[attr-defined]
        assert np.all(np.isfinite(lim)) and max(abs(v) for v in lim) < 5.0
