"""A target beyond the reach of an arm with a slide, within its limits: "unreachable" with a gap.

Reference: the reach bound by hand. The Stanford arm's tool origin is never farther
from its base origin than the sum of its link lengths with the slide at its upper
limit (the triangle inequality over the chain's translations).
"""

from __future__ import annotations

import numpy as np
import pytest

import kinematica as km
from kinematica.ik.reach import limited_reach


def far(distance: float) -> np.ndarray:
    T = np.eye(4)
    T[:3, 3] = [distance, 0.0, 0.0]
    return T


def test_limited_reach_is_the_sum_of_the_stanford_arms_lengths():
    stanford = km.load("stanford")
    by_hand = sum(abs(link.a) + abs(link.d) for link in stanford.links)
    by_hand += stanford.qlim[2, 1] + float(np.linalg.norm(stanford.tool[:3, 3]))
    assert limited_reach(stanford.chain) == pytest.approx(by_hand, rel=1e-12)


@pytest.mark.parametrize("distance", [1e200, 1e50])
def test_stanford_far_pose_is_unreachable_with_its_gap(distance):
    stanford = km.load("stanford")
    res = stanford.ik(far(distance))
    assert res.status == "unreachable", res.message
    expected = distance - limited_reach(stanford.chain)
    assert res.gap == pytest.approx(expected, rel=1e-12)
    assert "outside the reach" in res.message
    # as a revolute arm answers the same target
    assert km.load("puma560").ik(far(distance)).status == "unreachable"


def test_batch_answers_as_one_target():
    stanford = km.load("stanford")
    targets = np.stack([far(1e200), far(1e50), stanford.fk(np.array([0.1, 0.2, 0.5, 0, 0.3, 0]))])
    many = stanford.ik(targets)
    assert list(many.status[:2]) == ["unreachable", "unreachable"]
    assert many.status[2] == "ok"
    assert many.gap[0] == pytest.approx(1e200, rel=1e-12)


def test_ignoring_the_limits_proves_nothing():
    # Without its limits the slide reaches any distance: no gap can be claimed.
    res = km.load("stanford").ik(far(1e200), respect_limits=False)
    assert res.status != "unreachable" or res.gap is None


@pytest.mark.parametrize(("tol", "proven"), [(0.9e200, True), (1.1e200, False)])
def test_gap_must_exceed_the_position_tolerance(tol, proven):
    # A solution may miss by the tolerance: only a gap beyond it proves anything.
    res = km.load("stanford").ik(far(1e200), tol=(tol, 1e-10))
    assert (res.status == "unreachable" and res.gap is not None) is proven


def test_closed_form_out_of_limits_answer_is_kept():
    # 10 m away the closed form gives solutions, all with the slide past its limit:
    # "out_of_limits" says more than a gap would.
    assert km.load("stanford").ik(far(10.0)).status == "out_of_limits"
