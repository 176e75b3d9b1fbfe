"""DH extraction's tolerances (``dh/lines.py``, ``dh/extract.py``), both sides.

Each case sits a factor inside or outside the documented value, written here as a
literal: a test that read the constant would move with it.
"""

from __future__ import annotations

import math
import warnings

import pytest
from support.urdf import dh_table as _table
from support.urdf import extraction_rule as _rule
from support.urdf import two_joints as _two_joints

import kinematica as km
from kinematica.io import parse_urdf

#: dh/lines.py, the one line geometry (DH extraction, classification, builders,
#: singularities): the sine (parallel) or cosine (perpendicular) of an angle, and
#: a distance relative to 1 + the arm's size (m).
AXIS_ANGLE_TOL = 1e-9


AXIS_LENGTH_TOL = 1e-9


#: A case a factor 10 inside a tolerance, and one a factor 10 outside it.
FACTORS = [(0.1, True), (10.0, False)]


FK_CHECK_TOL = 1e-9  # dh/extract.py


ROUND_OFF_TOL = 1e-15  # dh/extract.py


@pytest.mark.parametrize("convention", ["standard", "modified"])
@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_extraction_reads_parallel_axes_by_axis_angle_tol(
    factor: float, inside: bool, convention: str
) -> None:
    """AXIS_ANGLE_TOL in DH extraction: two joint axes at an angle (rad, its sine)
    below it are parallel; axis 2 tilted by more, 0.5 m from axis 1, meets it far away.
    """
    urdf = _two_joints("0.5 0 0", f"0 {factor * AXIS_ANGLE_TOL!r} 0")
    assert _rule(urdf, convention) == ("parallel" if inside else "intersecting")


@pytest.mark.parametrize("convention", ["standard", "modified"])
@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_extraction_reads_meeting_and_coinciding_axes_by_axis_length_tol(
    factor: float, inside: bool, convention: str
) -> None:
    """AXIS_LENGTH_TOL in DH extraction: axes closer than it times 1 + the chain's
    size (m) meet, or coincide when parallel.

    The chain: joint 2 0.3 m above joint 1, the tip 1 m from joint 2 (size 1.3 m).
    """
    delta = factor * AXIS_LENGTH_TOL * (1.0 + 1.3)
    crossing = _two_joints(f"{delta!r} 0 0.3", f"{math.pi / 2!r} 0 0")
    assert _rule(crossing, convention) == ("intersecting" if inside else "skew")
    beside = _two_joints(f"{delta!r} 0 0.3", "0 0 0")
    assert _rule(beside, convention) == ("collinear" if inside else "parallel")


@pytest.mark.parametrize(("factor", "inside"), [(0.5, True), (2.0, False)])
def test_fk_check_tol_warns_beyond_it(factor: float, inside: bool) -> None:
    """FK_CHECK_TOL: an extracted table whose FK is farther than it (m) from the
    chain's is reported with a warning.

    Axis 2 tilted by half AXIS_ANGLE_TOL is taken as parallel: with the tip L up
    axis 2, the table is off by the tilt times L.
    """
    tilt = 0.5 * AXIS_ANGLE_TOL
    L = factor * FK_CHECK_TOL / tilt
    urdf = parse_urdf(_two_joints("0.5 0 0", f"0 {tilt!r} 0", f"0 0 {L!r}"))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        ex = km.urdf_to_dh(urdf)
    assert ex.rules[1].rule == "parallel"
    assert ex.fk_error == pytest.approx(factor * FK_CHECK_TOL, rel=0.3)
    warned = any("reproduces the chain's forward kinematics" in str(w.message) for w in caught)
    assert warned is not inside


@pytest.mark.parametrize(("factor", "inside"), [(0.5, True), (2.0, False)])
def test_fk_check_tol_warns_beyond_it_on_a_loaded_robots_to_dh(factor: float, inside: bool) -> None:
    """FK_CHECK_TOL through ``robot.to_dh()``: the table is measured against the chain
    the robot was loaded from (not against its own DH rows), so it warns as
    ``urdf_to_dh`` does (the same chain as in the test above).
    """
    tilt = 0.5 * AXIS_ANGLE_TOL
    L = factor * FK_CHECK_TOL / tilt
    urdf = parse_urdf(_two_joints("0.5 0 0", f"0 {tilt!r} 0", f"0 0 {L!r}"))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        robot = km.urdf_to_dh(urdf).robot
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        ex = robot.to_dh("standard")
    assert ex.fk_error == pytest.approx(factor * FK_CHECK_TOL, rel=1e-3)
    warned = any("reproduces the chain's forward kinematics" in str(w.message) for w in caught)
    assert warned is not inside


@pytest.mark.parametrize(("factor", "inside"), [(0.5, True), (20.0, False)])
def test_round_off_tol_tidies_lengths_and_angles(factor: float, inside: bool) -> None:
    """ROUND_OFF_TOL: a length or angle within it of a round value (0.3 m, π/2)
    is taken as that value; farther, as given.
    """
    extra = factor * ROUND_OFF_TOL
    a1 = float(_table(_two_joints(f"{0.3 + extra!r} 0 0", "0 0 0"))[0, 2])
    assert (a1 == 0.3) is inside
    rpy = f"{math.pi / 2 + extra!r} 0 0"
    alpha1 = float(_table(_two_joints("0 0 0.3", rpy))[0, 3])
    assert (alpha1 == math.pi / 2) is inside
