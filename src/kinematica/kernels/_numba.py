"""How kinematica compiles its kernels, and how many threads a batch uses.

Every kernel is compiled by numba on first use and cached on disk
(``cache=True``): in the package's ``__pycache__`` where that is writable, else
in numba's per-user cache directory (``NUMBA_CACHE_DIR`` overrides both).
``error_model="numpy"`` makes a division by zero give inf/NaN as numpy does,
never an exception inside a kernel. No ``fastmath``: it would break NaN
handling and the 1e-12 agreement with the references.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from typing import Any, TypeVar

import numba
import numpy as np
from numpy.typing import NDArray

__all__ = [
    "WORKERS_ENV",
    "Array",
    "ComplexArray",
    "IntArray",
    "batch_kernel",
    "inline_kernel",
    "kernel",
    "resolve_workers",
    "set_workers",
]

F = TypeVar("F", bound=Callable[..., Any])

#: Type hints of kernel arguments (numba reads none of them).
Array = NDArray[np.float64]
IntArray = NDArray[np.int64]
ComplexArray = NDArray[np.complex128]

#: Environment variable holding the library-wide default number of threads of
#: a batch (all cores when unset).
WORKERS_ENV = "KINEMATICA_WORKERS"


def kernel(fn: F) -> F:
    """Compile ``fn`` as a scalar kernel (one configuration or one target)."""
    return numba.njit(cache=True, nogil=True, error_model="numpy")(fn)  # type: ignore[return-value]


def inline_kernel(fn: F) -> F:
    """Compile ``fn`` as a small kernel inlined into its callers (tight loops)."""
    return numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")(fn)  # type: ignore[return-value]


def batch_kernel(fn: F) -> F:
    """Compile ``fn`` as a batch kernel: its ``numba.prange`` loops run in threads."""
    return numba.njit(cache=True, nogil=True, error_model="numpy", parallel=True)(fn)  # type: ignore[return-value]


def resolve_workers(workers: int | None) -> int:
    """The number of threads for a batch: ``workers``, the default, or all cores.

    Args:
        workers: Threads asked for, or ``None`` for the library-wide default
            (the ``KINEMATICA_WORKERS`` environment variable, else every core).

    Returns:
        A thread count between 1 and the number of cores numba may use.

    Raises:
        ValueError: When ``workers`` (or the environment variable) is not a
            positive whole number.
    """
    limit = int(numba.config.NUMBA_NUM_THREADS)  # type: ignore[attr-defined]
    if workers is None:
        text = os.environ.get(WORKERS_ENV, "").strip()
        if not text:
            return limit
        try:
            workers = int(text)
        except ValueError:
            raise ValueError(
                f"{WORKERS_ENV} must be a whole number of threads, got {text!r}"
            ) from None
    if isinstance(workers, bool) or not isinstance(workers, int) or workers < 1:
        raise ValueError(f"workers must be a positive whole number, got {workers!r}")
    return min(workers, limit)


def set_workers(workers: int | None) -> None:
    """Use ``workers`` threads (see :func:`resolve_workers`) for the next batch kernels."""
    numba.set_num_threads(resolve_workers(workers))
