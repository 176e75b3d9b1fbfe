"""Numeric IK (``robot.ik(..., method="numeric")``): every answer judged independently.

The solver's word is never taken: each returned configuration is put through
forward kinematics and compared with its target by the position distance and
:func:`kinematica.spatial.rotation_angle` (or the masked components of
:func:`kinematica.spatial.se3_error`), and checked against the joint limits. On
random arms the forward kinematics is the reference product of
``tests/support/helpers.py``, written from the slides and sharing no code with the
library.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from kinematica._core_testing.internals import LAMBDA_MIN, LIMIT_TOL, lm_rows
from support.helpers import JointSpec, RobotSpec, transforms

from kinematica.dh import Prismatic, Revolute
from kinematica.errors import ArgumentError, DimensionError, KinematicaError
from kinematica.ik.result import IKBatchResult, IKResult
from kinematica.robot import Robot, load
from kinematica.spatial import rotation_angle, se3_error

TOL = 1e-10
PI = math.pi


# ------------------------------------------------------------------ robots
def panda() -> Robot:
    """The built-in Franka Panda (modified DH, Franka's limits, flange as tool)."""
    return load("panda")


def iiwa14() -> Robot:
    """The built-in KUKA LBR iiwa 14 (standard DH, with its limits)."""
    return load("iiwa14")


def puma() -> Robot:
    """A PUMA 560-like 6R arm (standard DH), free joints."""
    joints = [
        Revolute(d=0.6718, alpha=PI / 2),
        Revolute(a=0.4318),
        Revolute(d=0.15005, a=0.0203, alpha=-PI / 2),
        Revolute(d=0.4318, alpha=PI / 2),
        Revolute(alpha=-PI / 2),
        Revolute(),
    ]
    return Robot.from_dh(joints, name="puma", convention="standard")


def stanford() -> Robot:
    """Stanford arm (RRPRRR), prismatic third joint with limits."""
    joints = [
        Revolute(d=0.412, alpha=-PI / 2),
        Revolute(d=0.154, alpha=PI / 2),
        Prismatic(theta=0.0, qlim=(0.3, 0.9)),
        Revolute(alpha=-PI / 2),
        Revolute(alpha=PI / 2),
        Revolute(d=0.263),
    ]
    return Robot.from_dh(joints, name="stanford", convention="standard")


def planar2r() -> Robot:
    """Two revolute joints in the xy plane, links 1.0 and 0.7 m."""
    return Robot.from_dh(
        [Revolute(a=1.0), Revolute(a=0.7)], name="planar 2R", convention="standard"
    )


def random_q(robot: Robot, count: int, seed: int) -> np.ndarray:
    lo, hi = robot.qlim.T
    return np.random.default_rng(seed).uniform(lo, hi, (count, robot.dof))


# ------------------------------------------------------------------ checks
def numeric(robot: Robot, target: np.ndarray, **kw) -> IKResult | IKBatchResult:
    return robot.ik(target, method="numeric", **kw)


def first(res: IKBatchResult) -> np.ndarray:
    """``(N, n)`` the first solution of each target of a flat batch, NaN where none."""
    q = np.full((res.size, res.solutions.shape[-1]), np.nan)
    if res.solutions.shape[-2] > 0:
        q[:] = res.solutions[:, 0]
    return q


def assert_reaches(robot: Robot, q: np.ndarray, targets: np.ndarray, mask=None) -> None:
    """Each configuration ``q (K, n)`` reaches its target by FK, within limits."""
    assert np.all(np.isfinite(q))
    T = robot.fk(q)
    if targets.shape[-1] == 3:  # positions
        dist = np.linalg.norm(T[..., :3, 3] - targets, axis=-1)
        assert dist.max() <= TOL, dist.max()
    elif mask is None:
        dist = np.linalg.norm(T[..., :3, 3] - targets[..., :3, 3], axis=-1)
        angle = rotation_angle(T[..., :3, :3], targets[..., :3, :3])
        assert dist.max() <= TOL, dist.max()
        assert angle.max() <= TOL, angle.max()
    else:
        e = se3_error(T, targets) * (np.asarray(mask) > 0)
        assert np.linalg.norm(e[..., :3], axis=-1).max() <= TOL
        assert np.linalg.norm(e[..., 3:], axis=-1).max() <= TOL
    lo, hi = robot.qlim.T
    assert np.all((q >= lo) & (q <= hi))


def assert_all_ok(res: IKBatchResult) -> None:
    bad = np.flatnonzero(res.status.ravel() != "ok")
    assert bad.size == 0, [res.message.ravel()[i] for i in bad[:5]]


# ------------------------------------------------- success on 7-DOF arms
@pytest.mark.parametrize("make", [panda, iiwa14], ids=["panda", "iiwa14"])
def test_random_reachable_poses_within_limits(make) -> None:
    robot = make()
    targets = robot.fk(random_q(robot, 1000, seed=11))
    res = numeric(robot, targets, seed=0)
    assert isinstance(res, IKBatchResult) and res.method == "numeric:lm"
    assert_all_ok(res)  # 100 % at 1e-10 m and 1e-10 rad
    np.testing.assert_array_equal(res.count, 1)
    assert_reaches(robot, first(res), targets)


def test_solution_at_the_start_takes_no_step() -> None:
    robot = iiwa14()
    q = random_q(robot, 3, seed=2)
    res = numeric(robot, robot.fk(q), q0=q)
    np.testing.assert_array_equal(first(res), q)  # not moved by a single ulp
    one = numeric(robot, robot.fk(q[0]), q0=q[0])
    np.testing.assert_array_equal(one.solutions, q[:1])


# ------------------------------------------------------------------ masks
def test_position_only_on_a_6dof_arm() -> None:
    robot = puma()
    targets = robot.fk(random_q(robot, 40, seed=3))[:, :3, 3]
    res = numeric(robot, targets)
    assert_all_ok(res)
    assert_reaches(robot, first(res), targets)


def test_position_mask_ignores_the_rotation_of_poses() -> None:
    robot = puma()
    T = robot.fk(random_q(robot, 5, seed=4))
    T[:, :3, :3] = np.eye(3)  # an orientation the arm need not reach
    res = numeric(robot, T, mask=[1, 1, 1, 0, 0, 0])
    assert_all_ok(res)
    assert_reaches(robot, first(res), T[:, :3, 3])


@pytest.mark.parametrize(
    "mask",
    [[1, 1, 1, 1, 1, 0], [1, 1, 1, 0, 1, 1], [0, 1, 1, 1, 1, 1]],
    ids=["free rz", "free rx", "free x"],
)
def test_five_component_mask(mask) -> None:
    robot = puma()
    targets = robot.fk(random_q(robot, 40, seed=5))
    res = numeric(robot, targets, mask=mask)
    assert_all_ok(res)
    assert_reaches(robot, first(res), targets, mask=mask)


def test_five_component_mask_leaves_the_free_component_free() -> None:
    # A target rotated about base z away from a reachable one is still met when
    # rz is free: the solver must not report it unreachable.
    robot = puma()
    T = robot.fk(random_q(robot, 10, seed=6))
    c, s = math.cos(0.7), math.sin(0.7)
    Rz = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])
    T[:, :3, :3] = Rz @ T[:, :3, :3]
    mask = [1, 1, 1, 1, 1, 0]
    res = numeric(robot, T, mask=mask)
    assert_all_ok(res)
    assert_reaches(robot, first(res), T, mask=mask)


def test_weighted_mask_still_meets_the_plain_tolerance() -> None:
    robot = iiwa14()
    targets = robot.fk(random_q(robot, 30, seed=7))
    res = numeric(robot, targets, mask=[3, 3, 3, 0.2, 0.2, 0.2])
    assert_all_ok(res)
    assert_reaches(robot, first(res), targets)  # unweighted: 1e-10 m and 1e-10 rad


# ---------------------------------------------------- honest statuses
def test_target_beyond_reach_is_unreachable_with_a_proven_gap() -> None:
    robot = panda()
    T = np.tile(np.eye(4), (2, 1, 1))
    T[0, :3, 3] = [3.0, 0.0, 0.5]
    T[1, :3, 3] = robot.fk(random_q(robot, 1, seed=8))[0, :3, 3]
    res = numeric(robot, T, mask=[1, 1, 1, 0, 0, 0])
    assert list(res.status) == ["unreachable", "ok"]
    gap = res.gap[0]
    assert gap > 1.0
    # A lower bound of the distance to every reachable tool position.
    reach = robot.fk(random_q(robot, 20000, seed=9))[:, :3, 3]
    assert gap <= np.linalg.norm(reach - T[0, :3, 3], axis=-1).min()
    assert np.isnan(res.gap[1])
    message = res[0].message
    assert f"at least {gap:.6g} m outside the reach" in message
    assert "closed form" not in message


@pytest.mark.parametrize(
    ("beyond", "weight", "status"),
    [
        (0.5 * TOL, 1.0, "ok"),  # within the tolerance of the stretched arm
        (1.5 * TOL, 1.0, "unreachable"),  # past it: proven
        (1.5 * TOL, 0.5, "ok"),  # weighted by 0.5 the miss is 0.75 TOL: accepted
        (2.5 * TOL, 0.5, "unreachable"),
    ],
)
def test_the_reach_proof_holds_the_weighted_tolerance(beyond, weight, status) -> None:
    # The 2R arm's reach bound (1.7 m) is its true reach: a target just past
    # it is unreachable exactly when the weighted miss exceeds the tolerance.
    robot = planar2r()
    target = np.array([1.7 + beyond, 0.0, 0.0])
    res = numeric(robot, target, mask=[weight] * 3 + [0.0] * 3)
    assert res.status == status, res.message
    if status == "unreachable":
        assert res.gap == pytest.approx(beyond, abs=1e-15)
    else:
        assert res.residuals[0, 0] <= TOL  # weighted, as the check measures it


def test_unreachable_within_the_bound_is_not_found_not_proven() -> None:
    # The 2R arm cannot reach within 0.3 m of its base; the crude bound cannot tell.
    robot = planar2r()
    res = numeric(robot, np.array([0.1, 0.0, 0.0]))
    assert isinstance(res, IKResult)
    assert res.status == "not_found" and res.gap is None and res.count == 0
    assert res.nearest_error[0] >= 0.2 - 1e-9  # every reachable point is >= 0.2 m away
    assert "did not converge" in res.message and "closed form" not in res.message


def test_nothing_is_returned_outside_the_limits() -> None:
    # A pose of the free arm needing q1 = 2.5 rad, with q1 limited to ±1 rad.
    free = puma()
    q = np.array([2.5, 0.3, -0.4, 0.2, 0.5, 0.1])
    limited = free.with_limits([(-1.0, 1.0)] + [None] * 5)
    res = numeric(limited, free.fk(q))
    assert res.status in ("ok", "not_found")
    if res.status == "ok":
        assert_reaches(limited, res.solutions, free.fk(q)[None])


def test_a_search_does_not_claim_out_of_limits() -> None:
    # One joint limited to [0, 1] and a target at q = -1e-9: the search stays
    # at the bound, 1e-9 m short; the check's polishing then reaches the target
    # just outside the limit. A search proves nothing about the rest of the
    # limits: not_found, the candidate listed among out_of_limits.
    robot = Robot.from_dh([Revolute(a=1.0, qlim=(0.0, 1.0))], name="1R", convention="standard")
    res = numeric(robot, robot.fk(np.array([-1e-9]))[:3, 3])
    assert res.status == "not_found"
    np.testing.assert_allclose(res.out_of_limits, [[-1e-9]], rtol=1e-6)
    assert "just outside the joint limits" in res.message
    far = numeric(robot, robot.fk(np.array([-0.5]))[:3, 3])  # stuck at the bound
    assert far.status == "not_found" and far.out_of_limits.shape == (0, 1)
    np.testing.assert_allclose(far.nearest_error[0], 2 * math.sin(0.25), rtol=1e-9)


def test_planar_2r_position_target() -> None:
    robot = planar2r()
    q = np.array([[0.3, 1.1], [-2.0, -0.5], [2.9, 2.0], [0.0, PI]])  # (4, 3) targets
    targets = robot.fk(q)[:, :3, 3]
    res = numeric(robot, targets)
    assert_all_ok(res)
    assert_reaches(robot, first(res), targets)


def test_planar_2r_full_pose_target() -> None:
    # A pose: the orientation about z follows from the position here, so the
    # target is reachable and both must be met.
    robot = planar2r()
    targets = robot.fk(np.array([[0.4, -1.3]]))
    res = numeric(robot, targets)
    assert_all_ok(res)
    assert_reaches(robot, first(res), targets)


def test_prismatic_arm_full_pose_within_limits() -> None:
    robot = stanford()
    targets = robot.fk(random_q(robot, 60, seed=9))
    res = numeric(robot, targets)
    assert_all_ok(res)
    assert_reaches(robot, first(res), targets)


def test_prismatic_joint_without_limits() -> None:
    # Cylindrical RPP arm, prismatic joints free: restarts sample them in ±1 m,
    # the targets need 1.5 m.
    robot = Robot.from_dh(
        [Revolute(d=0.5), Prismatic(alpha=-PI / 2), Prismatic()],
        name="cylindrical",
        convention="standard",
    )
    q = np.array([[0.4, 0.8, 1.5], [-2.0, -0.3, 0.6]])
    targets = robot.fk(q)[:, :3, 3]
    res = numeric(robot, targets)
    assert_all_ok(res)
    assert_reaches(robot, first(res), targets)


def test_ignoring_limits_wraps_angles() -> None:
    robot = puma()
    targets = robot.fk(random_q(robot, 20, seed=10))
    res = numeric(robot, targets, respect_limits=False)
    assert_all_ok(res)
    q = first(res)
    assert np.all((q > -PI) & (q <= PI))
    np.testing.assert_allclose(robot.fk(q), targets, atol=1e-9)


# ---------------------------------------- arms that are hard to converge on
def test_nearly_parallel_axes_converge() -> None:
    # Two prismatic axes 1e-9 rad from parallel: the target's y (a few nm) is
    # reached only along a direction of singular value 1e-9, which damping
    # above LAMBDA_MIN freezes (at 1e-18 these targets are not solved).
    assert LAMBDA_MIN == 1e-21
    eps = 1e-9
    robot = Robot.from_dh(
        [Prismatic(alpha=eps), Prismatic(theta=PI / 2, alpha=PI / 2), Prismatic()],
        name="PPP",
        convention="standard",
    )
    q = np.array([[0.3, 5.0, 0.2], [-2.0, 4.0, 1.0], [1.0, -3.0, 0.5], [0.0, 2.5, -0.7]])
    targets = robot.fk(q)[:, :3, 3]
    assert np.abs(targets[:, 1]).min() > 20 * TOL
    res = numeric(robot, targets)
    assert_all_ok(res)
    assert_reaches(robot, first(res), targets)


def test_a_near_miss_gets_gauss_newton_steps_across_a_fold() -> None:
    # A wrist whose axes miss each other by 0.4 µm, the tool 0.77 m off its
    # centre: the position is a fold of the wrist's sphere. The damped steps
    # stall 1.2e-10 m away; the first undamped step raises the error to
    # 1e-7 m, the next lands (found by hypothesis).
    a, lim = 4.220394602511202e-07, (-0.7835209183654359, 1.1880763871597824)
    tool = np.array(
        [
            [-0.7791679237711326, 0.4788705084995612, -0.4044507172147837, 0.3816555455393418],
            [-0.37958018683060596, 0.15300904801799142, 0.9124182774310639, -0.6632332887310044],
            [0.4988148236889352, 0.8644485336409562, 0.0625500148215552, 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ]
    )
    robot = Robot.from_dh(
        [
            Revolute(a=-a, alpha=PI / 2, offset=PI / 2, qlim=lim),
            Revolute(alpha=PI / 2, offset=PI / 2, qlim=(-6.103515625e-05, 0.14423010905537992)),
            Revolute(a=-a, alpha=-PI, offset=PI / 2, qlim=lim),
        ],
        tool=tool,
        name="wrist",
        convention="standard",
    )
    q = np.array([0.4454747566899011, 0.057049601567374666, 0.7471597799800846])
    target = robot.fk(q)[:3, 3]
    res = numeric(robot, target)
    assert res.status == "ok", res.message
    assert_reaches(robot, res.solutions, target[None])


# ------------------------------------------------ batch, determinism
def _same(a: IKResult, b: IKResult) -> None:
    assert a.status == b.status and a.message == b.message
    np.testing.assert_array_equal(a.solutions, b.solutions)
    np.testing.assert_array_equal(a.residuals, b.residuals)
    np.testing.assert_array_equal(a.out_of_limits, b.out_of_limits)
    assert a.gap == b.gap
    np.testing.assert_array_equal(a.nearest_error, b.nearest_error)


def test_batch_equals_one_by_one() -> None:
    # Reachable, beyond the reach bound (unreachable), inside the 2R arm's
    # hole (not found), out of limits for the search (not found), and a
    # malformed row: solution by solution and message by message.
    robot = planar2r().with_limits([(-2.0, 2.0), None])
    targets = np.array(
        [
            [1.2, 0.5, 0.0],
            [-0.3, 1.1, 0.0],
            [2.5, 0.0, 0.0],
            [0.1, 0.0, 0.0],
            robot.fk(np.array([3.0, 0.0]))[:3, 3],  # needs q1 = 3 > 2: not found
            [np.nan, 0.0, 0.0],
        ]
    )
    batch = numeric(robot, targets)
    assert list(batch.status) == ["ok", "ok", "unreachable", "not_found", "not_found", "invalid"]
    for i in range(5):
        _same(batch[i], numeric(robot, targets[i]))
    arm = panda()
    T = arm.fk(random_q(arm, 12, seed=12))
    T[3, :3, 3] = [2.0, 1.0, 0.0]
    batch = numeric(arm, T)
    for i in range(12):
        _same(batch[i], numeric(arm, T[i]))
    assert batch.status[3] == "unreachable" and (batch.status != "ok").sum() == 1


def test_batch_equals_one_by_one_where_the_check_completes_the_first_attempt() -> None:
    # Found by the pose audit (benchmarks/audit_ik.py, a calibrated UR): from this first
    # guess, near an elbow singularity (σmin/σmax 2e-5), LM's first attempt stops short of
    # the tolerance and the check's polish completes it; the full search would go on to a
    # restart converging 5e-4 rad away. One target and a batch must both take the first.
    rows = [
        (0.0891849682615843, -0.0009683410532165791, 1.5707792586092097),
        (-0.000549645834894505, -0.42562834192497045, 0.0009174807313572576),
        (-0.00044177736250496883, -0.39306164971486085, 0.00013142766726859751),
        (0.10992705352950112, 0.00023928029060217028, 1.5706205116734957),
        (0.0951199902115929, 0.0005970954545483546, -1.5706487519178873),
        (0.08302095454035964, 0.00010986051534969004, 0.0006190054810758967),
    ]
    base = np.array([
        [0.05724290865266923, 0.551452415789161, 0.8322400390087468, -0.23870029031817008],
        [0.16040840420449534, 0.8176963815755689, -0.5528487780747904, 0.18663749859021506],
        [-0.9853894627351916, 0.16514496867455503, -0.04165028273530469, -0.19465208603532091],
        [0.0, 0.0, 0.0, 1.0],
    ])  # fmt: skip
    tool = np.array([
        [0.3737208369063856, 0.2372890944318461, 0.8966753156665488, -0.08458222241199938],
        [0.9273503888303815, -0.11519727231472054, -0.35602084880999324, 0.1517838070138523],
        [0.018814685703747114, 0.9645846122113717, -0.2631017550053718, -0.0037197183243646847],
        [0.0, 0.0, 0.0, 1.0],
    ])  # fmt: skip
    robot = Robot.from_dh(
        [Revolute(d=d, a=a, alpha=al) for d, a, al in rows],
        base=base,
        tool=tool,
        convention="standard",
    )
    q = np.array([-2.8427797789929983, 1.428565127395248, 0.00020204669053613955,
                  -1.4875043597231448, 1.0932547274170918, 2.2158742580218593])  # fmt: skip
    q0 = np.array([-2.842780572777552, 1.4286828622204073, -4.2965574476743715e-05,
                   -1.487377059226306, 1.0932539426020735, 2.2158742080634304])  # fmt: skip
    T = robot.fk(q)
    one = robot.ik(T, method="numeric", q0=q0)
    batch = robot.ik(np.stack([T, T]), method="numeric", q0=np.stack([q0, q0]), workers=1)
    assert one.status == "ok"
    for i in range(2):
        _same(batch[i], one)


def test_deterministic_given_a_seed() -> None:
    robot = panda()
    targets = robot.fk(random_q(robot, 50, seed=13))
    a = numeric(robot, targets, seed=7)
    b = numeric(robot, targets, seed=7)
    c = numeric(robot, targets, seed=np.random.default_rng(7))
    np.testing.assert_array_equal(a.solutions, b.solutions)
    np.testing.assert_array_equal(a.solutions, c.solutions)
    d = numeric(robot, targets)  # no seed: a fixed default, still reproducible
    np.testing.assert_array_equal(d.solutions, numeric(robot, targets).solutions)


# ------------------------------------------------------------- shapes
@pytest.mark.parametrize("shape", [(), (1,), (3, 2)], ids=str)
def test_shapes(shape: tuple[int, ...]) -> None:
    robot = iiwa14()
    q = random_q(robot, max(1, math.prod(shape)), seed=14).reshape(*shape, 7)
    res = numeric(robot, robot.fk(q))
    if shape == ():
        assert isinstance(res, IKResult)
        assert res.solutions.shape == (1, 7) and res.branches == ("numeric",)
        assert res.residuals.shape == (1, 2) and res.free_joints == () and res.gap is None
        assert not res.complete
        assert_reaches(robot, res.solutions, robot.fk(q)[None])
        return
    assert isinstance(res, IKBatchResult)
    assert res.shape == shape and res.status.shape == shape and res.count.shape == shape
    assert res.solutions.shape == (*shape, 1, 7)
    assert res.residuals.shape == (*shape, 1, 2) and res.branches.shape == (*shape, 1)
    assert res.free.shape == (*shape, 7) and not res.free.any()
    assert res.gap.shape == shape and np.isnan(res.gap).all()
    assert res.nearest_error.shape == (*shape, 2)
    assert res.message.shape == shape
    assert np.all(res.residuals <= TOL)
    assert_reaches(robot, res.solutions[..., 0, :], robot.fk(q))


def test_single_pose_and_q0_forms() -> None:
    robot = puma()  # not redundant: a guess near a solution converges to it
    q = random_q(robot, 3, seed=15)
    T = robot.fk(q)
    near = q + 0.05
    a = numeric(robot, T, q0=near)  # (N, n)
    b = numeric(robot, T, q0=near[0])  # (n,), shared
    assert_all_ok(a)
    assert_all_ok(b)
    np.testing.assert_allclose(first(a), q, atol=1e-8)  # the nearby solution


def test_empty_batch() -> None:
    robot = iiwa14()
    res = numeric(robot, np.zeros((0, 4, 4)))
    assert isinstance(res, IKBatchResult)
    assert res.shape == (0,) and res.solutions.shape == (0, 0, 7)
    assert numeric(robot, np.zeros((0, 3))).solutions.shape == (0, 0, 7)


# -------------------------------------------------------------- input
def test_bad_input_is_named() -> None:
    robot = iiwa14()
    T = robot.fk(random_q(robot, 2, seed=16))
    with pytest.raises(DimensionError, match="target"):
        numeric(robot, np.zeros((2, 5)))
    with pytest.raises(DimensionError, match="NaN"):
        numeric(robot, np.full((4, 4), np.nan))
    with pytest.raises(DimensionError, match="q0"):
        numeric(robot, T, q0=np.zeros((3, 7)))
    with pytest.raises(DimensionError, match="q0"):
        numeric(robot, T, q0=np.zeros(6))
    with pytest.raises(DimensionError, match="mask"):
        numeric(robot, T, mask=[1, 1, 1])
    with pytest.raises(DimensionError, match="mask"):
        numeric(robot, T, mask=[1, 1, 1, -1, 1, 1])
    with pytest.raises(DimensionError, match="no error component"):
        numeric(robot, T, mask=[0, 0, 0, 0, 0, 0])
    with pytest.raises(KinematicaError, match="tol"):
        numeric(robot, T, tol=0.0)


@pytest.mark.parametrize("seed", [-1, "abc", 2.5, True, np.int64(-3), [1, 2]], ids=repr)
def test_seed_is_checked_up_front(seed) -> None:
    # Always, even when no restart would be drawn (q0 is a solution) and for
    # the closed-form path that never draws one.
    robot = iiwa14()
    q = random_q(robot, 1, seed=17)[0]
    calls = [
        lambda: robot.ik(robot.fk(q), method="numeric", q0=q, seed=seed),
        lambda: robot.ik(robot.fk(q[None]), method="numeric", seed=seed),
        lambda: load("puma560").ik(np.eye(4), seed=seed),  # closed form
    ]
    for call in calls:
        with pytest.raises(ArgumentError, match="seed") as info:
            call()
        assert isinstance(info.value, ValueError)


@pytest.mark.parametrize("workers", [0, -1, 1.5, "two"], ids=repr)
def test_workers_are_checked_up_front(workers) -> None:
    robot = iiwa14()
    T = robot.fk(random_q(robot, 1, seed=17)[0])
    with pytest.raises(ArgumentError, match="workers"):
        numeric(robot, T, workers=workers)  # one target: no thread is started


def test_base_and_tool_transforms_and_both_conventions() -> None:
    c, s = math.cos(0.4), math.sin(0.4)
    base = np.array([[c, -s, 0, 0.3], [s, c, 0, -0.2], [0, 0, 1, 0.1], [0, 0, 0, 1.0]])
    tool = np.eye(4)
    tool[:3, 3] = [0.02, 0.0, 0.15]
    for robot in (stanford().with_base(base).with_tool(tool), stanford().to_convention("modified")):
        targets = robot.fk(random_q(robot, 30, seed=18))
        res = numeric(robot, targets)
        assert_all_ok(res)
        assert_reaches(robot, first(res), targets)


# ------------------------------------------- huge targets, JSON, messages
@pytest.mark.parametrize("x", [1e300, 1.4e154, -3e200])
def test_huge_targets_are_unreachable_with_their_gap(x: float) -> None:
    robot = panda()
    T = np.eye(4)
    T[0, 3] = x
    for res in (numeric(robot, T), numeric(robot, T[None])[0], numeric(robot, T[:3, 3])):
        assert res.status == "unreachable"
        assert res.gap is not None and math.isclose(res.gap, abs(x), rel_tol=1e-12)
        assert "closed form" not in res.message


def test_a_distance_that_overflows_is_an_infinite_gap() -> None:
    robot = panda()
    res = numeric(robot, np.full(3, 1.5e308))
    assert res.status == "unreachable" and res.gap == math.inf
    assert "overflows" in res.message and "closed form" not in res.message


def test_messages_of_a_search_never_speak_of_a_closed_form() -> None:
    robot = planar2r()
    for target in ([0.1, 0.0, 0.0], [2.5, 0.0, 0.0], [1.0, 0.5, 0.0]):
        res = numeric(robot, np.array(target))
        assert "closed form" not in res.message, res.message


# ------------------------------------------------- the core's own model
@pytest.mark.parametrize(
    "mask",
    [[1, 1, 1, 0, 0, 0], [1, 1, 1, 1, 1, 0], [0, 1, 0, 1, 0, 0], [2, 1, 1, 0, 0.5, 0.5]],
    ids=str,
)
def test_error_jacobian_matches_finite_differences(mask) -> None:
    # The rows each LM step linearises: √w_k · ∂(−e_k)/∂q for the counted
    # components, e from kinematica.spatial.se3_error (numpy, not the core).
    # With only some rotation components counted the rows are the exact
    # derivative -J_r⁻¹(Δω) J_ω of the error, also far from the target.
    robot = stanford()
    chain, w = robot.chain, np.asarray(mask, dtype=float)
    counted = np.flatnonzero(w > 0)
    q = random_q(robot, 1, seed=19)[0]
    T = robot.fk(random_q(robot, 1, seed=20)[0])
    err, J = lm_rows(chain.core, w.tolist(), q, T)
    r = err.shape[0]
    assert r == counted.size
    np.testing.assert_allclose(err[:r], se3_error(robot.fk(q), T)[counted], atol=1e-13)
    h = 1e-6
    for i in range(robot.dof):
        dq = np.zeros(robot.dof)
        dq[i] = h
        up = se3_error(robot.fk(q + dq), T)[counted]
        down = se3_error(robot.fk(q - dq), T)[counted]
        fd = -(up - down) / (2 * h) * np.sqrt(w[counted])
        np.testing.assert_allclose(J[:r, i], fd, atol=1e-7)


# ------------------------------------------ random arms, degenerate geometry
SPECIAL = (0.0, PI / 2, -PI / 2, PI, -PI)
#: A Jacobian whose smallest singular value is below this fraction of its
#: largest is singular (the issue's "1e-6 away from a singular set").
RANK_TOL = 1e-6
#: Configurations this far off a special value (a folded or stretched arm,
#: aligned axes) are drawn as often as the special values themselves.
NUDGES = (0.0, 1e-8, -1e-9, 1e-10, -1e-11, 1e-12)


def _floats(lo: float, hi: float) -> st.SearchStrategy[float]:
    return st.floats(lo, hi, allow_nan=False, allow_infinity=False, allow_subnormal=False)


@st.composite
def degenerate_arms(draw: st.DrawFn) -> RobotSpec:
    """1-8 joints, mixed R/P, either convention, base and tool, limits or none.

    Lengths are often 0 (intersecting axes), a shared value (equal links) or
    1e-10; angles often special (parallel or perpendicular axes); offsets
    often 1e-10.
    """
    n = draw(st.integers(1, 8))
    shared = draw(st.sampled_from([0.25, 0.5, 1.0]))
    length = st.one_of(
        st.just(0.0), st.just(shared), st.just(-shared), st.just(1e-10), _floats(-1.0, 1.0)
    )
    angle = st.one_of(st.sampled_from(SPECIAL), _floats(-PI, PI))
    offset = st.one_of(angle, st.just(1e-10), st.just(PI / 2 + 1e-10))
    joints = []
    for _ in range(n):
        kind = draw(st.sampled_from("RRP"))
        qlim = None
        if draw(st.booleans()):
            if kind == "R":
                lo = draw(_floats(-PI, PI))
                qlim = (lo, lo + draw(_floats(0.05, 2 * PI)))
            else:
                lo = draw(_floats(-1.0, 0.5))
                qlim = (lo, lo + draw(_floats(0.05, 1.5)))
        joints.append(
            JointSpec(
                kind=kind,
                const=draw(angle if kind == "P" else length),
                a=draw(length),
                alpha=draw(angle),
                offset=draw(offset if kind == "R" else length),
                qlim=qlim,
            )
        )
    return RobotSpec(
        joints=tuple(joints),
        convention=draw(st.sampled_from(["standard", "modified"])),
        base=draw(transforms()),
        tool=draw(transforms()),
    )


def configuration(draw: st.DrawFn, spec: RobotSpec) -> np.ndarray:
    """Joint values within the limits: special values (nudged) or uniform."""
    q = []
    for j in spec.joints:
        lo, hi = j.qlim or ((-PI, PI) if j.kind == "R" else (-1.0, 1.0))
        v = draw(st.sampled_from(SPECIAL)) + draw(st.sampled_from(NUDGES))
        if j.kind == "P" or not lo <= v <= hi or draw(st.booleans()):
            v = draw(_floats(lo, hi))
        q.append(v)
    return np.array(q)


def assert_reference_reaches(spec: RobotSpec, res: IKResult, target: np.ndarray) -> None:
    """The solution reaches the target by the slides' FK (not the library's), within limits."""
    assert res.status == "ok", res.message
    (q,) = res.solutions
    T = spec.ref_fk(q)
    slack = 1e-13  # the two FKs' round-off (the check ran on the library's)
    position = target[:3, 3] if target.shape == (4, 4) else target
    assert np.linalg.norm(T[:3, 3] - position) <= TOL + slack
    if target.shape == (4, 4):
        assert rotation_angle(T[:3, :3], target[:3, :3]) <= TOL + slack
    for v, j in zip(q, spec.joints, strict=True):
        if j.qlim is not None:  # with the check's slack for floating point
            assert j.qlim[0] - LIMIT_TOL <= v <= j.qlim[1] + LIMIT_TOL


@settings(max_examples=400)
@given(st.data())
def test_targets_made_by_fk_are_always_found(data: st.DataObject) -> None:
    """Found, unless the configuration is singular; then ``not_found``, never ``unreachable``.

    At a configuration where the Jacobian loses rank (within ``RANK_TOL``,
    relative) the search converges only linearly and may stop a little over
    the tolerance: ``not_found`` (it proves nothing) is then the honest answer.
    """
    spec = data.draw(degenerate_arms())
    robot = spec.build()
    q = configuration(data.draw, spec)
    T = spec.ref_fk(q)
    for target in (T, T[:3, 3]):
        res = numeric(robot, target)
        assert isinstance(res, IKResult)
        if res.status == "not_found":
            J = robot.jacobian(q)[: 6 if target.shape == (4, 4) else 3]
            sigma = np.linalg.svd(J, compute_uv=False)
            assert sigma[-1] <= RANK_TOL * sigma[0], res.message
            continue
        assert_reference_reaches(spec, res, target)
