"""Drawn ellipsoids (``viz/ellipsoid.py``): the surface points are the scaled quadric."""

from __future__ import annotations

import numpy as np
import pytest

import kinematica as km


# ------------------------------------------------------------ drawn ellipsoids
def test_drawn_ellipsoid_points_are_the_scaled_quadric() -> None:
    pytest.importorskip("matplotlib")
    from kinematica.viz.ellipsoid import ELLIPSOID_SIZE, ellipsoid_points
    from kinematica.viz.geometry import robot_scale

    puma = km.load("puma560")
    q = np.radians([10, -30, 40, 20, 50, 0])
    pts, scale, radii = ellipsoid_points(puma, q, "force")
    e = km.ellipsoid(puma, q, "force")
    assert np.allclose(radii, e.radii)
    assert scale * radii.max() == pytest.approx(ELLIPSOID_SIZE * robot_scale(puma))
    local = (pts - e.center) @ e.directions / (e.radii * scale)
    assert np.allclose((local**2).sum(-1), 1.0, atol=1e-12)
    # a planar arm: the ellipse in its plane, J's rows of those axes
    arm = km.Robot.from_dh([km.Revolute(a=1.0), km.Revolute(a=1.0)], convention="standard")
    pts2, scale2, radii2 = ellipsoid_points(arm, [0.0, np.pi / 2], plane=(0, 1))
    golden = (1 + np.sqrt(5)) / 2
    assert np.allclose(radii2, [golden, 1 / golden])
    assert np.allclose(pts2[:, 2], 0.0)
    J = arm.jacobian([0.0, np.pi / 2])[:2]
    centre = arm.fk([0.0, np.pi / 2])[:2, 3]
    # points x = c + s·J u with |u| = 1: |J⁻¹ (x − c)| = s
    u = np.linalg.solve(J, (pts2[:, :2] - centre).T)
    assert np.allclose(np.linalg.norm(u, axis=0), scale2, rtol=1e-12)
