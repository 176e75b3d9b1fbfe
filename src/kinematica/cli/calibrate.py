"""Subcommand ``calibrate``: fit a robot to a measurement CSV file, write it and a report."""

from __future__ import annotations

import argparse
import dataclasses
import math
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from kinematica.cli.options import (
    PER_METRE,
    add_common,
    add_robot,
    angle_unit,
    dump,
    length_unit,
    robot_from_args,
)
from kinematica.errors import RobotFileError
from kinematica.io.atomic import unchanged, write_text_atomic

if TYPE_CHECKING:  # the library's modules load when the command runs
    from kinematica.calibration import CalibrationResult
    from kinematica.robot import Robot

__all__ = ["EXACT_FK", "calibrate", "register"]

#: A DH table whose FK is within this (m) of the calibrated arm's is written without a
#: note; beyond it the command says how far the table alone is (the file is exact: it
#: holds the arm's own transforms too).
EXACT_FK = 1e-12


def _write(path: Path, text: str) -> None:
    try:
        write_text_atomic(path, text)
    except OSError as exc:
        raise RobotFileError(
            f"cannot write the file: {exc.strerror or exc}; {unchanged(path)}", path=str(path)
        ) from exc


def _robot_file(result: CalibrationResult, path: Path, args: argparse.Namespace) -> None:
    """The calibrated arm as a robot file: its DH table, and its own transforms (exact)."""
    from kinematica.io.robotfile import dumps_robot_file
    from kinematica.robot.save import spec_from_robot

    units = {"angle": angle_unit(args), "length": "m"}
    spec = dataclasses.replace(spec_from_robot(result.robot), units=units)
    _write(path, dumps_robot_file(spec, path.suffix))


def _measurements(robot: Robot, args: argparse.Namespace) -> tuple[Any, Any, str]:
    """Joint readings and measurements of the CSV file, in SI."""
    from kinematica.calibration.datafile import read_measurements
    from kinematica.spatial import from_pose

    q, meas, kind = read_measurements(args.data, robot.dof)
    per_metre = PER_METRE[length_unit(robot, args)]
    angles = q if args.rad else np.deg2rad(q)
    q = np.where(robot.is_prismatic, q / per_metre, angles)
    meas = meas.copy()
    meas[:, :3] /= per_metre
    if kind == "pose":
        return q, from_pose(meas, euler=args.euler, degrees=not args.rad), kind
    return q, meas, kind


def calibrate(args: argparse.Namespace) -> int:
    """``kinematica calibrate ROBOT DATA.csv [-o FILE] [--urdf FILE] [--report FILE]``."""
    from kinematica.calibration import calibrate as fit
    from kinematica.calibration.report import write_report
    from kinematica.calibration.words import finding_text

    robot = robot_from_args(args)
    q, measured, kind = _measurements(robot, args)
    per_metre = PER_METRE[length_unit(robot, args)]
    from kinematica.calibration import DEFAULT_NOISE

    noise = DEFAULT_NOISE
    if args.noise is not None:
        sr = args.noise[1] if args.rad else math.radians(args.noise[1])
        noise = (args.noise[0] / per_metre, sr)
    result = fit(robot, q, measured, kind, loss=args.loss, noise=noise, params=args.params)  # type: ignore[arg-type]
    written: list[str] = []
    notes: list[str] = []
    if args.output:
        out = Path(args.output)
        if out.suffix.lower() == ".urdf":
            _write(out, result.urdf)
        else:
            _robot_file(result, out, args)
        if result.dh.fk_error > EXACT_FK:
            notes.append(
                f"the DH table alone reproduces the calibrated arm within "
                f"{result.dh.fk_error:.2g} m (nearly parallel axes: far common normals); "
                f"{out} holds the arm's own transforms too, and is exact"
            )
        written.append(str(out))
    if args.urdf:
        _write(Path(args.urdf), result.urdf)
        written.append(args.urdf)
    if args.report:
        written += [
            str(p) for p in write_report(result, args.report, args.lang, degrees=not args.rad)
        ]
    rms0, rms1 = result.rms(False), result.rms(True)
    if args.json:
        dump(
            {
                "robot": robot.name,
                "kind": kind,
                "measurements": int(q.shape[0]),
                "loss": result.loss,
                "rank": result.rank,
                "generic_count": result.generic_count,
                "condition": result.condition,
                "observability": result.observability,
                "rms_before": {"position_m": rms0[0], "orientation_rad": rms0[1]},
                "rms_after": {"position_m": rms1[0], "orientation_rad": rms1[1]},
                "parameters": [dataclasses.asdict(p) for p in result.parameters],
                "undetermined": [
                    {"name": f.name, "partners": list(f.partners), "structural": f.structural}
                    for f in result.undetermined
                ],
                "correlated": [{"a": a, "b": b, "correlation": r} for a, b, r in result.correlated],
                "dh_fk_error_m": result.dh.fk_error,
                "written": written,
                "notes": notes,
            }
        )
        return 0
    unit = length_unit(robot, args)
    scale = PER_METRE[unit]
    print(f"{robot.name}: {q.shape[0]} {kind} measurements, loss {result.loss}")
    print(
        f"RMS position {rms0[0] * scale:.6g} -> {rms1[0] * scale:.6g} {unit}"
        + (
            f", orientation {math.degrees(rms0[1]):.6g} -> {math.degrees(rms1[1]):.6g} deg"
            if kind == "pose"
            else ""
        )
    )
    print(
        f"identified {result.rank} parameters (a rich set of {kind} measurements: "
        f"{result.generic_count}), condition number {result.condition:.4g}"
    )
    for f in result.undetermined:
        print(f"  {finding_text(f, 'en', kind)}")
    for a, b, r in result.correlated:
        print(f"  correlated: {a} and {b} ({r:+.3f})")
    for path in written:
        print(f"wrote {path}")
    for note in notes:
        print(f"note: {note}")
    return 0


def register(sub: Any) -> None:
    """Add ``calibrate`` to the subparsers ``sub``."""
    from kinematica.calibration.fit import LOSSES

    p = sub.add_parser(
        "calibrate",
        help="fit a robot's kinematic parameters to measured tool poses or points (CSV), "
        "say which the data cannot determine, write the calibrated arm and a report",
    )
    add_robot(p)
    p.add_argument(
        "data",
        metavar="DATA.csv",
        help="one row per measurement: the joint readings, then x, y, z (a point) or x, y, "
        "z and three Euler angles (--euler) of the measured tool pose; angles in degrees "
        "(--rad), lengths in the robot file's unit (--units)",
    )
    p.add_argument(
        "-o",
        "--output",
        metavar="FILE",
        help="the calibrated robot, exact: .urdf, or a robot file (.yaml, .json, .toml) "
        "holding the DH table read off the calibrated axes and the arm's own transforms",
    )
    p.add_argument("--urdf", metavar="FILE", help="also write the calibrated arm as URDF (exact)")
    p.add_argument(
        "--report",
        metavar="report.md",
        help="write a Markdown report and its two pictures (FILE-histogram.png, "
        "FILE-residuals.png) beside it",
    )
    p.add_argument(
        "--lang", choices=("es", "en"), default="es", help="of the report: es (default) or en"
    )
    p.add_argument(
        "--loss",
        choices=LOSSES,
        default="linear",
        help="scipy's least_squares loss (default linear)",
    )
    p.add_argument(
        "--noise",
        nargs=2,
        type=float,
        default=None,
        metavar=("POSITION", "ORIENTATION"),
        help="measurement noise the residuals are weighted by: position in the length unit, "
        "orientation in degrees (--rad); default 10 µm and 10 µrad",
    )
    p.add_argument(
        "--params",
        nargs="+",
        metavar="NAME",
        help="fit only these parameters (theta2, d3, base_z...)",
    )
    add_common(p)
    p.set_defaults(run=calibrate)
