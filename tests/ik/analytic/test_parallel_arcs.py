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
simple roots. The pair system is at a fold there, and the answer now says so
(``near_singular``, as for the family's other folds).

Each case is judged by the audit's own ``judge`` (``tests/support/ik_singular_audit.py``:
a ``singular`` answer must reach the configuration from a representative along the
free joints, an ``ok`` must hold it), and reproduced against the code before the fix.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable

import numpy as np
import pytest
from numpy.typing import NDArray
from support.ik_singular_audit import TOL, conditioning, fk_error, judge

from kinematica.dh import Revolute
from kinematica.robot import Robot

pytestmark = pytest.mark.filterwarnings("ignore::kinematica.KinematicaWarning")

FloatArray = NDArray[np.float64]


def _robot(links: list[Revolute], convention: str, base: list[list[float]],
           tool: list[list[float]]) -> Callable[[], Robot]:  # fmt: skip
    """The arm's builder: an arm held at module level (or by a parametrize mark) lives
    until the interpreter's shutdown, after the core's teardown, which then reports its
    Chain as leaked."""
    return functools.partial(Robot.from_dh, links, convention=convention,  # type: ignore[arg-type]
                             base=np.array(base), tool=np.array(tool))  # fmt: skip


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

#: Axes 5 and 6 apart, at folds of the pair (q1, q5) (the audit's, seed 0).
NEAR_FOLDS = [
    (
        _robot(
            [
                Revolute(d=0.21947856136953414, alpha=-1.5707963267948966,
                         offset=2.4368189694838582),
                Revolute(a=-0.5625382668389771, alpha=math.pi),
                Revolute(a=-0.42409210386373253),
                Revolute(d=0.02757496376660526, a=-0.062108993768790956,
                         alpha=-1.5707963267948966, offset=3.0336871062742556),
                Revolute(d=-0.17562153109469514, a=-0.033812943395989184,
                         alpha=-1.5707963267948966, offset=0.3338064642066292),
                Revolute(d=0.054982770644092405, a=0.053291337811419426,
                         alpha=0.7198745016214247),
            ],
            "standard",
            [[0.5718505810615164, 0.4339523943083848, -0.6961840506745511, -0.24629676161560443],
             [-0.7037098718288439, 0.6956569558050779, -0.1444085043570633, 0.1569687878331424],
             [0.4216388611480659, 0.5724916761962849, 0.7031884181751928, 0.16041240606817475],
             [0.0, 0.0, 0.0, 1.0]],
            [[0.029802569567948356, 0.024729130817709333, -0.999249857110897, 0.083975804207437],
             [0.8279965577870817, 0.5594072278741232, 0.03853898928270616, 0.0078116265453805345],
             [0.559940628227575, -0.8285240029662323, -0.0038038623685980877, -0.16844304144820743],
             [0.0, 0.0, 0.0, 1.0]],
        ),
        [-0.1399839227862354, -2.175812516942464, 2.868662948641812, 3.0039966811334375,
         -0.333806716844718, -2.810892898735638],
    ),
    (
        _robot(
            [
                Revolute(d=0.128165994294629, alpha=1.5707963267948966,
                         offset=-1.2516852367083584),
                Revolute(a=0.3060885893600043),
                Revolute(a=-0.2322434498123379),
                Revolute(d=-0.14502901499182844, a=0.08210623636564904,
                         alpha=-1.5707963267948966, offset=2.2325157382733893),
                Revolute(d=0.0004549650032167063, a=0.10859802451600109,
                         alpha=-1.5707963267948966, offset=0.942823968832843),
                Revolute(d=0.019380226722030824, a=-0.01451359666615297,
                         alpha=-1.2161802540751958),
            ],
            "standard",
            [[-0.3487748340864818, 0.26821396360040994, 0.8980074525513165, -0.16583511756079772],
             [0.8155839664336797, -0.38518190576370914, 0.4318074723398653, 0.34090228976185544],
             [0.4617130156322794, 0.8830040595614468, -0.08440925301026847, -0.310093960550648],
             [0.0, 0.0, 0.0, 1.0]],
            [[0.6254605651472247, 0.7720777846253243, -0.11267198380150069, 0.01297101898818237],
             [0.7164282708607271, -0.511074557764184, 0.47490349453089126, 0.06088425969411343],
             [0.30907865367447007, -0.3777548026090401, -0.8727953339406564, 0.0689461200490592],
             [0.0, 0.0, 0.0, 1.0]],
        ),
        [0.8692871069135562, 0.22797758315112882, 0.5947081330785529, 0.6758925977251926,
         -0.9428239495384129, 0.7117982847376623],
    ),
]  # fmt: skip

CASES = [
    (PARALLEL_STANDARD, [-1.9455703313915924, -0.5286687431829291, 1.753580679671399,
                         -1.9606267227642493, 1.4922156317338073, -0.8111075395849436]),
    (PARALLEL_STANDARD, [-1.5683927263587538, 2.5269891790730066, -0.3818293939749675,
                         -1.040378874154547, -2.1171282415133263, 1.9514662556437097]),
    (PARALLEL_MODIFIED, [-1.2225813324884907, -0.8385712214972889, 2.7290783877163642,
                         0.38972540846657244, 1.6745941022477258, -2.5941173669142925]),
]  # fmt: skip


@pytest.mark.parametrize(("build", "q"), CASES)
def test_each_arc_of_q1_has_its_representative(build: Callable[[], Robot], q: list[float]) -> None:
    """The audit's targets: "singular" with q1 free, and the generating configuration
    reached from a representative along q1 (the other joints following); before, 0.08 to
    2 rad off every representative."""
    robot = build()
    qa = np.array(q)
    T = robot.fk(qa)
    res = robot.ik(T, respect_limits=False)
    assert res.status == "singular" and res.free_joints == (0,), res.message
    assert res.method == "analytic:three-parallel-6R"
    assert judge(robot, qa, T, res, float(conditioning(robot, qa[None])[0])) == []


#: Arclength step (rad, joint space) of the trace of a continuum of solutions, and
#: the most steps it may take before it closes.
TRACE_STEP = 0.01
TRACE_STEPS = 5000
#: Gauss-Newton corrections of each traced point back onto the pose.
TRACE_CORRECT = 4
#: A solution lies on a traced continuum when a traced point is this close (rad, max
#: over the joints, modulo 2π): traced points are TRACE_STEP apart. The first target's
#: representative on the configuration's arc is 2.2e-3 from its trace, those of the
#: other arc over 2 rad: 1000 times smaller or larger and the test below fails.
ON_TRACE_TOL = 0.01


def _wrapped(d: FloatArray) -> FloatArray:
    return np.remainder(d + math.pi, 2 * math.pi) - math.pi  # type: ignore[no-any-return]


def _pose_error(robot: Robot, q: FloatArray, T: FloatArray) -> FloatArray:
    """``(6,)`` the twist (m, rad; base frame) that takes fk(q) to T, to first order."""
    F = robot.fk(q)
    Re = T[:3, :3] @ F[:3, :3].T
    axis = np.array([Re[2, 1] - Re[1, 2], Re[0, 2] - Re[2, 0], Re[1, 0] - Re[0, 1]])
    return np.concatenate([T[:3, 3] - F[:3, 3], 0.5 * axis])


def _onto(robot: Robot, q: FloatArray, T: FloatArray) -> FloatArray:
    """q moved onto the pose T by TRACE_CORRECT Gauss-Newton steps (least-norm: across
    the continuum, not along it)."""
    for _ in range(TRACE_CORRECT):
        q = q + np.linalg.lstsq(robot.jacobian(q), _pose_error(robot, q, T), rcond=1e-9)[0]
    return q


def _trace(robot: Robot, q0: FloatArray, T: FloatArray) -> FloatArray:
    """``(n, 6)`` the closed curve of solutions of T through q0 (rad), TRACE_STEP apart.

    Pseudo-arclength continuation: a step along the Jacobian's null vector (rank 5 on
    the continuum), then back onto the pose across it. Arclength, not q1, parametrises
    the curve, so it turns at the ends of an arc of q1 (the folds where a walk along q1
    leaps between branches, whichever way round-off tips it) and comes back to q0.
    """
    q, prev, points = q0, np.zeros(6), [q0]
    for k in range(TRACE_STEPS):
        tangent = np.linalg.svd(robot.jacobian(q))[2][-1]
        if tangent @ prev < 0 or (k == 0 and tangent[0] < 0):
            tangent = -tangent
        prev = tangent
        q = _onto(robot, q + TRACE_STEP * tangent, T)
        points.append(q)
        if k > 5 and np.abs(_wrapped(q - q0)).max() < 0.6 * TRACE_STEP:
            return np.array(points)
    raise AssertionError(f"the continuum through {q0} did not close in {TRACE_STEPS} steps")


def _q1_arc(curve: FloatArray) -> tuple[float, float]:
    """``(start, length)`` of the arc of q1 a traced curve sweeps (rad)."""
    q1 = np.unwrap(curve[:, 0])
    return float(q1.min()), float(q1.max() - q1.min())


def _distance(curve: FloatArray, q: FloatArray) -> float:
    """How far q lies from the nearest point of a traced curve (rad, max over the joints)."""
    return float(np.abs(_wrapped(curve - q)).max(axis=1).min())


def _on_arc(q1: float, arc: tuple[float, float]) -> bool:
    return float(np.remainder(q1 - arc[0], 2 * math.pi)) <= arc[1]


def _arc_failures(robot: Robot, qa: FloatArray, T: FloatArray, sols: FloatArray) -> list[str]:
    """What the representatives of a singular answer with q1 free get wrong about the
    arcs, judged by the traced continua (no walk along q1): each must reach T; the
    continuum through qa must hold one of them; one whose q1 lies off qa's arc of q1
    must lie on another continuum, whose arc of q1 does not reach qa's q1."""
    out = []
    reach = np.array([float(fk_error(robot, s[None], T)[0]) for s in sols])
    out += [f"row {i} misses T by {e:.1e}" for i, e in enumerate(reach) if e > TOL]
    through_q = _trace(robot, qa, T)
    arc = _q1_arc(through_q)
    near = [_distance(through_q, s) for s in sols]
    if min(near) > ON_TRACE_TOL:
        out.append(f"no row on the continuum through q ({min(near):.1e} away)")
    traced: list[FloatArray] = []  # the other continua (each traced once)
    for i, s in enumerate(sols):
        if _on_arc(float(s[0]), arc) or reach[i] > TOL:
            continue
        if near[i] <= ON_TRACE_TOL:
            out.append(f"row {i} on the continuum through q, off its arc of q1 {arc}")
        curve = next((c for c in traced if _distance(c, s) <= ON_TRACE_TOL), None)
        if curve is None:
            curve = _trace(robot, s, T)
            traced.append(curve)
        other = _q1_arc(curve)
        if _on_arc(float(qa[0]), other):
            out.append(f"row {i}: its arc of q1 {other} holds q1 = {qa[0]}")
    return out


def _first_target() -> tuple[Robot, FloatArray, FloatArray, FloatArray]:
    build, q = CASES[0]
    robot = build()
    qa = np.array(q)
    T = robot.fk(qa)
    res = robot.ik(T, respect_limits=False)
    assert res.status == "singular" and res.count == 8
    return robot, qa, T, res.solutions


def test_a_pair_with_two_arcs_gets_a_representative_on_each() -> None:
    """The first target: both pairs of the parallel wrist exist on two arcs of q1 each
    (about -1.87 and 0.29 rad); before, all four branches were represented at the first
    q1 found (4 rows), and the configuration, on the other arc, was 1.96 rad off. Now 8
    rows at two values of q1, each a solution; the continuum through q (traced: it
    sweeps q1 from -1.9456 to -1.7506, q at its end) holds a row, and the rows at the
    other q1 lie on continua whose arcs of q1 do not reach q's."""
    robot, qa, T, sols = _first_target()
    q1s = np.unique(np.round(sols[:, 0], 9))
    assert len(q1s) == 2 and abs(math.remainder(q1s[1] - q1s[0], 2 * math.pi)) > 1.0
    assert _arc_failures(robot, qa, T, sols) == []
    # ON_TRACE_TOL's boundary: the row on q's continuum is within it, not a thousandth
    # of it; the rows of the other arc are farther than it, not 1000 times farther
    through_q = _trace(robot, qa, T)
    near = np.array([_distance(through_q, s) for s in sols])
    other = np.abs(_wrapped(sols[:, 0] - qa[0])) > 1.0
    assert ON_TRACE_TOL / 1000 < near[~other].min() <= ON_TRACE_TOL
    assert ON_TRACE_TOL < near[other].min() < 1000 * ON_TRACE_TOL


def _onto_at_q1(robot: Robot, q: FloatArray, T: FloatArray) -> FloatArray:
    """q's joints 2-6 fitted to T by least squares, q1 held."""
    q = q.copy()
    for _ in range(50):
        e = _pose_error(robot, q, T)
        q[1:] += np.linalg.lstsq(robot.jacobian(q)[:, 1:], e, rcond=1e-12)[0]
    return q


def test_the_arc_check_fails_on_wrong_representatives() -> None:
    """The check above, on answers made wrong: every row at the other arc's q1 (the
    answer before the fix); the row on q's arc with its q1 1e-3 rad off (the others
    kept), or moved 1e-3 rad past the arc's end (the others fitted by least squares)."""
    robot, qa, T, sols = _first_target()
    on = int(np.argmin([np.abs(_wrapped(s - qa)).max() for s in sols]))
    away = sols[np.abs(_wrapped(sols[:, 0] - qa[0])) > 1.0]
    assert any("no row on the continuum" in f for f in _arc_failures(robot, qa, T, away))
    shifted = sols.copy()
    shifted[on, 0] += 1e-3
    assert any(f.startswith(f"row {on} misses T") for f in _arc_failures(robot, qa, T, shifted))
    arc = _q1_arc(_trace(robot, qa, T))
    past = sols.copy()
    past[on, 0] = arc[0] - 1e-3  # past the arc's end: the best fit there misses T
    past[on] = _onto_at_q1(robot, past[on], T)
    assert any(f.startswith(f"row {on} misses T") for f in _arc_failures(robot, qa, T, past))


def test_a_double_root_lost_to_round_off_marks_the_target_near() -> None:
    """The audit's unflagged "ok": q at a fold of the shoulder (σmin 0 there), the
    quartic's double root split by round-off into a ± 1e-8 i; Newton from both seeds
    ended on the two simple roots, 2.3 rad from q, and the answer was "ok" without the
    flag. The seeds still polish there (a Newton step at a double root may go anywhere),
    so the answer is marked near: the merging pair's second root could not be kept."""
    robot = APART()
    T = robot.fk(APART_Q)
    assert conditioning(robot, APART_Q[None])[0] < 1e-10
    res = robot.ik(T, respect_limits=False)
    assert res.status == "ok" and res.method == "analytic:three-parallel-6R"
    assert res.near_singular
    assert judge(robot, APART_Q, T, res, float(conditioning(robot, APART_Q[None])[0])) == []
    # q2 0.3 rad on (q2 placed the shoulder on its fold): not near, q found
    moved = APART_Q + np.array([0.0, 0.3, 0.0, 0.0, 0.0, 0.0])
    far = robot.ik(robot.fk(moved), respect_limits=False)
    assert far.status == "ok" and not far.near_singular
    d = np.abs(np.remainder(far.solutions - moved + math.pi, 2 * math.pi) - math.pi)
    assert d.max(axis=1).min() < 1e-9


@pytest.mark.parametrize(("build", "q"), NEAR_FOLDS)
def test_near_a_fold_of_the_pair_the_configuration_is_found(
    build: Callable[[], Robot], q: list[float]
) -> None:
    """Two more targets at folds of the pair system (axes 5 and 6 apart): a rule that
    stopped Newton at any point meeting (1) and (2) to TRIG_TOL lost the configuration
    (0.04 and 1.1 rad off every solution, "ok"); the answer holds it, or is flagged."""
    robot = build()
    qa = np.array(q)
    T = robot.fk(qa)
    res = robot.ik(T, respect_limits=False)
    assert res.status == "ok", res.message
    assert judge(robot, qa, T, res, float(conditioning(robot, qa[None])[0])) == []
