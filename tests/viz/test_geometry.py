"""The geometry of the pictures (``viz/geometry.py``): when an arm is drawn in its plane."""

from __future__ import annotations

import pytest

import kinematica as km

#: A case a factor 10 inside a tolerance, and one a factor 10 outside it.
FACTORS = [(0.1, True), (10.0, False)]


VIZ_PLANAR_TOL = 1e-9  # viz/geometry.py PLANAR_TOL


@pytest.mark.parametrize(("factor", "inside"), FACTORS)
def test_viz_planar_tol_decides_the_2d_view(factor: float, inside: bool) -> None:
    """viz/geometry.PLANAR_TOL: an arm is drawn in 2-D when its revolute axes
    are parallel to a world axis within it (the sine of the angle): a 2R arm
    whose second axis is tilted by alpha is drawn in the x-y plane, or in 3-D.
    """
    pytest.importorskip("matplotlib")
    from kinematica import viz

    alpha = factor * VIZ_PLANAR_TOL
    arm = km.Robot.from_dh(
        [km.Revolute(a=0.4, alpha=alpha), km.Revolute(a=0.3)], convention="standard"
    )
    assert viz.drawing_plane(arm) == ((0, 1) if inside else None)
