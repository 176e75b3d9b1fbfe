"""Named tolerances not pinned elsewhere, each tested on both sides of its value.

Every case is placed a factor 10 below or above the value the constant's
documentation states, written here as a literal: a test that read the constant
itself would move with it, and could not notice it changed a thousandfold. The
constants here are compared with a quantity the test controls exactly (a
distance, a sine, an angle), so a factor of 10 leaves a wide margin for round-off.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
import test_dh_extract as dh_extract
from kinematica._core import internals

import kinematica as km
from kinematica.io import parse_urdf
from kinematica.motion import cartesian_path

# The documented values (m, rad, or a sine/cosine), one per constant.
POSITION_TOL = 1e-10  # ik/targets.py
ROTATION_TOL = 1e-10  # ik/targets.py
#: dh/lines.py, the one line geometry (DH extraction, classification, builders,
#: singularities): the sine (parallel) or cosine (perpendicular) of an angle, and
#: a distance relative to 1 + the arm's size (m).
AXIS_ANGLE_TOL = 1e-9
AXIS_LENGTH_TOL = 1e-9
IDENTITY_ANGLE_TOL = 10.0 * np.finfo(np.float64).eps  # spatial/axis_angle.py
COLLINEAR_TOL = 1e-9  # motion/cartesian.py

#: A case a factor 10 inside a tolerance, and one a factor 10 outside it.
FACTORS = [(0.1, True), (10.0, False)]

Q_2R = [0.4, 1.1]


def two_link() -> km.Robot:
    return km.Robot.from_dh([km.Revolute(a=1.0), km.Revolute(a=1.0)])


def pose(R: np.ndarray) -> np.ndarray:
    T = np.eye(4)
    T[:3, :3] = R
    return T


# --- ik/targets.py: default acceptance tolerances -----------------------------


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


# --- dh/lines.py, as the classification of ik/structure.py reads it -----------


def test_the_line_geometry_s_documented_values() -> None:
    assert km.dh.lines.AXIS_ANGLE_TOL == AXIS_ANGLE_TOL
    assert km.dh.lines.AXIS_LENGTH_TOL == AXIS_LENGTH_TOL
    assert km.dh.length_tol(2.0) == pytest.approx(3.0 * AXIS_LENGTH_TOL)


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_axis_angle_tol_is_the_sine_of_the_angle_between_parallel_axes(
    factor: float, inside: bool
) -> None:
    """AXIS_ANGLE_TOL: two axes are parallel when the sine of their angle is below it.

    A twist ``alpha`` between two joints tilts the second axis by ``alpha``.
    """
    robot = km.Robot.from_dh(
        [km.Revolute(a=1.0, alpha=factor * AXIS_ANGLE_TOL), km.Revolute(a=1.0)]
    )
    assert km.classify(robot).parallel == (((0, 1),) if inside else ())


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_axis_length_tol_is_the_distance_of_axes_that_meet(factor: float, inside: bool) -> None:
    """AXIS_LENGTH_TOL: two (non-parallel) axes meet when they pass closer than it
    times 1 + the arm's size (m).

    Perpendicular axes (twist 90°) a link length ``a`` apart are ``a`` apart; the
    arm's size is its 1 m link (plus ``a``).
    """
    a = factor * AXIS_LENGTH_TOL * (1.0 + 1.0)
    robot = km.Robot.from_dh([km.Revolute(a=a, alpha=math.pi / 2), km.Revolute(a=1.0)])
    s = km.classify(robot)
    assert s.features.size == pytest.approx(1.0 + a)
    assert s.parallel == ()
    assert s.intersecting == (((0, 1),) if inside else ())


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_axis_length_tol_decides_the_wrist_center(factor: float, inside: bool) -> None:
    """AXIS_LENGTH_TOL also bounds how far each of the last three axes may pass from
    their common point (the wrist center).

    Axes 0 and 1 meet at the base origin; axis 2 (twisted 60°, all three
    orthogonal to x) passes ``d`` from it along x. The least-squares point lies
    d/3 along x, so the axes pass d/3, d/3 and 2d/3 from it: all within the
    tolerance when d is a factor 10 below it, none when d is 10 times above it
    (the arm's size is d: the tolerance is AXIS_LENGTH_TOL to 1e-8).
    """
    d = factor * AXIS_LENGTH_TOL
    robot = km.Robot.from_dh(
        [km.Revolute(alpha=-math.pi / 2), km.Revolute(a=d, alpha=math.pi / 3), km.Revolute()]
    )
    wc = km.classify(robot).wrist_center
    assert (wc is not None) == inside


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_axis_angle_tol_is_the_cosine_of_the_angle_between_perpendicular_axes(
    factor: float, inside: bool
) -> None:
    """AXIS_ANGLE_TOL: two axes are perpendicular when |cos| of their angle is below it.

    A twist of 90° + ``e`` leaves the axes at cosine ``-sin(e)`` ~ ``e``.
    """
    e = factor * AXIS_ANGLE_TOL
    robot = km.Robot.from_dh([km.Revolute(a=1.0, alpha=math.pi / 2 + e), km.Revolute(a=1.0)])
    f = km.classify(robot).features
    assert abs(float(f.directions[0] @ f.directions[1])) == pytest.approx(e, rel=1e-3)
    assert f.is_perpendicular(0, 1) is inside


# --- spatial/axis_angle.py ----------------------------------------------------


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_identity_angle_tol_gives_the_conventional_axis(factor: float, inside: bool) -> None:
    """IDENTITY_ANGLE_TOL: below this angle the axis of R is round-off, and
    axis_angle_from_matrix returns the z axis by convention.

    A rotation about x by a tiny angle ``e`` has the exact skew part
    ``sin e`` ~ ``e``, so its angle is recovered; its axis is x above the
    tolerance and z (the convention) below it.
    """
    e = factor * IDENTITY_ANGLE_TOL
    axis, angle = km.axis_angle_from_matrix(km.matrix_from_axis_angle([1.0, 0.0, 0.0], e))
    assert float(angle) == pytest.approx(e, rel=1e-6)
    expected = [0.0, 0.0, 1.0] if inside else [1.0, 0.0, 0.0]
    assert np.array_equal(axis, expected)


# --- motion/cartesian.py ------------------------------------------------------


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_collinear_tol_rejects_a_via_on_the_line(factor: float, inside: bool) -> None:
    """COLLINEAR_TOL: three points closer than it (m) to one line define no circle.

    The ends are 0.1 m apart along x and via is halfway, lifted by ``h`` along
    y: |u × v| = 0.1 h (below 1 m², so the tolerance is not scaled). Lifted by
    less than COLLINEAR_TOL / 0.1 it is an error; by more, an arc through via.
    """
    puma = km.load("puma560")
    q = np.array([0.2, -0.5, 0.3, 0.4, 0.9, -0.1])
    T0 = puma.fk(q)
    T1 = T0.copy()
    T1[:3, 3] += [0.1, 0.0, 0.0]
    h = factor * COLLINEAR_TOL / 0.1
    via = T0[:3, 3] + [0.05, h, 0.0]
    if inside:
        with pytest.raises(km.KinematicaError, match="via lies on the line"):
            cartesian_path(puma, T0, T1, steps=4, q0=q, via=via)
    else:
        path = cartesian_path(puma, T0, T1, steps=4, q0=q, via=via)
        assert np.allclose(path.poses[-1], T1, atol=1e-9)


# --- robot/singularities.py: named singular configurations ---------------------

WRIST_TOL = 1e-6  # robot/singularities.py
ELBOW_TOL = 1e-6  # robot/singularities.py
SHOULDER_TOL = 1e-6  # robot/singularities.py
RANK_TOL = 1e-8  # robot/singularities.py
L2, L3 = 0.4, 0.3  # the link lengths of the built-in anthropomorphic-3r


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_wrist_tol_is_the_sine_between_axes_4_and_6(factor: float, inside: bool) -> None:
    """WRIST_TOL: the wrist is singular when the sine of the angle between axes
    4 and 6 is below it; on a PUMA that sine is |sin q5|.
    """
    puma = km.load("puma560")
    q = np.array([0.3, -0.7, 0.9, 0.5, factor * WRIST_TOL, -0.4])
    assert puma.singularities(q) == (["wrist"] if inside else [])


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_elbow_tol_is_the_rate_of_the_reach(factor: float, inside: bool) -> None:
    """ELBOW_TOL: the elbow is singular when the distance r of the wrist from
    the shoulder changes with q3 slower than this (m/rad).

    r(q3)² = L2² + L3² + 2 L2 L3 cos q3, so |dr/dq3| = L2 L3 sin q3 / r: q3 is
    solved for a given rate by fixed-point iteration.
    """
    rate = factor * ELBOW_TOL
    q3 = rate * (L2 + L3) / (L2 * L3)
    for _ in range(5):
        r = math.sqrt(L2**2 + L3**2 + 2 * L2 * L3 * math.cos(q3))
        q3 = math.asin(rate * r / (L2 * L3))
    arm = km.load("anthropomorphic-3r")
    assert arm.singularities(np.array([0.3, 0.5, q3])) == (["elbow"] if inside else [])


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_shoulder_tol_is_the_distance_from_axis_1(factor: float, inside: bool) -> None:
    """SHOULDER_TOL: the shoulder is singular when the wrist centre is closer
    than this (m) to axis 1: L2 cos q2 + L3 cos(q2 + q3) = dist.
    """
    dist, q2 = factor * SHOULDER_TOL, 1.2
    q = np.array([0.3, q2, math.acos((dist - L2 * math.cos(q2)) / L3) - q2])
    arm = km.load("anthropomorphic-3r")
    assert arm.singularities(q) == (["shoulder"] if inside else [])


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_rank_tol_is_the_relative_singular_value(factor: float, inside: bool) -> None:
    """RANK_TOL: a singular value of the Jacobian below it times the largest one
    is lost ("rank" on an arm with no named singularities).

    A revolute joint then a prismatic one along the radius: the singular
    values of the position rows are 1 (the slide) and the extension q2 (m, the
    turn), so their ratio is q2.
    """
    arm = km.Robot.from_dh([km.Revolute(alpha=-math.pi / 2), km.Prismatic(qlim=(0.0, 1.0))])
    s = np.linalg.svd(arm.jacobian([0.2, 0.5])[:3], compute_uv=False)
    assert s == pytest.approx([1.0, 0.5])
    assert arm.singularities([0.2, factor * RANK_TOL]) == (["rank"] if inside else [])


# --- dh/lines.py and dh/extract.py: DH tables from URDF -------------------------

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
    urdf = dh_extract._two_joints("0.5 0 0", f"0 {factor * AXIS_ANGLE_TOL!r} 0")
    assert dh_extract._rule(urdf, convention) == ("parallel" if inside else "intersecting")


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
    crossing = dh_extract._two_joints(f"{delta!r} 0 0.3", f"{math.pi / 2!r} 0 0")
    assert dh_extract._rule(crossing, convention) == ("intersecting" if inside else "skew")
    beside = dh_extract._two_joints(f"{delta!r} 0 0.3", "0 0 0")
    assert dh_extract._rule(beside, convention) == ("collinear" if inside else "parallel")


@pytest.mark.parametrize(("factor", "inside"), [(0.5, True), (2.0, False)])
def test_fk_check_tol_warns_beyond_it(factor: float, inside: bool) -> None:
    """FK_CHECK_TOL: an extracted table whose FK is farther than it (m) from the
    chain's is reported with a warning.

    Axis 2 tilted by half AXIS_ANGLE_TOL is taken as parallel: with the tip L up
    axis 2, the table is off by the tilt times L.
    """
    tilt = 0.5 * AXIS_ANGLE_TOL
    L = factor * FK_CHECK_TOL / tilt
    urdf = parse_urdf(dh_extract._two_joints("0.5 0 0", f"0 {tilt!r} 0", f"0 0 {L!r}"))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        ex = km.urdf_to_dh(urdf)
    assert ex.rules[1].rule == "parallel"
    assert ex.fk_error == pytest.approx(factor * FK_CHECK_TOL, rel=0.3)
    warned = any("reproduces the chain's forward kinematics" in str(w.message) for w in caught)
    assert warned is not inside


@pytest.mark.parametrize(("factor", "inside"), [(0.5, True), (20.0, False)])
def test_round_off_tol_tidies_lengths_and_angles(factor: float, inside: bool) -> None:
    """ROUND_OFF_TOL: a length or angle within it of a round value (0.3 m, π/2)
    is taken as that value; farther, as given.
    """
    extra = factor * ROUND_OFF_TOL
    a1 = float(dh_extract._table(dh_extract._two_joints(f"{0.3 + extra!r} 0 0", "0 0 0"))[0, 2])
    assert (a1 == 0.3) is inside
    rpy = f"{math.pi / 2 + extra!r} 0 0"
    alpha1 = float(dh_extract._table(dh_extract._two_joints("0 0 0.3", rpy))[0, 3])
    assert (alpha1 == math.pi / 2) is inside


# --- motion/workspace.py and viz/geometry.py: planar arms -----------------------

WORKSPACE_PLANAR_TOL = 1e-9  # motion/workspace.py PLANAR_TOL
VIZ_PLANAR_TOL = 1e-9  # viz/geometry.py PLANAR_TOL


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_workspace_planar_tol_is_a_thickness(factor: float, inside: bool) -> None:
    """motion/workspace.PLANAR_TOL: a workspace thinner than it (m) along an axis
    is planar (an area, no volume).

    A planar 2R arm on a z slide of travel t: the sampled points span at most
    t in z (and nearly all of it, with 2000 samples drawn uniformly).
    """
    t = factor * WORKSPACE_PLANAR_TOL
    arm = km.Robot.from_dh(
        [km.Revolute(a=0.4), km.Revolute(a=0.3), km.Prismatic(qlim=(0.0, t))], name="2R on a slide"
    )
    ws = km.workspace(arm, samples=2000, seed=3, manipulability=False)
    thickness = float(np.ptp(ws.points[:, 2]))
    assert 0.9 * t <= thickness <= t * (1 + 1e-9) + 1e-15
    assert ws.planar is inside
    assert (ws.area is not None) is inside and (ws.volume == 0.0) is inside


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_viz_planar_tol_decides_the_2d_view(factor: float, inside: bool) -> None:
    """viz/geometry.PLANAR_TOL: an arm is drawn in 2-D when its revolute axes
    are parallel to a world axis within it (the sine of the angle): a 2R arm
    whose second axis is tilted by alpha is drawn in the x-y plane, or in 3-D.
    """
    pytest.importorskip("matplotlib")
    from kinematica import viz

    alpha = factor * VIZ_PLANAR_TOL
    arm = km.Robot.from_dh([km.Revolute(a=0.4, alpha=alpha), km.Revolute(a=0.3)])
    assert viz.drawing_plane(arm) == ((0, 1) if inside else None)


# --- geometry.hpp ----------------------------------------------------------------

TRIG_TOL = 1e-10  # geometry.hpp


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_trig_tol_takes_a_near_miss_as_a_double_root(factor: float, inside: bool) -> None:
    """TRIG_TOL: a cos θ + b sin θ = c with |c| above r = hypot(a, b) by at most
    this (relative, r² - c² >= -2 TRIG_TOL r²) is a double root (1), beyond it
    no solution (0); ``out`` holds the least-squares angle atan2(b, a) either way.
    """
    a, b, r = 3.0, 4.0, 5.0
    c = r * math.sqrt(1.0 + 2.0 * factor * TRIG_TOL)  # r² - c² = -2 factor TRIG_TOL r²
    code, *out = internals.trig_linear(a, b, c)
    assert code == (1 if inside else 0)
    np.testing.assert_allclose(out, math.atan2(b, a), atol=1e-12)


# --- polynomial.hpp: Ferrari's roots, checked -------------------------------------

QUARTIC_CHECK = 1e-12  # polynomial.hpp


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_quartic_check_accepts_a_backward_error_below_it(factor: float, inside: bool) -> None:
    """QUARTIC_CHECK: a root whose backward error ``|P(x)| / Σ|k_i||x|^i``
    is ``factor * QUARTIC_CHECK`` passes the check below the constant and sends
    the quartic to the Aberth-Ehrlich iterations above it.
    """
    exact = np.array([1.0, 2.0, -0.5, 3.0])
    k = np.poly(exact)  # highest power first
    r = exact[1]
    slope = abs(np.polyval(np.polyder(k), r))
    bound = float(np.polyval(np.abs(k), r))
    roots = exact.astype(np.complex128)
    roots[1] += factor * QUARTIC_CHECK * bound / slope  # |P(x)| ≈ slope · shift
    assert internals.quartic_backward_ok(k.tolist(), roots.tolist()) is inside
    assert internals.quartic_backward_ok(k.tolist(), exact.astype(np.complex128).tolist())
    assert internals.QUARTIC_CHECK == QUARTIC_CHECK
