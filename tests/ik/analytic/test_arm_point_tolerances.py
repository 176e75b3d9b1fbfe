"""The decoupled family's named tolerances, each tested on both sides of its value.

Every case is placed a factor below or above the value the constant's documentation
states, written here as a literal: a test that read the constant itself would move
with it, and could not notice it changed a thousandfold (the literals are compared
with the core's constants once, below). The constants are compared with a quantity
the test controls exactly (a distance, a sine, an angle), so the factors leave a wide
margin for round-off. Tolerances of ``cpp/include/kinematica/solvers/arm_point.hpp``,
``arm_quartic.hpp``, ``spherical_wrist.hpp``, ``arm_position.hpp`` and of the builder
``kinematica.ik.analytic.arm_point``.
"""

from __future__ import annotations

import math

import kinematica._core as _core
import kinematica._core_testing as _core_testing
import numpy as np
import pytest
from support import wrist_arms as wrist_edges
from support import wrist_arms as wrist_parts

import kinematica as km
from kinematica.dh import Revolute

D = _core.decoupled
DT = _core_testing.decoupled

#: A case a factor 10 inside a tolerance, and one a factor 10 outside it.
FACTORS = [(0.1, True), (10.0, False)]

# The documented values, one per constant.
SELF_MOTION_TOL = 1e-14  # arm_quartic.hpp
ARM_DOUBLE_ROOT_TOL = 1e-14  # arm_point.hpp DOUBLE_ROOT_TOL
ARM_NEAR_TOL = 1e-6  # arm_quartic.hpp NEAR_TOL
ARM_SINGULAR_TOL = 1e-12  # arm_point.hpp SINGULAR_TOL
NEAR_SET_TOL = 1e-9  # arm_point.hpp
WRIST_SINGULAR_TOL = 1e-12  # spherical_wrist.hpp
AXIS_ANGLE_TOL = 1e-9  # dh/lines.py (the builder's line geometry)
AXIS_LENGTH_TOL = 1e-9  # dh/lines.py, times 1 + the arm's size
ARM_RANK_TOL = 1e-6  # arm_point_build.hpp PLACE_RANK_TOL
MAX_POSITION_DOF = 32  # arm_position.hpp
#: The README's singular pose of arm6-dh: its wrist centre on axis 1.
ARM6_SINGULAR_Q = np.radians([30, 20, -40, 10, 60, -20])


def test_the_documented_values_are_the_core_s() -> None:
    assert DT.SELF_MOTION_TOL == SELF_MOTION_TOL
    assert DT.DOUBLE_ROOT_TOL == ARM_DOUBLE_ROOT_TOL
    assert DT.NEAR_TOL == ARM_NEAR_TOL
    assert DT.SINGULAR_TOL == ARM_SINGULAR_TOL
    assert DT.NEAR_SET_TOL == NEAR_SET_TOL
    assert DT.WRIST_SINGULAR_TOL == WRIST_SINGULAR_TOL
    assert DT.MAX_POSITION_DOF == MAX_POSITION_DOF
    assert km.dh.lines.AXIS_ANGLE_TOL == AXIS_ANGLE_TOL
    assert km.dh.lines.AXIS_LENGTH_TOL == AXIS_LENGTH_TOL
    assert DT.PLACE_RANK_TOL == ARM_RANK_TOL


# --- arm_quartic.hpp ----------------------------------------------------------


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_self_motion_tol_is_relative_round_off_of_the_quartic(factor: float, inside: bool) -> None:
    """SELF_MOTION_TOL: the trigonometric polynomial F of q3 is identically 0
    (joints 1-3 have a self-motion, every q3 is a root) when its coefficients
    are below this fraction of the size of the terms they were computed from.

    A constant F = c with terms of size 3: a self-motion when c < 3 · 1e-14,
    else a nonzero constant with no root.
    """
    size = 3.0
    F = np.array([factor * SELF_MOTION_TOL * size, 0.0, 0.0, 0.0, 0.0])
    self_motion, q, _ = DT.trig_roots(F, size)
    assert self_motion == inside
    if inside:
        np.testing.assert_allclose(q, [-math.pi / 2, 0.0, math.pi / 2, math.pi])
    else:
        assert np.isnan(q).all()


# --- arm_point.hpp: the arm's radicands and singular sets ---------------------


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_arm_double_root_tol_is_round_off_of_a_fold(factor: float, inside: bool) -> None:
    """DOUBLE_ROOT_TOL: a fold's signed distance within it of (size + arm scale)
    is round-off, a double root (0 comes back); beyond, sqrt(diff · other).
    """
    size, other, scale = 3.0, 2.0, 1.0
    diff = factor * ARM_DOUBLE_ROOT_TOL * (size + scale)
    root, near = DT.clamped_root(diff, size, other, scale)
    if inside:
        assert root == 0.0 and near
    else:
        assert root == pytest.approx(math.sqrt(diff * other), rel=1e-12)
        assert not near


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_arm_near_tol_keeps_roots_just_past_a_fold(factor: float, inside: bool) -> None:
    """NEAR_TOL: a target past a fold by less than this (relative to the fold's
    size) still gives the mirrored candidates sqrt(|diff| · other) for the check
    to judge, and raises the near flag; farther past, NaN.
    """
    size, other, scale = 3.0, 2.0, 1.0
    diff = -factor * ARM_NEAR_TOL * size
    root, near = DT.clamped_root(diff, size, other, scale)
    if inside:
        assert root == pytest.approx(math.sqrt(-diff * other), rel=1e-12)
        assert near
    else:
        assert math.isnan(root) and not near


@pytest.mark.parametrize(("factor", "inside"), [(0.5, True), (2.0, False)])
def test_arm_singular_tol_frees_q1_on_axis_1(factor: float, inside: bool) -> None:
    """SINGULAR_TOL: a wrist centre within it (times the arm's size) of axis 1 is
    on the singular set: q1 is free (status "singular").
    """
    arm6 = km.load("arm6-dh")
    T = arm6.fk(ARM6_SINGULAR_Q)
    arm = wrist_edges.solver(arm6).params.arm
    scale = _core_testing.decoupled.arm_point_values(arm)["scale"]
    res = arm6.ik(wrist_edges.moved_target(T, np.array([factor * ARM_SINGULAR_TOL * scale, 0, 0])))
    assert (res.status == "singular") == inside
    assert (0 in res.free_joints) == inside


@pytest.mark.parametrize(("factor", "inside"), [(0.5, True), (2.0, False)])
def test_near_set_tol_flags_a_wrist_centre_near_axis_1(factor: float, inside: bool) -> None:
    """NEAR_SET_TOL: a wrist centre within it (times the arm's size) of axis 1,
    yet off the singular set, is flagged near it; solved.
    """
    arm6 = km.load("arm6-dh")
    T = arm6.fk(ARM6_SINGULAR_Q)
    arm = wrist_edges.solver(arm6).params.arm
    scale = _core_testing.decoupled.arm_point_values(arm)["scale"]
    shifted = wrist_edges.moved_target(T, np.array([factor * NEAR_SET_TOL * scale, 0.0, 0.0]))
    assert wrist_edges.near_flags(arm6, shifted[None])[0] == inside
    assert arm6.ik(shifted).status == "ok"


# --- spherical_wrist.hpp --------------------------------------------------------


@pytest.mark.parametrize(("factor", "inside"), [(0.5, True), (2.0, False)])
def test_wrist_singular_tol_is_the_sine_of_q5(factor: float, inside: bool) -> None:
    """WRIST_SINGULAR_TOL: axes 4 and 6 are aligned (q4 + q6 free) when the sine
    of the angle between them, q5 on a PUMA, is below it.
    """
    puma = km.load("puma560")
    q = np.array([0.3, -0.6, 0.2, 0.5, factor * WRIST_SINGULAR_TOL, -0.4])
    res = puma.ik(puma.fk(q), respect_limits=False)
    assert (res.status == "singular") == inside
    assert (res.free_joints == (3, 5)) == inside


# --- arm_position.hpp -----------------------------------------------------------


@pytest.mark.parametrize(
    ("n", "accepted"), [(MAX_POSITION_DOF, True), (MAX_POSITION_DOF + 1, False)]
)
def test_max_position_dof_bounds_the_arm_position_solver(n: int, accepted: bool) -> None:
    """MAX_POSITION_DOF: an arm-position solver serves chains of at most this many
    joints (its free joints are bits of a 32-bit mask); beyond, the builder gives no
    closed form (the numeric method answers).
    """
    rows = [Revolute(d=0.4, alpha=math.pi / 2), Revolute(a=0.45), Revolute(alpha=math.pi / 2)]
    rows += [Revolute(d=0.01 * (i + 1), alpha=0.3) for i in range(n - 3)]
    robot = km.Robot.from_dh(rows, name=f"{n} joints", convention="standard")
    assert (D.build_arm_position(robot.chain.core) is not None) is accepted
    q = np.zeros(n)
    q[:3] = 0.2  # joints 4..n at 0: a target the closed form's own configurations reach
    res = robot.ik(robot.fk(q)[:3, 3], seed=0)
    assert res.method == ("analytic:arm-position" if accepted else "numeric:lm")


# --- ik/analytic/arm_point.py: the closed-form builder's arm geometry ----------


@pytest.mark.parametrize(("factor", "kind"), [(0.5, "parallel"), (2.0, "general")])
def test_axis_angle_tol_parallel_shoulder(factor: float, kind: str) -> None:
    """AXIS_ANGLE_TOL: axes 1 and 2 twisted by less than it (rad) are parallel."""
    assert wrist_parts.shoulder(factor * AXIS_ANGLE_TOL, 0.2) == kind


@pytest.mark.parametrize(("factor", "kind"), [(0.5, "meet"), (2.0, "general")])
def test_axis_length_tol_meeting_shoulder(factor: float, kind: str) -> None:
    """AXIS_LENGTH_TOL: axes 1 and 2 offset by less than it times 1 + the arm's
    size (the sum of its link lengths) meet.
    """
    size = 0.4 + 0.4 + 0.05 + 0.1 + 0.4  # the arm of wrist_parts.shoulder, a1 aside
    a1 = factor * AXIS_LENGTH_TOL * (1.0 + size)
    assert wrist_parts.shoulder(math.pi / 2, a1) == kind


@pytest.mark.parametrize(("factor", "usable"), [(0.5, False), (2.0, True)])
def test_arm_rank_tol_needs_joints_1_to_3_to_place_the_point(factor: float, usable: bool) -> None:
    """PLACE_RANK_TOL: joints 1-3 place the tool point when the best ratio
    σmin/σmax of d(point)/d(q1..q3) over the builder's probes is above it.

    Joint 3 moves the point on a circle of radius eps: the ratio is linear in
    eps, so eps is scaled to put it at ``factor`` · RANK_TOL.
    """
    r1 = wrist_parts.rank_ratio(wrist_parts.arm_with_point_near_axis_3(1e-4))
    robot = wrist_parts.arm_with_point_near_axis_3(1e-4 * factor * ARM_RANK_TOL / r1)
    assert wrist_parts.rank_ratio(robot) == pytest.approx(factor * ARM_RANK_TOL, rel=0.05)
    assert _core_testing.decoupled.places_point(robot.chain.core, np.zeros(3)) == usable


@pytest.mark.parametrize("name", ["puma560", "stanford", "irb120"])
def test_the_core_s_rank_ratio_is_that_of_the_point_s_jacobian_by_differences(name: str) -> None:
    # places_point's ratio (the core's Gram matrix, Jacobi eigenvalues) against the SVD
    # of the tool origin's Jacobian taken by central differences (support/wrist_arms.py)
    robot = km.load(name)
    q = np.zeros((len(DT.PLACE_PROBES), robot.dof))
    q[:, :3] = DT.PLACE_PROBES
    best = float(_core_testing.internals.point_rank_ratios(robot.chain.core, q, np.zeros(3)).max())
    assert best == pytest.approx(wrist_parts.rank_ratio(robot), rel=1e-6)
