"""Pictures a student can read (issue 35, item 3), checked in the figures' own objects.

Each check draws the figure with the Agg renderer and reads the artists back:
every frame's label is anchored at its own frame's origin (projected with the
Axes' own projection matrix, independently of the placement code), no two
labels' drawn boxes overlap, the arrows' colours have a legend, the arm fills
its panel, and tick labels keep apart.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable

import numpy as np
import pytest

import kinematica as km

pytest.importorskip("matplotlib")
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from mpl_toolkits.mplot3d import proj3d

from kinematica import viz
from kinematica.viz.arm import AXIS_COLORS, SAME_PLACE

DOC_Q = np.radians([30, 40, -30, 10, 60, -20])


def _draw(fig: Figure) -> object:
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    return canvas.get_renderer()


def _labels(ax: object) -> list[object]:
    return [t for t in ax.texts if str(t.get_gid()).startswith("label-") and t.get_text()]  # type: ignore[attr-defined]


def _projected(ax: object, points: np.ndarray) -> np.ndarray:
    """``(N, 2)`` 2-D data coordinates of world points, by the Axes' own matrix."""
    if ax.name != "3d":  # type: ignore[attr-defined]
        return points
    x, y, _ = proj3d.proj_transform(*points.T, ax.M)  # type: ignore[attr-defined]
    return np.stack([x, y], axis=1)


def _overlapping(boxes: list[tuple[str, object]]) -> list[tuple[str, str]]:
    return [(a, b) for (a, ba), (b, bb) in itertools.combinations(boxes, 2) if ba.overlaps(bb)]  # type: ignore[attr-defined]


def _arm_figure(robot: km.Robot, q: np.ndarray, size: tuple[int, int] = (560, 500)) -> Figure:
    fig = Figure(figsize=(size[0] / 100, size[1] / 100), dpi=100)
    plane = viz.drawing_plane(robot)
    ax = fig.add_subplot(projection="3d" if plane is None else None)
    viz.plot(robot, q, ax=ax)
    return fig


# Builders, not robots: an arm held by a parametrize mark lives until the interpreter's
# shutdown, after the core's teardown (which then reports its Chain as leaked).
CASES = [
    ("arm6-dh tool", lambda: km.load("arm6-dh").with_tool(km.transl(0.0, 0.0, 0.05)), DOC_Q),
    ("arm6-dh", lambda: km.load("arm6-dh"), DOC_Q),
    ("puma560", lambda: km.load("puma560"), np.radians([10, -30, 20, 40, 50, -10])),
    ("iiwa14", lambda: km.load("iiwa14"), np.array([0.3, 0.5, -0.2, -1.2, 0.4, 0.9, 0.2])),
    ("planar-3r", lambda: km.load("planar-3r"), np.radians([30, 45, -60])),
    (
        "moved base",
        lambda: km.load("puma560").with_base(km.transl(0.3, 0.2, 0.1)),
        np.radians([0, -45, 30, 0, 20, 0]),
    ),
]


@pytest.mark.parametrize(("name", "build", "q"), CASES, ids=[c[0] for c in CASES])
def test_each_label_at_its_own_origin_and_none_over_another(
    name: str, build: Callable[[], km.Robot], q: np.ndarray
) -> None:
    robot = build()
    fig = _arm_figure(robot, q)
    ax = fig.axes[0]
    renderer = _draw(fig)
    frames = robot.fk(q, all_frames=True)
    frames[-1] = frames[-1] @ np.linalg.inv(robot.tool)  # S6: the flange, before the tool
    plane = viz.drawing_plane(robot)
    points = {f"label-S{i}": F[:3, 3] for i, F in enumerate(frames)}
    points["label-tool"] = robot.fk(q)[:3, 3]
    points["label-W"] = np.zeros(3)
    named: list[str] = []
    boxes = []
    for label in _labels(ax):
        world = points[label.get_gid()]
        shown = world if plane is None else world[list(plane)]
        np.testing.assert_allclose(label.xy, _projected(ax, shown[None])[0], atol=1e-9)
        box = label.get_window_extent(renderer)
        boxes.append((label.get_text(), box))
        named += label.get_text().split(", ")
        # beside its point: the box is within four text heights of the anchor
        anchor = ax.transData.transform(label.xy)
        nearest = np.clip(anchor, [box.x0, box.y0], [box.x1, box.y1])
        assert np.linalg.norm(nearest - anchor) <= 4 * box.height, label.get_text()
    assert _overlapping(boxes) == []
    # every frame named exactly once; frames in one place share one label
    frame_names = [n for n in named if n.startswith("S")]
    assert sorted(frame_names) == sorted(f"S{i}" for i in range(len(frames)))
    if not np.array_equal(robot.tool, np.eye(4)):
        assert "tool" in named
    if not np.array_equal(robot.base, np.eye(4)):
        assert "W" in named


def test_the_flange_has_its_own_label() -> None:
    # the notes' arm: S4 and S5 at the wrist centre, S6 l4 = 0.1 m further (issue 35)
    fig = _arm_figure(km.load("arm6-dh"), DOC_Q)
    _draw(fig)
    texts = {t.get_gid(): t.get_text() for t in _labels(fig.axes[0])}
    assert texts["label-S4"] == "S4, S5"
    assert texts["label-S6"] == "S6"


@pytest.mark.parametrize(
    ("d", "shown"),
    [
        (0.5e-6, ["S0", "S1, S2"]),  # within SAME_PLACE = 1e-6 of the arm's 1 + d: one label
        (2e-6, ["S0", "S1", "S2"]),  # just beyond: each at its own origin
        (1e-3, ["S0", "S1", "S2"]),
    ],
)
def test_frames_share_a_label_only_in_one_place(d: float, shown: list[str]) -> None:
    assert SAME_PLACE == 1e-6
    robot = km.Robot.from_dh([km.Revolute(a=1.0), km.Revolute(d=d)], convention="standard")
    fig = Figure(figsize=(5, 5), dpi=100)
    ax = fig.add_subplot(projection="3d")
    viz.plot(robot, [0.3, 0.2], ax=ax)
    renderer = _draw(fig)
    labels = _labels(ax)
    assert sorted(t.get_text() for t in labels) == shown
    assert _overlapping([(t.get_text(), t.get_window_extent(renderer)) for t in labels]) == []


def test_labels_follow_a_turned_view() -> None:
    robot = km.load("arm6-dh")
    fig = _arm_figure(robot, DOC_Q)
    ax = fig.axes[0]
    ax.view_init(elev=10, azim=120)
    renderer = _draw(fig)
    frames = robot.fk(DOC_Q, all_frames=True)
    labels = _labels(ax)
    for label in labels:
        i = int(label.get_gid().split("S")[1])
        np.testing.assert_allclose(label.xy, _projected(ax, frames[i, :3, 3][None])[0], atol=1e-9)
    assert _overlapping([(t.get_text(), t.get_window_extent(renderer)) for t in labels]) == []


def test_placement_rule_by_hand() -> None:
    from kinematica.viz.labels import place_boxes

    # three 20 x 10 boxes at one point: below-right, above-right, below-left, gap 2
    places = place_boxes(np.zeros((3, 2)), np.full((3, 2), [20.0, 10.0]), 2.0)
    assert [(ha, va, ring) for _, ha, va, ring in places] == [
        ("left", "top", 0),
        ("left", "bottom", 0),
        ("right", "top", 0),
    ]
    np.testing.assert_allclose(places[0][0], [2.0, -2.0])
    # four boxes fill the corners; the fifth (the sides would overlap them) goes one
    # ring out below-right: a box height + gap further, touching the first box's edge
    places = place_boxes(np.zeros((5, 2)), np.full((5, 2), [20.0, 10.0]), 2.0)
    assert [(ha, va, ring) for _, ha, va, ring in places][3:] == [
        ("right", "bottom", 0),
        ("left", "top", 1),
    ]
    np.testing.assert_allclose(places[4][0], [14.0, -14.0])
    # apart: each box in its first place
    places = place_boxes(np.array([[0.0, 0.0], [100.0, 0.0]]), np.full((2, 2), [20.0, 10.0]), 2.0)
    assert [ring for *_, ring in places] == [0, 0]


def test_axis_colours_have_a_legend() -> None:
    fig = _arm_figure(km.load("puma560"), np.zeros(6))
    legends = [a for a in fig.axes[0].get_children() if a.get_gid() == "axis-legend"]
    assert len(legends) == 1
    legend = legends[0]
    assert [t.get_text() for t in legend.get_texts()] == ["x axis", "y axis", "z axis"]
    assert [h.get_color() for h in legend.legend_handles] == list(AXIS_COLORS)
    fig = Figure()
    ax = viz.plot(
        km.load("puma560"), np.zeros(6), ax=fig.add_subplot(projection="3d"), frames=False
    )
    assert not [a for a in ax.get_children() if a.get_gid() == "axis-legend"]


def test_the_arm_fills_its_picture() -> None:
    from kinematica.viz.plot import arm_figure

    robot = km.load("arm6-dh").with_tool(km.transl(0.0, 0.0, 0.05))
    fig = arm_figure(robot, DOC_Q, size=(560, 500), title="seed 000 arm")
    ax = fig.axes[0]
    renderer = _draw(fig)
    origins = robot.fk(DOC_Q, all_frames=True)[:, :3, 3]
    px = ax.transData.transform(_projected(ax, origins))
    height = px[:, 1].max() - px[:, 1].min()
    assert height > 0.5 * fig.bbox.height  # in a cube around it: 0.36
    widths = [np.diff(lim)[0] for lim in (ax.get_xlim(), ax.get_ylim(), ax.get_zlim())]
    per_metre = np.array(ax.get_box_aspect()) / widths  # one length for a metre on every axis
    np.testing.assert_allclose(per_metre, per_metre[0], rtol=1e-9)
    # and nothing written runs off the picture or over another text
    texts = [fig._suptitle, *ax.texts] + [
        t for axis in (ax.xaxis, ax.yaxis, ax.zaxis) for t in (axis.label,)
    ]
    for text in texts:
        box = text.get_window_extent(renderer)
        assert box.x0 >= 0 and box.y0 >= 0, text.get_text()
        assert box.x1 <= fig.bbox.width and box.y1 <= fig.bbox.height, text.get_text()
    assert _overlapping(_tick_boxes(ax, renderer)) == []
    # thinned, not emptied: the 1.4 m tall z axis keeps a tick every 0.2 m or so
    z_ticks = [t for t in ax.zaxis.get_major_ticks() if 0 <= t.get_loc() <= ax.get_zlim()[1]]
    assert len(z_ticks) >= 5
    legend = next(a for a in fig.legends + ax.get_children() if a.get_gid() == "axis-legend")
    drawn = [(t.get_text(), t.get_window_extent(renderer)) for t in [fig._suptitle, *ax.texts]]
    assert [t for t, b in drawn if b.overlaps(legend.get_window_extent(renderer))] == []


def _tick_boxes(ax: object, renderer: object) -> list[tuple[str, object]]:
    """Drawn boxes of the tick labels within the view, and of the axes' names."""
    axes = [ax.xaxis, ax.yaxis] + ([ax.zaxis] if ax.name == "3d" else [])  # type: ignore[attr-defined]
    out = [(axis.label.get_text(), axis.label.get_window_extent(renderer)) for axis in axes]
    for axis in axes:
        lo, hi = sorted(axis.get_view_interval())
        for tick in axis.get_major_ticks():
            loc = tick.get_loc()
            if tick.label1.get_visible() and tick.label1.get_text() and lo <= loc <= hi:
                out.append((tick.label1.get_text(), tick.label1.get_window_extent(renderer)))
    return out


def test_solution_panels_thin_their_ticks_and_title_their_q() -> None:
    puma = km.load("puma560")
    T = puma.fk(np.radians([10, -30, 20, 40, 50, -10]))
    fig = Figure(figsize=(13.2, 7.45), dpi=100)
    viz.plot_solutions(puma, T, respect_limits=False, frames=True, labels=True, fig=fig)
    from kinematica.viz.solutions import fit_solutions

    fit_solutions(fig)
    renderer = _draw(fig)
    res = puma.ik(T, respect_limits=False)
    titles = [fig._suptitle, *fig.legends] + [ax.title for ax in fig.axes]
    boxes = [(str(t), t.get_window_extent(renderer)) for t in titles]
    assert _overlapping(boxes) == []
    for text, box in boxes:
        assert box.x0 >= 0 and box.x1 <= fig.bbox.width and box.y1 <= fig.bbox.height, text
    caption = next(t for t in fig.texts if t.get_gid() == "caption").get_window_extent(renderer)
    for ax, q in zip(fig.axes, res.solutions, strict=True):
        assert _overlapping(_tick_boxes(ax, renderer)) == []
        assert [t for t, box in _tick_boxes(ax, renderer) if box.overlaps(caption)] == []
        title = ax.get_title().replace("\n", " ")
        assert title.endswith("(deg)")
        printed = np.array([float(v) for v in title.split("q = [")[1].split("]")[0].split(",")])
        np.testing.assert_allclose(printed, np.degrees(q), atol=0.05 + 1e-9)
    fig = viz.plot_solutions(puma, T, respect_limits=False, degrees=False, fig=Figure())
    title = fig.axes[0].get_title().replace("\n", " ")
    assert title.endswith("(rad)")
    printed = np.array([float(v) for v in title.split("q = [")[1].split("]")[0].split(",")])
    np.testing.assert_allclose(printed, res.solutions[0], atol=5e-4 + 1e-12)


def test_trajectory_tool_path_ticks_keep_apart() -> None:
    robot = km.load("arm6-dh").with_tool(km.transl(0.0, 0.0, 0.05))
    t = np.linspace(0.0, 2.0, 11)
    qs = np.linspace(np.zeros(6), DOC_Q, 11)
    fig = viz.plot_trajectory(robot, t, qs, fig=Figure(figsize=(8.8, 3.84), dpi=80))
    renderer = _draw(fig)
    path_ax = next(ax for ax in fig.axes if ax.name == "3d")
    assert _overlapping(_tick_boxes(path_ax, renderer)) == []
    # and the panel's tick labels stay clear of the joint curves' panel
    curves = next(ax for ax in fig.axes if ax.name != "3d")
    left = curves.get_tightbbox(renderer)
    for text, box in _tick_boxes(path_ax, renderer):
        assert not box.overlaps(left), text


def test_animation_time_stamp_clear_of_the_ticks() -> None:
    from kinematica.viz.animate import animation_figure

    robot = km.load("arm6-dh").with_tool(km.transl(0.0, 0.0, 0.05))
    qs = np.linspace(np.zeros(6), DOC_Q, 5)
    fig, _, stamp = animation_figure(robot, qs, qs, (420, 380), 100.0, True, False)
    stamp.set_text("t = 2.00 s")
    renderer = _draw(fig)
    ticks = _tick_boxes(fig.axes[0], renderer)
    assert _overlapping(ticks) == []
    box = stamp.get_window_extent(renderer)
    assert [text for text, b in ticks if b.overlaps(box)] == []
    assert box.x0 >= 0 and box.x1 <= fig.bbox.width and box.y1 <= fig.bbox.height
    others = [fig._suptitle, *fig.axes[0].texts, fig.axes[0].get_legend()]
    assert [o for o in others if o.get_window_extent(renderer).overlaps(box)] == []


def test_box_sides_in_proportion_with_a_floor() -> None:
    from kinematica.viz._mpl import MARGIN, MIN_BOX_SIDE, equal_limits

    ax = Figure().add_subplot(projection="3d")
    # 2 m along x, 0.6 m along z, nothing along y: the y side is the floor's
    equal_limits(ax, np.array([[0.0, 0.0, 0.0], [2.0, 0.0, 0.6]]))
    widths = np.array([np.diff(lim)[0] for lim in (ax.get_xlim(), ax.get_ylim(), ax.get_zlim())])
    np.testing.assert_allclose(widths / 2.0, [1.0 + MARGIN, MIN_BOX_SIDE, 0.3 + MARGIN])
    aspect = np.array(ax.get_box_aspect())
    np.testing.assert_allclose(aspect / aspect[0], widths / widths[0], rtol=1e-12)
