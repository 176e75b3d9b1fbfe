"""An audit of IK statuses at targets within round-off of a singular set (issue 34, items 2-3).

Arms of every closed-form family that has singular sets inside its workspace: exact
UR-type arms (the three-parallel family's ``sample_arm``, random lengths, base and
tool, and the UR5), spherical-wrist arms (6R and RRP: the family's ``sample_arm``, the
PUMA 560, KUKA KR 6, ABB IRB 120 and the Stanford arm, with a random base and tool),
and SRS 7R arms of the iiwa type (the family's ``sample_arm`` edge ``"iiwa type"`` and
the iiwa 14) solved at the arm angle of the configuration that made each target.

Each configuration is placed on a singular set, then moved off it by a signed offset
of 10^U(-13, -6) rad along one joint (an eighth of them not moved at all):

* 6R arms: joint 2, 3 or 5 (shoulder, elbow, wrist) set to a root of the Jacobian's
  determinant as that joint alone turns (the roots bracketed on a grid and bisected to
  the last bit: a stretched or folded elbow, a wrist with axes 4 and 6 aligned, the
  wrist centre on axis 1 or 2, whatever the arm's offsets make them);
* SRS arms of the iiwa type: q2 or q6 at 0 or π (axes 1 and 3, or 5 and 7, on one
  line), or q4 at 0 (the elbow stretched onto the line from shoulder to wrist).

The target is the forward kinematics of the configuration (limits ignored). Each
answer is counted by what it says of a target made by FK:

* ``unreachable``, ``not_found``: false statuses (``not_found`` is only honest-ish);
* ``missing``: ``ok`` without ``near_singular`` and no solution within
  :data:`FOUND_TOL` plus :data:`ROUNDOFF` over the conditioning at the configuration
  that made the target (the smallest singular value of the Jacobian, lengths in units
  of the arm's size, over the largest; for an SRS arm, of the Jacobian of the pose and
  the arm angle) of that configuration (rad or m, modulo 2π): the pose audit's measure
  (``tests/support/ik_audit.py``); ``missing_fixed`` counts those farther than
  FOUND_TOL alone (reported, not held to 0: round-off over a conditioning of 1e-7
  already exceeds it);
* ``singular_missing``: ``singular`` and no representative from which that
  configuration is reached along the named free joints: the free joints moved from
  the representative's values to the configuration's in :data:`WALK_STEPS` steps (the
  shorter way round, then the longer), the other joints following by Gauss-Newton
  steps on the pose (they may have to: a shoulder's free q1 turns the wrist's target),
  end within :data:`FOUND_TOL` of it;
* ``duplicates``: two solutions within :data:`MERGE_SPAN` of each other whose midpoint
  reaches the target within the tolerance (one solution to tolerance, given twice);
  ``close_pairs`` counts those within :data:`CLOSE_TOL` whatever their midpoint does;
* ``bad_fk``: a solution that misses the target by more than the tolerance.

Used by ``tests/ik/test_singular_audit.py`` (a small sample) and
``benchmarks/ik_singular.py`` (the issue's 200,000 targets).
"""

from __future__ import annotations

import collections
import dataclasses
import math
from collections.abc import Callable, Iterator

import numpy as np
from numpy.typing import NDArray

import kinematica as km
from kinematica.ik.analytic.parallel import SPEC as PARALLEL
from kinematica.ik.analytic.sampling import random_transform
from kinematica.ik.analytic.spherical_wrist import SPECS as WRIST_SPECS
from kinematica.ik.analytic.srs import random_srs_rows
from kinematica.ik.registry import ArmSample
from kinematica.ik.structure import features

FloatArray = NDArray[np.float64]
PI = math.pi

#: Solutions reach their target to the default tolerances (m, rad).
TOL = 1e-10
#: The configuration that made a target is among the solutions of an ``ok`` without
#: ``near_singular`` when one is this close (rad or m, angles modulo 2π) plus ROUNDOFF
#: (rad; m in units of the arm's size) over the conditioning there: an exact closed
#: form's answer carries the round-off of the target over that conditioning.
FOUND_TOL = 1e-6
ROUNDOFF = 1e-12
#: Steps of the walk along the free joints of a singular answer, and Gauss-Newton
#: steps of the other joints at each (then POLISH more at the end).
WALK_STEPS = 100
FOLLOW = 3
POLISH = 10
#: Step of the central differences of the arm angle (rad).
ANGLE_STEP = 1e-6
#: Two solutions this close (rad or m) whose midpoint reaches the target within TOL are
#: one solution to tolerance: a change δ of the target moves branches at a fold by up to
#: √(2 δ / κ), 5e-7 for round-off of a target of 1 m at a curvature κ of 1 (the check's
#: MERGE_SPAN, which gives them once).
MERGE_SPAN = 1e-6
#: Two solutions this close are counted as a close pair (reported, not held to 0).
CLOSE_TOL = 1e-5
#: The offsets off the singular set: signed, 10^U(OFFSET_EXP) rad; one in
#: EXACT_EVERY is not moved.
OFFSET_EXP = (-13.0, -6.0)
EXACT_EVERY = 8
#: Grid of the determinant's scan along a joint (roots bracketed between neighbours).
GRID = 48

COUNTS = ("targets", "unreachable", "not_found", "missing", "singular_missing", "duplicates",
          "bad_fk", "missing_fixed", "close_pairs", "near", "singular")  # fmt: skip
#: The counts held to 0.
FAILURES = ("unreachable", "not_found", "missing", "singular_missing", "duplicates", "bad_fk")
NAMED_6R = ("puma560", "kr6", "irb120", "stanford", "ur5")


@dataclasses.dataclass
class Finding:
    """One audited target that failed: enough to reproduce it."""

    what: str
    family: str
    robot: km.Robot
    q: FloatArray
    status: str
    message: str
    detail: str


def _robot(arm: ArmSample, name: str) -> km.Robot:
    rows = [dataclasses.replace(j, qlim=None) for j in arm.links]
    return km.Robot.from_dh(rows, convention=arm.convention, base=arm.base, tool=arm.tool,
                            name=name)  # fmt: skip


def _named(name: str, rng: np.random.Generator) -> km.Robot:
    r = km.load(name)
    arm = ArmSample(tuple(r.links), r.convention, random_transform(rng, 0.5),  # type: ignore[arg-type]
                    random_transform(rng, 0.2))  # fmt: skip
    return _robot(arm, name)


def _srs_iiwa_type(rng: np.random.Generator) -> km.Robot:
    arm = ArmSample(tuple(random_srs_rows(rng, "iiwa type")), "standard",
                    random_transform(rng, 0.5), random_transform(rng, 0.2))  # fmt: skip
    return _robot(arm, "srs")


#: Arm makers per family: (family, maker) drawn in turn.
MAKERS: dict[str, list[Callable[[np.random.Generator], km.Robot]]] = {
    "UR-type": [lambda rng: _robot(PARALLEL.sample_arm(rng, False), "ur-type"),
                lambda rng: _named("ur5", rng)],
    "spherical wrist": [lambda rng: _robot(WRIST_SPECS[0].sample_arm(rng, False), "wrist"),
                        lambda rng: _robot(WRIST_SPECS[1].sample_arm(rng, False), "rrp"),
                        *(lambda rng, n=n: _named(n, rng) for n in NAMED_6R[:4])],
    "SRS": [_srs_iiwa_type, lambda rng: _named("iiwa14", rng)],
}  # fmt: skip


def _det(robot: km.Robot, q: FloatArray) -> FloatArray:
    return np.linalg.det(robot.jacobian(q))  # type: ignore[no-any-return]


def _offsets(rng: np.random.Generator, count: int) -> FloatArray:
    d = np.sign(rng.uniform(-1, 1, count)) * 10.0 ** rng.uniform(*OFFSET_EXP, count)
    d[rng.integers(0, EXACT_EVERY, count) == 0] = 0.0
    return d


def singular_6r(robot: km.Robot, rng: np.random.Generator, count: int) -> FloatArray:
    """``(count, 6)`` configurations within the offsets of a root of det J along q2, q3 or q5."""
    out = np.empty((0, robot.dof))
    prismatic = robot.is_prismatic
    while len(out) < count:
        m = 2 * (count - len(out)) + 8
        q = np.where(prismatic, rng.uniform(-0.5, 0.5, (m, 6)), rng.uniform(-PI, PI, (m, 6)))
        j = rng.choice([1, 2, 4], m)
        lo_t, hi_t = np.where(prismatic[j], 0.05, -PI), np.where(prismatic[j], 1.0, PI)
        t = lo_t[:, None] + (hi_t - lo_t)[:, None] * np.linspace(0.0, 1.0, GRID)[None]
        grid = np.repeat(q[:, None], GRID, axis=1)
        grid[np.arange(m)[:, None], np.arange(GRID)[None], j[:, None]] = t
        det = _det(robot, grid.reshape(-1, 6)).reshape(m, GRID)
        change = np.sign(det[:, :-1]) * np.sign(det[:, 1:]) <= 0
        has = change.any(axis=1)
        q, j, t, det, change = q[has], j[has], t[has], det[has], change[has]
        k = np.array([rng.choice(np.flatnonzero(c)) for c in change], dtype=int)
        rows = np.arange(len(q))
        lo, hi = t[rows, k], t[rows, k + 1]
        flo = det[rows, k]
        for _ in range(64):  # bisection to the last bit
            mid = 0.5 * (lo + hi)
            qm = q.copy()
            qm[rows, j] = mid
            fm = _det(robot, qm)
            left = np.sign(fm) * np.sign(flo) <= 0
            hi = np.where(left, mid, hi)
            lo = np.where(left, lo, mid)
            flo = np.where(left, flo, fm)
        q[rows, j] = 0.5 * (lo + hi) + _offsets(rng, len(q))
        out = np.concatenate([out, q])
    return out[:count]


def singular_srs(robot: km.Robot, rng: np.random.Generator, count: int) -> FloatArray:
    """``(count, 7)`` configurations of an iiwa-type arm near q2, q6 in {0, π} or q4 = 0."""
    q = rng.uniform(-PI, PI, (count, 7))
    j = rng.choice([1, 3, 5], count)
    at = np.where(j == 3, 0.0, rng.choice([0.0, PI], count))
    q[np.arange(count), j] = at + _offsets(rng, count)
    return q


def _distance(robot: km.Robot, a: FloatArray, b: FloatArray) -> FloatArray:
    d = a - b
    d = np.where(robot.is_prismatic, d, np.abs(np.remainder(d + PI, 2 * PI) - PI))
    return np.abs(d)  # type: ignore[no-any-return]


def fk_error(robot: km.Robot, q: FloatArray, T: FloatArray) -> FloatArray:
    """``(k,)`` the larger of the position (m) and rotation (rad) errors of fk(q) against T.

    A position target ``(3,)``: the position error only.
    """
    F = robot.fk(q)
    if T.shape == (3,):
        return np.linalg.norm(F[..., :3, 3] - T, axis=-1)  # type: ignore[no-any-return]
    p = np.linalg.norm(F[..., :3, 3] - T[:3, 3], axis=-1)
    return np.maximum(p, km.rotation_angle(F[..., :3, :3], T[:3, :3]))  # type: ignore[no-any-return]


def duplicates(robot: km.Robot, sols: FloatArray, T: FloatArray) -> tuple[int, int]:
    """``(pairs one to tolerance, pairs within CLOSE_TOL)`` among the rows of ``sols``."""
    dup = close = 0
    for a in range(len(sols)):
        for b in range(a):
            d = _distance(robot, sols[a], sols[b]).max()
            close += int(d < CLOSE_TOL)
            if d < MERGE_SPAN:
                diff = sols[a] - sols[b]
                diff = np.where(robot.is_prismatic, diff, np.remainder(diff + PI, 2 * PI) - PI)
                mid = sols[b] + 0.5 * diff
                dup += int(fk_error(robot, mid[None], T)[0] <= TOL)
    return dup, close


def _wrapped(robot: km.Robot, d: FloatArray) -> FloatArray:
    return np.where(robot.is_prismatic, d, np.remainder(d + PI, 2 * PI) - PI)  # type: ignore[no-any-return]


def _follow(robot: km.Robot, x: FloatArray, moving: NDArray[np.bool_], T: FloatArray) -> None:
    """One Gauss-Newton step of the joints ``moving`` of x (in place) towards the pose T."""
    F = robot.fk(x)
    Re = T[:3, :3] @ F[:3, :3].T
    axis = np.array([Re[2, 1] - Re[1, 2], Re[0, 2] - Re[2, 0], Re[1, 0] - Re[0, 1]])
    e = np.concatenate([T[:3, 3] - F[:3, 3], 0.5 * axis])
    J = robot.jacobian(x)[:, moving]
    x[moving] += np.linalg.lstsq(J, e, rcond=1e-12)[0]


def reached_along(robot: km.Robot, r: FloatArray, q: FloatArray, free: tuple[int, ...],
                  T: FloatArray) -> float:  # fmt: skip
    """How far from q a walk from r ends whose free joints go to q's (rad or m, max).

    The free joints turn the shorter way, and (revolute ones) the longer way round: a
    continuum may be an arc of a joint's turn, not the whole of it.
    """
    moving = np.ones(robot.dof, dtype=bool)
    moving[list(free)] = False
    short = _wrapped(robot, q - r)[list(free)]
    turn = np.where(robot.is_prismatic[list(free)], 0.0, 2 * PI * np.sign(short))
    best = math.inf
    for delta in (short, short - turn):
        x = r.astype(float).copy()
        for k in range(1, WALK_STEPS + 1):
            x[list(free)] = r[list(free)] + delta * k / WALK_STEPS
            for _ in range(FOLLOW):
                _follow(robot, x, moving, T)
        for _ in range(POLISH):
            _follow(robot, x, moving, T)
        best = min(best, float(np.abs(_wrapped(robot, x - q)).max()))
        if best <= FOUND_TOL:
            break
    return best


def conditioning(robot: km.Robot, q: FloatArray) -> FloatArray:
    """``(N,)`` smallest over largest singular value of the scaled Jacobian at each q.

    Position rows in units of the arm's size; an SRS arm's Jacobian gets the arm
    angle's gradient (central differences) as a seventh row: at a fixed arm angle its
    solutions are isolated where that 7x7 matrix is regular.
    """
    J = robot.jacobian(q).copy()
    J[:, :3] /= features(robot.chain).size
    if robot.dof == 7:
        grad = np.empty((len(q), 7))
        for j in range(7):
            step = np.zeros(7)
            step[j] = ANGLE_STEP
            hi, lo = robot.arm_angle(q + step), robot.arm_angle(q - step)
            grad[:, j] = np.remainder(hi - lo + PI, 2 * PI) - PI
        J = np.concatenate([J, np.nan_to_num(grad / (2 * ANGLE_STEP), nan=1e300)[:, None]], 1)
    sv = np.linalg.svd(J, compute_uv=False)
    return sv[:, -1] / sv[:, 0]  # type: ignore[no-any-return]


def judge(
    robot: km.Robot, q: FloatArray, T: FloatArray, one: km.ik.IKResult, cond: float
) -> list[tuple[str, str]]:
    """The checks one answer fails: ``(what, detail)`` (cond: :func:`conditioning` at q)."""
    status = str(one.status)
    if status in ("unreachable", "not_found"):
        return [(status, one.message)]
    if status not in ("ok", "singular"):
        return [("other", status)]
    bad: list[tuple[str, str]] = []
    sols = one.solutions
    err = fk_error(robot, sols, T)
    if (err > TOL).any():
        bad.append(("bad_fk", f"fk error {err.max():.3g}"))
    d = _distance(robot, sols, q)
    if status == "ok" and not one.near_singular:
        far = d.max(axis=1).min()
        if far > FOUND_TOL + ROUNDOFF / max(cond, 1e-300):
            bad.append(("missing", f"q {far:.3g} from every solution (conditioning {cond:.3g})"))
        if far > FOUND_TOL:
            bad.append(("missing_fixed", f"q {far:.3g} from every solution"))
    if status == "singular":
        far = d.max(axis=1).min()
        if far > FOUND_TOL:  # not a representative: reached along the free joints?
            fixed = np.ones(robot.dof, dtype=bool)
            fixed[list(one.free_joints)] = False
            for k in np.argsort(d[:, fixed].max(axis=1, initial=0.0)):  # nearest first
                far = min(far, reached_along(robot, sols[k], q, one.free_joints, T))
                if far <= FOUND_TOL:
                    break
        if far > FOUND_TOL:
            bad.append(("singular_missing", f"q {far:.3g} off every representative "
                                            f"(free {one.free_joints})"))  # fmt: skip
    dup, close = duplicates(robot, sols, T)
    if dup:
        bad.append(("duplicates", f"{dup} pairs one solution to tolerance"))
    if close:
        bad.append(("close_pairs", f"{close} pairs within {CLOSE_TOL:g}"))
    return bad


def arms(family: str, rng: np.random.Generator, count: int) -> Iterator[km.Robot]:
    """``count`` arms of a family, its makers in turn."""
    makers = MAKERS[family]
    for i in range(count):
        yield makers[i % len(makers)](rng)


def audit_arm(
    robot: km.Robot, family: str, rng: np.random.Generator, count: int
) -> tuple[collections.Counter[str], list[Finding]]:
    """Counts of :data:`COUNTS` over ``count`` targets of one arm, and its findings."""
    srs = family == "SRS"
    q = singular_srs(robot, rng, count) if srs else singular_6r(robot, rng, count)
    T = robot.fk(q)
    extra = {"arm_angle": np.nan_to_num(robot.arm_angle(q))} if srs else {}
    res = robot.ik(T, respect_limits=False, **extra)
    cond = conditioning(robot, q)
    counts: collections.Counter[str] = collections.Counter(targets=count)
    found: list[Finding] = []
    for i in range(count):
        one = res[i]
        counts["near"] += int(one.near_singular)
        counts["singular"] += int(one.status == "singular")
        for what, detail in judge(robot, q[i], T[i], one, float(cond[i])):
            counts[what] += 1
            found.append(Finding(what, family, robot, q[i], str(one.status), one.message, detail))
    return counts, found


def run(
    arms_per_family: int, targets_per_arm: int, seed: int = 0, keep: int = 20
) -> tuple[dict[str, collections.Counter[str]], list[Finding]]:
    """The audit over every family: counts per family, the first ``keep`` findings."""
    out: dict[str, collections.Counter[str]] = {}
    findings: list[Finding] = []
    for k, family in enumerate(MAKERS):
        rng = np.random.default_rng([seed, k])
        total: collections.Counter[str] = collections.Counter()
        for robot in arms(family, rng, arms_per_family):
            counts, found = audit_arm(robot, family, rng, targets_per_arm)
            total.update(counts)
            findings.extend(found[: max(0, keep - len(findings))])
        out[family] = total
    return out, findings
