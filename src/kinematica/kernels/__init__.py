"""numba-compiled kernels: each algorithm once, over one configuration or target.

A batch runs the same scalar kernel in a parallel loop; a single call calls it
directly. Kernels take arrays (a :class:`kinematica.dh.DHChain`'s ``links`` and
``ends``, solver parameters), never Python objects.
"""

from kinematica.kernels._numba import WORKERS_ENV, resolve_workers, set_workers
from kinematica.kernels.calls import fk, jacobian, joint_axes

__all__ = ["WORKERS_ENV", "fk", "jacobian", "joint_axes", "resolve_workers", "set_workers"]
