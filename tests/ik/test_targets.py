"""Targets as the IK reads them (``ik/targets.py``): acceptance and projection.

Each tolerance is tested inside and outside its documented value, written here as
a literal: a test that read the constant would move with it.
"""

from __future__ import annotations

import numpy as np
import pytest

import kinematica as km
from kinematica.ik.targets import QUIET_PROJECTION
from kinematica.spatial.checks import orthonormality_error

# The documented values (m, rad, or a sine/cosine), one per constant.
POSITION_TOL = 1e-10  # ik/targets.py


ROTATION_TOL = 1e-10  # ik/targets.py


#: A case a factor 10 inside a tolerance, and one a factor 10 outside it.
FACTORS = [(0.1, True), (10.0, False)]


Q_2R = [0.4, 1.1]


def two_link() -> km.Robot:
    return km.Robot.from_dh([km.Revolute(a=1.0), km.Revolute(a=1.0)], convention="standard")


def pose(R: np.ndarray) -> np.ndarray:
    T = np.eye(4)
    T[:3, :3] = R
    return T


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_position_tol_is_the_default_position_acceptance(factor: float, inside: bool) -> None:
    """POSITION_TOL: a solution must put the tool within it of the target (m).

    A planar 2R arm cannot move its tool out of its plane: a target lifted by
    ``e`` along z is missed by exactly ``e`` by its closest configuration. Below
    the default tolerance that configuration is a solution, above it is not.
    """
    robot = two_link()
    T = robot.fk(Q_2R).copy()
    e = factor * POSITION_TOL
    T[2, 3] += e
    res = robot.ik(T)
    if inside:
        assert res.success
        assert res.residuals[:, 0] == pytest.approx(e, rel=1e-3)
    else:
        assert not res.success and len(res.solutions) == 0


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_rotation_tol_is_the_default_rotation_acceptance(factor: float, inside: bool) -> None:
    """ROTATION_TOL: a solution must orient the tool within it of the target (rad).

    A planar 2R arm only turns its tool about z: a target tilted by ``e`` about
    the tool's x axis is missed by exactly the angle ``e``.
    """
    robot = two_link()
    e = factor * ROTATION_TOL
    T = robot.fk(Q_2R) @ pose(km.rotx(e))
    res = robot.ik(T)
    if inside:
        assert res.success
        assert res.residuals[:, 1] == pytest.approx(e, rel=1e-3)
    else:
        assert not res.success and len(res.solutions) == 0


@pytest.mark.parametrize(("error", "accepted"), [(1.5e-4, True), (3e-4, False)])
def test_projection_tol_is_2e_4(error: float, accepted: bool) -> None:
    # A target rotation orthonormal to 1.5e-4 (what a copy with 4 decimals can be)
    # is projected onto SO(3) (and said so); one orthonormal to 3e-4 only is an error.
    puma = km.load("puma560")
    T = puma.fk([0.2, -0.5, 0.3, 0.4, 0.8, -0.1])
    T[:3, :3] = T[:3, :3] @ np.diag([1.0 + error / 2.0, 1.0, 1.0])  # (RᵀR − I)₀₀ ≈ error
    if accepted:
        res = puma.ik(T, tol=1e-3)
        assert res.success and any("projected onto SO(3)" in n for n in res.notes)
    else:
        with pytest.raises(km.DimensionError, match="not orthonormal"):
            puma.ik(T)


Q6 = np.radians([30, 40, -30, 10, 60, -20])


def _scaled(T: np.ndarray, eps: float) -> np.ndarray:
    """T with its rotation scaled by 1 + eps: max |RᵀR − I| = 2 eps + eps²."""
    S = T.copy()
    S[:3, :3] *= 1.0 + eps
    return S


def test_projection_note_only_beyond_round_off_of_the_tolerance() -> None:
    arm = km.load("arm6-dh")
    T = arm.fk(Q6)
    assert QUIET_PROJECTION == ROTATION_TOL
    ten = np.round(T, 10)  # a copy printed with 10 decimals: ~5e-11 from orthonormal
    assert 0 < orthonormality_error(ten[:3, :3]) < QUIET_PROJECTION
    res = arm.ik(ten)
    assert res.status == "ok" and res.notes == ()
    six = np.round(T, 6)
    assert arm.ik(six).notes and "projected onto SO(3)" in arm.ik(six).notes[0]
    # both sides of the boundary: orthonormal to 0.9 and to 1.2 times the constant
    inside, outside = _scaled(T, 0.45 * QUIET_PROJECTION), _scaled(T, 0.6 * QUIET_PROJECTION)
    assert orthonormality_error(inside[:3, :3]) < QUIET_PROJECTION
    assert orthonormality_error(outside[:3, :3]) > QUIET_PROJECTION
    assert arm.ik(inside).notes == ()
    assert "projected onto SO(3)" in arm.ik(outside).notes[0]


def test_a_numpy_matrix_target_is_read_as_its_array() -> None:
    # numpy.matrix keeps two axes when indexed: read as a plain (4, 4) array
    for robot in (km.load("puma560"), km.load("panda"), km.load("iiwa14")):
        T = robot.fk(np.full(robot.dof, 0.2))
        found, expected = robot.ik(np.matrix(T)), robot.ik(T)
        assert found.status == expected.status and found.count == expected.count >= 1
        np.testing.assert_array_equal(found.solutions, expected.solutions)


def test_q0_is_checked_once_for_every_path() -> None:
    from kinematica.errors import DimensionError
    from kinematica.ik.targets import parse_q0

    np.testing.assert_array_equal(parse_q0([1.0, 2.0], 2, (3,)), [[1.0, 2.0]] * 3)
    assert parse_q0(None, 2, ()) is None
    for bad, words in [
        ([np.nan, 0.0], "q0 holds NaN or inf"),
        ([0.0, np.inf], "q0 holds NaN or inf"),
        ([0.0], "q0 must hold 2 joint values"),
        ("ab", "q0 must be numbers"),
        (np.zeros((2, 2)), "does not match targets of batch shape"),
    ]:
        with pytest.raises(DimensionError, match=words) as info:
            parse_q0(bad, 2, (3,))
        assert info.value.arg == "q0"
