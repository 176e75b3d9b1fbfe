"""Values given to IK and self-motion warn of degrees as fk warns of q (issue 35, item 5)."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import kinematica as km
from kinematica.io.plausible import PLAUSIBLE_ANGLE

Q_IIWA = [0.3, 0.5, -0.2, -1.2, 0.4, 0.9, 0.2]


@pytest.fixture(scope="module")
def iiwa() -> km.Robot:
    return km.load("iiwa14")


def _quiet(call) -> None:  # type: ignore[no-untyped-def]
    with warnings.catch_warnings():
        warnings.simplefilter("error", km.KinematicaWarning)
        call()


def test_q0_in_degrees_warns_as_fk_does() -> None:
    puma = km.load("puma560")
    T = puma.fk([0.1, 0.2, 0.3, 0.4, 0.5, 0.6])
    with pytest.warns(km.LimitWarning, match=r"q0: joint 1 = 10 rad is outside its limits"):
        puma.ik(T, q0=[10, 20, 30, 40, 50, 60])
    _quiet(lambda: puma.ik(T, q0=[0.1, 0.2, 0.3, 0.4, 0.5, 0.6]))


def test_arm_angle_beyond_a_turn_warns_at_the_boundary(iiwa: km.Robot) -> None:
    T = iiwa.fk(Q_IIWA)
    with pytest.warns(km.UnitWarning, match=r"arm_angle: 30 rad is more than a full turn"):
        iiwa.ik(T, arm_angle=30)
    with pytest.warns(km.UnitWarning, match="arm_angle"):
        iiwa.ik(T, arm_angle=PLAUSIBLE_ANGLE * 1.001)
    _quiet(lambda: iiwa.ik(T, arm_angle=PLAUSIBLE_ANGLE * 0.999))


def test_fixed_and_self_motion_values_of_a_free_joint_in_degrees_warn(iiwa: km.Robot) -> None:
    free = iiwa.with_limits([None] * 7)
    T = free.fk(Q_IIWA)
    with pytest.warns(km.UnitWarning, match=r"fixed: joint 1 = 20 rad is more than a full turn"):
        free.ik(T, fixed={"q1": 20})
    with pytest.warns(km.UnitWarning, match=r"values: joint 1 = 90 rad"):
        free.self_motion(T, "q1", values=[0.0, 90.0])
    _quiet(lambda: free.ik(T, fixed={0: 0.3}))
    with pytest.warns(km.UnitWarning, match=r"values: the arm angle = 45 rad"):
        iiwa.self_motion(iiwa.fk(Q_IIWA), "arm angle", values=[0.0, 45.0], samples=3)


def test_free_joints_have_the_names_the_messages_use() -> None:
    arm = km.load("arm6-dh")
    res = arm.ik(arm.fk(np.radians([30.0, 20.0, -40.0, 10.0, 60.0, -20.0])))  # centre on axis 1
    assert res.status == "singular"
    assert res.free_names == tuple(f"q{i + 1}" for i in res.free_joints) == ("q1",)
    assert "q1" in res.message
