"""One candidate design on the task: the pure function every worker runs.

:func:`evaluate_design` builds the robot at the candidate's parameter values,
solves IK for the whole task batch and returns an :class:`Evaluation`: the measures of
:data:`~kinematica.design.objectives.MEASURES` it is asked for (``needs=``; all
by default), and always the manipulability, ``total_length`` and ``reached``,
so that a checkpoint serves a later run on the same template and task (one
that needs a measure an evaluation lacks computes it again). The robot comes
from the template compiled once (:mod:`kinematica.design.compiled`), not from
its file read again. It depends on nothing but its arguments (the numeric IK seed is fixed),
so a candidate gets the very same numbers in this process, on any Dask worker,
and when read back from a checkpoint.
"""

from __future__ import annotations

from collections.abc import Collection, Mapping
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from kinematica.design.measures import measure_task, total_length
from kinematica.design.reachmeasures import ReachSettings, reach_measures
from kinematica.design.task import Task
from kinematica.design.template import DesignTemplate

__all__ = ["Evaluation", "evaluate_design"]


@dataclass(frozen=True)
class Evaluation:
    """A candidate design and how it does on the task.

    Attributes:
        params: The design variables, ``name -> value`` (template file units).
        measures: ``min_manipulability``, ``mean_manipulability``,
            ``worst_condition``, ``singularity_clearance`` (over the reached
            targets; NaN if none; the last two only when asked for),
            ``total_length`` (m) and ``reached`` (share of the targets reached
            within the joint limits).
        violation: Share of the targets not reached plus their mean distance
            outside the reach (m, where known); 0 for a feasible design.
    """

    params: Mapping[str, float]
    measures: Mapping[str, float]
    violation: float

    @property
    def feasible(self) -> bool:
        """Every target is reached within the joint limits."""
        return self.violation == 0.0

    @property
    def x(self) -> tuple[float, ...]:
        """The design variables as a tuple, in template order."""
        return tuple(self.params.values())


def evaluate_design(
    template: DesignTemplate,
    task: Task,
    x: ArrayLike,
    reach: ReachSettings | None = None,
    needs: Collection[str] | None = None,
    threads: int | None = None,
) -> Evaluation:
    """Measure the design ``x`` of ``template`` on ``task``.

    Args:
        template: The design template.
        task: The targets, in the robot's base frame.
        x: ``(p,)`` values of the design variables (``template.names`` order,
            file units), within their bounds.
        reach: Also measure ``dexterous_volume`` and ``task_reachability``
            (:mod:`kinematica.design.reachmeasures`) this way; None: not.
        needs: The measures the caller reads (names of
            :data:`~kinematica.design.objectives.MEASURES`); None: all.
        threads: Core threads of its batches (None: the library default).

    Returns:
        The evaluation.
    """
    xa = np.asarray(x, dtype=float)
    params = template.params(xa)
    robot = template.compiled.robot(xa)
    found = measure_task(robot, task, needs, threads)
    measures = found.summary()
    measures["total_length"] = total_length(robot)
    if reach is not None:
        measures.update(reach_measures(robot, task, reach, threads))
    return Evaluation(params=params, measures=measures, violation=found.violation)
