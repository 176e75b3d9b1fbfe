"""How kinematica compiles its kernels, and how many threads a batch uses.

Every kernel is compiled by numba on first use and cached on disk: in the
package's ``__pycache__`` where that is writable, else in numba's per-user
cache directory (``$XDG_CACHE_HOME/numba`` or ``~/.cache/numba`` on Linux);
``NUMBA_CACHE_DIR`` overrides both. A cache entry is keyed by the source of
every kernel (see :class:`_KernelCache`). ``error_model="numpy"`` makes a
division by zero give inf/NaN as numpy does, never an exception inside a
kernel. No ``fastmath``: it would break NaN handling and the 1e-12 agreement
with the references.
"""

from __future__ import annotations

import functools
import hashlib
import os
from collections.abc import Callable
from pathlib import Path
from typing import Any, TypeVar

import numba
import numpy as np
from numba.core.caching import FunctionCache
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
    "sources_fingerprint",
]

F = TypeVar("F", bound=Callable[..., Any])

#: Type hints of kernel arguments (numba reads none of them).
Array = NDArray[np.float64]
IntArray = NDArray[np.int64]
ComplexArray = NDArray[np.complex128]

#: Environment variable holding the library-wide default number of threads of
#: a batch (all cores when unset).
WORKERS_ENV = "KINEMATICA_WORKERS"


@functools.cache
def sources_fingerprint() -> str:
    """A hash of every source file of :mod:`kinematica.kernels` (read once, at import)."""
    root = Path(__file__).parent
    digest = hashlib.sha256()
    for path in sorted(root.rglob("*.py")):
        digest.update(path.relative_to(root).as_posix().encode() + b"\0")
        digest.update(path.read_bytes())
    return digest.hexdigest()


class _KernelCache(FunctionCache):
    """numba's on-disk cache of one kernel, keyed also by every kernel source.

    numba keys a cache entry by the source file of the kernel alone, yet the
    compiled code holds the kernels it calls or inlines from other files
    (``walk_row`` is inside every IK check): after an edit or an upgrade that
    changed only those, numba would load stale machine code (a documented
    numba limitation). Adding the fingerprint of every kernel source to the
    key closes that gap: any change to any kernel recompiles each on its next
    first use.
    """

    def _index_key(self, sig: Any, codegen: Any) -> tuple[Any, ...]:
        return (*super()._index_key(sig, codegen), sources_fingerprint())


def _compile(fn: Callable[..., Any], **options: Any) -> Any:
    """``numba.njit(**options)(fn)``, cached on disk by :class:`_KernelCache`."""
    sources_fingerprint()  # read as the kernels are defined: the sources this process runs
    dispatcher = numba.njit(nogil=True, error_model="numpy", **options)(fn)
    dispatcher._cache = _KernelCache(fn)  # what cache=True does, with our key
    return dispatcher


def kernel(fn: F) -> F:
    """Compile ``fn`` as a scalar kernel (one configuration or one target)."""
    return _compile(fn)


def inline_kernel(fn: F) -> F:
    """Compile ``fn`` as a small kernel inlined into its callers (tight loops)."""
    return _compile(fn, inline="always")


def batch_kernel(fn: F) -> F:
    """Compile ``fn`` as a batch kernel: its ``numba.prange`` loops run in threads."""
    return _compile(fn, parallel=True)


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
