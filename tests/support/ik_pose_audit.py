"""The pose audit of every 6R closed form (issue 20's "Done means"), counted, never stopped.

Arms of each class (:data:`CLASSES`) are drawn from a fixed seed and never seen
before: generic random DH arms (standard and modified by turns, with a random base
and tool), arms on the edges of the general 6R (all links equal, a joint's offsets
of 1e-10 m, two axes parallel within 1e-9 rad, a calibrated UR5), and the
degenerate arms of the spherical-wrist, spherical-shoulder and three-parallel
families (their spec's ``sample_arm(rng, degenerate=True)``). Poses are the FK of
random q within the limits. For each pose :func:`audit_arm` counts:

* ``singular``: the arm is singular at q (σmin/σmax of the 6 x 6 Jacobian, lengths
  in units of the arm's size, below :data:`SINGULAR_REL`); check a skips it;
* ``a``: q is not among the solutions (to :data:`FOUND_TOL` modulo 2π, in or out of
  the limits) where the arm is not singular at q;
* ``b``: a solution whose FK misses the target by more than :data:`TOL` (m, rad);
* ``c``: a solution of the references (EAIK's exact answers whose FK is within
  TOL, and a :data:`STARTS`-start numeric search, distinct to :data:`DISTINCT_TOL`)
  that is not among ours to DISTINCT_TOL; ``extra``: ours that no reference found;
* ``d``: a batch answer that differs from the single call's (any field);
* ``e``: a false status: "ok" with a solution failing b, a pose made by FK called
  "unreachable", or a target outside the reach (the pose's translation scaled past
  the bound on the reach) answered other than "unreachable" / "not_found" with a
  reason.

Used by ``benchmarks/audit_ik.py`` (10,000 poses per class) and
``tests/ik/test_audit.py`` (a few dozen).
"""

from __future__ import annotations

import collections
import dataclasses
import math
import time
from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.typing import NDArray

import kinematica as km
from kinematica.dh.joints import Revolute
from kinematica.ik.analytic import SOLVERS
from kinematica.ik.analytic.sampling import random_transform
from kinematica.ik.registry import ArmSample
from kinematica.ik.structure import arm_size, features
from support.helpers import assert_same_result
from support.ik_audit import conditioning
from support.ik_search import distinct, joint_distance

FloatArray = NDArray[np.float64]
PI = math.pi

#: Solutions reach their target to this (m and rad): the library's default tolerance.
TOL = 1e-10
#: The configuration that made a pose is among the solutions to this (rad, modulo 2π).
FOUND_TOL = 1e-9
#: The arm is singular at q when σmin/σmax of its 6 x 6 Jacobian (the linear rows
#: divided by the arm's size) is below this: there solutions merge or form an arc, and
#: round-off moves them by up to 1e-16 / σ, so q need not be among them to FOUND_TOL.
SINGULAR_REL = 1e-6
#: Two solutions of the references are one when this close (rad, modulo 2π). One of
#: ours matches a reference solution x within DISTINCT_TOL + 2 TOL / σmin(x) (σmin of
#: the Jacobian at x, linear rows divided by the arm's size): two configurations that
#: both reach the target to TOL are up to about that apart where the arm is nearly
#: singular (the search's solutions stop at TOL, ours are polished further).
DISTINCT_TOL = 1e-6
#: Random starts of the numeric search, per pose.
STARTS = 200
#: Far targets sit this many times the bound on the reach from the base (at least).
FAR = (1.05, 2.0)
#: Poses per arm (the last arm of a class may get fewer).
POSES_PER_ARM = 100
#: What is counted per class, in the table's order.
COUNTS = ("poses", "singular", "a", "a_far", "b", "c", "extra", "d", "e", "eaik")

#: The UR5's DH table (standard; d, a, alpha in m, m, rad): the calibrated UR's nominal.
UR5 = (
    (0.089159, 0.0, PI / 2),
    (0.0, -0.425, 0.0),
    (0.0, -0.39225, 0.0),
    (0.10915, 0.0, PI / 2),
    (0.09465, 0.0, -PI / 2),
    (0.0823, 0.0, 0.0),
)
#: The calibration error of a UR: every twist (rad) and every a, d (m) off by up to this.
CALIBRATION = 1e-3


# ------------------------------------------------------------------ arm classes
def _rows(rng: np.random.Generator) -> list[Revolute]:
    u = rng.uniform
    return [
        Revolute(d=u(-0.4, 0.4), a=u(-0.4, 0.4), alpha=u(-PI, PI), offset=u(-PI, PI))
        for _ in range(6)
    ]


def _placed(rows: list[Revolute], rng: np.random.Generator, note: str) -> ArmSample:
    """The rows in either convention (a coin), with a random base and tool."""
    convention = "modified" if rng.random() < 0.5 else "standard"
    base, tool = random_transform(rng, 0.5), random_transform(rng, 0.2)
    return ArmSample(tuple(rows), convention, base, tool, note)  # type: ignore[arg-type]


def generic(rng: np.random.Generator) -> ArmSample:
    """A random 6R arm: lengths and offsets in ±0.4 m, twists and joint offsets in ±π."""
    return _placed(_rows(rng), rng, "")


def equal_links(rng: np.random.Generator) -> ArmSample:
    """A random 6R arm whose six a are equal and six d are equal (its twists random)."""
    a, d = rng.uniform(0.1, 0.4), rng.uniform(0.1, 0.4)
    rows = [dataclasses.replace(r, a=a, d=d) for r in _rows(rng)]
    return _placed(rows, rng, f"a = {a:.4f}, d = {d:.4f} on every joint")


def tiny_offsets(rng: np.random.Generator) -> ArmSample:
    """A random 6R arm with one joint's a and d of ±1e-10 m (two axes meet but for that)."""
    rows, i = _rows(rng), int(rng.integers(6))
    s = rng.choice([-1.0, 1.0], 2)
    rows[i] = dataclasses.replace(rows[i], a=1e-10 * s[0], d=1e-10 * s[1])
    return _placed(rows, rng, f"joint {i + 1}: a, d = ±1e-10")


def near_parallel(rng: np.random.Generator) -> ArmSample:
    """A random 6R arm with one twist of ±1e-9 or π ± 1e-9 rad (axes parallel but for that)."""
    rows, i = _rows(rng), int(rng.integers(6))
    alpha = float(rng.choice([0.0, PI])) + 1e-9 * float(rng.choice([-1.0, 1.0]))
    rows[i] = dataclasses.replace(rows[i], alpha=alpha)
    return _placed(rows, rng, f"joint {i + 1}: alpha = {alpha!r}")


def calibrated_ur(rng: np.random.Generator) -> ArmSample:
    """The UR5 with every twist, a and d off by up to :data:`CALIBRATION` (uniform)."""
    e = lambda: float(rng.uniform(-CALIBRATION, CALIBRATION))  # noqa: E731
    rows = [Revolute(d=d + e(), a=a + e(), alpha=al + e()) for d, a, al in UR5]
    return _placed(rows, rng, "UR5, calibrated")


def _family(kind: str) -> Callable[[np.random.Generator], ArmSample]:
    spec = next(s for s in SOLVERS if s.kind == kind)

    def sample(rng: np.random.Generator) -> ArmSample:
        return spec.sample_arm(rng, True)

    sample.__doc__ = f"A degenerate arm of the {kind} family (its spec's sample_arm)."
    return sample


#: The arm classes of the audit, by name: ``rng -> ArmSample``.
CLASSES: dict[str, Callable[[np.random.Generator], ArmSample]] = {
    "generic": generic,
    "equal links": equal_links,
    "offsets 1e-10": tiny_offsets,
    "parallel 1e-9": near_parallel,
    "calibrated UR": calibrated_ur,
    "spherical wrist": _family("spherical-wrist-6R"),
    "spherical shoulder": _family("spherical-shoulder-6R"),
    "three parallel": _family("three-parallel-6R"),
}


# ------------------------------------------------------------------ references
def robot_from(arm: ArmSample, name: str) -> km.Robot:
    """The robot of a sample arm, its limits kept."""
    return km.Robot.from_dh(
        arm.links, convention=arm.convention, base=arm.base, tool=arm.tool, name=name
    )


def configurations(robot: km.Robot, rng: np.random.Generator, n: int) -> FloatArray:
    """``(n, 6)`` random q within the limits (a joint without limits: one turn)."""
    lo, hi = robot.qlim[:, 0], robot.qlim[:, 1]
    lo, hi = np.where(np.isfinite(lo), lo, -PI), np.where(np.isfinite(hi), hi, PI)
    return rng.uniform(lo, hi, (n, robot.dof))


def numeric_search(
    robot: km.Robot, T: FloatArray, rng: np.random.Generator, starts: int = STARTS
) -> FloatArray:
    """``(k, 6)`` the distinct solutions of ``robot.ik(method="numeric")`` from random starts.

    One batched call: the target repeated, one random q0 per row, one thread (a
    start that fails goes on from the solver's own restarts; what it finds counts).
    """
    q0 = rng.uniform(-PI, PI, (starts, robot.dof))
    many = np.broadcast_to(T, (starts, 4, 4))
    res = robot.ik(many, method="numeric", q0=q0, respect_limits=False, workers=1)
    if not res.count.any():
        return np.zeros((0, robot.dof))
    return distinct(robot, res.solutions[res.count > 0, 0], DISTINCT_TOL)


@dataclasses.dataclass(frozen=True)
class Eaik:
    """EAIK's model of an arm (``eaik.IK_HP.HPRobot``) and the rotation it leaves out.

    EAIK's end effector has the base's orientation at q = 0; ours has
    ``R0 = robot.fk(0)[:3, :3]``: a target R of ours is EAIK's ``R R0ᵀ``.
    """

    model: Any
    R0: FloatArray

    def solutions(self, robot: km.Robot, T: FloatArray) -> FloatArray:
        """``(k, 6)`` EAIK's exact answers (no least-squares ones) whose FK is within TOL."""
        target = T.copy()
        target[:3, :3] = T[:3, :3] @ self.R0.T
        sol = self.model.IK(target)
        Q = np.asarray(sol.Q, dtype=float).reshape(-1, robot.dof)
        exact = ~np.asarray(sol.is_LS, dtype=bool).reshape(-1)
        Q = Q[exact]
        return Q[fk_error(robot, Q, T) <= TOL] if len(Q) else Q


def eaik_model(robot: km.Robot) -> Eaik | None:
    """EAIK's model of the arm, when ``import eaik`` works and EAIK solves the arm (else None).

    The axes (directions ``H`` and a point on each) are the base-frame lines of
    :func:`~kinematica.ik.structure.features` at q = 0; ``P`` runs from the base origin
    through those points to the tool origin. The model is checked against our FK.
    """
    try:
        from eaik.IK_HP import HPRobot  # type: ignore[import-not-found]
    except ImportError:
        return None
    f = features(robot.chain)
    M = robot.fk(np.zeros(robot.dof))
    points = np.vstack([np.zeros(3), f.points, M[:3, 3]])
    try:
        model = HPRobot(f.directions.copy(), np.diff(points, axis=0))
    except RuntimeError:  # e.g. "Intersection point can't be calculated for two parallel axes!"
        return None
    if not model.hasKnownDecomposition():
        return None
    eaik = Eaik(model, M[:3, :3].copy())
    q = np.random.default_rng(0).uniform(-PI, PI, robot.dof)
    T = np.asarray(model.fwdKin(q), dtype=float)
    T[:3, :3] = T[:3, :3] @ eaik.R0
    if fk_error(robot, q[None], T)[0] > 1e-9:
        raise AssertionError("EAIK's model of the arm does not reproduce its FK")
    return eaik


# ------------------------------------------------------------------ the checks
def fk_error(robot: km.Robot, Q: FloatArray, T: FloatArray) -> FloatArray:
    """``(k,)`` the larger of position (m) and rotation (rad) error of each FK(Q[i]) from T."""
    if not len(Q):
        return np.zeros(0)
    F = robot.fk(Q)
    pos = np.linalg.norm(F[:, :3, 3] - T[:3, 3], axis=-1)
    return np.maximum(pos, km.rotation_angle(F[:, :3, :3], T[:3, :3]))


def far_target(robot: km.Robot, T: FloatArray, rng: np.random.Generator) -> FloatArray:
    """T with its translation scaled from the base origin past the bound on the reach."""
    origin = robot.chain.start[:3, 3]
    r = T[:3, 3] - origin
    norm = float(np.linalg.norm(r))
    direction = r / norm if norm > 1e-12 else np.array([1.0, 0.0, 0.0])
    far = T.copy()
    far[:3, 3] = origin + direction * arm_size(robot.chain) * rng.uniform(*FAR)
    return far


def sigma_min(robot: km.Robot, Q: FloatArray, size: float) -> FloatArray:
    """``(k,)`` the smallest singular value of the Jacobian at each row of Q (``(k, 6)``),
    its linear rows divided by the arm's ``size`` (m)."""
    if not len(Q):
        return np.zeros(0)
    J = robot.jacobian(Q).copy()
    J[:, :3] /= size
    return np.asarray(np.linalg.svd(J, compute_uv=False)[:, -1])


@dataclasses.dataclass
class Finding:
    """One failed check: enough to reproduce it (the arm, the pose's q, what was off)."""

    check: str
    arm: ArmSample
    q: FloatArray
    detail: str


def ours(one: km.ik.IKResult) -> FloatArray:
    """``(k, 6)`` every solution of an answer, within the limits or not."""
    return np.concatenate([one.solutions, one.out_of_limits])


def check_answer(
    robot: km.Robot, T: FloatArray, q: FloatArray, one: km.ik.IKResult, cond: float
) -> list[tuple[str, str]]:
    """Checks a, b and e of the answer ``one`` to the pose ``T = fk(q)``: ``(check, detail)``.

    ``cond`` is σmin/σmax at q (see :data:`SINGULAR_REL`); "a_far" is an "a" by
    more than :data:`DISTINCT_TOL`.
    """
    out = []
    sols = ours(one)
    err = fk_error(robot, sols, T)
    if (err > TOL).any():
        out.append(("b", f"{one.status}: FK error {err.max():.3g} ({one.method})"))
        if one.status == "ok":
            out.append(("e", f"ok with a solution off by {err.max():.3g}"))
    if one.status == "unreachable":
        out.append(("e", f"a pose made by FK is unreachable: {one.message}"))
    gap = float(joint_distance(robot, sols, q).min()) if len(sols) else math.inf
    if cond >= SINGULAR_REL and gap > FOUND_TOL:
        detail = (f"{one.status}, {len(sols)} solutions, nearest {gap:.3g} "
                  f"(σmin/σmax {cond:.2g}, {one.method}): {one.message}")  # fmt: skip
        out.append(("a", detail))
        if gap > DISTINCT_TOL:
            out.append(("a_far", detail))
    return out


def check_complete(
    robot: km.Robot, sols: FloatArray, ref: FloatArray, size: float
) -> tuple[list[tuple[FloatArray, float, float]], int]:
    """Check c: ``(missed, extra)``: the reference solutions none of ``sols`` matches
    (each with the distance to the nearest of ours and the match tolerance, see
    :data:`DISTINCT_TOL`), and how many of ``sols`` match no reference solution."""
    match = DISTINCT_TOL + 2 * TOL / sigma_min(robot, ref, size)
    missed = []
    for x, tol in zip(ref, match, strict=True):
        near = float(joint_distance(robot, sols, x).min()) if len(sols) else math.inf
        if near > tol:
            missed.append((x, near, float(tol)))
    extra = sum(not len(ref) or bool((joint_distance(robot, ref, s) > match).all()) for s in sols)
    return missed, extra


def check_far(status: str, message: str) -> str | None:
    """Check e of a target outside the reach: what is wrong with its answer, or None."""
    if status in ("unreachable", "not_found") and message:
        return None
    return f"target outside the reach: {status}: {message!r}"


def audit_arm(
    robot: km.Robot,
    arm: ArmSample,
    q: FloatArray,
    rng: np.random.Generator,
    starts: int = STARTS,
) -> tuple[collections.Counter[str], list[Finding]]:
    """The counts of :data:`COUNTS` on the poses ``robot.fk(q)``, and what failed."""
    counts: collections.Counter[str] = collections.Counter(poses=len(q))
    found: list[Finding] = []
    T = robot.fk(q)
    batch = robot.ik(T, workers=1)
    far = np.array([far_target(robot, t, rng) for t in T])
    far_res = robot.ik(far, workers=1)
    size = features(robot.chain).size
    cond = conditioning(robot, q, False, size)
    eaik = eaik_model(robot)

    def fail(check: str, i: int, detail: str) -> None:
        counts[check] += 1
        if check != "a_far":  # an "a" too, found already
            found.append(Finding(check, arm, q[i], detail))

    for i in range(len(q)):
        one = robot.ik(T[i])
        try:  # d: the batch's answer is the single call's, field by field
            assert_same_result(batch[i], one)
        except AssertionError as e:
            fail("d", i, str(e).splitlines()[0])
        counts["singular"] += not cond[i] >= SINGULAR_REL
        for check, detail in check_answer(robot, T[i], q[i], one, float(cond[i])):
            fail(check, i, detail)
        if one.free_joints:  # a continuum: no finite set to compare
            continue
        ref = numeric_search(robot, T[i], rng, starts)
        if eaik is not None:
            counts["eaik"] += 1
            ref = distinct(robot, np.concatenate([ref, eaik.solutions(robot, T[i])]),
                           DISTINCT_TOL)  # fmt: skip
        missed, extra = check_complete(robot, ours(one), ref, size)
        counts["extra"] += extra
        for x, near, tol in missed:
            fail("c", i, f"reference solution {x.tolist()} missed: nearest of our "
                         f"{len(ours(one))} at {near:.3g} > {tol:.3g} ({one.status}, "
                         f"{one.method})")  # fmt: skip
    for i in range(len(q)):
        wrong = check_far(str(far_res.status[i]), str(far_res.message[i]))
        if wrong:
            fail("e", i, wrong)
    return counts, found


@dataclasses.dataclass
class ClassReport:
    """The audit of one arm class: counts, seconds, the first findings."""

    name: str
    counts: collections.Counter[str]
    seconds: float
    findings: list[Finding]
    arms: int


def audit_class(
    name: str,
    poses: int,
    seed: int = 0,
    starts: int = STARTS,
    per_arm: int = POSES_PER_ARM,
    keep: int = 50,
) -> ClassReport:
    """``poses`` poses over arms of class ``name`` (``per_arm`` each), from ``seed``."""
    rng = np.random.default_rng([seed, list(CLASSES).index(name)])
    counts: collections.Counter[str] = collections.Counter()
    findings: list[Finding] = []
    t0 = time.perf_counter()
    done = arms = 0
    while done < poses:
        arm = CLASSES[name](rng)
        robot = robot_from(arm, name)
        q = configurations(robot, rng, min(per_arm, poses - done))
        c, f = audit_arm(robot, arm, q, rng, starts)
        counts.update(c)
        findings.extend(f[: max(0, keep - len(findings))])
        done += len(q)
        arms += 1
    return ClassReport(name, counts, time.perf_counter() - t0, findings, arms)
