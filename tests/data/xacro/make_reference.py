"""Write the reference expansions of rtb-data's xacro files, made by the xacro package.

Run once, by hand, where the ``xacro`` package is installed (``pip install xacro``):

    python tests/data/xacro/make_reference.py

The xacro package answers ``$(find pkg)`` with ROS's package index
(``ament_index_python``); here it is answered from ``RTB_PACKAGES`` instead, the only
change made to it. It writes, in ``reference/``:

- ``irb140.urdf`` and ``lbr_iiwa_14_r820.urdf``: the whole expansions, as xacro prints
  them (``xacro FILE``);
- ``digests.json``: for every robot of ``RTB_ROBOTS``, the sha256 of the canonical form
  (``support.xacro.canonical``) of its expansion, or the error xacro gave.

The test suite only reads these files.
"""

from __future__ import annotations

import json
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1]))  # tests/, for support

import xacro  # noqa: E402
from support.xacro import REFERENCE, RTB, RTB_PACKAGES, RTB_ROBOTS, digest  # noqa: E402
from xacro import substitution_args  # noqa: E402


def find(name: str) -> str:
    return str(RTB_PACKAGES[name])


def main() -> None:
    substitution_args._eval_find = find
    digests = {}
    for robot in RTB_ROBOTS:
        try:
            text = xacro.process_file(str(RTB / robot)).toprettyxml(indent="  ")
        except Exception as exc:  # xacro's own errors, kept as the reference answer
            digests[robot] = f"error: {' '.join(str(exc).split())}"
            continue
        digests[robot] = digest(ET.fromstring(text))
        name = Path(robot).name.removesuffix(".xacro")
        if name in ("irb140", "lbr_iiwa_14_r820"):
            (REFERENCE / f"{name}.urdf").write_text(text, encoding="utf-8")
    (REFERENCE / "digests.json").write_text(json.dumps(digests, indent=1) + "\n", encoding="utf-8")
    print(f"xacro {getattr(xacro, '__version__', '?')}: {len(digests)} files")


if __name__ == "__main__":
    main()
