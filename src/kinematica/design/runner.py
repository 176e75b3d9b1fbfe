"""Running candidate evaluations: here, or on a Dask cluster; cached, checkpointed.

The optimiser hands a :class:`Runner` whole generations of candidates. The
runner serves each from its cache (evaluations of this run, or read from the
checkpoint), computes the others in this process (``scheduler=None``) or on a
``dask.distributed`` cluster (``"local"``: a LocalCluster started here;
``"tcp://host:port"``: an existing scheduler; or a ``distributed.Client``), and
writes each to the checkpoint as soon as it is finished. Results come back in
the order asked, whatever order the workers finish in, and every evaluation is
a pure function of the candidate: the optimiser's path does not depend on the
number of workers.
"""

from __future__ import annotations

import hashlib
import os
import sys
from collections.abc import Sequence
from types import TracebackType
from typing import Any

import numpy as np
from numpy.typing import NDArray

from kinematica.design.checkpoint import VERSION, Checkpoint
from kinematica.design.evaluate import Evaluation, evaluate_design
from kinematica.design.measures import IK_SEED
from kinematica.design.task import Task
from kinematica.design.template import DesignTemplate
from kinematica.errors import KinematicaError

__all__ = ["Runner", "Scheduler"]

FloatArray = NDArray[np.float64]
Key = tuple[float, ...]
#: ``None`` (this process), ``"local"``, a scheduler address, or a ``distributed.Client``.
Scheduler = Any

#: How long to wait for an existing Dask scheduler to answer.
CONNECT_TIMEOUT = "10s"

_NEEDS_DASK = (
    "scheduler={!r} needs dask.distributed: pip install 'kinematica[dask]' "
    "(or pip install 'dask[distributed]')"
)


def fingerprint(template: DesignTemplate, task: Task) -> str:
    """What an evaluation depends on: template, task, measures' version, IK seed."""
    text = f"{template.fingerprint}|{task.fingerprint}|{VERSION}|{IK_SEED}"
    return hashlib.sha256(text.encode()).hexdigest()


def _default_workers() -> int:
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # not on Linux
        return max(1, os.cpu_count() or 1)


class Runner:
    """Evaluates candidates for one run (a context manager).

    Args:
        template: The design template.
        task: The task.
        scheduler: ``None``, ``"local"``, ``"tcp://host:port"`` or a
            ``distributed.Client`` (left open).
        workers: Worker processes of a ``"local"`` cluster (default: the
            cores this process may use). Given alone, it implies ``"local"``.
        checkpoint: A checkpoint file to resume from and append to, or ``None``.
        progress: Show a tqdm progress bar (``None``: when stderr is a terminal).
        total: The number of evaluations the bar counts to.
    """

    def __init__(
        self,
        template: DesignTemplate,
        task: Task,
        *,
        scheduler: Scheduler = None,
        workers: int | None = None,
        checkpoint: str | os.PathLike[str] | None = None,
        progress: bool | None = None,
        total: int = 0,
    ) -> None:
        if workers is not None and (
            isinstance(workers, bool) or not isinstance(workers, int) or workers < 1
        ):
            raise KinematicaError(f"workers must be a positive whole number, got {workers!r}")
        if workers is not None and scheduler is None:
            scheduler = "local"
        if workers is not None and scheduler != "local":
            raise KinematicaError("workers sets the size of a local cluster: use scheduler='local'")
        self.template = template
        self.task = task
        self.scheduler = scheduler
        self.workers = workers
        self.cache: dict[Key, Evaluation] = {}
        self.evaluated = 0  # computed in this run
        self.reused = 0  # taken from the checkpoint
        self._from_checkpoint: set[Key] = set()
        self._checkpoint = (
            None
            if checkpoint is None
            else Checkpoint(checkpoint, fingerprint(template, task), template.names)
        )
        if self._checkpoint is not None:
            self.cache.update(self._checkpoint.found)
            self._from_checkpoint = set(self._checkpoint.found)
        self._progress = progress
        self._total = total
        self._bar: Any = None
        self._client: Any = None
        self._cluster: Any = None
        self._remote: tuple[Any, Any] | None = None

    # ------------------------------------------------------------- lifecycle
    def __enter__(self) -> Runner:
        try:
            self._start_bar()
            self._start_cluster()
        except BaseException:
            self.close()
            raise
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self.close()

    def close(self) -> None:
        """Close the progress bar, the checkpoint, and a cluster started here."""
        if self._bar is not None:
            self._bar.close()
            self._bar = None
        if self._checkpoint is not None:
            self._checkpoint.close()
            self._checkpoint = None
        owned = self._cluster is not None or isinstance(self.scheduler, str)
        if self._client is not None and owned:
            self._client.close()
        if self._cluster is not None:
            self._cluster.close()
        self._client = self._cluster = self._remote = None

    def _start_bar(self) -> None:
        show = sys.stderr.isatty() if self._progress is None else self._progress
        if not show:
            return
        try:
            from tqdm.auto import tqdm
        except ImportError as exc:
            if self._progress:
                raise KinematicaError(
                    "progress=True needs tqdm: pip install 'kinematica[design]'"
                ) from exc
            return
        self._bar = tqdm(total=self._total, desc="design", unit="eval", file=sys.stderr)

    def _start_cluster(self) -> None:
        scheduler = self.scheduler
        if scheduler is None:
            return
        if isinstance(scheduler, str):
            try:
                from dask.distributed import Client, LocalCluster
            except ImportError as exc:
                raise KinematicaError(_NEEDS_DASK.format(scheduler)) from exc
            if scheduler == "local":
                try:
                    self._cluster = LocalCluster(
                        n_workers=self.workers or _default_workers(),
                        threads_per_worker=1,
                        processes=True,
                        dashboard_address=None,
                    )
                except Exception as exc:  # distributed raises bare RuntimeErrors here
                    raise KinematicaError(
                        f"could not start a local Dask cluster ({type(exc).__name__}: {exc}); "
                        "in a script, call optimize under `if __name__ == '__main__':` "
                        "(worker processes import the main module)"
                    ) from exc
                self._client = Client(self._cluster)
            else:
                try:
                    self._client = Client(scheduler, timeout=CONNECT_TIMEOUT)
                except (OSError, TimeoutError, ValueError) as exc:
                    raise KinematicaError(
                        f"cannot reach the Dask scheduler at {scheduler!r}: {exc}"
                    ) from exc
        elif hasattr(scheduler, "submit") and hasattr(scheduler, "scatter"):
            self._client = scheduler
        else:
            raise KinematicaError(
                "scheduler must be None, 'local', an address such as 'tcp://host:8786', "
                f"or a dask.distributed Client; got {scheduler!r}"
            )
        template, task = self._client.scatter([self.template, self.task], broadcast=True)
        self._remote = (template, task)

    # ------------------------------------------------------------ evaluation
    def _done(self, key: Key, ev: Evaluation) -> None:
        self.cache[key] = ev
        self.evaluated += 1
        if self._checkpoint is not None:
            self._checkpoint.append(ev)

    def evaluate(self, X: FloatArray) -> list[Evaluation]:
        """Evaluate the candidates ``X`` ``(S, p)``; results in the same order.

        Candidates are clipped into the template's bounds first: the optimiser's
        scaling of a unit cube back to the bounds may overshoot by a rounding.
        """
        inside = np.clip(np.asarray(X, dtype=float), self.template.lower, self.template.upper)
        keys = [tuple(float(v) for v in row) for row in inside]
        todo: list[Key] = []
        for key in keys:
            if key in self.cache:
                if key in self._from_checkpoint:
                    self._from_checkpoint.discard(key)
                    self.reused += 1
            elif key not in todo:
                todo.append(key)
        if self._client is None:
            for key in todo:
                self._done(key, evaluate_design(self.template, self.task, np.array(key)))
                self._tick(1)
        else:
            self._evaluate_remote(todo)
        self._tick(len(keys) - len(todo))
        return [self.cache[key] for key in keys]

    def _evaluate_remote(self, todo: Sequence[Key]) -> None:
        if not todo:
            return
        from dask.distributed import as_completed

        assert self._remote is not None
        template, task = self._remote
        futures = [
            self._client.submit(evaluate_design, template, task, np.array(key), pure=False)
            for key in todo
        ]
        index = {f.key: i for i, f in enumerate(futures)}
        for future in as_completed(futures):
            self._done(todo[index[future.key]], future.result())
            self._tick(1)

    def _tick(self, n: int) -> None:
        if self._bar is not None and n > 0:
            self._bar.update(n)
