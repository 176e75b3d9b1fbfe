"""Subcommand ``design``: link lengths for a task, the best robot file and a report."""

from __future__ import annotations

import argparse
import math
from pathlib import Path
from typing import Any

from kinematica.cli.format import fmt
from kinematica.cli.options import add_common, dump
from kinematica.errors import KinematicaError
from kinematica.io import ROBOT_FILE_SUFFIXES

__all__ = ["design", "register"]


def _objective(tokens: list[str]) -> str | dict[str, float] | list[str]:
    """``NAME`` | ``NAME=WEIGHT ...`` (weighted sum) | ``NAME NAME`` (Pareto front)."""
    if not any("=" in t for t in tokens):
        return tokens[0] if len(tokens) == 1 else tokens
    weights: dict[str, float] = {}
    for token in tokens:
        name, _, weight = token.partition("=")
        try:
            weights[name] = float(weight) if weight else 1.0
        except ValueError as exc:
            raise KinematicaError(
                f"--objective {token!r}: the weight after '=' must be a number"
            ) from exc
    return weights


def _reach(args: argparse.Namespace, objective: object) -> Any:
    """ReachSettings from --region, --tolerance, ... when given or named; else None."""
    from kinematica.design import ReachSettings
    from kinematica.design.reachmeasures import REACH_MEASURES

    names = objective if isinstance(objective, list | dict) else [objective]
    if args.region is None and args.tolerance is None and not set(names) & set(REACH_MEASURES):
        return None
    region = None if args.region is None else [args.region[:3], args.region[3:]]
    tolerance = args.tolerance
    if tolerance is not None and not args.rad:
        tolerance = math.radians(tolerance)
    return ReachSettings(
        region=region,
        resolution=args.reach_resolution,
        orientations=args.reach_orientations,
        tolerance=tolerance,
        samples=args.samples,
    )


def _finite(value: Any) -> Any:
    """JSON-safe: non-finite floats become None."""
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, dict):
        return {k: _finite(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_finite(v) for v in value]
    return value


def _outputs(args: argparse.Namespace) -> tuple[Path, Path, Path]:
    """The robot file, report and log paths; checked before the (long) run."""
    robot = Path(args.output)
    if robot.suffix.lower() not in ROBOT_FILE_SUFFIXES:
        raise KinematicaError(
            f"-o {robot}: the best robot file must end in {', '.join(ROBOT_FILE_SUFFIXES)}"
        )
    report = Path(args.report) if args.report else robot.with_name(f"{robot.stem}_report.md")
    log = Path(args.log) if args.log else robot.with_name(f"{robot.stem}_log.csv")
    for p in (robot, report, log):
        if not p.parent.is_dir():
            raise KinematicaError(f"{p}: no such folder {str(p.parent)!r}")
    return robot, report, log


def design(args: argparse.Namespace) -> int:
    """``kinematica design TEMPLATE --task FILE ...``: optimise, write files, print."""
    from kinematica.design import load_task, optimize
    from kinematica.design.report import write_log, write_report

    robot_path, report_path, log_path = _outputs(args)
    task = load_task(args.task, euler=args.euler, degrees=not args.rad)
    objective = _objective(args.objective)
    res = optimize(
        args.template,
        task,
        objective,
        budget=args.budget,
        seed=args.seed,
        scheduler=args.scheduler,
        workers=args.workers,
        checkpoint=args.checkpoint,
        progress=False if args.no_progress else None,
        reach=_reach(args, objective),
    )
    written = {"log": str(log_path), "report": str(report_path)}
    try:
        write_log(res, log_path)
        if res.feasible:
            res.write_robot(robot_path)
            written["robot"] = str(robot_path)
        pictures = write_report(
            res,
            report_path,
            robot_file=robot_path if res.feasible else None,
            log_file=log_path,
            pictures=not args.no_pictures,
        )[1:]
    except OSError as exc:
        raise KinematicaError(f"cannot write the results: {exc}") from exc
    written["pictures"] = ", ".join(str(p) for p in pictures)
    if args.json:
        front = None
        if res.front is not None:
            front = [{"params": dict(ev.params), "measures": dict(ev.measures)} for ev in res.front]
        dump(
            _finite(
                {
                    "template": res.template.name,
                    "task": {"name": res.task.name, "targets": len(res.task),
                             "kind": res.task.kind},
                    "objective": res.objective.describe(),
                    "status": "ok" if res.feasible else "infeasible",
                    "message": res.message,
                    "best_params": dict(res.best_params),
                    "best_value": res.best_value,
                    "best_measures": res.best_values,
                    "seed": res.seed,
                    "evaluations": len(res.history),
                    "computed": res.evaluated,
                    "reused": res.reused,
                    "files": {"robot": written.get("robot"), "report": written["report"],
                              "log": written["log"], "pictures": [str(p) for p in pictures]},
                    "front": front,
                }
            )
        )  # fmt: skip
        return 0 if res.feasible else 1
    print(f"{res.template.name}: {res.message}")
    print(f"seed {res.seed}; {res.evaluated} evaluations computed, {res.reused} from a checkpoint")
    for name, value in res.best_params.items():
        print(f"  {name} = {fmt(value, 6)}   (template {fmt(res.template.nominal[name], 6)})")
    for name, value in res.best_values.items():
        print(f"  {name}: {fmt(value, 6) if math.isfinite(value) else value}")
    if res.front is not None:
        print(f"Pareto front: {len(res.front)} designs (in the log, marked front = 1)")
    if not res.feasible:
        print("no robot file written: no design reached every target")
    for what in ("robot", "report", "log", "pictures"):
        if written.get(what):
            print(f"{what}: {written[what]}")
    return 0 if res.feasible else 1


def register(sub: Any) -> None:
    """Add ``design`` to the subparsers ``sub``."""
    p = sub.add_parser(
        "design",
        help="link lengths for a task: optimise a template's bounded parameters",
        description="Search the bounded parameters of a design template (a robot file with "
        "l1: {value: 0.3, min: 0.1, max: 0.9}) for the best objective on a task, every "
        "target reached within the joint limits. Writes the best robot file, a Markdown "
        "report with pictures, and the evaluation log.",
    )
    p.add_argument("template", metavar="TEMPLATE", help="robot file with bounded parameters")
    p.add_argument(
        "--task",
        required=True,
        metavar="FILE",
        help="targets: CSV/.npy rows of x y z (positions), x y z + 3 Euler angles "
        "(see --euler, --rad) or 16 matrix numbers; or JSON (positions, poses, a region)",
    )
    p.add_argument(
        "--objective",
        nargs="+",
        default=["min_manipulability"],
        metavar="NAME",
        help="min_manipulability (default), mean_manipulability, worst_condition, "
        "singularity_clearance, total_length, dexterous_volume (needs --region) or "
        "task_reachability (see --tolerance); NAME=WEIGHT ... for a weighted sum; "
        "two names for a Pareto front",
    )
    p.add_argument(
        "--region",
        nargs=6,
        type=float,
        metavar=("X0", "Y0", "Z0", "X1", "Y1", "Z1"),
        help="box (m, base frame) whose dexterous volume dexterous_volume measures",
    )
    p.add_argument(
        "--reach-resolution", type=float, default=0.05, metavar="M",
        help="voxel side (m) of --region's map (default 0.05)",
    )  # fmt: skip
    p.add_argument(
        "--reach-orientations", type=int, default=64, metavar="N",
        help="orientations asked per voxel of --region (default 64)",
    )  # fmt: skip
    p.add_argument(
        "--tolerance", type=float, metavar="ANGLE",
        help="task_reachability: orientations within ANGLE (degrees; rad with --rad) of each "
        "target's; default all of SO(3)",
    )  # fmt: skip
    p.add_argument(
        "--samples", type=int, default=64, metavar="N",
        help="task_reachability: orientations asked per target (default 64)",
    )  # fmt: skip
    p.add_argument("--budget", type=int, default=300, help="candidate evaluations (default 300)")
    p.add_argument("--seed", type=int, default=0, help="seed of the search (default 0)")
    p.add_argument(
        "--scheduler",
        metavar="local|ADDR",
        help="run candidates on Dask: 'local' (a local cluster) or a scheduler address "
        "tcp://host:port",
    )
    p.add_argument("--workers", type=int, help="worker processes of the local cluster")
    p.add_argument("--checkpoint", metavar="FILE", help="record evaluations; resume from it")
    p.add_argument(
        "-o", "--output", required=True, metavar="FILE", help="best robot file (.yaml/.json/.toml)"
    )
    p.add_argument("--report", metavar="FILE", help="Markdown report (default <output>_report.md)")
    p.add_argument("--log", metavar="FILE", help="evaluation log CSV (default <output>_log.csv)")
    p.add_argument("--no-pictures", action="store_true", help="report without pictures")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    add_common(p)
    p.set_defaults(run=design)
