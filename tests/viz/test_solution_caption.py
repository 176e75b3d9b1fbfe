"""The solutions figure says when two panels draw the same links, and only then."""

from __future__ import annotations

import itertools
import re
import warnings

import numpy as np
import pytest

import kinematica as km

pytest.importorskip("matplotlib")
from matplotlib.figure import Figure

from kinematica import viz
from kinematica.viz.arm import SAME_PLACE


def _caption(fig: Figure) -> str | None:
    found = [t.get_text() for t in fig.texts if t.get_gid() == "caption"]
    assert len(found) <= 1
    return found[0] if found else None


def _links(robot: km.Robot, q: np.ndarray) -> np.ndarray:
    """Every frame origin and the tool point, from the robot's own forward kinematics."""
    with warnings.catch_warnings():  # solutions outside the limits are asked for
        warnings.simplefilter("ignore", km.LimitWarning)
        frames = robot.fk(q, all_frames=True)[:, :3, 3]
        return np.concatenate([frames, robot.fk(q)[None, :3, 3]])


def _pairs_in(caption: str) -> tuple[set[tuple[int, int]], list[set[str]]]:
    """The pairs of panels (0-based) a caption names, and for each pair its joints."""
    pairs: set[tuple[int, int]] = set()
    joints = []
    for line in caption.replace("\n", " ").split("Panels ")[1:]:
        named = set(re.findall(r"q\d+", line.split("differ only in")[1]))
        for group in re.findall(r"\(([\d, ]+)\)", line.split(" look alike")[0]):
            panels = [int(v) - 1 for v in group.split(",")]
            for pair in itertools.combinations(panels, 2):
                pairs.add(pair)
                joints.append(named)
    return pairs, joints


CASES = [
    # a spherical wrist turned over (q4 + pi, -q5, q6 + pi) moves no frame origin
    ("puma560", np.radians([10, -30, 20, 40, 50, -10]), True, 4),
    # a shoulder without offset turned by pi, the upper arm over: the same elbow (issue 35)
    ("anthropomorphic-3r", np.array([0.3, 0.5, -0.9]), False, 2),
    # elbow up and down of a planar arm: every panel draws its own links
    ("planar-3r", np.array([0.3, 0.6, -0.5]), True, 0),
]


@pytest.mark.parametrize(("name", "q", "pose", "count"), CASES, ids=[c[0] for c in CASES])
def test_caption_names_exactly_the_panels_drawn_alike(
    name: str, q: np.ndarray, pose: bool, count: int
) -> None:
    robot = km.load(name)
    T = robot.fk(q) if pose else robot.fk(q)[:3, 3]
    fig = viz.plot_solutions(robot, T, respect_limits=False, fig=Figure())
    res = robot.ik(T, respect_limits=False)
    assert len(fig.axes) == res.count >= 2
    expected, differ = set(), []
    for i, j in itertools.combinations(range(res.count), 2):
        gap = np.abs(_links(robot, res.solutions[i]) - _links(robot, res.solutions[j])).max()
        assert gap < 1e-9 or gap > 1e-3  # alike or plainly apart
        if gap < 1e-9:
            expected.add((i, j))
            turned = np.abs(np.angle(np.exp(1j * (res.solutions[i] - res.solutions[j]))))
            differ.append({f"q{k + 1}" for k in np.flatnonzero(turned > 1e-3)})
    assert len(expected) == count
    caption = _caption(fig)
    if count == 0:
        assert caption is None
        return
    assert caption is not None
    pairs, joints = _pairs_in(caption)
    assert pairs == expected
    assert sorted(map(sorted, joints)) == sorted(map(sorted, differ))


def test_caption_boundary_same_place() -> None:
    # rotating q1 of a 2R arm (a = 1, 1; scale 2) by delta moves its tip by 2 * delta
    from kinematica.viz.solutions import same_links

    assert SAME_PLACE == 1e-6
    arm = km.Robot.from_dh([km.Revolute(a=1.0), km.Revolute(a=1.0)], convention="standard")
    near = np.array([[0.0, 0.0], [0.5 * SAME_PLACE, 0.0]])  # the tip moves 0.5 SAME_PLACE * 2
    far = np.array([[0.0, 0.0], [2.0 * SAME_PLACE, 0.0]])  # the tip moves 2 SAME_PLACE * 2
    assert [g for g, _ in same_links(arm, near)] == [[0, 1]]
    assert same_links(arm, far) == []


def test_caption_boundary_joints_that_differ() -> None:
    # the last joint turns about an axis through every point after it: it moves no link
    from kinematica.viz.solutions import same_links

    arm = km.Robot.from_dh([km.Revolute(a=1.0), km.Revolute(alpha=0.0)], convention="standard")
    small = np.array([[0.2, 0.0], [0.2, 0.5 * SAME_PLACE]])
    large = np.array([[0.2, 0.0], [0.2, 2.0 * SAME_PLACE]])
    flipped = np.array([[0.2, 0.0], [0.2, np.pi]])
    assert same_links(arm, small) == [([0, 1], [])]
    assert same_links(arm, large) == [([0, 1], [1])]
    assert same_links(arm, flipped) == [([0, 1], [1])]
    wrapped = np.array([[0.2, -np.pi + 0.25 * SAME_PLACE], [0.2, np.pi - 0.25 * SAME_PLACE]])
    assert same_links(arm, wrapped) == [([0, 1], [])]  # the same angle, modulo 2 pi
