"""Objectives a designer states: one measure, a weighted sum, or a Pareto pair.

Measures of a design on a task (see :mod:`kinematica.design.measures`):

=========================  ========  ===============================================
name                       sense     value
=========================  ========  ===============================================
``min_manipulability``     maximise  the worst (smallest) manipulability over the task
``mean_manipulability``    maximise  the mean manipulability over the task
``worst_condition``        minimise  the largest condition number over the task
``singularity_clearance``  maximise  the smallest singular value over the task
``total_length``           minimise  the sum of the link lengths (m)
``dexterous_volume``       maximise  the dexterous volume (m³) in a region (``reach=``)
``task_reachability``      maximise  the share of orientations near the targets' reached
=========================  ========  ===============================================

The last two are measured only when a run gives
:class:`~kinematica.design.reachmeasures.ReachSettings` (``reach=``).

Reaching every target within the joint limits is a hard constraint, never
traded against these. ``objective=`` takes a name, a mapping ``{name: weight}``
(a weighted sum ``Σ wᵢ·sᵢ·fᵢ``, minimised, with ``sᵢ = -1`` for measures to
maximise and ``+1`` for those to minimise) or a sequence of two names (their
Pareto front).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Literal

from kinematica.errors import KinematicaError

__all__ = ["MEASURES", "Measure", "Objective"]

Sense = Literal["max", "min"]


@dataclass(frozen=True)
class Measure:
    """A measure of a design on a task.

    Attributes:
        name: Its name in ``objective=``.
        sense: ``"max"`` (larger is better) or ``"min"``.
        description: One line for people and reports.
    """

    name: str
    sense: Sense
    description: str

    @property
    def sign(self) -> float:
        """``-1`` for a measure to maximise, ``+1`` for one to minimise."""
        return -1.0 if self.sense == "max" else 1.0


MEASURES: dict[str, Measure] = {
    m.name: m
    for m in (
        Measure("min_manipulability", "max", "worst (smallest) manipulability over the task"),
        Measure("mean_manipulability", "max", "mean manipulability over the task"),
        Measure("worst_condition", "min", "largest condition number over the task"),
        Measure("singularity_clearance", "max", "smallest singular value over the task"),
        Measure("total_length", "min", "sum of the link lengths (m)"),
        Measure("dexterous_volume", "max", "dexterous volume in the region (m³)"),
        Measure(
            "task_reachability", "max", "mean share of the orientations within tolerance reached"
        ),
    )
}


def _measure(name: object) -> Measure:
    if not isinstance(name, str) or name not in MEASURES:
        raise KinematicaError(f"unknown objective {name!r}; expected one of: {', '.join(MEASURES)}")
    return MEASURES[name]


@dataclass(frozen=True)
class Objective:
    """What a design run optimises.

    Attributes:
        terms: ``(measure name, weight)`` pairs; one pair with weight 1 for a
            single measure.
        pareto: True for the Pareto front of the two measures of ``terms``.
    """

    terms: tuple[tuple[str, float], ...]
    pareto: bool = False

    @classmethod
    def parse(cls, objective: str | Mapping[str, float] | Sequence[str] | Objective) -> Objective:
        """An objective from a name, ``{name: weight}``, or two names (Pareto).

        Raises:
            KinematicaError: An unknown name, a weight that is not a positive
                finite number, or a sequence of other than one or two names.
        """
        if isinstance(objective, Objective):
            return objective
        if isinstance(objective, str):
            return cls(((_measure(objective).name, 1.0),))
        if isinstance(objective, Mapping):
            if not objective:
                raise KinematicaError("a weighted objective needs at least one measure")
            terms = []
            for name, weight in objective.items():
                _measure(name)
                if (
                    isinstance(weight, bool)
                    or not isinstance(weight, int | float)
                    or not math.isfinite(weight)
                    or weight <= 0
                ):
                    raise KinematicaError(
                        f"the weight of {name} must be a positive number, found {weight!r}"
                    )
                terms.append((name, float(weight)))
            return cls(tuple(terms))
        names = list(objective)
        if len(names) == 1:
            return cls.parse(names[0])
        if len(names) != 2:
            raise KinematicaError(
                f"a Pareto front takes exactly two objectives, found {len(names)}: {names}"
            )
        a, b = (_measure(n).name for n in names)
        if a == b:
            raise KinematicaError(f"a Pareto front needs two different objectives, found {a} twice")
        return cls(((a, 1.0), (b, 1.0)), pareto=True)

    @property
    def names(self) -> tuple[str, ...]:
        """The measures involved."""
        return tuple(name for name, _ in self.terms)

    @property
    def weighted(self) -> bool:
        """A weighted sum of several measures."""
        return not self.pareto and len(self.terms) > 1

    def signed(self, measures: Mapping[str, float]) -> tuple[float, ...]:
        """Each measure as a value to minimise (``sᵢ·fᵢ``), NaN when unknown."""
        return tuple(MEASURES[n].sign * measures.get(n, math.nan) for n in self.names)

    def value(self, measures: Mapping[str, float]) -> float:
        """The objective as a designer reads it.

        The measure itself for a single measure; the weighted sum
        ``Σ wᵢ·sᵢ·fᵢ`` (lower is better) for several; NaN for a Pareto pair.
        """
        if self.pareto:
            return math.nan
        if len(self.terms) == 1:
            return float(measures.get(self.terms[0][0], math.nan))
        return self.scalar(measures)

    def scalar(self, measures: Mapping[str, float]) -> float:
        """The value minimised: ``Σ wᵢ·sᵢ·fᵢ`` (NaN for a Pareto pair)."""
        if self.pareto:
            return math.nan
        signed = self.signed(measures)
        return float(sum(w * v for (_, w), v in zip(self.terms, signed, strict=True)))

    def describe(self) -> str:
        """One line, e.g. ``maximise min_manipulability``."""
        if self.pareto:
            a, b = self.names
            sa, sb = MEASURES[a].sense, MEASURES[b].sense
            return f"Pareto front of {a} ({sa}imise) and {b} ({sb}imise)"
        if len(self.terms) == 1:
            m = MEASURES[self.terms[0][0]]
            return f"{m.sense}imise {m.name}"
        parts = [f"{w:g}·{'-' if MEASURES[n].sense == 'max' else ''}{n}" for n, w in self.terms]
        return "minimise " + " + ".join(parts)
