"""The spherical-wrist solvers' building blocks, and their tolerances on both sides.

Each named tolerance of the core's decoupled family (``kinematica._core.decoupled``,
``cpp/include/kinematica/solvers/arm_*.hpp``) and of the builder is pinned by a case
just inside and one just outside it; the references are polynomials and geometries
built here with known roots and known rank.
"""

from __future__ import annotations

import math

import kinematica._core as _core
import numpy as np
import pytest
from support.wrist_arms import arm_with_point_near_axis_3, rank_ratio

from kinematica import _core_testing, load
from kinematica.core import Chain
from kinematica.dh import Revolute
from kinematica.ik.analytic import arm_position, spherical_wrist
from kinematica.ik.solve import closed_form
from kinematica.ik.structure import features
from kinematica.robot import Robot

D = _core.decoupled
DT = _core_testing.decoupled
PI = math.pi


# ------------------------------------------------------------- clamped roots
@pytest.mark.parametrize(("factor", "double"), [(0.5, True), (2.0, False)])
def test_double_root_tol(factor: float, double: bool) -> None:
    """A fold's signed distance within DOUBLE_ROOT_TOL of its size is round-off: one root."""
    size = 3.0
    diff = factor * DT.DOUBLE_ROOT_TOL * (size + 1.0)
    root, near = DT.clamped_root(diff, size, 2.0, 1.0)
    assert (root == 0.0) == double
    assert near == double  # a double root is a fold
    if not double:
        assert root == pytest.approx(math.sqrt(diff * 2.0))


@pytest.mark.parametrize(("factor", "candidate"), [(0.5, True), (2.0, False)])
def test_near_tol_keeps_mirrored_roots_just_past_a_fold(factor: float, candidate: bool) -> None:
    size = 3.0
    diff = -factor * DT.NEAR_TOL * size
    root, near = DT.clamped_root(diff, size, 2.0, 1.0)
    assert math.isfinite(root) == candidate
    assert near == candidate
    if candidate:
        assert root == pytest.approx(math.sqrt(-diff * 2.0))


def test_clamped_root_of_another_failed_factor_is_nan() -> None:
    assert math.isnan(DT.clamped_root(1.0, 2.0, -1.0, 1.0)[0])
    assert DT.clamped_root(4.0, 4.0, 4.0, 1.0) == (4.0, False)


# ----------------------------------------------------------------- quartics
def test_trig_roots_are_those_of_the_trigonometric_polynomial() -> None:
    rng = np.random.default_rng(51)
    for _ in range(200):
        F = rng.normal(size=5)
        self_motion, q, _ = DT.trig_roots(F, np.abs(F).sum())
        assert not self_motion
        real = q[~np.isnan(q)]
        grid = np.linspace(-PI, PI, 20001)
        f = F[0] + F[1] * np.cos(grid) + F[2] * np.sin(grid)
        f += F[3] * np.cos(2 * grid) + F[4] * np.sin(2 * grid)
        sign_changes = int(np.sum(np.sign(f[:-1]) != np.sign(f[1:])))
        assert len(real) == sign_changes  # generic: simple roots only
        for x in real:
            val = F[0] + F[1] * math.cos(x) + F[2] * math.sin(x)
            val += F[3] * math.cos(2 * x) + F[4] * math.sin(2 * x)
            assert abs(val) < 1e-12 * np.abs(F).sum()
        assert (np.diff(real) > 0).all() and (np.abs(real) <= PI).all()


@pytest.mark.parametrize(("factor", "self_motion"), [(0.5, True), (2.0, False)])
def test_self_motion_tol(factor: float, self_motion: bool) -> None:
    """F that is 0 to round-off of the terms it came from: every q3 is a root."""
    F = np.array([factor * DT.SELF_MOTION_TOL, 0.0, 0.0, 0.0, 0.0])
    found, q, _ = DT.trig_roots(F, 1.0)
    assert found == self_motion
    if self_motion:
        np.testing.assert_allclose(q, [-PI / 2, 0.0, PI / 2, PI])
    else:
        assert np.isnan(q).all()  # a nonzero constant has no root


@pytest.mark.parametrize(("factor", "real"), [(0.5, True), (2.0, False)])
def test_imag_tol(factor: float, real: bool) -> None:
    """A complex pair this close to the real axis is a double root split by round-off."""
    eps = factor * DT.IMAG_TOL * (1.0 + 0.5)
    k = np.real(np.poly([0.5 + 1j * eps, 0.5 - 1j * eps, -2.0, 3.0]))
    q, near = DT.slide_roots(k)
    found = q[~np.isnan(q)]
    assert len(found) == (4 if real else 2)
    assert near != real  # dropped, yet near the real axis: near a fold
    np.testing.assert_allclose(found[[0, -1]], [-2.0, 3.0], atol=1e-12)


@pytest.mark.parametrize(("factor", "taken"), [(0.5, True), (2.0, False)])
def test_max_newton_step(factor: float, taken: bool) -> None:
    """Newton steps on F longer than MAX_NEWTON_STEP are round-off at a double root."""
    step = factor * DT.MAX_NEWTON_STEP
    assert (DT.bounded_step(step * 3.0, 3.0) == pytest.approx(step)) == taken
    assert (DT.bounded_step(step * 3.0, 3.0) == 0.0) != taken


@pytest.mark.parametrize(("factor", "usable"), [(0.5, False), (2.0, True)])
def test_rank_tol(factor: float, usable: bool) -> None:
    # the ratio is linear in eps: aim it at factor · RANK_TOL
    r1 = rank_ratio(arm_with_point_near_axis_3(1e-4))
    eps = 1e-4 * factor * DT.PLACE_RANK_TOL / r1
    robot = arm_with_point_near_axis_3(eps)
    assert rank_ratio(robot) == pytest.approx(factor * DT.PLACE_RANK_TOL, rel=0.05)
    assert _core_testing.decoupled.places_point(robot.chain.core, np.zeros(3)) == usable


# --- the flip as the no-flip's twin (q4 + π, -q5, q6 + π) -----------------------

#: TWIN_TOL's documented value (cpp/include/kinematica/solvers/spherical_wrist.hpp), as a literal.
TWIN_TOL_VALUE = 1e-13


def puma_with_twisted_wrist(eps: float) -> Robot:
    """The PUMA 560 with α4 off its right angle by ``eps``: ``h4ᵀh5 ≈ eps`` at q = 0."""
    puma = load("puma560")
    rows = list(puma.links)
    r = rows[3]
    rows[3] = Revolute(d=r.d, a=r.a, alpha=r.alpha + eps, offset=r.offset)
    return Robot.from_dh(rows, base=puma.base, tool=puma.tool, convention="standard")


def twin_flag(robot: Robot) -> bool:
    closed = closed_form(robot.chain, "pose")
    assert closed is not None and closed.name == "spherical-wrist"
    return bool(_core_testing.decoupled.wrist_twin(robot.chain.core))


def test_twin_tol_value() -> None:
    assert DT.TWIN_TOL == TWIN_TOL_VALUE


@pytest.mark.parametrize(("factor", "twin"), [(0.1, True), (10.0, False)])
def test_twin_tol_decides_the_flip_by_identity(factor: float, twin: bool) -> None:
    robot = puma_with_twisted_wrist(factor * TWIN_TOL_VALUE)
    assert twin_flag(robot) == twin
    # either way every solution is exact by FK (the identity errs by ~eps)
    rng = np.random.default_rng(3)
    T = robot.fk(rng.uniform(-2.0, 2.0, (50, 6)))
    res = robot.ik(T, respect_limits=False)
    assert np.all(res.count == 8)
    for i in range(len(T)):
        F = robot.fk(res[i].solutions)
        assert np.max(np.abs(F - T[i])) < 1e-12


def test_the_twin_flip_is_the_solved_flip() -> None:
    # The same solver with the identity switched off solves the flip's own
    # angles: both give the same eight candidates (modulo 2π), to round-off.
    for name in ("puma560", "irb120", "kr6", "stanford"):
        robot = load(name)
        closed = closed_form(robot.chain, "pose")
        assert closed is not None and _core_testing.decoupled.wrist_twin(robot.chain.core)
        solved = _core_testing.decoupled.wrist_solved_flip(robot.chain.core)
        rng = np.random.default_rng(5)
        lo = np.where(np.isfinite(robot.qlim[:, 0]), robot.qlim[:, 0], -1.0)
        hi = np.where(np.isfinite(robot.qlim[:, 1]), robot.qlim[:, 1], 1.0)
        for T in robot.fk(rng.uniform(lo, hi, (200, 6))):
            Q1, *info1 = closed.params.candidates(robot.chain.core, T)
            Q2, *info2 = solved.candidates(robot.chain.core, T)
            assert np.array_equal(np.isnan(Q1), np.isnan(Q2))
            d = np.abs(np.remainder(np.nan_to_num(Q1 - Q2) + PI, 2 * PI) - PI)
            assert d.max() < 1e-9, name
            np.testing.assert_array_equal(info1, info2)


# ------------------------------------------------------------- the binding
def test_the_built_arm_is_read_only() -> None:
    """The core's builder alone fills an ArmPoint: the product reads its shape (arm_shape),
    the tests its values (the test extension), and nothing writes it."""
    arm = D.build_spherical_wrist(load("puma560").chain.core).arm
    assert D.arm_shape(arm) == ("meet", False, True)
    values = _core_testing.decoupled.arm_point_values(arm)
    assert (values["kind"], values["prismatic"], values["parallel23"]) == (0, False, True)
    assert values["scale"] > 0.0 and values["r_lo"] <= values["r_hi"]
    with pytest.raises(AttributeError):
        arm.scale = 1.0
    with pytest.raises(TypeError):
        D.ArmPoint()
    with pytest.raises(TypeError):  # the core's builder alone fills a family's Params
        D.SphericalWristParams()
    with pytest.raises(TypeError):
        D.ArmPositionParams()


def test_core_builders_decline_other_structures() -> None:
    """Each family's builder in the core reads the structure itself (a C++ program may
    hand it any chain): a chain of another structure gets None."""
    ur5, puma, iiwa = load("ur5"), load("puma560"), load("iiwa14")
    assert D.build_spherical_wrist(ur5.chain.core) is None  # axes 4-6 do not meet
    assert D.build_spherical_wrist(puma.chain.core) is not None
    assert D.build_spherical_shoulder(ur5.chain.core) is None  # axes 1-3 do not meet
    assert _core.srs.build(puma.chain.core) is None  # 6 joints
    assert _core.srs.build(iiwa.chain.core) is not None
    assert D.build_arm_position(puma.chain.core) is not None
    assert (
        D.build_arm_position(Robot.from_dh([Revolute(a=0.3)] * 3, convention="standard").chain.core)
        is None
    )
    planar = load("planar-3r").chain.core
    assert _core.planar.build(planar) is not None and _core.elbow.build(planar) is None
    elbow = load("anthropomorphic-3r").chain.core
    assert _core.elbow.build(elbow) is not None and _core.planar.build(elbow) is None
    assert _core.planar.build(puma.chain.core) is None and _core.elbow.build(ur5.chain.core) is None
    with pytest.raises(ValueError, match="h must be of size 3 along axis 0"):
        _core_testing.decoupled.arm_geometry(
            np.eye(3)[:2], np.zeros((3, 3)), False, np.ones(3), 1.0
        )
    with pytest.raises(ValueError, match="3 joints or more"):
        _core_testing.decoupled.places_point(
            Robot.from_dh([Revolute(a=0.3)] * 2, convention="standard").chain.core, np.zeros(3)
        )


def test_solvers_take_chains_of_their_size_only() -> None:
    puma = load("puma560")
    closed = closed_form(puma.chain, "pose")
    assert closed is not None
    arm7 = Robot.from_dh([*puma.links, Revolute(d=0.1)], convention="standard")
    with pytest.raises(ValueError, match="takes a chain of 6 joints, got 7"):
        closed.params.candidates(arm7.chain.core, np.eye(4))
    with pytest.raises(ValueError):
        closed.params.candidates(puma.chain.core, np.eye(3))


@pytest.mark.parametrize("degenerate", [False, True])
def test_sample_arms_are_of_the_family(degenerate: bool) -> None:
    rng = np.random.default_rng(61)
    for spec in (*spherical_wrist.SPECS, arm_position.SPEC):
        for _ in range(15):
            s = spec.sample_arm(rng, degenerate)
            eye = np.eye(4)
            chain = Chain.from_dh(
                s.links,
                s.convention,
                eye if s.base is None else s.base,
                eye if s.tool is None else s.tool,
            )
            f = features(chain)
            assert spec.handles(f), (spec.kind, s.note)
            closed = spec.build(chain, f, spec.targets[0])
            assert closed is not None, (spec.kind, s.note)
            assert bool(s.note) == degenerate
