"""Running candidate evaluations: here, or on a Dask cluster; cached, checkpointed.

The optimiser hands a :class:`Runner` whole generations of candidates. The
runner serves each from its cache (evaluations of this run, or read from the
checkpoint), computes the others in this process (``scheduler=None``) or on a
``dask.distributed`` cluster (``"local"``: a LocalCluster started here;
``"tcp://host:port"``: an existing scheduler; or a ``distributed.Client``;
:func:`kinematica.reach.cluster.dask_client`), a generation's candidates in
runs of up to :data:`CANDIDATES_PER_TASK` a Dask task (about two tasks a
worker), and writes each to the checkpoint as soon as its run is finished. Results come back in
the order asked, whatever order the workers finish in, and every evaluation is
a pure function of the candidate: the optimiser's path does not depend on the
number of workers.
"""

from __future__ import annotations

import hashlib
import math
import os
import sys
from collections.abc import Collection, Sequence
from contextlib import ExitStack
from types import TracebackType
from typing import Any

import numpy as np
from numpy.typing import NDArray

from kinematica.design.checkpoint import VERSION, Checkpoint
from kinematica.design.evaluate import Evaluation, evaluate_design
from kinematica.design.measures import IK_SEED
from kinematica.design.objectives import MEASURES
from kinematica.design.reachmeasures import REACH_MEASURES, ReachSettings
from kinematica.design.task import Task
from kinematica.design.template import DesignTemplate
from kinematica.errors import KinematicaError
from kinematica.reach.cluster import Scheduler, check_workers, dask_client, default_workers

__all__ = ["CANDIDATES_PER_TASK", "Runner", "Scheduler", "balanced_runs"]

FloatArray = NDArray[np.float64]
Key = tuple[float, ...]

#: Dask tasks per worker for one generation: each task evaluates a run of
#: candidates, so that a task's overhead (a few ms) is small against its work.
TASKS_PER_WORKER = 2
#: Most candidates in one Dask task (a checkpoint records them when it returns).
CANDIDATES_PER_TASK = 16


def fingerprint(template: DesignTemplate, task: Task, reach: ReachSettings | None = None) -> str:
    """What an evaluation depends on: template, task, measures' version, IK seed, reach."""
    text = f"{template.fingerprint}|{task.fingerprint}|{VERSION}|{IK_SEED}"
    if reach is not None:
        text += f"|{reach.key}"
    return hashlib.sha256(text.encode()).hexdigest()


def balanced_runs(todo: Sequence[Key], workers: int) -> list[list[Key]]:
    """``todo`` cut into runs of sizes differing by one at most, in order.

    ``TASKS_PER_WORKER`` runs a worker (fewer if there are fewer candidates),
    more if a run would hold over :data:`CANDIDATES_PER_TASK`: a generation of 10
    on 2 workers is 4 runs of 3, 3, 2, 2 (5 a worker), not 3, 3, 3, 1 (6 on one
    worker, 4 on the other, which caps the speed-up at 10/6).
    """
    count = len(todo)
    runs = max(math.ceil(count / CANDIDATES_PER_TASK), min(count, TASKS_PER_WORKER * workers))
    if runs == 0:
        return []
    base, extra = divmod(count, runs)
    out, start = [], 0
    for i in range(runs):
        size = base + (1 if i < extra else 0)
        out.append(list(todo[start : start + size]))
        start += size
    return out


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
        reach: The reachability measures' settings (None: not measured).
        needs: The measures the run reads (None: all); an evaluation (from the
            checkpoint) lacking one of them is computed again.
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
        reach: ReachSettings | None = None,
        needs: Collection[str] | None = None,
    ) -> None:
        scheduler, workers = check_workers(workers, scheduler)
        self.needs = None if needs is None else tuple(sorted(set(needs)))
        self.template = template
        self.task = task
        self.reach = reach
        self.scheduler = scheduler
        self.workers = workers
        self.cache: dict[Key, Evaluation] = {}
        self.evaluated = 0  # computed in this run
        self.reused = 0  # taken from the checkpoint
        self._from_checkpoint: set[Key] = set()
        self._checkpoint = (
            None
            if checkpoint is None
            else Checkpoint(checkpoint, fingerprint(template, task, reach), template.names)
        )
        if self._checkpoint is not None:
            self.cache.update(self._checkpoint.found)
            self._from_checkpoint = set(self._checkpoint.found)
        self._progress = progress
        self._total = total
        self._bar: Any = None
        self._client: Any = None
        self._stack = ExitStack()
        self._remote: tuple[Any, Any] | None = None
        self._workers = 1

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
        self._stack.close()  # closes a client and a cluster started here, not one given
        self._client = self._remote = None

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
        self._client = self._stack.enter_context(dask_client(self.scheduler, self.workers))
        if self._client is None:
            return
        self._workers = self.workers or (
            default_workers()
            if self.scheduler == "local"
            else max(1, len(self._client.scheduler_info().get("workers", {})))
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
            if key in self.cache and not self._lacks(self.cache[key]):
                if key in self._from_checkpoint:
                    self._from_checkpoint.discard(key)
                    self.reused += 1
            elif key not in todo:
                todo.append(key)
        if self._client is None:
            for key in todo:
                ev = evaluate_design(
                    self.template, self.task, np.array(key), self.reach, self.needs
                )
                self._done(key, ev)
                self._tick(1)
        else:
            self._evaluate_remote(todo)
        self._tick(len(keys) - len(todo))
        return [self.cache[key] for key in keys]

    def _lacks(self, ev: Evaluation) -> bool:
        """Whether ``ev`` lacks a measure this run reads (one evaluated with fewer)."""
        needs = MEASURES if self.needs is None else self.needs
        return any(
            name not in ev.measures
            for name in needs
            if name not in REACH_MEASURES or self.reach is not None
        )

    def _evaluate_remote(self, todo: Sequence[Key]) -> None:
        if not todo:
            return
        from dask.distributed import as_completed

        assert self._remote is not None
        template, task = self._remote
        runs = balanced_runs(todo, self._workers)
        futures = [
            self._client.submit(
                _evaluate_run, template, task, np.array(run), self.reach, self.needs, pure=False
            )
            for run in runs
        ]
        index = {f.key: i for i, f in enumerate(futures)}
        for future in as_completed(futures):
            run = runs[index[future.key]]
            for key, ev in zip(run, future.result(), strict=True):
                self._done(key, ev)
            self._tick(len(run))

    def _tick(self, n: int) -> None:
        if self._bar is not None and n > 0:
            self._bar.update(n)


def _evaluate_run(
    template: DesignTemplate,
    task: Task,
    X: FloatArray,
    reach: ReachSettings | None,
    needs: Collection[str] | None,
) -> list[Evaluation]:
    """Candidates ``X`` ``(s, p)`` one after the other: one Dask task (one core thread)."""
    return [evaluate_design(template, task, x, reach, needs, threads=1) for x in X]
