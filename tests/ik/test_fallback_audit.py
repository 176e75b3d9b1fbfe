"""No false status on random arms of every family, near-degenerate ones included.

The small version of ``benchmarks/ik_degenerate.py`` (the audit of
``tests/support/ik_audit.py``: arms generic, degenerate and jittered within the line
geometry's tolerances, targets by FK, a third within 1e-9 rad of a fold): every
target was made by forward kinematics, so none may be "unreachable",
"not_found" or "out_of_limits", every solution reaches it, and "ok" holds the
configuration that made it wherever the arm is not singular there.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from support.ik_audit import COUNTS, FOLD, JITTER_LENGTH, JITTER_TWIST, SPECIAL_TOL, jitter, run

import kinematica as km
from kinematica.ik.analytic import SOLVERS
from kinematica.ik.structure import features

pytestmark = pytest.mark.filterwarnings("ignore::kinematica.KinematicaWarning")


def test_no_false_status_on_random_arms_of_every_family() -> None:
    counts, cases = run(arms_per_case=4, targets_per_arm=10, seed=21)
    total = {k: sum(c[k] for c in counts.values()) for k in COUNTS}
    assert total["targets"] >= 300
    assert len(counts) == sum(len(s.targets) for s in SOLVERS)
    false = {k: v for k, v in total.items() if k != "targets" and v}
    assert not false, (false, [(c.what, c.spec, c.kind, c.note, c.message) for c in cases])


def test_jitter_moves_special_twists_and_zero_lengths_within_the_tolerances() -> None:
    rng = np.random.default_rng(3)
    spec = next(s for s in SOLVERS if s.kind == "three-parallel-6R")
    arm = spec.sample_arm(rng, False)
    moved = jitter(arm, rng)
    for before, after in zip(arm.links, moved.links, strict=True):
        special = min(abs(before.alpha - s) for s in (0.0, np.pi / 2, -np.pi / 2, np.pi, -np.pi))
        if special <= SPECIAL_TOL:
            assert 0.0 < abs(after.alpha - before.alpha) <= JITTER_TWIST
        else:
            assert after.alpha == before.alpha
        assert after.a == before.a or (before.a == 0.0 and abs(after.a) == JITTER_LENGTH)
    rows = [dataclasses.replace(j, qlim=None) for j in moved.links]
    robot = km.Robot.from_dh(rows, convention=moved.convention, base=moved.base, tool=moved.tool)
    f = features(robot.chain)
    assert spec.handles(f) and f.near_degenerate
    assert FOLD == 1e-9
