"""URDF in and out: time to read a maker's URDF, extract its DH table, export one.

Run with ``make bench`` (or ``.venv/bin/python benchmarks/urdf.py``). For the
ROS-Industrial KUKA KR 16-2 and the Franka Panda URDFs of tests/data/urdf it
prints the median time of:

* reading the XML with ``defusedxml`` into the links-and-joints model, beside the
  unprotected standard-library ``xml.etree`` parse of the same bytes (baseline:
  the cost of the hardening);
* the whole ``km.load`` (read, chain, DH extraction by the rules, FK check, Robot);
* Pinocchio's ``buildModelFromUrdf`` of the same file, when installed (baseline);
* ``robot.to_dh("modified")`` and ``robot.to_urdf()`` of the loaded robot.

No assertions: figures only.
"""

from __future__ import annotations

import sys
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import fmt_time, header, median_of, table

import kinematica as km
from kinematica.io import read_urdf

DATA = Path(__file__).resolve().parents[1] / "tests" / "data" / "urdf"
FILES = [("kuka_kr16_2.urdf", None), ("franka_panda.urdf", "panda_hand_tcp")]


def _times(path: Path, tip: str | None, pinocchio: Any) -> dict[str, float]:
    data = path.read_bytes()
    robot = km.load(path, tip=tip)
    times = {
        "xml.etree parse (unprotected)": median_of(lambda: ET.fromstring(data)),
        "read_urdf (defusedxml, checks)": median_of(lambda: read_urdf(path)),
        "km.load (read + DH extraction)": median_of(lambda: km.load(path, tip=tip)),
        'robot.to_dh("modified")': median_of(lambda: robot.to_dh("modified")),
        "robot.to_urdf()": median_of(robot.to_urdf),
    }
    if pinocchio is not None:
        times["Pinocchio buildModelFromUrdf"] = median_of(
            lambda: pinocchio.buildModelFromUrdf(str(path))
        )
    return times


def main() -> None:
    print(header("URDF in and out (median of 15 calls)"))
    try:
        import pinocchio
    except ImportError:
        pinocchio = None
        print("Pinocchio not installed: its column is skipped")
    rows = []
    for name, tip in FILES:
        times = _times(DATA / name, tip, pinocchio)
        base = times["km.load (read + DH extraction)"]
        for what, t in times.items():
            rows.append((f"{name}: {what}", fmt_time(t), f"{t / base:.2f}x"))
    print(table(rows, ("what", "time", "vs km.load")))


if __name__ == "__main__":
    main()
