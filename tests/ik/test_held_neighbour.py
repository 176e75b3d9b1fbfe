"""A 7R arm held where the arm left is nearly a continuum: the neighbours' sweeps.

rtb-data's iiwa 14 URDF (its shoulder 0.44 mm off an SRS arm's) held at q4 near 0, and
there at 0 (axes 3 and 5 parallel 0.44 mm apart), and the Realman RM75 held at q4 = 0
(axes 3 and 5 parallel 0.77 µm apart). Each answer is checked against what does not
come from the sweeps: every row's forward kinematics (the robot's own FK) meets the
target to 1e-10, the held joint is at its value, the configuration that made the pose
is among the rows, the answer is never a plain complete ``ok`` (``near_singular``,
``complete`` False) and never the numeric search's; on one pose every solution an
independent multi-start search finds is among the rows. The neighbours' bounds are
checked at their boundaries on arms made for them.
"""

from __future__ import annotations

import math
from pathlib import Path

import kinematica._core as _core
import numpy as np
import pytest

import kinematica as km
from kinematica.ik.held_coaxial import NEAR_COAXIAL_TOL, PARALLEL_TOL, near_coaxial_pair
from kinematica.ik.held_neighbour import NEIGHBOUR_TOL, srs_neighbour
from kinematica.ik.structure import features
from kinematica.ik.tolerance import Tolerance

pytestmark = pytest.mark.filterwarnings("ignore::kinematica.KinematicaWarning")

DATA = Path(__file__).parent.parent / "data"
PI = math.pi
#: Rows reach their target to this (m, rad).
FK_TOL = 1e-10


def _iiwa() -> km.Robot:
    return km.load(str(DATA / "urdf" / "kuka_lbr_iiwa_14_r820.urdf"))


def _rm75() -> km.Robot:
    return km.load(str(DATA / "makers" / "realman_rm75.urdf"))


def _wrapped(d: np.ndarray) -> np.ndarray:
    return np.abs(np.remainder(d + PI, 2 * PI) - PI)


def _held(robot: km.Robot, q: np.ndarray, method: str) -> np.ndarray:
    """The rows of ``robot.ik`` with q4 held at q's value, checked; returns them."""
    T = robot.fk(q)
    res = robot.ik(T, fixed={3: float(q[3])}, respect_limits=False)
    assert res.method == method, res.message
    assert res.near_singular and not res.complete  # never a plain complete "ok"
    assert "nearly a continuum" in res.message
    rows = np.concatenate([res.solutions, res.out_of_limits])
    assert len(rows) >= 1
    assert np.all(rows[:, 3] == q[3])
    F = robot.fk(rows)
    assert np.linalg.norm(F[:, :3, 3] - T[:3, 3], axis=1).max() <= FK_TOL
    assert max(float(km.rotation_angle(f[:3, :3], T[:3, :3])) for f in F) <= FK_TOL
    assert (
        _wrapped(rows[:, None] - rows[None])
        .max(axis=2)[np.triu_indices(len(rows), 1)]
        .min(initial=PI)
        > 1e-6
    )  # distinct
    return rows


@pytest.mark.parametrize("elbow", [0.06, 0.04, 0.005, -0.03])
def test_the_iiwa_urdf_held_near_its_stretched_elbow(elbow: float) -> None:
    """Values where the arm left has no closed form (at 0.02 and -0.07 the general 6R's)."""
    robot = _iiwa()
    rng = np.random.default_rng(round(1000 * abs(elbow)) + 7)
    q = rng.uniform(robot.qlim[:, 0], robot.qlim[:, 1])
    q[3] = elbow
    rows = _held(robot, q, "sweep:srs-neighbour")
    # σ6/σ1 ≈ 1e-9 there: the rows are determined to about 1e-16 / 1e-9 rad
    assert _wrapped(rows - q).max(axis=1).min() <= 1e-6
    assert len(rows) == 8


def test_a_crossing_where_the_shoulder_swings_is_found() -> None:
    """q2 near 0: the self-motion swings q1 and q3 between two samples (refined there)."""
    robot = _iiwa()
    q = np.array([-2.204, -0.003, 0.602, 0.05, -2.089, 1.794, -2.624])
    rows = _held(robot, q, "sweep:srs-neighbour")
    assert _wrapped(rows - q).max(axis=1).min() <= 1e-6


def test_a_branch_touching_the_value_between_samples_is_found() -> None:
    """The RM75 at q4 = 1.5502: a branch comes within 7e-10 of it between two samples."""
    robot = _rm75()
    q = np.array([-0.217, 1.7283, 1.6211, 1.5502, 1.6218, 0.9281, 4.3921])
    rows = _held(robot, q, "sweep:srs-neighbour")
    assert _wrapped(rows - q).max(axis=1).min() <= 1e-6


def test_every_solution_a_multi_start_search_finds_is_among_the_rows() -> None:
    robot = _iiwa()
    q = np.random.default_rng(3).uniform(robot.qlim[:, 0], robot.qlim[:, 1])
    q[3] = 0.05
    rows = _held(robot, q, "sweep:srs-neighbour")
    T = robot.fk(q)
    rng = np.random.default_rng(4)
    held = robot.chain.locked(3, 0.05)
    found = 0
    for _ in range(12):
        start = rng.uniform(-2.9, 2.9, 7)
        start[3] = 0.05
        one = robot.ik(T, fixed={3: 0.05}, method="numeric", q0=start, respect_limits=False)
        for s in one.solutions:
            found += 1
            i = int(np.argmin(_wrapped(rows - s).max(axis=1)))
            # the search stops within the tolerance: along the weak direction that is up
            # to the tolerance over σ6 (the held arm's smallest singular value there)
            sigma = np.linalg.svd(held.jacobian(np.delete(rows[i], 3))[0], compute_uv=False)
            assert _wrapped(rows[i] - s).max() <= 10 * FK_TOL / sigma[-1]
    assert found >= 6  # the search itself found solutions to compare


def test_the_iiwa_urdf_held_where_axes_3_and_5_are_parallel() -> None:
    robot = _iiwa()
    q = np.random.default_rng(5).uniform(robot.qlim[:, 0], robot.qlim[:, 1])
    q[3] = 0.0
    rows = _held(robot, q, "sweep:coaxial-neighbour")
    # σ6/σ1 ≈ 2e-11 at the solutions: determined to about 1e-16 / 2e-11 rad
    assert _wrapped(rows - q).max(axis=1).min() <= 1e-5


def test_the_rm75_held_where_axes_3_and_5_are_0_77_micrometres_apart() -> None:
    robot = _rm75()
    for seed in (0, 2):
        q = np.random.default_rng(seed).uniform(robot.qlim[:, 0], robot.qlim[:, 1])
        q[3] = 0.0
        rows = _held(robot, q, "sweep:coaxial-neighbour")
        # each row exact (above), but each circle's points meet 1e-10 over a span: the
        # configuration that made the pose is on a row's circle (q3 + q5 and the other
        # joints to round-off over σ6) and near the row along it (1.8e-6 and 2.3e-5 here)
        d = _wrapped(rows - q)
        i = int(np.argmin(d.max(axis=1)))
        assert d[i].max() <= 1e-4
        assert abs(float(_wrapped((rows[i, 2] + rows[i, 4]) - (q[2] + q[4])))) <= 1e-6


# ------------------------------------------------------------------ the bounds
def _srs(offset: float) -> km.Robot:
    """The iiwa's DH rows with joint 1 moved ``offset`` (m) off axis 2."""
    return km.Robot.from_dh(
        [
            km.Revolute(d=0.36, a=offset, alpha=-PI / 2),
            km.Revolute(alpha=PI / 2),
            km.Revolute(d=0.42, alpha=PI / 2),
            km.Revolute(alpha=-PI / 2),
            km.Revolute(d=0.4, alpha=-PI / 2),
            km.Revolute(alpha=PI / 2),
            km.Revolute(d=0.126),
        ],
        convention="standard",
    )


def _shift(robot: km.Robot) -> float:
    """How far the SRS neighbour moves the arm's axes (m): its axes' points compared."""
    found = srs_neighbour(robot.chain)
    assert found is not None
    a, b = features(robot.chain), features(found[0])
    return float(np.linalg.norm(np.cross(a.directions, b.points - a.points), axis=1).max())


def test_the_srs_neighbour_stands_in_within_its_bound() -> None:
    assert srs_neighbour(_srs(0.0).chain) is None  # SRS itself: its own closed form
    size = features(_srs(0.0).chain).size
    per_metre = _shift(_srs(1e-6)) / 1e-6  # the axes move in proportion to the offset
    inside = _srs(0.5 * NEIGHBOUR_TOL * (1.0 + size) / per_metre)
    outside = _srs(2.0 * NEIGHBOUR_TOL * (1.0 + size) / per_metre)
    assert srs_neighbour(inside.chain) is not None
    assert srs_neighbour(outside.chain) is None


def _pair(distance: float, twist: float = 0.0) -> km.Robot:
    """A 6R arm whose axes 3 and 4 are parallel (``twist`` off) ``distance`` (m) apart."""
    return km.Robot.from_dh(
        [
            km.Revolute(d=0.3, alpha=PI / 2),
            km.Revolute(a=0.4, alpha=0.3),
            km.Revolute(d=0.1, a=distance, alpha=twist),
            km.Revolute(d=0.2, a=0.05, alpha=PI / 2),
            km.Revolute(d=0.25, alpha=-PI / 2),
            km.Revolute(d=0.1),
        ],
        convention="standard",
    )


def test_a_pair_is_nearly_coaxial_within_its_bounds() -> None:
    size = features(_pair(0.0).chain).size
    near = NEAR_COAXIAL_TOL * (1.0 + size)
    found = near_coaxial_pair(_pair(0.5 * near).chain)
    assert found is not None and found[0].first == 2
    assert near_coaxial_pair(_pair(2.0 * near).chain) is None
    assert near_coaxial_pair(_pair(0.0).chain) is None  # one line: kinematica.ik.coaxial's
    assert near_coaxial_pair(_pair(1e-4, 0.5 * PARALLEL_TOL).chain) is not None
    assert near_coaxial_pair(_pair(1e-4, 2.0 * PARALLEL_TOL).chain) is None


# ------------------------------------------------------------ the core's repair
def test_the_core_s_repair_takes_a_nearby_row_to_the_solution() -> None:
    from kinematica.ik.held_sweep import repaired
    from kinematica.ik.solvers import POSE_WEIGHTS, check_options

    robot = km.load("puma560")
    q = np.array([0.3, -0.5, 0.4, 0.2, 0.6, -0.1])
    T = robot.fk(q)
    rows = np.stack([q + 1e-4, q + 2.0, np.full(6, np.nan)])
    out, ok = repaired(robot.chain, T, rows, Tolerance())
    assert ok.tolist() == [True, False, False]
    assert np.abs(out[0] - q).max() <= 1e-12  # back to the configuration (regular there)
    assert np.isnan(out[2]).all()
    with pytest.raises((ValueError, TypeError)):  # a row of the wrong length: refused
        opts = check_options(Tolerance(), False, False, POSE_WEIGHTS)
        _core.repair_candidates(robot.chain.core, np.stack([T]), np.zeros((1, 5)), opts)
