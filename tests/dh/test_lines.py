"""The line geometry of joint axes (``dh/lines.py``) as the classification reads it.

Each tolerance is tested a factor 10 inside and outside its documented value,
written here as a literal: a test that read the constant would move with it.
"""

from __future__ import annotations

import math

import pytest

import kinematica as km

#: dh/lines.py, the one line geometry (DH extraction, classification, builders,
#: singularities): the sine (parallel) or cosine (perpendicular) of an angle, and
#: a distance relative to 1 + the arm's size (m).
AXIS_ANGLE_TOL = 1e-9


AXIS_LENGTH_TOL = 1e-9


#: A case a factor 10 inside a tolerance, and one a factor 10 outside it.
FACTORS = [(0.1, True), (10.0, False)]


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
        [km.Revolute(a=1.0, alpha=factor * AXIS_ANGLE_TOL), km.Revolute(a=1.0)],
        convention="standard",
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
    robot = km.Robot.from_dh(
        [km.Revolute(a=a, alpha=math.pi / 2), km.Revolute(a=1.0)], convention="standard"
    )
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
        [km.Revolute(alpha=-math.pi / 2), km.Revolute(a=d, alpha=math.pi / 3), km.Revolute()],
        convention="standard",
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
    robot = km.Robot.from_dh(
        [km.Revolute(a=1.0, alpha=math.pi / 2 + e), km.Revolute(a=1.0)], convention="standard"
    )
    f = km.classify(robot).features
    assert abs(float(f.directions[0] @ f.directions[1])) == pytest.approx(e, rel=1e-3)
    assert f.is_perpendicular(0, 1) is inside


def test_cross3_gives_np_cross_s_floats() -> None:
    # the builders take cross3 for np.cross on one pair: the same operations, the same bits
    import numpy as np

    from kinematica.dh.lines import cross3

    rng = np.random.default_rng(3)
    a = rng.normal(size=(500, 3)) * 10.0 ** rng.uniform(-12, 3, size=(500, 1))
    b = rng.normal(size=(500, 3))
    assert all(np.array_equal(cross3(x, y), np.cross(x, y)) for x, y in zip(a, b, strict=True))
    assert np.array_equal(cross3(a[0], [1.0, 0.0, 0.0]), np.cross(a[0], [1.0, 0.0, 0.0]))


def test_the_features_of_a_puma_table_are_those_found_by_hand() -> None:
    """The core's feature set of a PUMA-type table (standard DH) at q = 0, by hand.

    Frame 1 is the base turned 90° about x (z1 = -y0); rows 2-3 move the origin
    to (a2 + a3, -d3, 0) with z3 = z0; row 4 adds d4 along z3, where axes 4, 5
    and 6 meet: the wrist centre is (a2 + a3, -d3, d4). Axes 2 and 3 (both -y0)
    are parallel; 1-2, 4-5 and 5-6 meet (2-3 are a3 apart); the first three have
    no common point (2 and 3 are a2 apart); every twist is 0 or ±90°, so the slack is 0.
    """
    import numpy as np

    from kinematica.ik.structure import features

    a2, a3, d3, d4 = 0.4318, 0.0203, 0.15005, 0.4318
    robot = km.Robot.from_dh(
        [
            km.Revolute(alpha=math.pi / 2),
            km.Revolute(a=a2),
            km.Revolute(d=d3, a=a3, alpha=-math.pi / 2),
            km.Revolute(d=d4, alpha=math.pi / 2),
            km.Revolute(alpha=-math.pi / 2),
            km.Revolute(),
        ],
        convention="standard",
    )
    f = features(robot.chain)
    assert f.joint_types == "RRRRRR"
    assert f.parallel == ((1, 2),)
    assert f.intersecting == ((0, 1), (3, 4), (4, 5))
    assert f.size == pytest.approx(a2 + a3 + d3 + d4, rel=1e-15)
    assert f.wrist_center is not None and not f.wrist_center.flags.writeable
    np.testing.assert_allclose(f.wrist_center, [a2 + a3, -d3, d4], rtol=0, atol=1e-15)
    assert f.shoulder_center is None
    assert f.slack == 0.0 and not f.near_degenerate


@pytest.mark.parametrize(
    ("rows", "slack"),
    [
        # axis 2 tilted by 1e-10 rad from axis 1 (parallel within AXIS_ANGLE_TOL, not exactly):
        # 2 ε size, size 2 m (the two 1 m links)
        ([km.Revolute(a=1.0, alpha=1e-10), km.Revolute(a=1.0)], 2.0 * math.sin(1e-10) * 2.0),
        # perpendicular axes 5e-11 m apart (meeting within length_tol, not exactly): δ
        ([km.Revolute(a=5e-11, alpha=math.pi / 2), km.Revolute(a=1.0)], 5e-11),
    ],
)
def test_the_near_degenerate_slack_is_its_relations_sum_by_hand(
    rows: list[km.Revolute], slack: float
) -> None:
    from kinematica.ik.structure import features

    f = features(km.Robot.from_dh(rows, convention="standard").chain)
    assert f.near_degenerate
    assert f.slack == pytest.approx(slack, rel=1e-6)


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_axis_angle_tol_bounds_the_rank_of_lines_meeting_at_a_point(
    factor: float, inside: bool
) -> None:
    """AXIS_ANGLE_TOL is also the rank tolerance of common_point's normal matrix.

    Three lines through the origin, along z and tilted θ from it about y and x,
    are not parallel (sine θ ≫ AXIS_ANGLE_TOL) but nearly so: the smallest
    eigenvalue of Σ (I - h hᵀ) grows as θ². θ is chosen (numpy's eigvalsh, an
    independent solver) so that it is ``factor`` times the tolerance: inside it
    the lines have no common point, outside it the point is the origin.
    """
    import numpy as np

    def lines(theta: float) -> np.ndarray:
        s, c = math.sin(theta), math.cos(theta)
        return np.array([[0.0, 0.0, 1.0], [s, 0.0, c], [0.0, s, c]])

    def smallest(h: np.ndarray) -> float:
        A = sum(np.eye(3) - np.outer(x, x) for x in h)
        return float(np.linalg.eigvalsh(A)[0])

    target = factor * AXIS_ANGLE_TOL
    theta = 1e-4 * math.sqrt(target / smallest(lines(1e-4)))
    h = lines(theta)
    assert smallest(h) == pytest.approx(target, rel=1e-3)
    c = km.dh.lines.common_point(h, np.zeros((3, 3)), 1.0)
    assert (c is None) == inside
    if c is not None:
        assert np.array_equal(c, np.zeros(3))
