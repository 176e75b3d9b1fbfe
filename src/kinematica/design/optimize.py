"""``optimize``: link lengths for a task, by differential evolution.

The search is scipy's ``differential_evolution`` (seeded, ``updating="deferred"``,
no gradient polish), asked for whole generations at once (``vectorized``) so
that a generation's candidates are evaluated together: here, or in parallel on
Dask workers. Every target reached within the joint limits is a hard
constraint, by the feasibility rule (Deb 2000): a design that reaches every
target beats any that does not, and among those that do not, the one with the
smaller violation wins. The template's ``value`` s are the first candidate.

A Pareto front of two measures is traced by splitting the budget between
subproblems: the two measures alone (the front's ends, which fix the ideal
point and the ranges), then augmented Tchebycheff scalarisations
``max(λ·u1, (1-λ)·u2) + ρ·(u1 + u2)`` of the normalised measures for evenly
spaced ``λ``, which reach every Pareto point, on convex and non-convex fronts
alike. The front is the non-dominated subset of every feasible evaluation.
"""

from __future__ import annotations

import inspect
import math
import os
from collections.abc import Callable, Mapping, Sequence
from typing import Final

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.design.evaluate import Evaluation, evaluate_design
from kinematica.design.objectives import MEASURES, Objective
from kinematica.design.reachmeasures import REACH_MEASURES, ReachSettings, as_reach_settings
from kinematica.design.result import DesignResult
from kinematica.design.runner import Runner, Scheduler
from kinematica.design.task import Task
from kinematica.design.taskfile import as_task
from kinematica.design.template import DesignTemplate, load_template
from kinematica.errors import KinematicaError
from kinematica.io import RobotSpec

__all__ = ["optimize"]

FloatArray = NDArray[np.float64]
Energy = Callable[[Evaluation], float]

#: Energy of an infeasible design: ``INFEASIBLE * (1 + violation)``, above any
#: feasible design's energy (which is clipped to ``±VALUE_CAP``).
INFEASIBLE: Final = 1e100
VALUE_CAP: Final = 1e99
#: Smallest population scipy's differential evolution accepts.
MIN_POPULATION: Final = 5
#: Population members per design variable (and at least ``MIN_MEMBERS``).
MEMBERS_PER_VARIABLE: Final = 5
MIN_MEMBERS: Final = 10
#: Weight of the sum in the augmented Tchebycheff scalarisation (it keeps
#: weakly dominated points off the front).
TCHEBYCHEFF_RHO: Final = 1e-3
#: Points of a Pareto front: its two ends and this many minus two between.
FRONT_SIZE: Final = 7


def _energy(scalar: Callable[[Mapping[str, float]], float]) -> Energy:
    """The value differential evolution minimises, with the feasibility rule."""

    def energy(ev: Evaluation) -> float:
        if not ev.feasible:
            return INFEASIBLE * (1.0 + ev.violation)
        v = scalar(ev.measures)
        return VALUE_CAP if math.isnan(v) else min(max(v, -VALUE_CAP), VALUE_CAP)

    return energy


def _rng_keyword() -> str:
    """The name of the generator argument: ``rng`` since scipy 1.15, ``seed`` before."""
    from scipy.optimize import differential_evolution

    params = inspect.signature(differential_evolution).parameters
    return "rng" if "rng" in params else "seed"


def _population(budget: int, p: int) -> tuple[int, int]:
    """``(popsize, maxiter)`` for scipy: whole generations within ``budget``."""
    members = min(max(MIN_MEMBERS, MEMBERS_PER_VARIABLE * p), budget)
    popsize = max(1, members // p)
    size = max(MIN_POPULATION, popsize * p)
    if size > budget:
        raise KinematicaError(
            f"a budget of {budget} evaluations is below one generation of {size} candidates"
        )
    return popsize, budget // size - 1


def _search(
    runner: Runner,
    template: DesignTemplate,
    energy: Energy,
    budget: int,
    seed: int,
    history: list[Evaluation],
) -> None:
    """One differential-evolution run; every evaluation is appended to ``history``."""
    try:
        from scipy.optimize import differential_evolution
    except ImportError as exc:
        raise KinematicaError(
            "kinematica.design needs scipy: pip install 'kinematica[design]'"
        ) from exc

    def func(X: FloatArray) -> FloatArray:  # X: (p, S), one generation
        evs = runner.evaluate(X.T)
        history.extend(evs)
        return np.array([energy(ev) for ev in evs])

    popsize, maxiter = _population(budget, len(template.names))
    x0 = np.array(list(template.nominal.values()))
    differential_evolution(
        func,
        bounds=list(zip(template.lower, template.upper, strict=True)),
        maxiter=maxiter,
        popsize=popsize,
        tol=0.0,
        atol=0.0,
        polish=False,
        updating="deferred",
        vectorized=True,
        x0=x0,
        **{_rng_keyword(): np.random.default_rng(seed)},
    )


def _best(history: Sequence[Evaluation], energy: Energy) -> Evaluation:
    """The first evaluation of least energy."""
    energies = [energy(ev) for ev in history]
    return history[int(np.argmin(energies))]


def _nondominated(evs: Sequence[Evaluation], objective: Objective) -> list[Evaluation]:
    """The feasible, distinct, non-dominated evaluations, best first measure first."""
    unique: dict[tuple[float, ...], Evaluation] = {}
    for ev in evs:
        if ev.feasible and not any(math.isnan(v) for v in objective.signed(ev.measures)):
            unique.setdefault(ev.x, ev)
    pts = list(unique.values())
    F = np.array([objective.signed(ev.measures) for ev in pts]).reshape(len(pts), 2)
    le = np.all(F[:, None, :] <= F[None, :, :], axis=-1)
    lt = np.any(F[:, None, :] < F[None, :, :], axis=-1)
    dominated = np.any(le & lt, axis=0)  # [i, j]: i dominates j
    front = [pts[j] for j in np.flatnonzero(~dominated)]
    return sorted(front, key=lambda ev: objective.signed(ev.measures))


def _tchebycheff(
    objective: Objective, ideal: FloatArray, scale: FloatArray, weights: tuple[float, float]
) -> Callable[[Mapping[str, float]], float]:
    """``max(w1·u1, w2·u2) + ρ·(u1 + u2)`` of the normalised measures ``u``."""
    w = np.array(weights)

    def scalar(measures: Mapping[str, float]) -> float:
        u = (np.array(objective.signed(measures)) - ideal) / scale
        return float(np.max(w * u) + TCHEBYCHEFF_RHO * np.sum(u))

    return scalar


def _pareto(
    runner: Runner,
    template: DesignTemplate,
    objective: Objective,
    budget: int,
    seed: int,
    front_size: int,
    history: list[Evaluation],
) -> tuple[Energy, list[Evaluation]]:
    """Trace the front; returns the knee's energy function and the front."""
    if isinstance(front_size, bool) or not isinstance(front_size, int) or front_size < 2:
        raise KinematicaError(f"front_size must be a whole number >= 2, got {front_size!r}")
    share = budget // front_size
    if share < MIN_POPULATION:
        raise KinematicaError(
            f"a Pareto front of {front_size} subproblems needs a budget of at least "
            f"{front_size * MIN_POPULATION} evaluations, got {budget}"
        )
    seeds = [int(s.generate_state(1)[0]) for s in np.random.SeedSequence(seed).spawn(front_size)]
    ends = []
    for k, name in enumerate(objective.names):
        energy = _energy(Objective(((name, 1.0),)).scalar)
        start = len(history)
        _search(runner, template, energy, share, seeds[k], history)
        ends.append(_best(history[start:], energy))
    feasible = [ev for ev in history if ev.feasible]
    if not feasible:
        return _energy(Objective(((objective.names[0], 1.0),)).scalar), []
    F = np.array([objective.signed(ev.measures) for ev in feasible])
    ideal = np.nanmin(F, axis=0)
    nadir = np.array([objective.signed(ends[1].measures)[0], objective.signed(ends[0].measures)[1]])
    scale = np.where(np.isfinite(nadir - ideal) & (nadir - ideal > 0), nadir - ideal, 1.0)
    for k in range(2, front_size):
        lam = (k - 1) / (front_size - 1)
        energy = _energy(_tchebycheff(objective, ideal, scale, (lam, 1.0 - lam)))
        _search(runner, template, energy, share, seeds[k], history)
    knee = _energy(_tchebycheff(objective, ideal, scale, (1.0, 1.0)))
    return knee, _nondominated(history, objective)


def _check_reach(obj: Objective, reach: ReachSettings | None) -> None:
    """An objective naming a reachability measure needs the settings that measure it."""
    wanted = [n for n in obj.names if n in REACH_MEASURES]
    if wanted and reach is None:
        raise KinematicaError(
            f"the objective {wanted[0]} is measured from reachability: give "
            "reach=kinematica.design.ReachSettings(region=..., tolerance=...)"
        )
    if "dexterous_volume" in wanted and reach is not None and reach.region is None:
        raise KinematicaError(
            "dexterous_volume is measured in a region: give ReachSettings(region=[lower, upper])"
        )


def optimize(
    template: DesignTemplate | RobotSpec | str | os.PathLike[str],
    task: Task | ArrayLike | str | os.PathLike[str],
    objective: str | Mapping[str, float] | Sequence[str] | Objective = "min_manipulability",
    *,
    budget: int = 300,
    seed: int | None = None,
    scheduler: Scheduler = None,
    workers: int | None = None,
    checkpoint: str | os.PathLike[str] | None = None,
    progress: bool | None = None,
    front_size: int = FRONT_SIZE,
    reach: ReachSettings | None = None,
) -> DesignResult:
    """Choose a design template's parameters for a task.

    Args:
        template: A robot file whose ``parameters`` carry bounds
            (``l1: {value: 0.3, min: 0.1, max: 0.9}``), or its spec/template.
        task: A :class:`Task`, a task file (CSV, JSON, ``.npy``, ``.npz``), or
            targets: positions ``(N, 3)`` or poses ``(N, 4, 4)`` (m, base frame).
        objective: A measure's name (``"min_manipulability"``,
            ``"mean_manipulability"``, ``"worst_condition"``,
            ``"singularity_clearance"``, ``"total_length"``), ``{name:
            weight}`` for a weighted sum, or two names for a Pareto front.
            Reaching every target within the joint limits is always required.
        budget: Most candidate evaluations (whole generations of differential
            evolution; a Pareto front shares it among ``front_size`` runs).
        seed: Seed of the search: the same seed gives the same result, with
            any scheduler and any number of workers. Drawn at random if ``None``
            (and kept in the result).
        scheduler: ``None`` (this process), ``"local"`` (a ``dask.distributed``
            LocalCluster started for the run), ``"tcp://host:port"`` (an
            existing scheduler whose workers have kinematica installed), or a
            ``distributed.Client``.
        workers: Worker processes of the local cluster (default: the cores
            available). Given alone, it implies ``scheduler="local"``.
        checkpoint: A file recording every finished evaluation. If it exists
            (same template and task), the run resumes: the search is replayed
            from ``seed`` and evaluations found there are not computed again.
        progress: A tqdm progress bar on stderr (``None``: when it is a terminal).
        front_size: Subproblems of a Pareto front (its two ends included).
        reach: Also measure ``dexterous_volume`` (in ``reach.region``) and
            ``task_reachability`` (within ``reach.tolerance``) for every
            candidate (:class:`~kinematica.design.reachmeasures.ReachSettings`);
            needed by an objective that names them.

    Returns:
        The :class:`DesignResult`.

    Raises:
        KinematicaError: A malformed template, task or objective (the
            message says which), a budget below one generation, a missing
            optional dependency (scipy; dask for a scheduler), or a checkpoint
            of another problem.
    """
    tmpl = load_template(template)
    tk = as_task(task)
    obj = Objective.parse(objective)
    settings = as_reach_settings(reach)
    _check_reach(obj, settings)
    if isinstance(budget, bool) or not isinstance(budget, int) or budget < 1:
        raise KinematicaError(f"budget must be a positive whole number, got {budget!r}")
    if seed is None:
        seed = int(np.random.SeedSequence().generate_state(1)[0])
    elif isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise KinematicaError(f"seed must be a non-negative whole number, got {seed!r}")
    history: list[Evaluation] = []
    front: list[Evaluation] | None = None
    with Runner(
        tmpl,
        tk,
        scheduler=scheduler,
        workers=workers,
        checkpoint=checkpoint,
        progress=progress,
        total=budget,
        reach=settings,
        needs=obj.names,
    ) as runner:
        if obj.pareto:
            energy, front = _pareto(runner, tmpl, obj, budget, seed, front_size, history)
        else:
            energy = _energy(obj.scalar)
            _search(runner, tmpl, energy, budget, seed, history)
    best = _best(front or history, energy)
    if not best.feasible:
        best = min(history, key=lambda ev: ev.violation)
    if any(name not in best.measures for name in MEASURES if name not in REACH_MEASURES):
        # the search measured what the objective reads; the result holds every measure
        best = evaluate_design(tmpl, tk, np.array(best.x), settings)
    value = energy(best) if obj.pareto else obj.value(best.measures)
    reached = best.measures.get("reached", 0.0)
    if best.feasible:
        message = f"{obj.describe()}: {value:.6g} after {len(history)} evaluations"
    else:
        value = math.nan
        message = (
            f"no design reached every target within the joint limits "
            f"(the best reached {reached:.1%}) after {len(history)} evaluations"
        )
    return DesignResult(
        best_params=dict(best.params),
        best_robot=tmpl.robot_at(best.params),
        best_value=value,
        best=best,
        feasible=best.feasible,
        history=tuple(history),
        front=None if front is None else tuple(front),
        objective=obj,
        template=tmpl,
        task=tk,
        seed=seed,
        evaluated=runner.evaluated,
        reused=runner.reused,
        message=message,
    )
