"""The pose audit of every 6R closed form (issue 20's "Done means"), counted, never stopped.

Arms of each class (:data:`support.audit_arms.CLASSES`) are drawn from a fixed seed
and never seen before; poses are the FK of random q within the limits. For each pose
:func:`audit_arm` counts:

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
  reason;
* ``scaled``: every :data:`SCALED_EVERY`-th pose also gets a *scaled* target (its
  translation from the base origin times :data:`SCALED`: often unreachable, but no
  bound says so): an answer "unreachable" or "not_found" where the numeric search
  finds a solution, or without a reason, is an ``e``; solutions are held to b and c
  like a pose's; ``scaled_out`` counts those answered "unreachable" / "not_found".

Used by ``benchmarks/audit_ik.py`` (10,000 poses per class) and
``tests/ik/test_audit.py`` (a few dozen).
"""

from __future__ import annotations

import collections
import dataclasses
import math
import time
from typing import Any

import numpy as np
from numpy.typing import NDArray

import kinematica as km
from kinematica.ik.registry import ArmSample
from kinematica.ik.structure import arm_size, features
from support.audit_arms import CLASSES, configurations, robot_from
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
#: Scaled targets: every SCALED_EVERY-th pose's translation from the base origin
#: times a factor drawn in SCALED.
SCALED = (1.1, 1.6)
SCALED_EVERY = 10
#: Poses per arm (the last arm of a class may get fewer).
POSES_PER_ARM = 100
#: What is counted per class, in the table's order.
COUNTS = ("poses", "singular", "a", "a_far", "b", "c", "extra", "d", "e", "scaled",
          "scaled_out", "eaik")  # fmt: skip


# ------------------------------------------------------------------ references
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


def scaled_search(
    robot: km.Robot, S: FloatArray, one: km.ik.IKResult, rng: np.random.Generator
) -> FloatArray:
    """The references of a scaled target S that ``one`` answered: the numeric search's
    solutions where ``one`` found some, else whether the library's own search (its first
    guess and :data:`STARTS` restarts, stopping at the first success) finds one.

    A start of :func:`numeric_search` that fails goes on through the solver's restarts:
    on an unreachable target STARTS starts would cost STARTS² attempts.
    """
    if len(ours(one)):
        return numeric_search(robot, S, rng)
    res = robot.ik(S, method="numeric", respect_limits=False)
    return np.concatenate([res.solutions, res.out_of_limits])


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
    if fk_error(robot, q[None], T)[0] > 10 * TOL:  # EAIK's FK rounds as ours does, or near
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


def moved_target(robot: km.Robot, T: FloatArray, distance: float) -> FloatArray:
    """T with its translation moved along the ray from the base origin to ``distance`` (m)."""
    origin = robot.chain.start[:3, 3]
    r = T[:3, 3] - origin
    norm = float(np.linalg.norm(r))
    direction = r / norm if norm > 1e-12 else np.array([1.0, 0.0, 0.0])
    moved = T.copy()
    moved[:3, 3] = origin + direction * distance
    return moved


def far_target(robot: km.Robot, T: FloatArray, rng: np.random.Generator) -> FloatArray:
    """T with its translation scaled from the base origin past the bound on the reach."""
    return moved_target(robot, T, arm_size(robot.chain) * rng.uniform(*FAR))


def scaled_target(robot: km.Robot, T: FloatArray, rng: np.random.Generator) -> FloatArray:
    """T with its distance from the base origin times a factor in :data:`SCALED`."""
    distance = float(np.linalg.norm(T[:3, 3] - robot.chain.start[:3, 3]))
    return moved_target(robot, T, distance * rng.uniform(*SCALED))


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


def _fk_checks(
    robot: km.Robot, T: FloatArray, one: km.ik.IKResult, what: str
) -> list[tuple[str, str]]:
    """Checks b and e of every solution of ``one``: FK within TOL of T; "ok" only if so."""
    out = []
    err = fk_error(robot, ours(one), T)
    if (err > TOL).any():
        out.append(("b", f"{what}{one.status}: FK error {err.max():.3g} ({one.method})"))
        if one.status == "ok":
            out.append(("e", f"{what}ok with a solution off by {err.max():.3g}"))
    return out


def check_answer(
    robot: km.Robot, T: FloatArray, q: FloatArray, one: km.ik.IKResult, cond: float
) -> list[tuple[str, str]]:
    """Checks a, b and e of the answer ``one`` to the pose ``T = fk(q)``: ``(check, detail)``.

    ``cond`` is σmin/σmax at q (see :data:`SINGULAR_REL`); "a_far" is an "a" by
    more than :data:`DISTINCT_TOL`.
    """
    out = _fk_checks(robot, T, one, "")
    sols = ours(one)
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


def check_scaled(
    robot: km.Robot, S: FloatArray, one: km.ik.IKResult, ref: FloatArray, size: float
) -> list[tuple[str, str]]:
    """Checks b, c and e of the answer ``one`` to a scaled target S, given the numeric
    search's solutions ``ref``: ``(check, detail)``."""
    out = _fk_checks(robot, S, one, "scaled target: ")
    sols = ours(one)
    if one.status in ("unreachable", "not_found") and len(ref):
        out.append(("e", f"scaled target {one.status} ({one.message}) but the search "
                         f"found {len(ref)} solutions, e.g. {ref[0].tolist()}"))  # fmt: skip
    elif one.status != "ok" and not one.message:
        out.append(("e", f"scaled target {one.status} without a reason"))
    if not one.free_joints:
        for x, near, tol in check_complete(robot, sols, ref, size)[0]:
            out.append(("c", f"scaled target: reference solution {x.tolist()} missed: "
                             f"nearest of our {len(sols)} at {near:.3g} > {tol:.3g}"))  # fmt: skip
    return out


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
    for i in range(0, len(q), SCALED_EVERY):
        S = scaled_target(robot, T[i], rng)
        one = robot.ik(S)
        counts["scaled"] += 1
        counts["scaled_out"] += one.status in ("unreachable", "not_found")
        for check, detail in check_scaled(robot, S, one, scaled_search(robot, S, one, rng), size):
            fail(check, i, detail)
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
