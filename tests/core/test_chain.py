"""The core's chain (``chain.hpp``): exact twists snapped, both sides of the tolerance.

Its fixed parts and reversed chain are checked against transforms composed here
with numpy (the motions and ``np.linalg.inv``).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from support.helpers import assert_transform_close, rot_x, rot_z, transform_from, tras_z
from support.urdf import URDF_DIR

import kinematica as km


@pytest.mark.parametrize(("eps", "exact"), [(1e-17, True), (1e-13, False)])
def test_snap_tol_is_1e_15(eps: float, exact: bool) -> None:
    # A twist within 1e-15 of 90 degrees has its cosine snapped to exactly 0:
    # then the frame of a joint at q = 0 has exact zeros; 1e-13 off it does not.
    robot = km.Robot.from_dh([km.Revolute(alpha=math.pi / 2 + eps)], convention="standard")
    T = robot.fk([0.0])
    assert bool(T[1, 1] == 0.0) == exact


# ------------------------------------------------- fixed parts, the reversed chain
#: The arms the tests below run on, by name (built in each test: a robot held by a
#: ``parametrize`` mark lives until the interpreter's shutdown, after the core's types,
#: and nanobind then reports its chain as leaked).
ARMS = ["standard", "modified", "urdf"]


def _arm(kind: str) -> km.Robot:
    """A standard or modified DH arm with base, tool, a slide and limits, or a URDF arm."""
    if kind == "urdf":
        return km.load(URDF_DIR / "ur5_robot.urdf")
    rng = np.random.default_rng(5)
    rows = [
        km.Revolute(d=0.3, a=0.1, alpha=0.7, offset=0.2, qlim=(-1.0, 2.0)),
        km.Revolute(d=-0.1, a=0.4, alpha=-1.2, offset=-0.4),
        km.Prismatic(theta=0.3, a=0.05, alpha=math.pi / 2, offset=0.2, qlim=(0.0, 0.5)),
        km.Revolute(d=0.2, alpha=2.0, offset=1.0),
    ]
    base, tool = transform_from(rng.normal(size=4), [0.1, -0.2, 0.3]), tras_z(0.05) @ rot_x(0.4)
    return km.Robot.from_dh(rows, convention=kind, base=base, tool=tool, name=kind)


@pytest.mark.parametrize("kind", ARMS)
def test_fixed_parts_rebuild_the_forward_kinematics(kind: str) -> None:
    # T = start · Π_i [M_i(q_i) F_i] · tool, composed here with numpy
    robot = _arm(kind)
    chain = robot.chain
    q = np.random.default_rng(6).uniform(-1.0, 1.0, (4, chain.dof))
    for qi in q:
        T = chain.start.copy()
        for j, F in enumerate(chain.fixed_parts):
            T = T @ (tras_z(qi[j]) if chain.prismatic[j] else rot_z(qi[j])) @ F
        assert_transform_close(T @ chain.tool, robot.fk(qi), atol=1e-14)


@pytest.mark.parametrize("kind", ARMS)
def test_reversed_chain_is_the_inverse_transform(kind: str) -> None:
    robot = _arm(kind)
    chain = robot.chain
    back = chain.reversed()
    q = np.random.default_rng(7).uniform(-1.0, 1.0, (6, chain.dof))
    T = chain.fk(q)[0]
    T_back = back.fk(np.ascontiguousarray(-q[:, ::-1]))[0]
    assert_transform_close(T_back, np.linalg.inv(T), atol=1e-14)
    np.testing.assert_array_equal(back.prismatic, chain.prismatic[::-1])
    np.testing.assert_array_equal(back.own_limits, -chain.own_limits[::-1, ::-1])
    twice = back.reversed().fk(q)[0]
    assert_transform_close(twice, T, atol=1e-14)
