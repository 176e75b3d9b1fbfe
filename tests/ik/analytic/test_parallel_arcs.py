"""UR-type arms at the singular targets the issue 34 audit found answered wrongly.

``benchmarks/ik_singular.py`` (seed 0: 67,200 targets on 240 UR-type arms, each made by
FK of a configuration placed on a singular set) found 26 ``singular`` answers with q1
free whose representatives missed the generating configuration, every one on an arm
whose axes 5 and 6 are parallel: a pair's continuum spans one or more arcs of q1, and
all the pairs were represented at the first q1 at which any of them existed. Now each
arc of each pair has its own representative (``solvers/parallel.hpp``'s
``free_q1_arcs``). And one ``ok`` without ``near_singular`` and without the
configuration: a shoulder fold of an arm whose axes 5 and 6 are apart, where the
quartic's double root was split by round-off and Newton from it leapt onto the two
simple roots (``parallel_quartic.hpp``'s ``NEWTON_LEAP``).

Each case is judged by the audit's own ``judge`` (``tests/support/ik_singular_audit.py``:
a ``singular`` answer must reach the configuration from a representative along the
free joints, an ``ok`` must hold it), and reproduced against the code before the fix.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.typing import NDArray
from support.ik_singular_audit import conditioning, judge, reached_along

from kinematica import _core
from kinematica.dh import Revolute
from kinematica.ik.analytic.parallel import pack
from kinematica.ik.structure import features
from kinematica.robot import Robot

pytestmark = pytest.mark.filterwarnings("ignore::kinematica.KinematicaWarning")

FloatArray = NDArray[np.float64]
NEWTON_LEAP = 1e-3  # parallel_quartic.hpp


def _robot(links: list[Revolute], convention: str, base: list[list[float]],
           tool: list[list[float]]) -> Robot:  # fmt: skip
    return Robot.from_dh(links, convention=convention, base=np.array(base),  # type: ignore[arg-type]
                         tool=np.array(tool))  # fmt: skip


#: Axes 5 and 6 parallel (standard table): two of the audit's targets on one arm.
PARALLEL_STANDARD = _robot(
    [
        Revolute(d=0.23123825602498327, alpha=-1.5707963267948966, offset=-2.883320782605004),
        Revolute(a=-0.3709481235623401),
        Revolute(a=-0.26880295141492366, alpha=math.pi),
        Revolute(d=-0.185902877338333, a=-0.039950018796399235, alpha=-1.5707963267948966,
          offset=0.04394600566293194),
        Revolute(d=-0.12110324379524946, a=0.03447862045786326, offset=-3.086973093175152),
        Revolute(d=-0.12773760089217748, a=0.027183165719266766, alpha=-0.7427947606288958),
    ],
    "standard",
    [[0.014866549924323014, 0.9895861933251605, -0.1431717558513754, -0.10273434430054107],
     [0.9407141221349217, 0.03468538844143465, 0.33742238254832874, 0.22173877847287293],
     [0.33887449905425393, -0.1396999993159807, -0.9304020550718082, -0.2492790496118371],
     [0.0, 0.0, 0.0, 1.0]],
    [[0.07941223841827161, 0.877020860386053, 0.47384396887277935, -0.08058848145072846],
     [0.05842974361223613, 0.470432665427155, -0.8804993312663623, -0.06917377448227549],
     [-0.9951279623499725, 0.09760900443509407, -0.01388599302829574, -0.0848982759341769],
     [0.0, 0.0, 0.0, 1.0]],
)  # fmt: skip

#: Axes 5 and 6 parallel (modified table).
PARALLEL_MODIFIED = _robot(
    [
        Revolute(d=0.38442697351184496, offset=-1.354426562663815),
        Revolute(alpha=-1.5707963267948966),
        Revolute(a=-0.4927454723954476),
        Revolute(d=-0.1297015261764634, a=0.4062501889695055, offset=0.8613600789041191),
        Revolute(d=-0.1388169215849407, a=-0.0028001617691965353, alpha=-1.5707963267948966,
          offset=-0.09569365099404559),
        Revolute(d=-0.08341322264415658, a=0.09997496968035563),
    ],
    "modified",
    [[0.672829358703823, 0.5346378505120623, 0.5113345508236697, 0.3358978634074584],
     [0.5805070034546241, -0.8100065018062228, 0.08307277515395065, 0.027109765817378673],
     [0.45859816070971693, 0.24093948582888516, -0.8553571716903865, -0.2284929047246419],
     [0.0, 0.0, 0.0, 1.0]],
    [[0.5649590042135448, -0.2575316894410394, 0.7838997081844613, -0.16087833953917424],
     [-0.5750605766278969, -0.8041956937692776, 0.15024852522184806, -0.15265130839445712],
     [0.5917150131325303, -0.5356740754008854, -0.6024339201746324, 0.12670651389622603],
     [0.0, 0.0, 0.0, 1.0]],
)  # fmt: skip

#: Axes 5 and 6 apart (the quartic), at a fold of its shoulder.
APART = _robot(
    [
        Revolute(d=0.06640382514421565, alpha=-1.5707963267948966, offset=1.2241793227323345),
        Revolute(a=0.42101951889960704, alpha=math.pi),
        Revolute(a=-0.3158100712939884, alpha=math.pi),
        Revolute(d=0.1574679847634794, a=-0.0011849120128719637, alpha=1.5707963267948966,
          offset=3.035951871296186),
        Revolute(d=-0.14254230586750238, a=0.09696605553689328, alpha=-1.5707963267948966,
          offset=2.302966710836115),
        Revolute(d=-0.06313780434002034, a=-0.04176701988445702, alpha=2.6143453073730374),
    ],
    "standard",
    [[-0.9093895957913531, 0.12907305176048597, -0.3954120766689797, -0.11257778128232798],
     [-0.09985708883169253, -0.990580513142969, -0.09369529759530365, 0.08633764571278513],
     [-0.4037810358059175, -0.045720829942685386, 0.9137124716412994, -0.002252892474771895],
     [0.0, 0.0, 0.0, 1.0]],
    [[-0.6776665020682993, -0.6527317430767374, -0.3386877375319619, -0.0416969430927841],
     [0.49425042838696626, -0.745311733751564, 0.44746724301510293, 0.06865442268050381],
     [-0.5445040183633316, 0.13583700199960597, 0.8276857391993313, -0.12351596046158231],
     [0.0, 0.0, 0.0, 1.0]],
)  # fmt: skip
APART_Q = np.array([0.6045296272403049, 0.008115897588295784, -0.11897428230462449,
                    -0.8866950044665054, -1.229415699992534, -2.65496658476232])  # fmt: skip

CASES = [
    (PARALLEL_STANDARD, [-1.9455703313915924, -0.5286687431829291, 1.753580679671399,
                         -1.9606267227642493, 1.4922156317338073, -0.8111075395849436]),
    (PARALLEL_STANDARD, [-1.5683927263587538, 2.5269891790730066, -0.3818293939749675,
                         -1.040378874154547, -2.1171282415133263, 1.9514662556437097]),
    (PARALLEL_MODIFIED, [-1.2225813324884907, -0.8385712214972889, 2.7290783877163642,
                         0.38972540846657244, 1.6745941022477258, -2.5941173669142925]),
]  # fmt: skip


@pytest.mark.parametrize(("robot", "q"), CASES)
def test_each_arc_of_q1_has_its_representative(robot: Robot, q: list[float]) -> None:
    """The audit's targets: "singular" with q1 free, and the generating configuration
    reached from a representative along q1 (the other joints following); before, 0.08 to
    2 rad off every representative."""
    qa = np.array(q)
    T = robot.fk(qa)
    res = robot.ik(T, respect_limits=False)
    assert res.status == "singular" and res.free_joints == (0,), res.message
    assert res.method == "analytic:three-parallel-6R"
    assert judge(robot, qa, T, res, float(conditioning(robot, qa[None])[0])) == []


def test_a_pair_with_two_arcs_gets_a_representative_on_each() -> None:
    """The first target: both pairs of the parallel wrist exist on two arcs of q1 each
    (about -1.87 and 0.29 rad); before, all four branches were represented at the first
    q1 found (4 rows), and the configuration, on the other arc, was 1.96 rad off. Now 8
    rows at two values of q1, each a solution, and q reached along q1 from one of them."""
    robot, q = CASES[0]
    qa = np.array(q)
    T = robot.fk(qa)
    res = robot.ik(T, respect_limits=False)
    assert res.status == "singular" and res.count == 8
    q1s = np.unique(np.round(res.solutions[:, 0], 9))
    assert len(q1s) == 2 and abs(math.remainder(q1s[1] - q1s[0], 2 * math.pi)) > 1.0
    reached = [reached_along(robot, r, qa, (0,), T) for r in res.solutions]
    assert min(reached) < 1e-6
    # from the representatives of the other arc the walk along q1 does not get there
    other = np.abs(np.remainder(res.solutions[:, 0] - qa[0] + math.pi, 2 * math.pi) - math.pi)
    assert all(d > 1e-3 for d, o in zip(reached, other, strict=True) if o > 1.0)


def test_a_double_root_of_the_quartic_is_kept_at_a_shoulder_fold() -> None:
    """The audit's unflagged "ok": q at a fold of the shoulder (σmin 0 there), the
    quartic's double root split by round-off into a ± 1e-8 i; Newton from it took a
    first step of about a radian onto a simple root, and both seeds ended on the other
    two roots: 4 solutions, q 2.3 rad from every one."""
    robot = APART
    T = robot.fk(APART_Q)
    assert conditioning(robot, APART_Q[None])[0] < 1e-10
    res = robot.ik(T, respect_limits=False)
    assert res.status == "ok" and res.method == "analytic:three-parallel-6R"
    d = np.abs(np.remainder(res.solutions - APART_Q + math.pi, 2 * math.pi) - math.pi)
    assert d.max(axis=1).min() < 1e-6
    assert judge(robot, APART_Q, T, res, float(conditioning(robot, APART_Q[None])[0])) == []


def _equations(robot: Robot, T: FloatArray) -> tuple[object, FloatArray, FloatArray, FloatArray]:
    """ParallelParams and x6, L1, L2 of equations (1) and (2) at target T (as solve())."""
    P, mode = pack(robot.chain, features(robot.chain))  # type: ignore[misc]
    assert mode == _core.parallel.Mode.general
    G = T @ np.linalg.inv(np.asarray(P.home))
    x6 = G[:3, :3] @ np.asarray(P.h6)
    w6 = G[:3, :3] @ np.asarray(P.p6) + G[:3, 3] - np.asarray(P.p1)
    rows = [np.asarray(v) for v in (P.kperp, P.hk, P.kpar)]
    return P, x6, np.array([r @ x6 for r in rows]), np.array([r @ w6 for r in rows])


def test_newton_leap_keeps_a_seed_that_meets_the_equations() -> None:
    """NEWTON_LEAP: Newton from the double root (which meets (1) and (2) to round-off)
    stays there; the simple roots nearby are more than 1 rad away."""
    assert _core.parallel.NEWTON_LEAP == NEWTON_LEAP
    T = APART.fk(APART_Q)
    P, x6, L1, L2 = _equations(APART, T)
    q1, q5, res, *_ = _core.parallel.newton(P, x6, L1, L2, APART_Q[0], APART_Q[4])
    assert res < 1e-12
    assert abs(q1 - APART_Q[0]) < 1e-6 and abs(q5 - APART_Q[4]) < 1e-6
    # from a seed 0.3 rad off (its residual above TRIG_TOL) the steps are taken: a root
    q1, q5, res, *_ = _core.parallel.newton(P, x6, L1, L2, APART_Q[0] + 0.3, APART_Q[4])
    assert res < 1e-10
