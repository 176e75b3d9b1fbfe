"""Expand xacro files with the ``xacro`` package, for comparison: a script the tests run.

``python real_xacro.py PACKAGES_JSON FILE...`` prints a JSON object FILE -> the expanded
URDF text, or ``"error: ..."`` for a file xacro refuses. ``$(find pkg)`` is answered from
PACKAGES_JSON (name -> folder) instead of ROS's package index. The test files it is run on
are the project's own (trusted): the xacro package runs their expressions.
"""

from __future__ import annotations

import json
import sys


def main(argv: list[str]) -> None:
    import xacro
    from xacro import substitution_args

    packages = json.loads(argv[0])
    substitution_args._eval_find = lambda name: packages[name]
    out = {}
    for path in argv[1:]:
        try:
            out[path] = xacro.process_file(path).toxml()
        except Exception as exc:  # xacro raises many types: each is an answer here
            out[path] = "error: " + " ".join(str(exc).split())
        finally:
            xacro.all_includes.clear()
    json.dump(out, sys.stdout)


if __name__ == "__main__":
    main(sys.argv[1:])
