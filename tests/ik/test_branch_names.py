"""The 7R arms' branch names say what each branch is, checked by hand on the iiwa and Panda.

iiwa 14 (SRS): axes 1-3 meet at the shoulder S, 3-5 at the elbow E, 5-7 at the wrist
W, and the arm is straight at q = 0. At one arm angle the 8 solutions place S, E and
W at the same points; each branch is a flip about one of them, read off the sign of
q2 (shoulder), q4 (the elbow bent either way from straight, q4* = 0) and q6 (wrist).

Panda (solved with q7 held): axes 1-3 meet at S and axes 5 and 6 at a point P; q4
alone sets |S - P|, largest at its stretched angle q4*, found here by brute force
from forward kinematics; "elbow bent positive / negative" is the sign of q4 - q4*
(wrapped to (-π, π]), and the shoulder's no-flip is sin q2 > 0.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

import kinematica as km


def wrap(x: float) -> float:
    return math.remainder(x, 2 * math.pi)


def meeting_point(robot: km.Robot, q: np.ndarray, i: int, j: int) -> np.ndarray:
    """The point where axes i and j (0-based) meet: the middle of their common normal."""
    d, p = robot.joint_axes(q)
    u, v, w = d[i], d[j], p[i] - p[j]
    A, B, C, D, E = u @ u, u @ v, v @ v, u @ w, v @ w
    s, t = (B * E - C * D) / (A * C - B * B), (A * E - B * D) / (A * C - B * B)
    return (p[i] + s * u + p[j] + t * v) / 2


@pytest.fixture(scope="module")
def iiwa() -> km.Robot:
    return km.load("iiwa14")


@pytest.fixture(scope="module")
def panda() -> km.Robot:
    return km.load("panda")


@pytest.mark.parametrize(
    ("q", "expected"),
    [
        (
            [0.3, 0.7, -0.4, 1.2, 0.5, -0.8, 0.2],
            "shoulder no-flip, elbow bent positive, wrist flip",
        ),
        (
            [-1.0, -0.6, 0.9, 1.1, -0.3, 1.4, 0.5],
            "shoulder flip, elbow bent positive, wrist no-flip",
        ),
        (
            [2.0, 1.1, 0.4, -0.9, 1.2, 0.6, -1.0],
            "shoulder no-flip, elbow bent negative, wrist no-flip",
        ),
    ],
)
def test_iiwa_names_are_the_signs_of_q2_q4_q6(
    iiwa: km.Robot, q: list[float], expected: str
) -> None:
    q_known = np.array(q)
    psi = float(iiwa.arm_angle(q_known))
    res = iiwa.ik(iiwa.fk(q_known), arm_angle=psi, respect_limits=False)
    assert res.count == 8 and len(set(res.branches)) == 8  # every branch its own name
    k = int(np.argmin(np.abs(np.vectorize(wrap)(res.solutions - q_known)).max(axis=1)))
    assert np.allclose(res.solutions[k], q_known, atol=1e-9)
    assert res.branches[k] == expected
    for sol, name in zip(res.solutions, res.branches, strict=True):
        shoulder, elbow, wrist = name.split(", ")
        assert shoulder == ("shoulder no-flip" if sol[1] > 0 else "shoulder flip")
        assert elbow == ("elbow bent positive" if wrap(sol[3]) > 0 else "elbow bent negative")
        assert wrist == ("wrist no-flip" if sol[5] > 0 else "wrist flip")
        # the same shoulder, elbow and wrist points in all 8: branches are not positions
        for i, j in ((0, 1), (2, 3), (4, 5)):
            here = meeting_point(iiwa, sol, i, j)
            assert np.allclose(here, meeting_point(iiwa, q_known, i, j), atol=1e-9)


def test_panda_elbow_is_the_bend_from_its_stretched_angle(panda: km.Robot) -> None:
    def reach(q4: float) -> float:  # |S - P| at q4, every other joint at 0
        q = np.zeros(7)
        q[3] = q4
        return float(np.linalg.norm(meeting_point(panda, q, 0, 1) - meeting_point(panda, q, 4, 5)))

    grid = np.linspace(-math.pi, math.pi, 3601)
    q4_star = float(grid[np.argmax([reach(x) for x in grid])])
    assert q4_star == pytest.approx(-0.467, abs=2e-3)  # the offsets of 0.0825 m tilt it
    seen = set()
    for q4 in (-1.6, -2.6, 1.0):
        q_known = np.array([0.3, 0.5, 0.2, q4, 0.4, 1.7, 0.0])  # q7 = 0, the value held
        with warnings.catch_warnings():  # q4 = 1 is beyond the Panda's limits: said, used
            warnings.simplefilter("ignore", km.LimitWarning)
            res = panda.ik(panda.fk(q_known), respect_limits=False)
        assert res.parameter == ("q7", 0.0)
        assert len(set(res.branches)) == res.count == 8  # every branch its own name
        for sol, name in zip(res.solutions, res.branches, strict=True):
            shoulder, elbow, _ = name.split(", ")
            bent = "positive" if wrap(sol[3] - q4_star) > 0 else "negative"
            assert elbow == f"elbow bent {bent}", (q4, sol[3])
            assert shoulder == ("shoulder no-flip" if math.sin(sol[1]) > 0 else "shoulder flip")
            seen.add(name)
        assert "branch" not in " ".join(res.branches)
    # both bends occur (the Panda's limits, q4 in [-3.07, -0.07], keep only some of them)
    assert {n.split(", ")[1] for n in seen} == {"elbow bent positive", "elbow bent negative"}
