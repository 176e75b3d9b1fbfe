"""A URDF's FK is the file's own, whatever its axes: the general chain of the core.

A DH table describes nearly parallel axes only approximately (their common normal
is far away); the robot computes with the file's transforms instead. Each chain
here is compared with an independent product of the file's transforms
(tests/support/urdf.py, scipy rotations): truncated rpy values, axes 1e-9 and
1e-3 off parallel (a calibrated arm), prismatic joints along odd axes.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from support.helpers import assert_transform_close
from support.urdf import random_joint_values, reference_chain, urdf_from_joints

import kinematica as km

#: FK of a loaded URDF equals the file's own to this (m; unitless for rotations),
#: for chains of links of about a metre.
EXACT_ATOL = 1e-12

pytestmark = pytest.mark.filterwarnings(
    "ignore:q. joint .* outside its limits", "ignore:the extracted .* DH table"
)

_NEAR = (1e-9, -1e-9, 1e-6, 1e-3, -1e-3)
_TRUNCATED = (1.5707963, 3.1415926, -1.570796325, 3.141592653)


def _fk_matches(text: str, tmp_path, name: str = "arm") -> None:
    path = tmp_path / f"{name}.urdf"
    path.write_text(text)
    ref = reference_chain(text)
    rng = np.random.default_rng(11)
    for convention in ("standard", "modified"):
        robot = km.load(path, convention=convention)
        for batch in [(), (7,), (2, 3)]:
            q = random_joint_values(ref, rng, batch)
            assert_transform_close(robot.fk(q), ref.fk_batch(q), atol=EXACT_ATOL)
        q = random_joint_values(ref, rng, ())
        assert_transform_close(robot.fk(q, all_frames=True)[-1], ref.fk(q), atol=EXACT_ATOL)
        # the Jacobian is the file's too: finite differences of the reference FK
        J = robot.jacobian(q)
        h = 1e-6
        for i in range(robot.dof):
            dq = np.zeros(robot.dof)
            dq[i] = h
            fd = (ref.fk(q + dq)[:3, 3] - ref.fk(q - dq)[:3, 3]) / (2 * h)
            np.testing.assert_allclose(J[:3, i], fd, atol=1e-8)


def _perturbed_ur5(off: float) -> str:
    """A UR5-like chain (axes 2, 3, 4 parallel) with those axes turned by ``off`` rad."""
    joints = [
        {"type": "revolute", "xyz": [0, 0, 0.089159], "rpy": [0, 0, 0], "axis": (0, 0, 1)},
        {"type": "revolute", "xyz": [0, 0.13585, 0], "rpy": [0, math.pi / 2, 0], "axis": (0, 1, 0)},
        {"type": "revolute", "xyz": [0, -0.1197, 0.425], "rpy": [off, 0, 0], "axis": (0, 1, 0)},
        {
            "type": "revolute",
            "xyz": [0, 0, 0.39225],
            "rpy": [0, math.pi / 2 + off, off],
            "axis": (0, 1, 0),
        },
        {"type": "revolute", "xyz": [0, 0.093, 0], "rpy": [0, 0, 0], "axis": (0, 0, 1)},
        {"type": "revolute", "xyz": [0, 0, 0.09465], "rpy": [0, 0, 0], "axis": (0, 1, 0)},
        {"type": "fixed", "xyz": [0, 0.0823, 0], "rpy": [0, 0, math.pi / 2], "axis": (0, 0, 1)},
    ]
    return urdf_from_joints(joints, name=f"ur5_off_{off:g}")


@pytest.mark.parametrize("off", [0.0, 1e-9, -1e-9, 1e-3])
def test_calibrated_arm_with_axes_nearly_parallel(off: float, tmp_path) -> None:
    _fk_matches(_perturbed_ur5(off), tmp_path)


def test_truncated_pi_in_every_rpy(tmp_path) -> None:
    joints = [
        {"type": "revolute", "xyz": [0.1, 0, 0.3], "rpy": [t, 0, -t / 2], "axis": (0, 0, 1)}
        for t in _TRUNCATED
    ]
    _fk_matches(urdf_from_joints(joints, name="truncated"), tmp_path)


def test_prismatic_joints_on_odd_axes(tmp_path) -> None:
    joints = [
        {
            "type": "prismatic",
            "xyz": [0.2, -0.1, 0.3],
            "rpy": [0.3, -0.2, 1.1],
            "axis": (0.3, -0.5, 0.81),
        },
        {"type": "revolute", "xyz": [0, 0.4, 0], "rpy": [1.5707963, 0, 0], "axis": (0, 0, -1)},
        {"type": "prismatic", "xyz": [0.1, 0.1, 0.1], "rpy": [0, 0, 0], "axis": (-0.7, 0.1, 1e-9)},
        {"type": "revolute", "xyz": [0.5, 0, 0], "rpy": [0, 3.1415926, 0], "axis": (1, 1e-9, 0)},
    ]
    _fk_matches(urdf_from_joints(joints, name="odd_slides"), tmp_path)


_angle = st.one_of(
    st.sampled_from((0.0, math.pi / 2, -math.pi / 2, math.pi, *_TRUNCATED)),
    st.builds(
        lambda s, e: s + e, st.sampled_from((0.0, math.pi / 2, math.pi)), st.sampled_from(_NEAR)
    ),
    st.floats(-math.pi, math.pi, allow_nan=False),
)
_length = st.one_of(
    st.just(0.0), st.floats(-1.0, 1.0, allow_nan=False), st.sampled_from((1e-10, -3e-13))
)
_axis = st.one_of(
    st.sampled_from([(0, 0, 1), (0, 1, 0), (1, 0, 0), (0, 0, -1), (0, -1, 0)]),
    st.tuples(*(st.sampled_from((0.0, 1e-9, -1e-3, 0.4, -0.7, 1.0)) for _ in range(3))).filter(
        lambda v: math.sqrt(sum(c * c for c in v)) > 0.1
    ),
)


@st.composite
def _chains(draw: st.DrawFn) -> list[dict[str, object]]:
    n = draw(st.integers(1, 7))
    joints: list[dict[str, object]] = []
    for _ in range(n):
        joints.append(
            {
                "type": draw(st.sampled_from(["revolute", "continuous", "prismatic"])),
                "xyz": [draw(_length) for _ in range(3)],
                "rpy": [draw(_angle) for _ in range(3)],
                "axis": draw(_axis),
            }
        )
    return joints


@settings(max_examples=40, deadline=None)
@given(joints=_chains())
def test_random_chains_with_nearly_parallel_axes(joints, tmp_path_factory) -> None:
    _fk_matches(urdf_from_joints(joints), tmp_path_factory.mktemp("urdf"))
