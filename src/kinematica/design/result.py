"""The result of a design run: the best design, every evaluation, the Pareto front."""

from __future__ import annotations

import dataclasses
import math
import os
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from kinematica.design.evaluate import Evaluation
from kinematica.design.objectives import MEASURES, Objective
from kinematica.design.task import Task
from kinematica.design.template import DesignTemplate
from kinematica.io import RobotSpec, write_robot_file
from kinematica.robot import Robot

__all__ = ["DesignResult"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class DesignResult:
    """What :func:`kinematica.design.optimize` found.

    Attributes:
        best_params: The best design's variables, ``name -> value``, in the
            template file's units.
        best_robot: The robot at ``best_params``.
        best_value: The objective at the best design: the measure itself for
            one measure (e.g. the worst manipulability, to maximise); the
            weighted sum ``Σ wᵢ·sᵢ·fᵢ`` (lower is better) for several; for a
            Pareto pair, the equal-weight Tchebycheff distance of the chosen
            front point from the ideal point (0 ideal, 1 the worst on the
            front). NaN when no candidate reached every target.
        best: The best design's :class:`Evaluation` (every measure).
        feasible: Some candidate reached every target within the joint
            limits. When none did, ``best_*`` is the candidate that reached
            the most (``best_value`` NaN).
        history: Every evaluation in the order the optimiser asked for it
            (repeats included): ``len(history)`` is at most the budget.
        front: For a Pareto pair, the non-dominated feasible designs found,
            sorted by the first measure (best first); ``None`` otherwise.
        objective: The objective.
        template: The design template.
        task: The task.
        seed: The seed used (drawn at random when none was given).
        evaluated: Evaluations computed by this run.
        reused: Evaluations read from the checkpoint instead.
        message: One sentence for people.
    """

    best_params: Mapping[str, float]
    best_robot: Robot
    best_value: float
    best: Evaluation
    feasible: bool
    history: tuple[Evaluation, ...]
    front: tuple[Evaluation, ...] | None
    objective: Objective
    template: DesignTemplate
    task: Task
    seed: int
    evaluated: int
    reused: int
    message: str

    @property
    def best_values(self) -> dict[str, float]:
        """Every measure at the best design (see :class:`Evaluation`)."""
        return dict(self.best.measures)

    @property
    def best_spec(self) -> RobotSpec:
        """The best design as a robot description (plain parameters, no bounds)."""
        spec = self.template.spec_at(self.best_params)
        note = f"Designed by kinematica.design: {self.objective.describe()} on {self.task.name}"
        text = f"{spec.description.rstrip()}\n{note}" if spec.description else note
        return dataclasses.replace(spec, parameter_bounds={}, description=text)

    def write_robot(self, path: str | os.PathLike[str]) -> None:
        """Write the best design as a robot file (``.yaml``, ``.json`` or ``.toml``).

        The file keeps the template's DH table as written (expressions of the
        parameters) with the parameters as plain numbers: ``km.load`` reads it
        as the designed robot.
        """
        write_robot_file(self.best_spec, path)

    def _repr_html_(self) -> str:
        """The best design against the template: variables and measures, as HTML (Jupyter)."""
        from kinematica.io.html_table import html_table, number

        start = self.template.nominal
        # The search starts from the template's values: its measures when it was evaluated.
        at_start = next((ev.measures for ev in self.history if dict(ev.params) == dict(start)), {})
        rows = [[name, number(start[name]), number(value)]
                for name, value in self.best_params.items()]  # fmt: skip
        rows += [[name, number(at_start[name]) if name in at_start else "", number(value)]
                 for name, value in self.best.measures.items()]  # fmt: skip
        evaluations = len(self.history)
        caption = f"{self.objective.describe()} on {self.task.name}: {evaluations} evaluations"
        return html_table(["", "template", "best"], rows, caption, (self.message,))

    def progress(self) -> FloatArray:
        """Best-so-far over the history, among the designs reaching every target.

        Returns:
            ``(E,)`` the objective's value (in :attr:`best_value`'s sense) for
            one measure or a weighted sum; ``(E, 2)`` each measure's own
            best-so-far for a Pareto pair. NaN until a feasible design is seen.
        """
        feasible = np.array([ev.feasible for ev in self.history], dtype=bool)
        if self.objective.pareto:
            columns = []
            for name in self.objective.names:
                sign = MEASURES[name].sign
                signed = [sign * ev.measures.get(name, math.nan) for ev in self.history]
                columns.append(sign * _running_min(np.array(signed), feasible))
            return np.stack(columns, axis=-1) if columns else np.empty((0, 2))
        scalar = np.array([self.objective.scalar(ev.measures) for ev in self.history])
        best = _running_min(scalar, feasible)
        if len(self.objective.terms) == 1:
            best = MEASURES[self.objective.names[0]].sign * best
        return best


def _running_min(values: FloatArray, feasible: NDArray[np.bool_]) -> FloatArray:
    """Running minimum over the feasible, non-NaN entries; NaN before the first."""
    usable = np.where(feasible & ~np.isnan(values), values, np.inf)
    out = np.minimum.accumulate(usable) if usable.size else usable
    return np.where(np.isinf(out) & (out > 0), np.nan, out)
