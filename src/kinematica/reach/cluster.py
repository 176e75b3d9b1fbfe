"""A Dask client for ``scheduler=``: none, a local cluster, or an existing scheduler.

``scheduler=None`` runs in this process; ``"local"`` starts a
``dask.distributed.LocalCluster`` of ``workers`` single-threaded processes, set
up for kinematica's tasks (:func:`worker_config`);
``"tcp://host:port"`` connects to a scheduler already running (on this machine
or on many); a ``distributed.Client`` is used as it is and left open.
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

from kinematica.errors import ArgumentError, KinematicaError

__all__ = [
    "CONNECT_TIMEOUT",
    "MALLOC_MMAP_THRESHOLD",
    "MALLOC_TRIM_THRESHOLD",
    "Scheduler",
    "check_workers",
    "dask_client",
    "default_workers",
    "worker_config",
]

#: ``None`` (this process), ``"local"``, a scheduler address, or a ``distributed.Client``.
Scheduler = Any

#: How long to wait for an existing Dask scheduler to answer.
CONNECT_TIMEOUT = "10s"
#: glibc's malloc settings of a ``"local"`` cluster's workers (bytes): memory freed
#: stays with the process up to the trim threshold, and arrays below the mmap
#: threshold come from its heap (see :func:`worker_config`).
MALLOC_TRIM_THRESHOLD = 64 << 20
MALLOC_MMAP_THRESHOLD = 32 << 20


def worker_config() -> dict[str, Any]:
    """Dask settings for the workers of a ``"local"`` cluster (the nanny hands them on).

    * No statistical profiler: it samples the running task's stack every 10 ms,
      a thread's work taken from the task's core.
    * glibc's malloc thresholds (:data:`MALLOC_TRIM_THRESHOLD`,
      :data:`MALLOC_MMAP_THRESHOLD`) in the environment the nanny starts a
      worker with. Dask sets ``MALLOC_TRIM_THRESHOLD_=65536`` there, which
      also freezes glibc's mmap threshold at 128 KiB: every array of a block
      of IK (a few MB each) is then mapped afresh and faulted in page by page.
      Measured on a 2-million-pose UR5 map: 410,000 page faults and 0.83 s of
      system time in a worker against 181,000 and 0.43 s serially; with these
      thresholds 3,800 and 0.02 s, and the worker's CPU time 11 % below the
      serial run's instead of 16 % above it.

    Returns:
        The settings, for ``dask.config.set``.
    """
    import dask

    environ = dict(dask.config.get("distributed.nanny.pre-spawn-environ", default={}) or {})
    environ.update(
        MALLOC_TRIM_THRESHOLD_=MALLOC_TRIM_THRESHOLD, MALLOC_MMAP_THRESHOLD_=MALLOC_MMAP_THRESHOLD
    )
    return {
        "distributed.worker.profile.enabled": False,
        "distributed.nanny.pre-spawn-environ": environ,
    }


_NEEDS_DASK = (
    "scheduler={!r} needs dask.distributed: pip install 'kinematica[dask]' "
    "(or pip install 'dask[distributed]')"
)


def default_workers() -> int:
    """The cores this process may use (the size of a default local cluster)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # not on Linux
        return max(1, os.cpu_count() or 1)


def check_workers(workers: object, scheduler: Scheduler) -> tuple[Scheduler, int | None]:
    """``(scheduler, workers)`` checked: ``workers`` alone implies ``"local"``.

    Raises:
        ArgumentError: ``workers`` is not a positive whole number, or is given
            with another scheduler than ``"local"``.
    """
    if workers is None:
        return scheduler, None
    if isinstance(workers, bool) or not isinstance(workers, int) or workers < 1:
        raise ArgumentError(
            f"workers must be a positive whole number, got {workers!r}", arg="workers"
        )
    if scheduler is None:
        scheduler = "local"
    if scheduler != "local":
        raise ArgumentError(
            "workers sets the size of a local cluster: use scheduler='local'", arg="workers"
        )
    return scheduler, workers


@contextmanager
def dask_client(scheduler: Scheduler, workers: int | None = None) -> Iterator[Any]:
    """A ``distributed.Client`` for ``scheduler`` (None for ``None``), closed after if ours.

    Args:
        scheduler: ``None``, ``"local"``, ``"tcp://host:port"`` or a Client.
        workers: Processes of a ``"local"`` cluster (default: :func:`default_workers`).

    Raises:
        KinematicaError: dask.distributed is not installed, the cluster does not
            start, the scheduler does not answer, or ``scheduler`` is none of these.
    """
    if scheduler is None:
        yield None
        return
    if not isinstance(scheduler, str):
        if hasattr(scheduler, "submit") and hasattr(scheduler, "scatter"):
            yield scheduler
            return
        raise KinematicaError(
            "scheduler must be None, 'local', an address such as 'tcp://host:8786', "
            f"or a dask.distributed Client; got {scheduler!r}"
        )
    try:
        import dask
        from dask.distributed import Client, LocalCluster
    except ImportError as exc:
        raise KinematicaError(_NEEDS_DASK.format(scheduler)) from exc
    cluster = None
    if scheduler == "local":
        try:
            with dask.config.set(worker_config()):
                cluster = LocalCluster(
                    n_workers=workers or default_workers(),
                    threads_per_worker=1,
                    processes=True,
                    dashboard_address=None,
                )
        except Exception as exc:  # distributed raises bare RuntimeErrors here
            raise KinematicaError(
                f"could not start a local Dask cluster ({type(exc).__name__}: {exc}); "
                "in a script, run it under `if __name__ == '__main__':` "
                "(worker processes import the main module)"
            ) from exc
        client = Client(cluster)
    else:
        try:
            client = Client(scheduler, timeout=CONNECT_TIMEOUT)
        except (OSError, TimeoutError, ValueError) as exc:
            raise KinematicaError(
                f"cannot reach the Dask scheduler at {scheduler!r}: {exc}"
            ) from exc
    try:
        yield client
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
