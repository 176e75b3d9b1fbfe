"""The compiled core as the layers above use it: chains and the threads of a batch.

The algorithms themselves live once, in C++17 (``cpp/include/kinematica``), compiled
into the extension :mod:`kinematica._core` when the package is installed; this
package holds the Python side of what every layer shares: a :class:`Chain` (the
compiled chain with the joint facts Python needs) and :func:`resolve_workers`.
"""

from kinematica.core.chain import Chain
from kinematica.core.linalg import singular_values
from kinematica.core.workers import WORKERS_ENV, resolve_workers

__all__ = ["WORKERS_ENV", "Chain", "resolve_workers", "singular_values"]
