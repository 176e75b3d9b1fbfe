"""Array copies inside kernels, as loops.

numba compiles ``a[:] = b`` between arrays through its general broadcasting
machinery: about two seconds of compile time per call site, against a few
milliseconds for the loop. (Filling with a scalar, ``a[:] = 0.0``, is cheap.)
"""

from __future__ import annotations

from kinematica.kernels._numba import Array, kernel

__all__ = ["copy1", "copy2"]


@kernel
def copy1(dst: Array, src: Array) -> None:
    """``dst[i] = src[i]`` for ``(n,)`` arrays."""
    for i in range(dst.shape[0]):
        dst[i] = src[i]


@kernel
def copy2(dst: Array, src: Array) -> None:
    """``dst[i, j] = src[i, j]`` for ``(m, n)`` arrays."""
    for i in range(dst.shape[0]):
        for j in range(dst.shape[1]):
            dst[i, j] = src[i, j]
