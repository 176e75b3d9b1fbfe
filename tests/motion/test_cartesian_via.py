"""Cartesian paths through several poses: lines, slerps, blended corners, one IK branch."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation, Slerp

import kinematica as km
from kinematica.motion import cartesian_path, cartesian_via_path
from kinematica.motion.cartesian_via import ROTATION_LENGTH, BlendedPolyline

PUMA_Q = np.array([0.2, -0.5, 0.3, 0.4, 0.9, -0.1])


def poses_through(T0: np.ndarray, offsets: list[list[float]]) -> np.ndarray:
    P = np.stack([T0] * len(offsets))
    P[:, :3, 3] += np.array(offsets)
    return P


def test_collinear_waypoints_make_no_corner() -> None:
    puma = km.load("puma560")
    T0 = puma.fk(PUMA_Q)
    P = poses_through(T0, [[0, 0, 0], [0.02, 0.04, 0], [0.05, 0.1, 0], [0.06, 0.12, 0]])
    path = cartesian_via_path(puma, P, blend=0.01, steps=41, q0=PUMA_Q)
    line = cartesian_path(puma, P[0], P[-1], steps=41, q0=PUMA_Q)
    assert path.ok and line.ok
    assert np.allclose(path.poses, line.poses, atol=1e-15)
    assert np.allclose(path.q, line.q, atol=1e-12)


def test_corner_blend_by_hand() -> None:
    # a square corner: (0,0,0) -> (0.2,0,0) -> (0.2,0.2,0), one orientation; both segments
    # have the rate L = 0.4 (m per unit s), so the blend spans δ = r/L either side of s = 0.5
    # and the corner point of the parabola is p1 + (v_out - v_in)·δ/4: √2·r/4 from the corner.
    r = 0.03
    P = poses_through(np.eye(4), [[0, 0, 0], [0.2, 0, 0], [0.2, 0.2, 0]])
    geo = BlendedPolyline(P, r)
    assert np.allclose(geo.knots, [0, 0.5, 1]) and geo.delta[1] == pytest.approx(r / 0.4)
    p = geo(np.array([0.5]))[0, :3, 3]
    assert np.allclose(p, [0.2 - r / 4, r / 4, 0], atol=1e-15)
    # the blend leaves the first line exactly r before the corner and joins the second r after
    s_in, s_out = 0.5 - r / 0.4, 0.5 + r / 0.4
    assert np.allclose(geo(np.array([s_in, s_out]))[:, :3, 3], [[0.2 - r, 0, 0], [0.2, r, 0]])
    # outside the blend the path is on the lines; inside, strictly inside the corner
    s = np.linspace(0, 1, 401)
    q = geo(s)[:, :3, 3]
    on_lines = (s <= s_in) | (s >= s_out)
    assert np.all((np.abs(q[on_lines, 1]) < 1e-15) | (np.abs(q[on_lines, 0] - 0.2) < 1e-15))
    inside = ~on_lines
    assert np.all(q[inside, 0] < 0.2) and np.all(q[inside, 1] > 0)
    # tangent continuity: one-sided difference quotients agree at the blend's ends
    h = 1e-6
    for sk in (s_in, s_out):
        left = (geo(sk) - geo(sk - h)) / h
        right = (geo(sk + h) - geo(sk)) / h
        assert np.abs(left - right).max() < 1e-4
    # any batch shape of s
    for shape in ((), (1,), (3, 2)):
        assert geo(np.full(shape, 0.3)).shape == (*shape, 4, 4)
    # no blend: every pose passed, with a corner
    sharp = BlendedPolyline(P, 0.0)
    assert np.allclose(sharp(np.array([0.0, 0.5, 1.0])), P, atol=1e-15)


def test_orientation_slerps_per_segment_and_blends_smoothly() -> None:
    R0 = np.eye(3)
    R1 = km.rotx(0.4) @ km.rotz(0.3)
    R2 = R1 @ km.roty(-0.5)
    P = np.stack(
        [
            km.make_transform(R0, [0, 0, 0]),
            km.make_transform(R1, [0.1, 0, 0]),
            km.make_transform(R2, [0.1, 0.1, 0]),
        ]
    )
    geo = BlendedPolyline(P, 0.02)
    # segment lengths |Δp| + ROTATION_LENGTH·θ (angles by scipy)
    L = 0.1 + ROTATION_LENGTH * np.array([Rotation.from_matrix(R1).magnitude(), 0.5])
    assert np.allclose(geo.knots, [0, L[0] / L.sum(), 1])
    # on the first segment, away from the blend: scipy's slerp between R0 and R1
    u = np.linspace(0, 0.8, 9)
    s = u * geo.knots[1]
    s = s[s < geo.knots[1] - geo.delta[1]]
    ref = Slerp([0, 1], Rotation.from_matrix([R0, R1]))(s / geo.knots[1]).as_matrix()
    assert np.allclose(geo(s)[:, :3, :3], ref, atol=1e-12)
    # continuous rates d/ds at both ends of the blend
    h = 1e-6
    for sk in (geo.knots[1] - geo.delta[1], geo.knots[1] + geo.delta[1]):
        left = (geo(sk) - geo(sk - h)) / h
        right = (geo(sk + h) - geo(sk)) / h
        assert np.abs(left - right).max() < 1e-4
    assert np.allclose(geo(1.0), P[-1], atol=0)


def test_blended_path_is_followed_on_one_branch() -> None:
    puma = km.load("puma560")
    T0 = puma.fk(PUMA_Q)
    P = poses_through(T0, [[0, 0, 0], [0.1, 0, 0], [0.1, 0.1, 0], [0.1, 0.1, 0.1]])
    P[3, :3, :3] = T0[:3, :3] @ km.rotx(0.3)
    path = cartesian_via_path(puma, P, blend=0.02, steps=80, q0=PUMA_Q)
    assert path.ok and np.allclose(path.q[0], PUMA_Q)
    assert np.allclose(puma.fk(path.q), path.poses, atol=1e-9)
    assert np.allclose(path.poses[-1], P[-1], atol=1e-15)


def test_corner_path_through_the_wrist_singularity_is_an_event() -> None:
    puma = km.load("puma560")
    q_sing = np.array([0.2, -0.5, 0.3, 0.4, 0.0, -0.1])
    Ts = puma.fk(q_sing)
    P = poses_through(Ts, [[0, -0.07, -0.035], [0, 0.13, 0.065], [0.05, 0.13, 0.065]])
    path = cartesian_via_path(puma, P, blend=0.01, steps=60, q0=q_sing)
    kinds = [(e.kind, e.names) for e in path.events]
    assert ("singularity", ("wrist",)) in kinds, kinds


def test_bad_input() -> None:
    puma = km.load("puma560")
    T0 = puma.fk(PUMA_Q)
    P = poses_through(T0, [[0, 0, 0], [0.1, 0, 0]])
    with pytest.raises(km.KinematicaError, match="poses 2 and 3 are equal"):
        cartesian_via_path(puma, np.stack([P[0], P[1], P[1]]))
    with pytest.raises(km.DimensionError, match="k >= 2"):
        cartesian_via_path(puma, P[:1])
    with pytest.raises(km.KinematicaError, match="blend must be"):
        cartesian_via_path(puma, P, blend=-0.1)
    with pytest.raises(km.KinematicaError, match="steps"):
        cartesian_via_path(puma, P, steps=1)
