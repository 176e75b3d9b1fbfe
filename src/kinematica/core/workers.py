"""How many threads a batch uses: ``workers=``, ``KINEMATICA_WORKERS``, or every core.

A batch tells the core how many threads it may use; nothing here changes a
process-wide setting, and a single configuration or target never starts a thread.
"""

from __future__ import annotations

import os

import kinematica._core as _core
from kinematica.errors import ArgumentError

__all__ = ["WORKERS_ENV", "resolve_workers"]

#: Environment variable holding the library-wide default number of threads of a
#: batch (every core when unset).
WORKERS_ENV = "KINEMATICA_WORKERS"


def resolve_workers(workers: int | None) -> int:
    """The number of threads for a batch: ``workers``, the default, or all cores.

    Args:
        workers: Threads asked for, or ``None`` for the library-wide default (the
            ``KINEMATICA_WORKERS`` environment variable, else every core).

    Returns:
        A thread count between 1 and the number of cores.

    Raises:
        ArgumentError: When ``workers`` (or the environment variable) is not a
            positive whole number (``arg="workers"``).
    """
    limit = _core.hardware_threads()
    if workers is None:
        text = os.environ.get(WORKERS_ENV, "").strip()
        if not text:
            return limit
        try:
            workers = int(text)
        except ValueError:
            raise ArgumentError(
                f"{WORKERS_ENV} must be a whole number of threads, got {text!r}", arg="workers"
            ) from None
    if isinstance(workers, bool) or not isinstance(workers, int) or workers < 1:
        raise ArgumentError(
            f"workers must be a positive whole number, got {workers!r}", arg="workers"
        )
    return min(workers, limit)
