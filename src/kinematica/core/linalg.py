"""Small dense linear algebra the layers share, in the core: singular values of a batch.

``singular_values`` is the core's one-sided Jacobi (``cpp/include/kinematica/singular.hpp``),
the same scalar function :meth:`kinematica.core.Chain.singular_values` runs on each
Jacobian; here it takes matrices of any origin, batched.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

import kinematica._core as _core
from kinematica.core.workers import resolve_workers

__all__ = ["singular_values"]

FloatArray = NDArray[np.float64]


def singular_values(A: FloatArray, workers: int | None = None) -> FloatArray:
    """The singular values of ``A (..., m, n)``, largest first, ``min(m, n) <= 6``.

    Args:
        A: ``(..., m, n)`` float matrices.
        workers: Threads for a batch (None: the library default).

    Returns:
        ``(..., min(m, n))``; NaN for a matrix holding NaN/inf.

    Raises:
        ValueError: ``A`` is not of rank 2 or more, or both its sides exceed 6.
    """
    a = np.asarray(A, dtype=np.float64)
    if a.ndim < 2:
        raise ValueError(f"A must be (..., m, n) matrices, got shape {a.shape}")
    m, n = a.shape[-2:]
    S = _core.singular_values(a.reshape(-1, m, n), resolve_workers(workers))
    return S.reshape(*a.shape[:-2], S.shape[-1])
