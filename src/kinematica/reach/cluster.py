"""A Dask client for ``scheduler=``: none, a local cluster, or an existing scheduler.

``scheduler=None`` runs in this process; ``"local"`` starts a
``dask.distributed.LocalCluster`` of ``workers`` single-threaded processes
(without Dask's statistical profiler, :data:`WORKER_CONFIG`: it samples the
running task's stack every 10 ms, a thread's work taken from the task's core);
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
    "WORKER_CONFIG",
    "Scheduler",
    "check_workers",
    "dask_client",
    "default_workers",
]

#: ``None`` (this process), ``"local"``, a scheduler address, or a ``distributed.Client``.
Scheduler = Any

#: How long to wait for an existing Dask scheduler to answer.
CONNECT_TIMEOUT = "10s"
#: Dask settings of the workers of a ``"local"`` cluster (the nanny hands them on).
WORKER_CONFIG = {"distributed.worker.profile.enabled": False}

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
            with dask.config.set(WORKER_CONFIG):
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
