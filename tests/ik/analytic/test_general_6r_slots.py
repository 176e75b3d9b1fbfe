"""The general 6R's candidate slots: a closing candidate is never crowded out by junk.

Split pairs and an arm's extraneous real roots give candidates that close no loop; on an
Agilex Piper perturbed by 3.1e-9 (seed 7 of the perturbed-arm audit, docs/ik-audit.md)
18 of them (misses 1.7e-5 to 0.93) had filled their class's slots and the further slots
when the roots of the generating configuration and of one more solution came (misses
2e-12 and 3e-12), and those two were dropped (answered ok with 2 of 4 solutions). A
further slot now yields to a candidate that closes better. Checked against the
configuration that made the pose and the forward kinematics of every solution.
"""

from __future__ import annotations

import numpy as np
import pytest

import kinematica as km
from kinematica.dh.joints import Revolute

pytestmark = pytest.mark.filterwarnings("ignore::kinematica.KinematicaWarning")

#: Every solution's FK reaches its target to this (m, rad).
FK_TOL = 1e-10
#: The generating configuration is among the solutions to this (rad, modulo 2π).
FOUND_TOL = 1e-9

#: The Agilex Piper of tests/data/makers as ``robot.to_dh()`` gives it, every d, a and α
#: moved by ±3.1018152779046812e-09: perturbed arm #125 of ``benchmarks/audit_makers.py
#: --arms agilex_piper --poses 0 --perturbed 126 --perturbed-poses 10 --seed 7``; rows
#: (d, a, α, θ0), standard convention, base and tool the identity.
ROWS = (
    (0.12299999689818472, -3.1018152779046812e-09, -1.5707999844010672, -6.976229645337024e-06),
    (-3.1018152779046812e-09, -0.2850300031018153, -3.1018152779046812e-09, 0.10095000000067644),
    (9.179543643926454e-07, -0.021984003101815277, 1.5708000031018152, 1.3825926535897932),
    (0.2507500031035068, 3.1018152779046812e-09, -1.5707999968981847, 0.0),
    (3.373634796846234e-07, 8.825589818472209e-05, 1.5707999968981847, 0.0),
    (0.09099999689879862, -3.1018152779046812e-09, 3.1018152779046812e-09, 0.0),
)
#: Its 7th audit pose's configuration (σmin/σmax 2.8e-3: a regular pose).
Q_GEN = (
    -1.5422735116188868,
    1.3975582934121442,
    -2.912940494602013,
    1.5668072831523059,
    -1.2182177532196865,
    2.0231724642472453,
)


def test_a_closing_candidate_takes_the_slot_of_one_that_closes_nothing() -> None:
    rows = [Revolute(d=d, a=a, alpha=al, offset=th) for d, a, al, th in ROWS]
    robot = km.Robot.from_dh(rows, convention="standard")
    q = np.array(Q_GEN)
    T = robot.fk(q)
    res = robot.ik(T, respect_limits=False)
    assert res.method == "analytic:general-6R" and str(res.status) == "ok"
    assert res.count == 4  # 2 before
    gap = np.abs((res.solutions - q + np.pi) % (2 * np.pi) - np.pi).max(axis=1)
    assert gap.min() <= FOUND_TOL
    F = robot.fk(res.solutions)
    assert np.abs(F[:, :3, 3] - T[:3, 3]).max() <= FK_TOL
    assert res.residuals.max() <= FK_TOL
