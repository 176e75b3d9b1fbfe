"""Robot-file speed: reading, checking and refusing files, with baselines from the same run.

Run with ``make bench`` (or ``.venv/bin/python benchmarks/robot_files.py``). Prints:

* loading a built-in model and a robot file (``km.load``), against the bare
  parse of the same text by the format's reader (``tomllib``, ``json``, PyYAML):
  what the checks of ``kinematica.io`` (expressions, units, plausibility) cost;
* the largest accepted YAML file (``MAX_FILE_SIZE``), read by PyYAML's
  pure-Python loader and by its libyaml loader (which ``kinematica.io`` uses
  when PyYAML has it);
* how long the hostile files of issue 7 take to be refused: a 50 MB YAML, a
  20,000-joint JSON, a 1,000-term expression, a FIFO.

No assertions: the figures are for the README and for spotting regressions.
"""

from __future__ import annotations

import json
import os
import sys
import tempfile
import tomllib
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import yaml
from _common import fmt_time, header, median_of, per_call, table

import kinematica as km
from kinematica.errors import KinematicaError
from kinematica.io.builtin import builtin_path
from kinematica.io.robotfile import MAX_FILE_SIZE

ARM = """\
name: Seed 6-DOF arm
convention: standard
units: {angle: deg, length: m}
parameters: {l1: 0.5, l2: 0.4, l3: 0.4, l4: 0.1}
joints:
  - {theta: q1,      d: l1, a: 0,  alpha: 90,  limits: [-160, 160]}
  - {theta: q2 + 90, d: 0,  a: l2, alpha: 0}
  - {theta: q3 - 90, d: 0,  a: 0,  alpha: -90}
  - {theta: q4 - 90, d: l3, a: 0,  alpha: -90}
  - {theta: q5,      d: 0,  a: 0,  alpha: 90}
  - {theta: q6,      d: l4, a: 0,  alpha: 0}
tool: {xyz: [0, 0, 0.05]}
"""


def _refused(path: Path) -> float:
    def attempt() -> None:
        try:
            km.load(path)
        except KinematicaError:
            return
        raise AssertionError(f"{path.name} was accepted")

    return median_of(attempt, repeats=5)


def main() -> None:
    print(header("Robot files: load, check, refuse"))
    folder = Path(tempfile.mkdtemp())
    arm = folder / "arm.yaml"
    arm.write_text(ARM)
    puma_text = builtin_path("puma560").read_text()

    def load_puma() -> object:
        return km.load("puma560")

    def parse_puma() -> object:
        return tomllib.loads(puma_text)

    def load_arm() -> object:
        return km.load(arm)

    def parse_arm() -> object:
        return yaml.load(ARM, Loader=yaml.CSafeLoader)

    rows = [
        ["km.load('puma560') (TOML, built in)", fmt_time(per_call(load_puma, 500))],
        ["  tomllib.loads of the same text", fmt_time(per_call(parse_puma, 500))],
        ["km.load('arm.yaml') (the README's arm)", fmt_time(per_call(load_arm, 300))],
        ["  yaml.load of the same text (libyaml)", fmt_time(per_call(parse_arm, 300))],
    ]
    print()
    print(table(rows, ["operation", "per call"]))

    line = "  - {theta: q1, d: 0, a: 0.1, alpha: 0}\n"
    big = "convention: standard\njoints:\n" + line * ((MAX_FILE_SIZE - 40) // len(line))
    rows = [
        [f"PyYAML SafeLoader, {len(big):,} bytes", fmt_time(
            median_of(lambda: yaml.load(big, Loader=yaml.SafeLoader), repeats=3))],
        [f"PyYAML CSafeLoader (libyaml), {len(big):,} bytes", fmt_time(
            median_of(lambda: yaml.load(big, Loader=yaml.CSafeLoader), repeats=3))],
    ]  # fmt: skip
    print()
    print(table(rows, ["largest accepted YAML, parse only", "time"]))

    huge = folder / "huge.yaml"
    with huge.open("wb") as f:
        f.truncate(50_000_000)
    snake = folder / "snake.json"
    rows_ = [{"theta": f"q{i}", "d": 0, "a": 0.01, "alpha": 0} for i in range(1, 20_001)]
    snake.write_text(json.dumps({"convention": "standard", "joints": rows_}))
    snake_dict = json.loads(snake.read_text())
    long_expr = folder / "long.yaml"
    theta = "q1" + " + 1" * 1000
    long_expr.write_text(
        f"convention: standard\njoints:\n  - {{theta: '{theta}', d: 0, a: 1, alpha: 0}}\n"
    )
    rows = [
        ["50 MB YAML (refused by its size)", fmt_time(_refused(huge))],
        [f"20,000-joint JSON, {snake.stat().st_size:,} bytes", fmt_time(_refused(snake))],
        [
            "  the same, already parsed (refused by its joint count)",
            fmt_time(median_of(lambda: _parse_refused(snake_dict), repeats=5)),
        ],
        ["1,000-term expression", fmt_time(_refused(long_expr))],
    ]
    if hasattr(os, "mkfifo"):
        fifo = folder / "fifo.yaml"
        os.mkfifo(fifo)
        rows.append(["FIFO named x.yaml", fmt_time(_refused(fifo))])
    print()
    print(table(rows, ["hostile file, until the error", "time"]))


def _parse_refused(data: object) -> None:
    from kinematica.io import parse_robot_dict

    try:
        parse_robot_dict(data)
    except KinematicaError:
        return
    raise AssertionError("accepted")


if __name__ == "__main__":
    main()
