"""The core's shared check of IK candidates (``check.hpp``): its tolerances, both sides.

Each test uses literal distances a factor of 5-50 inside and outside the value the
docstring states, so that a constant changed a thousandfold fails a test. Inputs
are built by hand (exact solutions of a planar 2R arm, perturbed on purpose) and
go straight to the core's check, so the solvers play no part. Last, the check's
forward kinematics of candidates that share leading joints (walked once for all
of them) against a walk from the base, to the last bit.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from kinematica._core import internals

import kinematica as km
from kinematica import _core

L1 = L2 = 1.0


POSITION = np.array([1.0, 1.0, 1.0, 0.0, 0.0, 0.0])


def two_link(qlim: tuple[float, float] | None = None) -> km.Robot:
    return km.Robot.from_dh([km.Revolute(a=L1), km.Revolute(a=L2, qlim=qlim)])


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
    opts.tol_position = opts.tol_rotation = 1e-10
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
