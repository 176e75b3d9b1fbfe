"""Task measures: singular values against hand formulas and finite differences of
the slides' DH product; generic rank; reach within limits; total length."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from support.helpers import PROPERTY, RobotSpec, random_q, robot_specs, seeds

import kinematica as km
from kinematica.design import Task, generic_rank, measure_task, task_singular_values, total_length
from kinematica.design.measures import RANK_TOL
from kinematica.errors import KinematicaError

L1, L2 = 0.5, 0.3


def planar_2r(l1: float = L1, l2: float = L2, qlim: tuple[float, float] | None = None) -> km.Robot:
    return km.Robot.from_dh(
        [km.Revolute(a=l1, qlim=qlim), km.Revolute(a=l2)], convention="standard"
    )


def svals_2r(l1: float, l2: float, q2: float) -> tuple[float, float]:
    """By hand: in link 2's frame J = [[l1 s2, 0], [l1 c2 + l2, l2]], so
    σ1² + σ2² = tr(JᵀJ) = l1² + 2 l1 l2 c2 + 2 l2² and σ1 σ2 = |det J| = l1 l2 |s2|."""
    t = l1**2 + 2 * l1 * l2 * math.cos(q2) + 2 * l2**2
    d = (l1 * l2 * math.sin(q2)) ** 2
    root = math.sqrt(max(t * t - 4 * d, 0.0))
    return math.sqrt((t + root) / 2), math.sqrt(max((t - root) / 2, 0.0))


@pytest.mark.parametrize("q2", [0.3, 1.2, math.pi / 2, 2.5, -2.0])
def test_planar_2r_singular_values_by_hand(q2: float) -> None:
    s = task_singular_values(planar_2r(), [0.7, q2])
    assert s.shape == (2,)
    np.testing.assert_allclose(s, svals_2r(L1, L2, q2), rtol=1e-12)
    assert math.isclose(s.prod(), L1 * L2 * abs(math.sin(q2)), rel_tol=1e-12)


@pytest.mark.parametrize("batch", [(), (1,), (3, 2)])
def test_batch_shapes(batch: tuple[int, ...]) -> None:
    rng = np.random.default_rng(1)
    q = rng.uniform(-3, 3, (*batch, 2))
    s = task_singular_values(planar_2r(), q)
    assert s.shape == (*batch, 2)
    expected = np.vectorize(lambda q2: L1 * L2 * abs(math.sin(q2)))(q[..., 1])
    np.testing.assert_allclose(s.prod(axis=-1), expected, rtol=1e-12)
    puma = km.load("puma560")
    assert task_singular_values(puma, np.zeros((*batch, 6)), "pose").shape == (*batch, 6)
    assert task_singular_values(puma, np.zeros((*batch, 6)), "position").shape == (*batch, 3)


def test_rows_must_be_position_or_pose() -> None:
    with pytest.raises(KinematicaError, match="rows must be 'position' or 'pose'"):
        task_singular_values(planar_2r(), [0, 1], "orientation")  # type: ignore[arg-type]


def _fd_jacobian(spec: RobotSpec, q: np.ndarray, h: float = 1e-6) -> np.ndarray:
    """Central differences of the slides' DH product: linear rows d p / dq, angular
    rows vee(dR/dq · Rᵀ). Shares no code with kinematica's Jacobian or FK."""
    R0 = spec.ref_fk(q)[:3, :3]
    J = np.zeros((6, spec.dof))
    for j in range(spec.dof):
        dq = np.zeros(spec.dof)
        dq[j] = h
        Tp, Tm = spec.ref_fk(q + dq), spec.ref_fk(q - dq)
        J[:3, j] = (Tp[:3, 3] - Tm[:3, 3]) / (2 * h)
        W = (Tp[:3, :3] - Tm[:3, :3]) / (2 * h) @ R0.T
        J[3:, j] = [W[2, 1], W[0, 2], W[1, 0]]
    return J


@given(spec=robot_specs(max_dof=7), seed=seeds)
@PROPERTY
def test_singular_values_match_finite_differences_on_random_robots(
    spec: RobotSpec, seed: int
) -> None:
    robot = spec.build()
    q = random_q(spec, np.random.default_rng(seed))
    J = _fd_jacobian(spec, q)
    for rows, Jr in (("position", J[:3]), ("pose", J)):
        r = generic_rank(robot, rows)  # type: ignore[arg-type]
        fd = np.linalg.svd(Jr, compute_uv=False)
        ours = task_singular_values(robot, q, rows)  # type: ignore[arg-type]
        assert ours.shape == (r,)
        np.testing.assert_allclose(ours, fd[:r], atol=1e-6)
        # the rank is generic: the arm does not move in the other directions at all
        np.testing.assert_allclose(fd[r:], 0.0, atol=1e-6)


def test_planar_arms_rank_is_that_of_their_plane() -> None:
    planar3 = km.load("planar-3r")
    assert generic_rank(planar3, "position") == 2
    assert generic_rank(planar3, "pose") == 3
    assert generic_rank(km.load("scara"), "pose") == 4
    assert generic_rank(km.load("puma560"), "pose") == 6
    # a planar 3R's position manipulability is that of its in-plane 2x3 Jacobian
    q = np.array([0.2, 0.9, -0.4])
    J = planar3.jacobian(q)[:2]
    s = task_singular_values(planar3, q)
    assert math.isclose(s.prod(), math.sqrt(np.linalg.det(J @ J.T)), rel_tol=1e-12)


def test_rank_tolerance_on_both_sides() -> None:
    def twisted(eps: float) -> km.Robot:
        # a planar 3R whose second axis is tilted by eps: it moves out of its plane by ~eps
        return km.Robot.from_dh(
            [km.Revolute(a=0.5), km.Revolute(a=0.4, alpha=eps), km.Revolute(a=0.3)],
            convention="standard",
        )

    # largest σ3/σ1 over the sampled configurations: ~4e-7 and ~4e-11
    assert RANK_TOL == 1e-9
    assert generic_rank(twisted(1e-6)) == 3  # rank 2 if RANK_TOL were 1000x larger
    assert generic_rank(twisted(1e-10)) == 2  # rank 3 if RANK_TOL were 1000x smaller


def test_total_length_of_the_seed_arm() -> None:
    # l1 + l2 + l3 + l4 = 0.5 + 0.4 + 0.4 + 0.1, tool 0.05 along z
    robot = km.load("arm6-dh").with_tool(km.transl(0, 0, 0.05))
    assert math.isclose(total_length(robot), 1.45, rel_tol=1e-15)
    # a prismatic joint counts its constant offset, not its stroke
    pr = km.Robot.from_dh(
        [km.Prismatic(a=0.2, offset=0.1), km.Revolute(a=-0.3, d=0.05)], convention="standard"
    )
    assert math.isclose(total_length(pr), 0.2 + 0.1 + 0.3 + 0.05, rel_tol=1e-15)


def test_ring_measures_by_hand() -> None:
    # targets on a ring of radius r: cos q2 = (r² - l1² - l2²) / (2 l1 l2) for every target
    r = 0.6
    task = Task.ring(r, 9)
    found = measure_task(planar_2r(), task)
    c2 = (r * r - L1 * L1 - L2 * L2) / (2 * L1 * L2)
    s1, s2 = svals_2r(L1, L2, math.acos(c2))
    assert found.reached.all() and found.rank == 2
    np.testing.assert_allclose(found.manipulability, L1 * L2 * math.sqrt(1 - c2 * c2), rtol=1e-9)
    np.testing.assert_allclose(found.condition, s1 / s2, rtol=1e-9)
    np.testing.assert_allclose(found.clearance, s2, rtol=1e-9)
    assert found.violation == 0.0
    summary = found.summary()
    assert summary["reached"] == 1.0
    w = L1 * L2 * math.sqrt(1 - c2 * c2)
    assert math.isclose(summary["min_manipulability"], w, rel_tol=1e-9)


def test_unreached_targets_make_the_violation() -> None:
    # 0.9 > l1 + l2 = 0.8: two of the four targets are 0.1 m outside the reach
    task = Task.from_positions([[0.6, 0, 0], [0, 0.9, 0], [-0.9, 0, 0], [0, -0.6, 0]])
    found = measure_task(planar_2r(), task)
    np.testing.assert_array_equal(found.reached, [True, False, False, True])
    assert np.isnan(found.manipulability[1]) and np.isnan(found.condition[2])
    assert found.gap[0] == 0.0
    np.testing.assert_allclose(found.gap[1:3], 0.1, rtol=1e-9)
    assert math.isclose(found.violation, 0.5 + 0.05, rel_tol=1e-9)
    assert found.summary()["reached"] == 0.5
    far = measure_task(planar_2r(), Task.from_positions([[2.0, 0, 0]]))
    assert math.isnan(far.summary()["min_manipulability"])


def test_reach_is_within_the_joint_limits() -> None:
    # q1 in [-0.5, 0.5]: target at angle phi has q1 = phi ∓ beta, beta = atan2(l2 s2, l1 + l2 c2)
    r = 0.6
    limits = (-0.5, 0.5)
    phis = np.linspace(-math.pi, math.pi, 24, endpoint=False)
    task = Task.from_positions(np.c_[r * np.cos(phis), r * np.sin(phis), 0 * phis])
    found = measure_task(planar_2r(qlim=limits), task)
    c2 = (r * r - L1 * L1 - L2 * L2) / (2 * L1 * L2)
    beta = math.atan2(L2 * math.sqrt(1 - c2 * c2), L1 + L2 * c2)
    by_hand = (np.abs(phis - beta) <= 0.5) | (np.abs(phis + beta) <= 0.5)
    assert 0 < by_hand.sum() < len(phis)
    np.testing.assert_array_equal(found.reached, by_hand)


def test_best_branch_is_taken_per_target() -> None:
    # PUMA 560 poses: its IK branches have different |det J|; the target's value is the best
    puma = km.load("puma560").with_limits([None] * 6)  # all eight branches
    q = np.array([[0.2, -0.5, 0.3, 0.4, 0.8, -0.1], [1.0, 0.3, -0.8, -0.5, 1.2, 0.4]])
    T = puma.fk(q)
    found = measure_task(puma, Task.from_poses(T))
    for i in range(2):
        sols = puma.ik(T[i]).solutions
        dets = np.abs(np.linalg.det(puma.jacobian(sols)))
        assert len(sols) == 8 and dets.max() > 1.1 * dets.min()  # the branches differ
        assert math.isclose(found.manipulability[i], dets.max(), rel_tol=1e-9)
        conds = np.linalg.cond(puma.jacobian(sols))
        assert math.isclose(found.condition[i], conds.min(), rel_tol=1e-9)


@given(
    l1=st.floats(0.05, 1.0),
    l2=st.sampled_from([None, 1e-10]) | st.floats(0.05, 1.0),
    where=st.sampled_from(["inside", "stretched", "folded", "outside", "inner hole"]),
    t=st.floats(0.01, 0.99),
    convention=st.sampled_from(["standard", "modified"]),
)
@PROPERTY
def test_random_2r_designs_on_rings_by_hand(
    l1: float, l2: float | None, where: str, t: float, convention: str
) -> None:
    # l2 None: equal links; 1e-10: l2 = l1 + 1e-10 (degenerate, nearly equal)
    l2 = l1 if l2 is None else (l1 + l2 if l2 == 1e-10 else l2)
    lo, hi = abs(l1 - l2), l1 + l2
    r = {
        "inside": lo + max(t * (hi - lo), 1e-6),
        "stretched": hi,
        "folded": max(lo, 1e-6),
        "outside": hi * (1.01 + t),
        "inner hole": lo * t,
    }[where]
    robot = planar_2r(l1, l2).to_convention(convention)
    if where == "inner hole" and r < 1e-6:
        return  # targets at the base itself: not a ring
    found = measure_task(robot, Task.ring(r, 5))
    reachable = lo - 1e-12 <= r <= hi + 1e-12
    assert bool(found.reached.all()) == reachable and bool(found.reached.any()) == reachable
    if not reachable:
        assert found.violation >= 1.0
        return
    c2 = np.clip((r * r - l1 * l1 - l2 * l2) / (2 * l1 * l2), -1.0, 1.0)
    w = l1 * l2 * math.sqrt(1.0 - c2 * c2)
    # at the boundary the arm is singular: w = 0 up to the IK's 1e-10 m tolerance
    np.testing.assert_allclose(found.manipulability, w, rtol=1e-6, atol=1e-4 * l1 * l2)
    assert found.violation == 0.0


@pytest.mark.parametrize("count", [1, 2, 3, 4])
def test_a_task_of_any_number_of_positions(count: int) -> None:
    # three positions are a (3, 3) array, which robot.ik would read as a rotation:
    # the task of exactly three is measured as the others are, target by target
    r = 0.6
    task = Task.ring(r, count)
    found = measure_task(planar_2r(), task)
    c2 = (r * r - L1 * L1 - L2 * L2) / (2 * L1 * L2)
    assert found.reached.shape == (count,) and found.reached.all()
    np.testing.assert_allclose(found.manipulability, L1 * L2 * math.sqrt(1 - c2 * c2), rtol=1e-9)
    far = measure_task(planar_2r(), Task.from_positions([[0.6, 0, 0], [0, 0.9, 0], [1.0, 0, 0]]))
    np.testing.assert_array_equal(far.reached, [True, False, False])
    np.testing.assert_allclose(far.gap, [0.0, 0.1, 0.2], rtol=1e-9, atol=0.0)
