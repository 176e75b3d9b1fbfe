"""Velocity and force ellipsoids (``robot/ellipsoid.py``): radii, directions, surface points.

References: numpy's SVD of the Jacobian, and the quadric the surface lies on.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import kinematica as km


# ------------------------------------------------------------ ellipsoids
def test_ellipsoid_radii_are_the_singular_values() -> None:
    puma = km.load("puma560")
    q = puma.random_q(8, seed=7)
    for axes, rows in (("trans", slice(0, 3)), ("rot", slice(3, 6)), ("all", slice(None))):
        J = puma.jacobian(q)[:, rows]
        s = np.linalg.svd(J, compute_uv=False)
        vel = km.ellipsoid(puma, q, "velocity", axes)
        force = km.ellipsoid(puma, q, "force", axes)
        assert np.allclose(vel.radii, s, rtol=1e-12)
        assert np.allclose(force.radii, 1.0 / s, rtol=1e-12)
        # directions: orthonormal and J Jᵀ u_k = σ_k² u_k
        D = vel.directions
        m = D.shape[-1]
        assert np.allclose(np.swapaxes(D, -1, -2) @ D, np.eye(m), atol=1e-12)
        JJt = J @ np.swapaxes(J, -1, -2)
        assert np.allclose(JJt @ D, D * s[:, None, :] ** 2, atol=1e-10)
        assert np.allclose(vel.center, puma.fk(q)[:, :3, 3])


def test_ellipsoid_of_a_2_joint_arm_in_3_rows_is_flat() -> None:
    arm = km.Robot.from_dh([km.Revolute(a=1.0), km.Revolute(a=1.0)], convention="standard")
    vel = km.ellipsoid(arm, [0.0, math.pi / 2])
    force = km.ellipsoid(arm, [0.0, math.pi / 2], "force")
    golden = (1 + math.sqrt(5)) / 2
    assert np.allclose(vel.radii, [golden, 1 / golden, 0.0], atol=1e-15)
    assert np.allclose(force.radii[:2], [1 / golden, golden]) and force.radii[2] == np.inf
    assert np.allclose(np.abs(vel.directions[:, 2]), [0, 0, 1])  # the flat axis is z
    with pytest.raises(km.KinematicaError, match="infinite radius"):
        force.surface()


def test_ellipsoid_surface_points_satisfy_the_quadric() -> None:
    puma = km.load("puma560")
    q = puma.random_q(2, seed=8)
    e = km.ellipsoid(puma, q)
    pts = e.surface(resolution=9)
    assert pts.shape == (2, 9, 9, 3)
    local = np.einsum("bji,buvj->buvi", e.directions, pts - e.center[:, None, None, :])
    assert np.allclose(((local / e.radii[:, None, None, :]) ** 2).sum(-1), 1.0, atol=1e-12)


def test_ellipsoid_bad_input() -> None:
    puma = km.load("puma560")
    with pytest.raises(km.KinematicaError, match="kind must be"):
        km.ellipsoid(puma, np.zeros(6), "torque")  # type: ignore[arg-type]
    with pytest.raises(km.KinematicaError, match="3-D"):
        km.ellipsoid(puma, np.zeros(6), axes="all").surface()
