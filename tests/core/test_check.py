"""The core's shared check of IK candidates (``check.hpp``): its tolerances, both sides.

Each test uses literal distances a factor of 5-50 inside and outside the value the
docstring states, so that a constant changed a thousandfold fails a test. Inputs
are built by hand (exact solutions of a planar 2R arm, perturbed on purpose) and
go straight to the core's check, so the solvers play no part. Last, the check's
forward kinematics of candidates that share leading joints (walked once for all
of them) against a walk from the base, to the last bit.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from kinematica._core_testing import internals
from support.parallel_arms import random_arm

import kinematica as km
from kinematica import _core
from kinematica.ik import closed_form

L1 = L2 = 1.0


POSITION = np.array([1.0, 1.0, 1.0, 0.0, 0.0, 0.0])


def two_link(qlim: tuple[float, float] | None = None) -> km.Robot:
    return km.Robot.from_dh(
        [km.Revolute(a=L1), km.Revolute(a=L2, qlim=qlim)], convention="standard"
    )


def target_of(q: list[float]) -> np.ndarray:
    """The pose of the 2R arm at ``q``, by hand: x = c1 + c12, y = s1 + s12."""
    x = L1 * math.cos(q[0]) + L2 * math.cos(q[0] + q[1])
    y = L1 * math.sin(q[0]) + L2 * math.sin(q[0] + q[1])
    T = np.eye(4)
    T[:2, 3] = x, y
    return T


def check(robot: km.Robot, T: np.ndarray, Q: np.ndarray, respect_limits: bool = True):  # type: ignore[no-untyped-def]
    """The core's shared check of hand-made candidates Q (m, n) of a position target."""
    opts = _core.CheckOptions()
    opts.tol = _core.Tolerance(1e-10, 1e-10)
    opts.respect_limits = respect_limits
    opts.complete = True
    opts.weights = POSITION.tolist()
    q, res, _, _, count, out, _ = internals.check(
        robot.chain.core,
        T,
        np.ascontiguousarray(Q, dtype=float),
        opts,
        math.nan,
        False,
        False,
        None,
    )
    return q, res, count, out


@pytest.mark.parametrize(("delta", "count"), [(2e-6, 2), (2e-9, 1)])
def test_dedup_tol_is_1e_7(delta: float, count: int) -> None:
    # Two exact solutions of one target, elbow ±delta apart (nearly stretched):
    # 4e-6 apart they are two solutions, 4e-9 apart one (DEDUP_TOL = 1e-7).
    robot = two_link()
    a, b = [0.3 - delta / 2, delta], [0.3 + delta / 2, -delta]
    T = target_of(a)
    assert np.hypot(*(target_of(b)[:2, 3] - T[:2, 3])) < 1e-15
    _, res, n, _ = check(robot, T, np.array([a, b]))
    assert n == count
    assert np.all(res[:n, 0] <= 1e-10)


@pytest.mark.parametrize(("offset", "solved"), [(1e-7, True), (1e-3, False)])
def test_polish_limit_is_1e_5(offset: float, solved: bool) -> None:
    # A candidate 1e-7 rad off is polished into the solution; 1e-3 off is not a candidate.
    robot = two_link()
    q = [0.4, 1.1]
    T = target_of(q)
    _, res, n, _ = check(robot, T, np.array([[q[0] + offset, q[1] - offset]]))
    assert n == int(solved)
    if solved:
        assert res[0, 0] < 1e-14


@pytest.mark.parametrize(("residual", "polished"), [(2e-11, False), (2e-9, True)])
def test_acceptance_tolerance_is_1e_10(residual: float, polished: bool) -> None:
    # A candidate within 1e-10 m is taken as it is (its residual reported); one
    # beyond it is polished first (its residual drops to round-off).
    robot = two_link()
    q = [0.4, 1.1]
    T = target_of(q)
    # moving q2 by e moves the tool by e * L2 (the second link's length is 1)
    _, res, n, _ = check(robot, T, np.array([[q[0], q[1] + residual]]))
    assert n == 1
    if polished:
        assert res[0, 0] < 1e-14
    else:
        assert res[0, 0] == pytest.approx(residual, rel=1e-3)


@pytest.mark.parametrize(("beyond", "inside"), [(2e-13, True), (2e-11, False)])
def test_limit_tol_is_1e_12(beyond: float, inside: bool) -> None:
    # An exact solution whose q2 is `beyond` past its upper limit: within the
    # 1e-12 slack it counts as inside the limits, beyond it as outside.
    q = [0.4, 1.1]
    robot = two_link(qlim=(-1.0, q[1] - beyond))
    _, _, n_in, n_out = check(robot, target_of(q), np.array([q]))
    assert (n_in, n_out) == ((1, 0) if inside else (0, 1))


def repair_options() -> _core.CheckOptions:
    """The check's options for a nearby arm's candidates (CheckOptions.repair)."""
    opts = _core.CheckOptions()
    opts.tol = _core.Tolerance(1e-10, 1e-10)
    opts.weights = POSITION.tolist()
    opts.gap_slack = 1e-9
    opts.repair = True
    return opts


def test_repair_damping_is_100() -> None:
    # A step of the repair minimises |J dq - e|² + μ |e|² |dq|² (REPAIR_DAMPING μ = 100
    # per rad²): along a singular direction of value σ it is |e| σ / (σ² + μ |e|²),
    # 1 / (2 √μ) = 0.05 rad where σ = √μ |e|. The 2R arm nearly stretched (σmin 4.5e-4),
    # the target moved by σmin / 10 along the direction it cannot follow: the undamped
    # step would be 0.1 rad; μ a thousand times larger makes it 1e-4, smaller 0.0999.
    robot = two_link()
    q = np.array([0.3, 1e-3])
    U, S, _ = np.linalg.svd(robot.jacobian(q)[:3])
    T = target_of(list(q))
    T[:3, 3] += U[:, 1] * S[1] / 10
    assert internals.REPAIR_DAMPING == 100.0
    step = float(
        np.linalg.norm(internals.repair_step(robot.chain.core, T, q, repair_options()) - q)
    )
    assert step == pytest.approx(0.05, rel=1e-6)


def test_repair_damping_floor_is_1e_15() -> None:
    # Where μ |e|² is below REPAIR_DAMPING_FLOOR s (s the normal matrix's mean diagonal,
    # 2.5 here), the step along a singular direction of value σ is |e| σ / (σ² + 1e-15 s).
    # The 2R arm stretched to σmin = 1e-8, the target 1e-10 along the direction it cannot
    # follow: 3.8e-4 rad; a floor a thousand times larger gives 4e-7, smaller 1e-2.
    robot = two_link()
    q = np.array([0.3, 2.2e-8])
    J = robot.jacobian(q)[:3]
    U, S, _ = np.linalg.svd(J)
    T = target_of(list(q))
    T[:3, 3] += U[:, 1] * 1e-10
    s = float(np.trace(J.T @ J)) / 2.0
    assert internals.REPAIR_DAMPING_FLOOR == 1e-15
    step = float(
        np.linalg.norm(internals.repair_step(robot.chain.core, T, q, repair_options()) - q)
    )
    want = 1e-10 * S[1] / (S[1] ** 2 + 1e-15 * s)
    assert step == pytest.approx(want, rel=0.3)


@pytest.mark.parametrize("psi", [1e-5, 1e-6])
def test_the_repair_reaches_a_solution_beside_a_fold(psi: float) -> None:
    # The 2R arm's target with the elbow at ±psi (two solutions 2 psi apart, σmin about
    # psi / 2): from the elbow at 3e-3 the repair's steps halve the distance to the root
    # on their side, to round-off. A constant damping of 1e-12 times the normal matrix's
    # mean diagonal (the polish's) stalls where σmin² falls below it: from psi = 1e-6 it
    # stopped 2.6e-7 rad off (the residual 1.5e-13, within the tolerances).
    robot = two_link()
    q = np.array([0.3, psi])
    T = target_of(list(q))
    out, p_err, _ = internals.repair(robot.chain.core, T, np.array([0.3, 3e-3]), repair_options())
    assert np.abs(out - q).max() <= 1e-8
    assert p_err <= 1e-14  # REPAIR_QUIET x 1e-10


@pytest.mark.filterwarnings("ignore::kinematica.KinematicaWarning")  # rows beyond the limits
def test_candidates_sharing_leading_joints_get_the_residuals_of_their_own_fk() -> None:
    # The PUMA's tool origin is its wrist centre: every wrist (q4, q5, q6) on a
    # placement of joints 1-3 reaches a position target. Rows share 0 to 5 leading
    # joints with the row before them (a +0.0 after a -0.0 shares nothing there); the
    # check walks the shared joints once, and must give each row's residual exactly as
    # FK from the base does.
    robot = km.load("puma560")
    rng = np.random.default_rng(8)
    q = np.array([0.3, -0.7, 0.4, 0.0, 0.0, 0.0])
    T = robot.fk(q)
    other = robot.ik(T[:3, 3], respect_limits=False).solutions  # every placement of joints 1-3
    placements = [q[:3], other[np.argmax(np.abs(other[:, 0] - q[0]))][:3]]
    rows = []
    for k, keep in enumerate([0, 3, 4, 5, 3, 1, 3, 4, 4]):
        row = np.concatenate([placements[k % 3 == 2], rng.uniform(-3.0, 3.0, 3)])
        if rows and keep > 3:
            row[:keep] = rows[-1][:keep]
        rows.append(row)
    rows[7][4], rows[8][4] = -0.0, 0.0  # equal, not the same bits
    Q = np.array(rows)
    opts = _core.CheckOptions()
    opts.respect_limits = False
    opts.complete = True
    opts.weights = POSITION.tolist()
    qs, res, _, _, count, _, _ = internals.check(
        robot.chain.core, T, Q, opts, math.nan, False, False, None
    )
    assert count == len(rows)
    for qi, (p_err, r_err) in zip(qs[:count], res[:count], strict=True):
        dx, dy, dz = (T[:3, 3] - robot.fk(qi)[:3, 3]).tolist()
        assert p_err == math.sqrt(dx * dx + dy * dy + dz * dz)
        assert r_err == 0.0  # rotation not counted


def test_repair_patience_outlasts_steps_that_overshoot_and_land() -> None:
    # REPAIR_PATIENCE (6): a three-parallel arm whose axes 2 and 3 are 5e-10 off parallel,
    # its wrist 1e-6 rad from aligned (σmin 6e-8): the family's candidate nearest the
    # generating q is 3e-3 rad off it. The repair's steps alternately overshoot (the
    # residual up to 8e-7) and land, the best falling every two or three steps: with a
    # patience of 3 it stopped 2.4e-4 rad off (the residual 1.4e-11, within the
    # tolerances); it now reaches round-off, 3e-8 rad off.
    rng = np.random.default_rng(4)
    robot = random_arm(rng, "meet", square=True)
    links = list(robot.links)
    links[1] = dataclasses.replace(links[1], alpha=links[1].alpha + 5e-10)
    robot = km.Robot.from_dh(links, base=robot.base, tool=robot.tool, convention="standard")
    q = np.array([-1.8043360707549974, -2.307837226526689, 0.03810703212573863,
                  1.7912437217382067, 0.09957063778417395, 1.6887427728460738])  # fmt: skip
    T = robot.fk(q)
    assert internals.REPAIR_PATIENCE == 6
    assert np.linalg.svd(robot.jacobian(q), compute_uv=False)[-1] < 1e-7
    raw = np.asarray(closed_form(robot.chain, "pose").params.candidates(robot.chain.core, T)[0])
    raw = raw[np.isfinite(raw).all(axis=1)]
    x = raw[np.argmin(np.abs(np.angle(np.exp(1j * (raw - q)))).max(axis=1))]
    assert 1e-3 < np.abs(np.angle(np.exp(1j * (x - q)))).max() < 1e-2
    opts = repair_options()
    opts.weights = [1.0] * 6
    out, p_err, r_err = internals.repair(robot.chain.core, T, x, opts)
    assert max(p_err, r_err) <= 1e-14
    assert np.abs(np.angle(np.exp(1j * (out - q)))).max() <= 1e-7
