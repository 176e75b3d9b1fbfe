"""xacro expansion: kinematica's own expander beside the xacro package, same files, same run.

Run with ``make bench`` (or ``.venv/bin/python benchmarks/xacro_expansion.py``). For rtb-data's
xacro descriptions in tests/data/xacro (the KUKA KR 6 R900 and the Panda, and all 35 in
one pass) it prints the median time of:

* ``xacro_to_urdf``: kinematica's expander (the default: no code of the file runs);
* the xacro package's ``process_file`` in this process (what ``trust_xacro=True`` runs,
  without the child process that path adds), its ``$(find pkg)`` answered from the same
  package map;
* ``xacro_to_urdf(trust=True)``: the trusted path as the loaders run it (a child Python).

No assertions: figures only.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(1, str(Path(__file__).resolve().parents[1] / "tests"))

from _common import fmt_time, header, median_of, table
from support.xacro import RTB, RTB_PACKAGES, RTB_ROBOTS

from kinematica.io.xacro import xacro_to_urdf

KR6 = "kuka_description/kuka_kr6/urdf/kr6r900sixx.xacro"
PANDA = "qut_frankie_description/robots/panda_arm.urdf.xacro"
#: xacro 2 cannot read the KR 210's ROS 1 properties: left out of the xacro package's pass
FOR_BOTH = [r for r in RTB_ROBOTS if "kr210" not in r]


def _xacro_package() -> Any:
    try:
        import xacro
        from xacro import substitution_args
    except ImportError:
        return None
    substitution_args._eval_find = lambda name: str(RTB_PACKAGES[name])
    return xacro


def main() -> None:
    print(header("xacro expansion (median of 15 calls)"))
    xacro = _xacro_package()
    if xacro is None:
        print("the xacro package is not installed: its columns are skipped")
    rows = []

    def ours(files: list[str]) -> None:
        for f in files:
            xacro_to_urdf(RTB / f, max_bytes=2**24, packages=RTB_PACKAGES)

    def theirs(files: list[str]) -> None:
        for f in files:
            xacro.process_file(str(RTB / f))
            xacro.all_includes.clear()

    for what, files in (("KR 6 R900", [KR6]), ("Panda", [PANDA]), ("all 34", FOR_BOTH)):
        base = median_of(lambda files=files: ours(files))
        rows.append((f"{what}: kinematica's expander", fmt_time(base), "1.00x"))
        if xacro is not None:
            t = median_of(lambda files=files: theirs(files))
            rows.append((f"{what}: xacro package, in process", fmt_time(t), f"{t / base:.2f}x"))
    if xacro is not None:
        t = median_of(
            lambda: xacro_to_urdf(RTB / KR6, max_bytes=2**24, packages=RTB_PACKAGES, trust=True),
            repeats=5,
        )
        rows.append(("KR 6 R900: trust_xacro=True (child)", fmt_time(t), "-"))
    print(table(rows, ("what", "time", "vs kinematica")))


if __name__ == "__main__":
    main()
