"""robot.ik's one-target path (every default: straight to the core) gives the general path's answer.

``robot.ik(T)`` with no settings (or ``method="numeric"`` alone) skips the target
parsing and option handling for a rigid pose ``(4, 4)`` or a position ``(3,)``;
``robot.ik(T, options=IKOptions(...))`` asks for the same thing through the general path. Both
must give the same result, field by field, on every built-in arm (closed forms
and the numeric search), for reachable, singular, out-of-limits and
unreachable targets, and the targets the one-target path leaves to the general
one (not rigid, not finite) must still be explained there.
"""

from __future__ import annotations

import numpy as np
import pytest
from support.helpers import assert_same_result

import kinematica as km
from kinematica.errors import KinematicaError
from kinematica.ik import IKOptions


def _targets(robot: km.Robot) -> list[np.ndarray]:
    rng = np.random.default_rng(7)
    lo, hi = robot.qlim.T
    lo, hi = np.maximum(lo, -3.0), np.minimum(hi, 3.0)
    qs = [rng.uniform(lo, hi) for _ in range(4)]
    qs.append(np.clip(np.zeros(robot.dof), lo, hi))  # often singular (stretched or folded)
    poses = [robot.fk(q) for q in qs]
    far = poses[0].copy()
    far[:3, 3] += 100.0  # beyond any reach
    return [*poses, far]


@pytest.mark.parametrize("name", km.builtin_names())
@pytest.mark.parametrize("method", ["auto", "numeric"])
def test_one_pose_and_one_position_match_the_general_path(name: str, method: str) -> None:
    robot = km.load(name)
    general = IKOptions(method=method)
    for T in _targets(robot):
        assert_same_result(robot.ik(T, method=method), robot.ik(T, options=general))
        p = np.ascontiguousarray(T[:3, 3])
        assert_same_result(robot.ik(p, method=method), robot.ik(p, options=general))


def test_targets_the_one_target_path_leaves_are_explained_by_the_general_path() -> None:
    robot = km.load("puma560")
    T = robot.fk(np.full(6, 0.3))
    skewed = T.copy()
    skewed[:3, :3] *= 1.0 + 1e-6  # not rigid to round-off: projected, with a note
    res = robot.ik(skewed)
    assert res.status == "ok" and res.notes
    assert_same_result(res, robot.ik(skewed, options=IKOptions()))
    for bad in (np.full((4, 4), np.nan), np.array([np.nan, 0.0, 0.0])):
        with pytest.raises(KinematicaError, match="NaN"):
            robot.ik(bad)


@pytest.mark.parametrize("method", ["auto", "numeric"])
@pytest.mark.parametrize("workers", [0, "two"], ids=repr)
def test_a_bad_setting_is_refused_on_the_one_target_path_too(method: str, workers: object) -> None:
    robot = km.load("puma560")
    T = robot.fk(np.full(6, 0.3))
    with pytest.raises(KinematicaError, match="workers"):
        robot.ik(T, method=method, workers=workers)
