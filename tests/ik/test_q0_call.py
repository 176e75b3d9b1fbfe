"""``robot.ik(T, q0=q)`` of one pose: ``q0`` beside the kept request, one core call.

A call giving ``q0`` as a float64 vector, and no other setting but ``method``, ``tol``,
``respect_limits`` (and ``fixed`` of one joint), is read into a
:class:`~kinematica.ik.request.Q0Call` or a :class:`~kinematica.ik.request.HeldCall`; the
plan's prepared call sorts the solutions nearest ``q0`` in the core
(``Prepared.__call__``/``Prepared.at`` with ``q0``), where ``q0`` is within the joints'
own limits and a turn (else ``robot.ik`` warns and the general path solves). Its
answers are held here against the general path, which a ``q0`` given as a list takes (a
new request, parsed targets, ``solver.ik``), field by field and bit for bit; and bad
``q0`` values against the same errors and warnings.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import kinematica as km
from kinematica.dh import Revolute
from kinematica.errors import DimensionError, LimitWarning, UnitWarning
from kinematica.ik import IKOptions, IKResult
from kinematica.ik.request import HeldCall, IKRequest, Q0Call

FIELDS = ("status", "count", "method", "branches", "out_of_limits_branches", "free_joints",
          "notes", "parameter", "complete", "gap", "near_singular")  # fmt: skip


def _same(a: IKResult, b: IKResult) -> None:
    for field in FIELDS:
        assert getattr(a, field) == getattr(b, field), field
    np.testing.assert_array_equal(a.solutions, b.solutions)
    np.testing.assert_array_equal(a.out_of_limits, b.out_of_limits)
    np.testing.assert_array_equal(a.residuals, b.residuals)


def _cases(robot: km.Robot, n: int, seed: int) -> list[tuple[np.ndarray, np.ndarray]]:
    """Poses of random configurations, q0 a configuration nearby (a fifth out of reach)."""
    rng = np.random.default_rng(seed)
    Q = robot.random_q(n, seed=seed)
    T = np.ascontiguousarray(robot.fk(Q))
    T[::5, :3, 3] *= 4.0  # beyond the reach: answered by the search from q0 or proved out
    lo, hi = robot.chain.qlim[:, 0], robot.chain.qlim[:, 1]
    q0 = np.clip(Q + rng.normal(scale=0.3, size=Q.shape), lo, hi)
    return list(zip(T, q0, strict=True))


@pytest.mark.parametrize("name", ["puma560", "ur5", "kr6", "stanford"])
def test_q0_alone_is_the_plans_one_call_with_the_general_paths_answer(name: str) -> None:
    robot = km.load(name)
    assert type(IKRequest.parse(q0=np.zeros(robot.dof))) is Q0Call
    for T, q0 in _cases(robot, 30, 3):
        lean = robot.ik(T, q0=q0)
        _same(lean, robot.ik(T, q0=q0.tolist()))  # a list: the general path
        if lean.count > 1:  # nearest q0 first (revolute joints' differences wrapped)
            d = lean.solutions - q0
            d = np.where(robot.chain.prismatic, d, (d + np.pi) % (2 * np.pi) - np.pi)
            assert np.all(np.diff(np.linalg.norm(d, axis=1)) >= -1e-12)
        listed = q0.tolist()
        free = robot.ik(T, q0=q0, respect_limits=False)
        _same(free, robot.ik(T, q0=listed, respect_limits=False))
        _same(robot.ik(T, options=IKOptions(q0=q0, tol=1e-9)), robot.ik(T, q0=listed, tol=1e-9))


@pytest.mark.parametrize(("name", "k"), [("panda", 6), ("iiwa14", 0), ("iiwa14", 6)])
def test_q0_with_a_held_end_joint_is_one_core_call_with_the_general_paths_answer(
    name: str, k: int
) -> None:
    robot = km.load(name)
    assert type(IKRequest.parse(q0=np.zeros(7), fixed={k: 0.3})) is HeldCall
    for T, q0 in _cases(robot, 20, 4):
        v = float(q0[k])
        lean = robot.ik(T, fixed={k: v}, q0=q0)
        _same(lean, robot.ik(T, fixed={k: v}, q0=q0.tolist()))
        _same(
            robot.ik(T, options=IKOptions(fixed={k: v}, q0=q0)),
            robot.ik(T, fixed={k: v}, q0=q0.tolist()),
        )


@pytest.mark.parametrize("name", ["puma560", "panda"])
def test_a_bad_q0_gets_the_general_paths_error(name: str) -> None:
    robot = km.load(name)
    n = robot.dof
    T = robot.fk(robot.random_q(1, seed=1)[0])
    fixed = {n - 1: 0.1} if n == 7 else None
    with pytest.raises(DimensionError, match="q0 holds NaN or inf"):
        robot.ik(T, q0=np.full(n, np.nan), fixed=fixed)
    with pytest.raises(DimensionError, match="q0 holds NaN or inf"):
        robot.ik(T, q0=np.r_[np.inf, np.zeros(n - 1)], fixed=fixed)
    with pytest.raises(DimensionError, match=f"q0 must hold {n} joint values"):
        robot.ik(T, q0=np.zeros(n + 1), fixed=fixed)


def test_q0_outside_its_limits_or_beyond_a_turn_warns_as_before() -> None:
    puma = km.load("puma560")
    T = puma.fk(np.full(6, 0.2))
    outside = np.full(6, 0.2)
    outside[1] = puma.chain.qlim[1, 1] + 0.5
    with pytest.warns(LimitWarning, match="q0") as caught:
        warned = puma.ik(T, q0=outside)
    assert len(caught) == 1  # once: the core's call declines such a q0, the check warns
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", LimitWarning)
        _same(warned, puma.ik(T, q0=outside.tolist()))
    plan = puma.chain.memo[IKRequest.parse().lean]
    assert plan.prepared(T, outside) is None
    assert plan.prepared(T, np.full(6, 0.2)).__class__ is IKResult
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # within its limits: no warning
        puma.ik(T, q0=np.full(6, 0.2))
    free = km.Robot.from_dh([Revolute(a=1.0), Revolute(a=1.0)], convention="standard")
    with pytest.warns(UnitWarning, match="q0: joint 2"):
        free.ik(free.fk([0.1, 0.2])[:3, 3], q0=np.array([0.1, 200.0]))
