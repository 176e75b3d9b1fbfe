"""Design measures from reachability, against geometry worked by hand (issue 37 item 3).

The elbow arm of ``tests/support/reach_arms.py`` (every joint unlimited, a
spherical wrist) puts its wrist centre exactly on the shell ``R_IN <= |w| <=
R_OUT`` about the shoulder and turns the tool to any orientation there; with a
tool offset d along the tool's z axis the wrist centre of a pose ``(p, R)`` is
``p - d·R e3``. So a target's share of orientations reached is a count of the
orientations whose wrist centre lies in the shell, computed here without the IK.
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
from support.reach_arms import R_IN, R_OUT, elbow_wrist

import kinematica as km
from kinematica.design import ReachSettings, Task, reach_measures, task_reachability
from kinematica.design.reachmeasures import MAX_SAMPLES
from kinematica.errors import ArgumentError, KinematicaError
from kinematica.reach import ball_set, so3_set
from kinematica.reach.orientations import _SERIES_ANGLE

#: A (target, orientation) pair whose wrist centre lies within this (m) of the shell's
#: boundary is left out: there IK and the formula may differ by round-off.
MARGIN = 1e-7


def _angles(R: np.ndarray) -> np.ndarray:
    return np.arccos(np.clip((np.trace(R, axis1=-2, axis2=-1) - 1.0) / 2.0, -1.0, 1.0))


@pytest.mark.parametrize("radius", [0.0, 1e-3, 0.3, 1.5, math.pi])
def test_ball_set_spreads_the_haar_measure_of_the_ball(radius: float) -> None:
    n = 200
    R = ball_set(n, radius)
    assert R.shape == (n, 3, 3)
    np.testing.assert_allclose(R @ np.transpose(R, (0, 2, 1)), np.broadcast_to(np.eye(3), R.shape),
                               atol=1e-14)  # fmt: skip
    np.testing.assert_allclose(np.linalg.det(R), 1.0, atol=1e-14)
    theta = _angles(R)
    assert theta.max() <= radius + 1e-7
    if radius > 0:
        # the share of the ball's Haar measure within half the radius, in closed form
        share = (radius / 2 - math.sin(radius / 2)) / (radius - math.sin(radius))
        assert abs(np.count_nonzero(theta <= radius / 2) - share * n) <= 1.0
        # the axes spread over the sphere: their mean is near 0
        axis = np.stack([R[:, 2, 1] - R[:, 1, 2], R[:, 0, 2] - R[:, 2, 0], R[:, 1, 0] - R[:, 0, 1]])
        unit = axis / np.linalg.norm(axis, axis=0)
        assert np.linalg.norm(unit.mean(axis=1)) < 0.05


def test_ball_set_angles_at_the_series_switch() -> None:
    """θ − sin θ to 1e-13 relative either side of _SERIES_ANGLE, and far from it."""
    from kinematica.reach.orientations import _versine_integral

    mpmath.mp.dps = 40
    for t in [1e-4, 1e-3, _SERIES_ANGLE * (1 - 1e-9), _SERIES_ANGLE * (1 + 1e-9), 0.5, 3.0]:
        exact = float(mpmath.mpf(t) - mpmath.sin(mpmath.mpf(t)))
        assert abs(float(_versine_integral(np.array(t))) - exact) <= 1e-13 * exact


def _wrist_counts(targets: np.ndarray, R: np.ndarray, d: float) -> tuple[np.ndarray, np.ndarray]:
    """(orientations whose wrist centre is in the shell, target decided clear of its edge)."""
    wc = targets[:, None, :] - d * R[..., :, 2]
    r = np.linalg.norm(wc, axis=-1)
    ok = (r >= R_IN) & (r <= R_OUT)
    clear = (np.abs(r - R_IN) > MARGIN) & (np.abs(r - R_OUT) > MARGIN)
    return ok.sum(axis=-1), clear.all(axis=-1)


def test_no_tool_offset_index_is_one_in_the_wrist_shell_and_zero_outside() -> None:
    robot = elbow_wrist()
    rng = np.random.default_rng(0)
    p = rng.uniform(-1.0, 1.0, (300, 3))
    r = np.linalg.norm(p, axis=1)
    clear = (np.abs(r - R_IN) > MARGIN) & (np.abs(r - R_OUT) > MARGIN)
    inside = (r >= R_IN) & (r <= R_OUT)
    R = km.matrix_from_euler(rng.uniform(-np.pi, np.pi, (300, 3)), "xyz")
    poses = np.tile(np.eye(4), (300, 1, 1))
    poses[:, :3, :3], poses[:, :3, 3] = R, p
    for task, tol in [(Task.from_poses(poses), 0.4), (Task.from_positions(p), None)]:
        index = task_reachability(robot, task, tol, 16)
        np.testing.assert_array_equal(index[clear], np.where(inside[clear], 1.0, 0.0))
    assert inside[clear].sum() > 50 and (~inside[clear]).sum() > 50


@pytest.mark.parametrize("tol", [0.05, 0.5, math.pi])
def test_tool_offset_counts_the_orientations_whose_wrist_centre_is_in_the_shell(
    tol: float,
) -> None:
    d, n = 0.15, 48
    robot = elbow_wrist(d)
    rng = np.random.default_rng(1)
    # positions near the shell's edges, where the tolerance decides
    direction = rng.standard_normal((200, 3))
    direction /= np.linalg.norm(direction, axis=1, keepdims=True)
    radius = rng.choice([R_IN, R_OUT], 200) + rng.uniform(-1.2 * d, 1.2 * d, 200)
    p = direction * radius[:, None]
    poses = np.tile(np.eye(4), (200, 1, 1))
    poses[:, :3, :3], poses[:, :3, 3] = (
        km.matrix_from_euler(rng.uniform(-np.pi, np.pi, (200, 3)), "xyz"),
        p,
    )
    task = Task.from_poses(poses)
    expected, decided = _wrist_counts(p, poses[:, None, :3, :3] @ ball_set(n, tol), d)
    got = task_reachability(robot, task, tol, n) * n
    assert decided.mean() > 0.95
    np.testing.assert_array_equal(got[decided], expected[decided])
    assert np.count_nonzero((expected > 0) & (expected < n)) > 0  # fractional cases seen
    # a position task asks all of SO(3): the so3_set's own count
    expected, decided = _wrist_counts(p, np.broadcast_to(so3_set(n), (200, n, 3, 3)), d)
    got = task_reachability(robot, Task.from_positions(p), None, n) * n
    np.testing.assert_array_equal(got[decided], expected[decided])


def test_dexterous_volume_of_a_box_by_hand() -> None:
    """No tool offset: a voxel is dexterous iff its centre lies in the wrist shell."""
    h = 0.1
    region = np.array([[-0.2, -0.8, -0.8], [0.8, 0.8, 0.8]])
    settings = ReachSettings(region=region, resolution=h, orientations=12, samples=8)
    task = Task.from_positions([[0.5, 0.0, 0.0]])
    got = reach_measures(elbow_wrist(), task, settings)
    axes = [np.arange(lo + h / 2, hi, h) for lo, hi in zip(region[0], region[1], strict=True)]
    c = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1)
    r = np.linalg.norm(c, axis=-1)
    assert np.all((np.abs(r - R_IN) > MARGIN) & (np.abs(r - R_OUT) > MARGIN))
    count = np.count_nonzero((r >= R_IN) & (r <= R_OUT))
    assert got["dexterous_volume"] == pytest.approx(count * h**3, rel=1e-12)
    assert got["task_reachability"] == 1.0
    assert math.isnan(reach_measures(elbow_wrist(), task, ReachSettings())["dexterous_volume"])


ELBOW = """
name: elbow arm, forearm free
convention: standard
parameters:
  fore: {value: 0.2, min: 0.1, max: 0.6}
joints:
  - {theta: q1, d: 0, a: 0, alpha: 90}
  - {theta: q2, d: 0, a: 0.5, alpha: 0}
  - {theta: q3, d: 0, a: 0, alpha: 90}
  - {theta: q4, d: fore, a: 0, alpha: -90}
  - {theta: q5, d: 0, a: 0, alpha: 90}
  - {theta: q6, d: 0.15, a: 0, alpha: 0}
"""


def test_optimize_for_task_reachability(tmp_path) -> None:  # type: ignore[no-untyped-def]
    """A target 0.9 m out along z, tool z pointing outwards, tolerance 0.6 rad.

    The wrist centre of an orientation whose tool z is γ off the base z lies
    |0.9 e3 - 0.15 z| from the shoulder, 0.75 m at γ = 0 (feasible from fore =
    0.25 m), farthest at γ = 0.6: every orientation of the set is reached only
    from a forearm of at least that distance less 0.5 m; the best design does.
    """
    path = tmp_path / "elbow.yaml"
    path.write_text(ELBOW)
    T = np.eye(4)
    T[:3, 3] = [0.0, 0.0, 0.9]  # tool z (the base z) pointing outwards along the target
    res = km.design.optimize(
        path,
        Task.from_poses(T[None]),
        "task_reachability",
        budget=20,
        seed=0,
        reach=ReachSettings(tolerance=0.6, samples=32),
    )
    assert res.feasible and res.best.measures["task_reachability"] == 1.0
    # by hand: with fore = f the wrist centre must lie within 0.5 + f of the shoulder; the
    # farthest one of the tolerance set is |0.75 e3 - 0.15 z| with z 0.6 rad off e3
    far = math.hypot(0.9 - 0.15 * math.cos(0.6), 0.15 * math.sin(0.6))
    z = ball_set(32, 0.6)[:, :, 2]  # the set's tool z axes (the target's rotation is I)
    need = float(np.max(np.linalg.norm([0.0, 0.0, 0.9] - 0.15 * z, axis=1))) - 0.5
    assert far - 0.5 - 0.01 <= need <= far - 0.5 + 1e-12
    assert res.best_params["fore"] >= need - 1e-9
    values = [ev.measures["task_reachability"] for ev in res.history]
    assert min(values) < 1.0  # the template's forearm (0.2 m) reaches none


def test_reach_objectives_need_their_settings(tmp_path) -> None:  # type: ignore[no-untyped-def]
    path = tmp_path / "elbow.yaml"
    path.write_text(ELBOW)
    task = Task.from_positions([[0.0, 0.0, 0.6]])
    with pytest.raises(KinematicaError, match="reach="):
        km.design.optimize(path, task, "task_reachability", budget=10, seed=0)
    with pytest.raises(KinematicaError, match="region"):
        km.design.optimize(path, task, "dexterous_volume", budget=10, seed=0, reach=ReachSettings())
    with pytest.raises(ArgumentError, match="reach must be"):
        km.design.optimize(path, task, budget=10, seed=0, reach="yes")  # type: ignore[arg-type]
    with pytest.raises(ArgumentError, match="region"):
        ReachSettings(region=[[0, 0, 0]])
    with pytest.raises(ArgumentError, match="tolerance"):
        ReachSettings(tolerance=4.0)
    with pytest.raises(ArgumentError, match="resolution"):
        ReachSettings(resolution=0.0)
    assert ReachSettings(samples=MAX_SAMPLES).samples == MAX_SAMPLES
    with pytest.raises(ArgumentError, match="samples"):
        ReachSettings(samples=MAX_SAMPLES + 1)
