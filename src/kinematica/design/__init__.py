"""Robot design: link lengths for a task ("dimensiones óptimas de los eslabones").

A *design template* is a robot file whose parameters carry bounds
(``l1: {value: 0.3, min: 0.1, max: 0.9}``; others may be expressions of them,
``l2: 1 - l1``). A *task* is the targets the arm must reach (positions or
poses, from a file, an array or a sampled region). :func:`optimize` searches
the bounded parameters by differential evolution for the best objective
(worst or mean manipulability, condition number, singularity clearance, total
length; with :class:`ReachSettings`, the dexterous volume in a region and the
task's reachability index within an orientation tolerance; weighted sums; a
Pareto front of two), with every target reached within
the joint limits as a hard constraint; candidates run here or on a Dask
cluster, with a checkpoint to resume from. Needs the ``design`` extra (scipy,
tqdm); Dask needs the ``dask`` extra::

    from kinematica import design

    res = design.optimize("arm.yaml", design.Task.ring(0.6, 32),
                          objective="min_manipulability", budget=200, seed=1)
    res.best_params, res.best_value
    res.write_robot("best.yaml")
"""

from kinematica.design.checkpoint import CheckpointError
from kinematica.design.evaluate import Evaluation, evaluate_design
from kinematica.design.measures import (
    TaskMeasures,
    generic_rank,
    measure_task,
    task_singular_values,
    total_length,
)
from kinematica.design.objectives import MEASURES, Measure, Objective
from kinematica.design.optimize import optimize
from kinematica.design.reachmeasures import ReachSettings, reach_measures, task_reachability
from kinematica.design.result import DesignResult
from kinematica.design.task import Task, TaskError
from kinematica.design.taskfile import as_task, load_task
from kinematica.design.template import DesignTemplate, load_template

__all__ = [
    "MEASURES",
    "CheckpointError",
    "DesignResult",
    "DesignTemplate",
    "Evaluation",
    "Measure",
    "Objective",
    "ReachSettings",
    "Task",
    "TaskError",
    "TaskMeasures",
    "as_task",
    "evaluate_design",
    "generic_rank",
    "load_task",
    "load_template",
    "measure_task",
    "optimize",
    "reach_measures",
    "task_reachability",
    "task_singular_values",
    "total_length",
]
