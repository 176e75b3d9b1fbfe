"""Arms with axes 2, 3, 4 parallel (UR type) for the tests, and how their answers are judged.

Random arms of the class in its three modes (axes 5 and 6 meeting, apart,
parallel), with the degenerate geometries users meet: equal links (the elbow
folds onto axis 2), twists of ±90° (the wrist can align), offsets of 1e-10,
either DH convention, random base and tool. Answers are judged by forward
kinematics, and the configuration that made a target is looked for among the
solutions to within what its conditioning allows.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from kinematica.dh import Revolute
from kinematica.ik.result import IKBatchResult, IKResult
from kinematica.robot import Robot, classify
from support.helpers import assert_transform_close, transform_from

FloatArray = NDArray[np.float64]
PI = math.pi

#: Position (m) and rotation (rad) every returned solution must reach (the default tolerance).
TOL = 1e-10
#: The generating q is found to within ``FOUND_SCALE / σ_min(J(q))`` rad (at
#: least ``FOUND_FLOOR``): round-off of the target (~1e-16) moves a solution by
#: about 1e-16 / σ_min; this leaves a margin of 1,000 over what the solver reaches.
FOUND_SCALE = 1e-13
FOUND_FLOOR = 1e-9

UR5_ROWS = [
    Revolute(d=0.089159, alpha=PI / 2),
    Revolute(a=-0.425),
    Revolute(a=-0.39225),
    Revolute(d=0.10915, alpha=PI / 2),
    Revolute(d=0.09465, alpha=-PI / 2),
    Revolute(d=0.0823),
]
UR5 = Robot.from_dh(UR5_ROWS, name="UR5", convention="standard")
#: The UR5 with axes 5 and 6 apart (a5 = 5 cm): the quartic.
UR5_A5 = Robot.from_dh(
    [*UR5_ROWS[:4], Revolute(d=0.09465, a=0.05, alpha=-PI / 2), UR5_ROWS[5]],
    name="UR5 a5",
    convention="standard",
)
#: The UR5 with axes 5 and 6 parallel (α5 = 0, a5 = 6 cm).
UR5_P56 = Robot.from_dh(
    [*UR5_ROWS[:4], Revolute(d=0.09465, a=0.06), UR5_ROWS[5]], name="UR5 p56", convention="standard"
)

MODES = ("meet", "apart", "parallel")


def twist(rng: np.random.Generator, square: bool) -> float:
    """±90° (``square``: the wrist can align), else a twist well away from 0 and π."""
    if square:
        return float(rng.choice([-1.0, 1.0]) * PI / 2)
    return float(rng.uniform(0.3, PI - 0.3) * rng.choice([-1.0, 1.0]))


def random_arm(
    rng: np.random.Generator,
    mode: str = "meet",
    modified: bool = False,
    square: bool = False,
    equal: bool = False,
    tiny: bool = False,
) -> Robot:
    """A random arm of the class.

    Args:
        rng: Random numbers.
        mode: Axes 5 and 6 ``"meet"`` (a5 = 0), lie ``"apart"`` or are ``"parallel"``.
        modified: Rewrite the table in the modified convention.
        square: Twists of ±90° at joints 1, 4, 5 (UR-like: the wrist aligns at some q5).
        equal: Links 2 and 3 of equal length (the elbow folds onto axis 2).
        tiny: Offsets of 1e-10 in a1, d2, d3 (nearly, not exactly, zero).
    """
    u = rng.uniform
    small = 1e-10 if tiny else 0.0
    a2 = u(0.2, 0.6) * rng.choice([-1, 1])
    a3 = abs(a2) * rng.choice([-1, 1]) if equal else u(0.2, 0.6) * rng.choice([-1, 1])
    a5 = {"meet": 0.0, "apart": u(0.03, 0.15) * rng.choice([-1, 1]), "parallel": u(0.03, 0.15)}
    rows = [
        Revolute(d=u(0.05, 0.4), a=small, alpha=twist(rng, square), offset=u(-PI, PI)),
        Revolute(d=small, a=a2, alpha=float(rng.choice([0.0, PI]))),
        Revolute(d=small, a=a3, alpha=float(rng.choice([0.0, PI]))),
        Revolute(d=u(-0.2, 0.2), a=u(-0.1, 0.1), alpha=twist(rng, square), offset=u(-PI, PI)),
        Revolute(
            d=u(-0.2, 0.2),
            a=a5[mode],
            alpha=0.0 if mode == "parallel" else twist(rng, square),
            offset=u(-PI, PI),
        ),
        Revolute(d=u(-0.2, 0.2), a=u(-0.1, 0.1), alpha=u(-PI, PI), offset=u(-PI, PI)),
    ]
    base = transform_from(rng.normal(size=4), rng.uniform(-0.5, 0.5, 3))
    tool = transform_from(rng.normal(size=4), rng.uniform(-0.2, 0.2, 3))
    robot = Robot.from_dh(rows, base=base, tool=tool, convention="standard")
    if modified:
        robot = robot.to_convention("modified")
    assert classify(robot).kind == "three-parallel-6R"
    return robot


def joint_gap(sols: FloatArray, q: FloatArray) -> float:
    """Smallest largest-joint difference (rad, modulo 2π) between ``q (6,)`` and ``sols (k, 6)``."""
    if len(sols) == 0:
        return math.inf
    return float(np.abs(np.angle(np.exp(1j * (sols - q)))).max(axis=-1).min())


def found_tolerance(robot: Robot, q: FloatArray) -> float:
    """How close to ``q`` a solution must be: its conditioning's allowance."""
    smin = float(np.linalg.svd(robot.jacobian(q), compute_uv=False)[-1])
    return max(FOUND_FLOOR, FOUND_SCALE / max(smin, 1e-300))


def assert_reaches(robot: Robot, res: IKResult, T: FloatArray) -> None:
    """Every solution of ``res`` puts the tool on ``T`` (our FK, position and rotation)."""
    if res.count == 0:
        return
    reached = robot.fk(res.solutions)
    assert_transform_close(reached, np.broadcast_to(T, reached.shape), atol=TOL)


def assert_honest(robot: Robot, q: FloatArray, res: IKResult) -> None:
    """``res`` answers ``fk(q)``: ok or singular, every solution exact, q among them if ok."""
    T = robot.fk(q)
    assert res.status in ("ok", "singular"), (res.status, res.message, q.tolist())
    assert_reaches(robot, res, T)
    if res.status == "singular":
        assert res.free_joints, "a continuum names its free joints"
    else:
        tol = found_tolerance(robot, q)
        assert joint_gap(res.solutions, q) <= tol, (q.tolist(), res.solutions.tolist(), tol)


def assert_honest_batch(robot: Robot, q: FloatArray, many: IKBatchResult) -> None:
    """:func:`assert_honest` for every target ``robot.fk(q (N, 6))`` of a batch, at once."""
    T = robot.fk(q)
    assert set(many.status.tolist()) <= {"ok", "singular"}, many.message[
        ~np.isin(many.status, ["ok", "singular"])
    ]
    real = ~np.isnan(many.solutions[..., 0])
    reached = robot.fk(np.where(real[..., None], many.solutions, 0.0))
    want = np.broadcast_to(T[:, None], reached.shape)
    assert_transform_close(reached[real], want[real], atol=TOL)
    assert many.free[many.status == "singular"].any(axis=-1).all()
    smin = np.linalg.svd(robot.jacobian(q), compute_uv=False)[:, -1]
    tol = np.maximum(FOUND_FLOOR, FOUND_SCALE / np.maximum(smin, 1e-300))
    d = np.abs(np.angle(np.exp(1j * (many.solutions - q[:, None, :])))).max(axis=-1)
    gap = np.where(real, d, np.inf).min(axis=1)
    ok = many.status == "ok"
    assert (gap[ok] <= tol[ok]).all(), q[ok][gap[ok] > tol[ok]].tolist()
