"""A design run on paper: the evaluation log (CSV) and a Markdown report with pictures.

The report states the template, task, objective, seed and budget; the best
design against the template's own values; every measure before and after;
and three pictures (matplotlib, optional: without it the report says so):
the task's coverage before and after (targets reached, coloured by
manipulability), the objective's progress, and the Pareto front when there
is one.
"""

from __future__ import annotations

import csv
import math
import os
from pathlib import Path
from typing import Any

import numpy as np

from kinematica.design.evaluate import Evaluation, evaluate_design
from kinematica.design.measures import TASK_MEASURES, TaskMeasures, measure_task
from kinematica.design.objectives import MEASURES
from kinematica.design.result import DesignResult
from kinematica.errors import KinematicaError
from kinematica.io.atomic import atomic_path, write_failed, write_text_atomic
from kinematica.io.markdown import markdown_code, markdown_text

__all__ = ["write_log", "write_report"]

#: Front points listed in the report's table (all are in the log).
FRONT_ROWS = 15


def write_log(result: DesignResult, path: str | os.PathLike[str]) -> Path:
    """Write every evaluation as a CSV row, in the order they were asked for.

    Columns: ``evaluation`` (1-based), the design variables, ``feasible``,
    ``violation``, every measure, ``objective`` (the value to minimise, or
    empty for a Pareto pair) and ``front`` (1 for a Pareto-front point).
    """
    p = Path(path)
    names = list(result.template.names)
    measures = [*MEASURES, "reached"]
    front = {ev.x for ev in result.front or ()}
    try:
        with atomic_path(p) as tmp, tmp.open("w", newline="", encoding="utf-8") as f:
            out = csv.writer(f)
            header = ["evaluation", *names, "feasible", "violation", *measures, "objective"]
            out.writerow([*header, "front"])
            for i, ev in enumerate(result.history, start=1):
                obj = result.objective.scalar(ev.measures)
                out.writerow(
                    [
                        i,
                        *(repr(ev.params[n]) for n in names),
                        int(ev.feasible),
                        repr(ev.violation),
                        *(repr(ev.measures.get(m, math.nan)) for m in measures),
                        "" if math.isnan(obj) else repr(obj),
                        int(ev.x in front),
                    ]
                )
    except OSError as exc:
        raise KinematicaError(write_failed(p, exc, "the evaluation log")) from exc
    return p


def _nominal(result: DesignResult) -> Evaluation:
    nominal = tuple(result.template.nominal.values())
    for ev in result.history:
        if ev.x == nominal and all(m in ev.measures for m in TASK_MEASURES):
            return ev
    return evaluate_design(result.template, result.task, np.array(nominal))


def _bounds(result: DesignResult) -> list[tuple[str, float, float]]:
    t = result.template
    return [(n, float(lo), float(hi)) for n, lo, hi in zip(t.names, t.lower, t.upper, strict=True)]


def _fmt(v: float) -> str:
    return "—" if math.isnan(v) else f"{v:.6g}"


def _figure(**kwargs: Any) -> Any:
    from matplotlib.figure import Figure  # no pyplot: no global state, no display

    return Figure(**kwargs)


def _coverage(result: DesignResult, path: Path) -> None:
    before = measure_task(result.template.robot_at(result.template.nominal), result.task)
    after = measure_task(result.best_robot, result.task)
    P = result.task.positions
    both = np.concatenate([before.manipulability, after.manipulability])
    finite = both[np.isfinite(both)]
    vmax = float(finite.max()) if finite.size else 1.0
    fig = _figure(figsize=(10, 8.5), layout="constrained")
    axes = fig.subplots(2, 2)
    for col, (title, m) in enumerate((("template", before), ("best design", after))):
        views = ((0, 1, ("x (m)", "y (m)")), (0, 2, ("x (m)", "z (m)")))
        for row, (i, j, labels) in enumerate(views):
            ax = axes[row, col]
            _scatter(ax, P[:, i], P[:, j], m, vmax, fig)
            ax.set_xlabel(labels[0])
            ax.set_ylabel(labels[1])
            ax.set_aspect("equal", adjustable="datalim")
            view = "top view" if row == 0 else "side view"
            ax.set_title(f"{title}: {np.mean(m.reached):.0%} reached ({view})")
    fig.suptitle(f"Task coverage: {result.task.name} ({len(result.task)} targets)")
    _save(fig, path)


def _save(fig: Any, path: Path) -> None:
    """Write a report figure atomically (see :mod:`kinematica.io.atomic`)."""
    try:
        with atomic_path(path) as tmp:
            fig.savefig(tmp, dpi=90, format="png")
    except OSError as exc:
        raise KinematicaError(write_failed(path, exc, "the picture")) from exc


def _scatter(ax: Any, x: Any, y: Any, m: TaskMeasures, vmax: float, fig: Any) -> None:
    ok = m.reached
    art = ax.scatter(x[ok], y[ok], c=m.manipulability[ok], cmap="viridis", vmin=0, vmax=vmax, s=18)
    if (~ok).any():
        ax.scatter(x[~ok], y[~ok], marker="x", color="red", s=30, label="not reached")
        ax.legend(loc="upper right", fontsize=8)
    fig.colorbar(art, ax=ax, label="manipulability")


def _progress(result: DesignResult, path: Path) -> None:
    best = result.progress()
    n = np.arange(1, len(result.history) + 1)
    fig = _figure(figsize=(8, 4.5), layout="constrained")
    if result.objective.pareto:
        axes = fig.subplots(1, 2)
        for j, name in enumerate(result.objective.names):
            axes[j].plot(n, best[:, j], color="C0")
            axes[j].set_xlabel("evaluation")
            axes[j].set_ylabel(f"best {name} so far")
    else:
        ax = fig.subplots()
        values = [result.objective.value(ev.measures) for ev in result.history]
        feasible = [ev.feasible for ev in result.history]
        y = np.where(feasible, values, np.nan)
        ax.plot(n, y, ".", color="0.6", ms=4, label="each feasible candidate")
        ax.plot(n, best, color="C0", lw=2, label="best so far")
        ax.set_xlabel("evaluation")
        ax.set_ylabel(result.objective.describe())
        ax.legend()
    fig.suptitle("Objective progress")
    _save(fig, path)


def _front(result: DesignResult, path: Path) -> None:
    a, b = result.objective.names
    feasible = [ev for ev in result.history if ev.feasible]
    fig = _figure(figsize=(7, 5), layout="constrained")
    ax = fig.subplots()
    ax.plot(
        [ev.measures[a] for ev in feasible],
        [ev.measures[b] for ev in feasible],
        ".",
        color="0.7",
        ms=4,
        label="feasible candidates",
    )
    front = result.front or ()
    ax.plot([ev.measures[a] for ev in front], [ev.measures[b] for ev in front], "o-", ms=4,
            label="Pareto front")  # fmt: skip
    if result.feasible:
        ax.plot(result.best.measures[a], result.best.measures[b], "*", ms=16, color="C3",
                label="chosen (knee)")  # fmt: skip
    ax.set_xlabel(f"{a} ({MEASURES[a].sense}imise)")
    ax.set_ylabel(f"{b} ({MEASURES[b].sense}imise)")
    ax.legend()
    fig.suptitle("Pareto front")
    _save(fig, path)


def write_report(
    result: DesignResult,
    path: str | os.PathLike[str],
    *,
    robot_file: str | os.PathLike[str] | None = None,
    log_file: str | os.PathLike[str] | None = None,
    pictures: bool = True,
) -> list[Path]:
    """Write the Markdown report of a run, and its pictures beside it.

    Args:
        result: The run.
        path: The report (``.md``); pictures are ``<stem>_coverage.png``,
            ``<stem>_progress.png`` and ``<stem>_front.png`` in its folder.
        robot_file: The best robot file written, named in the report.
        log_file: The evaluation log written, named in the report.
        pictures: Draw the pictures (needs matplotlib; skipped with a note
            in the report when it is not installed).

    Returns:
        The files written, the report first.
    """
    p = Path(path)
    written = [p]
    tmpl, task, obj = result.template, result.task, result.objective
    nominal = _nominal(result)
    units = tmpl.units
    lines = [
        f"# Design of {markdown_text(tmpl.name)}",
        "",
        f"- Template: {markdown_code(str(tmpl.spec.source))}; design variables (file "
        f"units: lengths in {units.get('length', 'm')}, angles in {units.get('angle', 'deg')}): "
        + ", ".join(f"{n} in [{lo:g}, {hi:g}]" for n, lo, hi in _bounds(result)),
        f"- Task: {markdown_text(task.name)}, {len(task)} {task.kind} targets, every one to be "
        "reached within the joint limits",
        f"- Objective: {obj.describe()}",
        f"- Search: differential evolution, seed {result.seed}, {len(result.history)} evaluations "
        f"({result.evaluated} computed, {result.reused} from the checkpoint)",
        f"- Result: {result.message}",
        "",
        "## Best design",
        "",
        "| parameter | template | best |",
        "|---|---|---|",
        *(f"| {n} | {tmpl.nominal[n]:.6g} | {result.best_params[n]:.6g} |" for n in tmpl.names),
        "",
        "| measure | template | best |",
        "|---|---|---|",
        *(
            f"| {m} ({MEASURES[m].sense}imise) | {_fmt(nominal.measures.get(m, math.nan))} "
            f"| {_fmt(result.best.measures.get(m, math.nan))} |"
            for m in MEASURES
        ),
        f"| targets reached | {nominal.measures.get('reached', 0):.1%} "
        f"| {result.best.measures.get('reached', 0):.1%} |",
        "",
        "Manipulability is the product of the singular values of the Jacobian rows the "
        "task constrains (position rows for position targets, all six for poses), at the "
        "best IK solution of each target.",
        "",
    ]
    if result.front is not None:
        a, b = obj.names
        lines += ["## Pareto front", "", f"| {' | '.join(tmpl.names)} | {a} | {b} |"]
        lines += ["|" + "---|" * (len(tmpl.names) + 2)]
        step = max(1, math.ceil(len(result.front) / FRONT_ROWS))
        for ev in result.front[::step]:
            cells = [f"{ev.params[n]:.6g}" for n in tmpl.names]
            cells += [_fmt(ev.measures[a]), _fmt(ev.measures[b])]
            lines.append("| " + " | ".join(cells) + " |")
        lines += ["", f"{len(result.front)} points; every one is in the evaluation log.", ""]
    if pictures:
        try:
            import matplotlib  # noqa: F401
        except ImportError:
            pictures = False
            lines += ["(Pictures need matplotlib: pip install 'kinematica[design]'.)", ""]
    if pictures:
        figures = [("Task coverage, before and after", "coverage", _coverage)]
        figures.append(("Objective progress", "progress", _progress))
        if result.front is not None:
            figures.append(("Pareto front", "front", _front))
        for title, suffix, draw in figures:
            png = p.with_name(f"{p.stem}_{suffix}.png")
            draw(result, png)
            written.append(png)
            lines += [f"## {title}", "", f"![{title}]({png.name})", ""]
    files = [("best robot file", robot_file), ("evaluation log", log_file)]
    named = [f"- {what}: {markdown_code(Path(f).name)}" for what, f in files if f is not None]
    if named:
        lines += ["## Files", "", *named, ""]
    try:
        write_text_atomic(p, "\n".join(lines))
    except OSError as exc:
        raise KinematicaError(write_failed(p, exc, "the report")) from exc
    return written
