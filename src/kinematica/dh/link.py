"""The DH link matrix ``i-1Ai`` of both conventions, batched.

Standard (Paul, distal: Rot(z)·Tras(z)·Tras(x)·Rot(x), in that order)::

    i-1Ai = Rot(z, θi) · Tras(z, di) · Tras(x, ai) · Rot(x, αi)

Modified (Craig, proximal: Rot(x)·Tras(x)·Rot(z)·Tras(z))::

    i-1Ai = Rot(x, α(i-1)) · Tras(x, a(i-1)) · Rot(z, θi) · Tras(z, di)
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.dh.joints import Convention, check_convention

__all__ = ["link_matrix"]

FloatArray = NDArray[np.float64]


def link_matrix(
    theta: ArrayLike,
    d: ArrayLike,
    a: ArrayLike,
    alpha: ArrayLike,
    convention: Convention = "standard",
) -> FloatArray:
    """Homogeneous link transform from the four DH parameters.

    Args:
        theta: Joint angle about z, radians, shape ``(...)``.
        d: Offset along z, metres, ``(...)``.
        a: Length along x, metres, ``(...)``; ``a_(i-1)`` for ``"modified"``.
        alpha: Twist about x, radians, ``(...)``; ``alpha_(i-1)`` for ``"modified"``.
        convention: ``"standard"`` or ``"modified"``.

    Returns:
        ``(..., 4, 4)`` transform of frame i in frame i-1 (the four inputs broadcast).
    """
    conv = check_convention(convention)
    th, dd, aa, al = np.broadcast_arrays(
        *(np.asarray(v, dtype=float) for v in (theta, d, a, alpha))
    )
    ct, st, ca, sa = np.cos(th), np.sin(th), np.cos(al), np.sin(al)
    A = np.zeros((*th.shape, 4, 4))
    A[..., 3, 3] = 1.0
    if conv == "standard":
        A[..., 0, :] = np.stack([ct, -st * ca, st * sa, aa * ct], -1)
        A[..., 1, :] = np.stack([st, ct * ca, -ct * sa, aa * st], -1)
        A[..., 2, 1] = sa
        A[..., 2, 2] = ca
        A[..., 2, 3] = dd
    else:
        A[..., 0, :] = np.stack([ct, -st, np.zeros_like(ct), aa], -1)
        A[..., 1, :] = np.stack([st * ca, ct * ca, -sa, -sa * dd], -1)
        A[..., 2, :] = np.stack([st * sa, ct * sa, ca, ca * dd], -1)
    return A
