"""The pose audit of every 6R closed form: random arms never seen, every check counted.

Run with ``nice -n 19 .venv/bin/python benchmarks/audit_ik.py`` (the full audit: 10,000
poses per arm class, some minutes a class); ``--poses N`` per class, ``--arms NAME ...``
a few classes (see ``--help``), ``--seed`` another sample, ``--starts`` the numeric
search's starts per pose, ``--show`` how many failures to print. ``make bench`` runs a
small one. The audit is ``tests/support/ik_pose_audit.py``'s (its docstring says what
each column counts): per class, the poses, those made where the arm is singular
(excluded from check a), the failures of checks a-e, our solutions no reference
found ("extra"), the poses EAIK answered too, and the time; then the first failures
with enough to reproduce them. No assertions: ``tests/ik/test_audit.py`` runs the
same functions on a few poses per class and asserts.
"""

from __future__ import annotations

import argparse
import sys
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from _common import header, table
from support.audit_arms import CLASSES
from support.ik_pose_audit import (
    FOUND_TOL,
    SINGULAR_REL,
    STARTS,
    TOL,
    ClassReport,
    audit_class,
)

import kinematica as km

#: The columns of the table: (heading, count) or the time.
COLUMNS = (
    ("poses", "poses"),
    ("singular", "singular"),
    ("a: q missing", "a"),
    ("a > 1e-6", "a_far"),
    ("b: FK > tol", "b"),
    ("c: ref missed", "c"),
    ("extra", "extra"),
    ("d: batch ≠ one", "d"),
    ("e: status", "e"),
    ("scaled", "scaled"),
    ("scaled out", "scaled_out"),
    ("EAIK poses", "eaik"),
)


def report_table(reports: list[ClassReport]) -> str:
    """The table of the reports: one row per class, its counts and time."""
    rows = [
        [r.name, str(r.arms), *(str(r.counts[k]) for _, k in COLUMNS), f"{r.seconds:.0f} s"]
        for r in reports
    ]
    return table(rows, ["class", "arms", *(h for h, _ in COLUMNS), "time"])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--poses", type=int, default=10_000, help="poses per arm class")
    parser.add_argument(
        "--arms", nargs="+", choices=list(CLASSES), default=list(CLASSES), metavar="CLASS",
        help=f"arm classes (default all: {', '.join(repr(c) for c in CLASSES)})",
    )  # fmt: skip
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--starts", type=int, default=STARTS, help="numeric starts per pose")
    parser.add_argument("--show", type=int, default=5, help="failures to print per class")
    args = parser.parse_args()
    warnings.simplefilter("ignore", km.KinematicaWarning)
    print(header("IK audit: random 6R arms, poses by FK, every solution checked"))
    print(
        f"singular: σmin/σmax of the 6x6 Jacobian (lengths / arm size) < {SINGULAR_REL:g}; "
        f"a: q found to {FOUND_TOL:g} rad; b: FK within {TOL:g} m and rad; c: references "
        f"= EAIK's exact answers + a {args.starts}-start numeric search"
    )
    reports = []
    for name in args.arms:
        reports.append(audit_class(name, args.poses, args.seed, args.starts, keep=args.show))
        print(f"{name}: {reports[-1].seconds:.0f} s", file=sys.stderr, flush=True)
    print(report_table(reports))
    np.set_printoptions(precision=17)
    for r in reports:
        for f in r.findings:
            print(f"\n{r.name} ({f.arm.note or 'generic'}): check {f.check}: {f.detail}")
            print(f"  q = {f.q.tolist()}")
            print(f"  convention = {f.arm.convention!r}, links = {f.arm.links!r}")
            print(f"  base = {np.asarray(f.arm.base).tolist()}")
            print(f"  tool = {np.asarray(f.arm.tool).tolist()}")


if __name__ == "__main__":
    main()
