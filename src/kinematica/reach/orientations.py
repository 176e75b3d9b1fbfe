"""Fixed, evenly spread sets of tool orientations: all of SO(3), a cone, a plane.

A reachability map asks, at every voxel centre, which of a fixed set of tool
orientations the arm reaches. The set is deterministic (the same map on every
machine and every Dask worker) and spread evenly over what it samples.

**All of SO(3)** (:func:`so3_set`). The Hopf fibration writes a rotation as the
direction of its z axis (a point of the sphere S²) and a spin about that axis
(a point of the circle S¹); the uniform (Haar) measure of SO(3) is then the
product of the uniform measures of S² and S¹ (Yershova, Jain, LaValle and
Mitchell, "Generating uniform incremental grids on SO(3) using the Hopf
fibration", IJRR 29(7), 2010). With ZYZ angles ``R = Rz(λ) Ry(θ) Rz(ψ)`` the
z axis is the direction of colatitude ``θ`` and longitude ``λ``, and ``ψ`` the
spin. Rotation ``i`` of ``N``:

* its z axis is point ``i`` of the spherical Fibonacci lattice: ``cos θᵢ = 1 −
  (2i + 1)/N`` (equal-area bands) and ``λᵢ = 2π·frac(i/Φ)``, Φ the golden ratio
  (Swinbank and Purser, QJRMS 132, 2006; González, Math. Geosci. 42, 2010);
* its spin is ``ψᵢ = 2π·frac(i/√2)``, a Kronecker sequence whose ratio √2 is
  rationally independent of 1/Φ, so that spins do not follow longitudes.

Every one of the ``N`` rotations has its own z direction: a question that
depends on the tool axis only (where a tool offset puts the wrist centre) sees
an N-point lattice of the sphere, not a few directions repeated.

**A cone** (:func:`cone_set`, a reachability map's ``approach=``): the same
construction with ``cos θ`` spread over ``[cos α, 1]``, the cap of half-angle
α, turned so that its axis is the given direction. With α = 0 every rotation
has that z axis and only the spins differ (a SCARA's tool pointing down).

**A ball** (:func:`ball_set`, a design task's orientation tolerance): the
rotations within an angle ε of the identity. In axis-angle form the Haar
measure has density ``∝ 1 − cos θ`` in the angle θ, uniform in the axis, so
the angles are the quantiles ``(i + ½)/N`` of ``(θ − sin θ) / (ε − sin ε)``
and the axes points of the spherical Fibonacci lattice, visited in the order
of the √2 sequence so that the axis does not follow the angle.

**A plane** (:func:`planar_set`): a planar arm reaches only rotations about
its joints' common axis; ``N`` turns ``2π(k + ½)/N`` about it.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.arguments import check_count, check_number
from kinematica.errors import ArgumentError

__all__ = [
    "MAX_ORIENTATIONS",
    "ball_set",
    "cone_set",
    "planar_set",
    "rotation_about",
    "so3_set",
]

FloatArray = NDArray[np.float64]

#: Most orientations a set holds (a map solves this many poses per voxel).
MAX_ORIENTATIONS = 100_000

_GOLDEN = (1.0 + math.sqrt(5.0)) / 2.0
_SPIN = math.sqrt(2.0)


def _zyz(lam: FloatArray, cos_theta: FloatArray, psi: FloatArray) -> FloatArray:
    """``(N, 3, 3)`` rotations ``Rz(λ) Ry(θ) Rz(ψ)``."""
    st = np.sqrt(np.clip(1.0 - cos_theta**2, 0.0, 1.0))
    ct = cos_theta
    cl, sl, cp, sp = np.cos(lam), np.sin(lam), np.cos(psi), np.sin(psi)
    R = np.empty((lam.size, 3, 3))
    R[:, 0, 0] = cl * ct * cp - sl * sp
    R[:, 0, 1] = -cl * ct * sp - sl * cp
    R[:, 0, 2] = cl * st
    R[:, 1, 0] = sl * ct * cp + cl * sp
    R[:, 1, 1] = -sl * ct * sp + cl * cp
    R[:, 1, 2] = sl * st
    R[:, 2, 0] = -st * cp
    R[:, 2, 1] = st * sp
    R[:, 2, 2] = ct
    return R


def _count(n: object) -> int:
    return check_count(n, "orientations", lo=1, hi=MAX_ORIENTATIONS)


def _fibonacci(n: int, cos_lo: float) -> FloatArray:
    """``(n, 3, 3)``: z axes on the Fibonacci lattice of the cap ``cos θ >= cos_lo``."""
    i = np.arange(n, dtype=np.float64)
    cos_theta = 1.0 - (1.0 - cos_lo) * (i + 0.5) / n
    lam = 2.0 * math.pi * np.mod(i / _GOLDEN, 1.0)
    psi = 2.0 * math.pi * np.mod(i / _SPIN, 1.0)
    return _zyz(lam, cos_theta, psi)


def so3_set(n: int) -> FloatArray:
    """``n`` rotations spread evenly over SO(3) (see the module docs).

    Args:
        n: Number of rotations, 1 to :data:`MAX_ORIENTATIONS`.

    Returns:
        ``(n, 3, 3)`` rotation matrices (tool frame in the base frame).
    """
    return _fibonacci(_count(n), -1.0)


def rotation_about(axis: FloatArray, angle: ArrayLike) -> FloatArray:
    """``(..., 3, 3)`` rotations by ``angle`` (rad) about the unit ``axis`` (3,)."""
    k = np.asarray(axis, dtype=np.float64)
    K = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    a = np.asarray(angle, dtype=np.float64)[..., None, None]
    out: FloatArray = np.eye(3) + np.sin(a) * K + (1.0 - np.cos(a)) * (K @ K)
    return out


def _unit(direction: ArrayLike, name: str) -> FloatArray:
    try:
        v = np.asarray(direction, dtype=np.float64)
    except (TypeError, ValueError):
        raise ArgumentError(f"{name} must be 3 numbers, got {direction!r}", arg=name) from None
    if v.shape != (3,) or not np.all(np.isfinite(v)):
        raise ArgumentError(f"{name} must be 3 finite numbers, got {direction!r}", arg=name)
    norm = float(np.linalg.norm(v))
    if norm == 0.0:
        raise ArgumentError(f"{name} must not be the zero vector", arg=name)
    out: FloatArray = v / norm
    return out


def _turn_z_to(a: FloatArray) -> FloatArray:
    """The smallest rotation taking the base z axis to the unit vector ``a``.

    About ``z × a`` by the angle between them; about x by π for ``a = −z``
    (any axis normal to z would do there).
    """
    z = np.array([0.0, 0.0, 1.0])
    axis = np.cross(z, a)
    s = float(np.linalg.norm(axis))
    angle = math.atan2(s, float(a[2]))
    axis = np.array([1.0, 0.0, 0.0]) if s == 0.0 else axis / s
    out: FloatArray = rotation_about(axis, np.array(angle))
    return out


def cone_set(n: int, axis: ArrayLike, half_angle: float) -> FloatArray:
    """``n`` rotations whose tool z axis lies within ``half_angle`` of ``axis``.

    Args:
        n: Number of rotations.
        axis: ``(3,)`` the cone's axis in the base frame (any length but zero),
            e.g. ``(0, 0, -1)`` for a tool pointing down.
        half_angle: The cone's half-angle (rad), 0 to π (π: all of SO(3)).

    Returns:
        ``(n, 3, 3)`` rotations; z axes on the Fibonacci lattice of the cap,
        spins by the √2 sequence (module docs), turned by the smallest rotation
        taking the base z axis to ``axis`` (about z, π: the SO(3) set itself).
    """
    count = _count(n)
    a = _unit(axis, "approach")
    alpha = check_number(half_angle, "half_angle", lo=0.0, hi=math.pi, unit="rad", what="an angle")
    local = _fibonacci(count, math.cos(alpha))
    out: FloatArray = _turn_z_to(a) @ local
    return out


def planar_set(n: int, normal: ArrayLike, start: ArrayLike | None = None) -> FloatArray:
    """``n`` rotations turned ``2π(k + ½)/n`` about ``normal`` (a planar arm's).

    Args:
        n: Number of rotations.
        normal: ``(3,)`` the plane's normal (the arm's joint axis), base frame.
        start: ``(3, 3)`` the rotation turned (the tool's at q = 0); identity if None.

    Returns:
        ``(n, 3, 3)`` rotations ``Rot(normal, φk) · start``.
    """
    count = _count(n)
    k = _unit(normal, "normal")
    phi = 2.0 * math.pi * (np.arange(count) + 0.5) / count
    R0 = np.eye(3) if start is None else np.asarray(start, dtype=np.float64)
    out: FloatArray = rotation_about(k, phi) @ R0
    return out


#: Below this angle (rad), ``θ − sin θ`` is summed from its series (no cancellation):
#: through θ¹³ the series is exact to round-off there, and above it the difference
#: loses at most 2·10⁻¹⁴ of its value.
_SERIES_ANGLE = 0.3
#: Bisection steps for an angle of the ball's set (2^-60 of π: below round-off).
_BISECT_STEPS = 60


def _versine_integral(theta: FloatArray) -> FloatArray:
    """``θ − sin θ`` (the Haar measure of the ball of radius θ, up to a constant)."""
    t = np.asarray(theta, dtype=np.float64)
    t2 = t * t
    series = t * t2 / 6.0  # θ³/3! (1 − θ²/20 (1 − θ²/42 (1 − θ²/72 (1 − θ²/110 (1 − θ²/156)))))
    series = series * (
        1 - t2 / 20 * (1 - t2 / 42 * (1 - t2 / 72 * (1 - t2 / 110 * (1 - t2 / 156))))
    )
    out: FloatArray = np.where(t < _SERIES_ANGLE, series, t - np.sin(t))
    return out


def ball_set(n: int, radius: float) -> FloatArray:
    """``n`` rotations spread evenly over those within ``radius`` of the identity.

    Args:
        n: Number of rotations.
        radius: The largest rotation angle (rad), 0 to π (π: all of SO(3)).

    Returns:
        ``(n, 3, 3)`` rotations (module docs); a target's tolerance set is
        ``R_target @ ball_set(n, radius)``.
    """
    count = _count(n)
    eps = check_number(radius, "tolerance", lo=0.0, hi=math.pi, unit="rad", what="an angle")
    i = np.arange(count, dtype=np.float64)
    goal = (i + 0.5) / count * _versine_integral(np.array(eps))
    lo, hi = np.zeros(count), np.full(count, eps)
    for _ in range(_BISECT_STEPS):
        mid = 0.5 * (lo + hi)
        below = _versine_integral(mid) < goal
        lo, hi = np.where(below, mid, lo), np.where(below, hi, mid)
    angle = 0.5 * (lo + hi)
    order = np.argsort(np.mod(i * _SPIN, 1.0), kind="stable")
    cos_colat = 1.0 - 2.0 * (order + 0.5) / count
    lon = 2.0 * math.pi * np.mod(order / _GOLDEN, 1.0)
    sin_colat = np.sqrt(np.clip(1.0 - cos_colat**2, 0.0, 1.0))
    axes = np.stack([sin_colat * np.cos(lon), sin_colat * np.sin(lon), cos_colat], axis=-1)
    K = np.zeros((count, 3, 3))
    K[:, 0, 1], K[:, 0, 2], K[:, 1, 2] = -axes[:, 2], axes[:, 1], -axes[:, 0]
    K -= np.transpose(K, (0, 2, 1))
    a = angle[:, None, None]
    out: FloatArray = np.eye(3) + np.sin(a) * K + (1.0 - np.cos(a)) * (K @ K)
    return out
