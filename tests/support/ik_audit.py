"""An audit of IK statuses on random arms of every solver family, near-degenerate ones too.

For each closed-form family (:data:`kinematica.ik.analytic.SOLVERS`) and target
kind, arms come from the family's own ``sample_arm`` (generic, or one of its edge
geometries), and half of them are *jittered*: every twist within 1e-12 of 0,
±π/2 or π moved by up to 5e-10 rad, and lengths and offsets that were 0 set to
±1e-10 m, so their axes are parallel, normal or meeting only within the line
geometry's tolerance. Targets are the forward kinematics of random
configurations; a third of them have one revolute joint within 1e-9 rad of 0, ±π/2
or π (an elbow folded or stretched, a wrist aligned). Each target was made by FK,
so it is reachable and its generating configuration ``q`` solves it; the audit
counts every answer that says otherwise:

* ``bad_fk``: a solution whose FK misses the target by more than the tolerance;
* ``missing``: "ok" without ``q`` among its solutions where the arm is not
  singular at ``q`` (the Jacobian's smallest singular value, lengths in units
  of the arm's size, at least :data:`SINGULAR_REL` of its largest), split by
  the method that answered (``missing_closed``, ``missing_numeric``);
* ``unreachable``, ``not_found``, ``out_of_limits`` (limits are not respected,
  so there is none): false statuses.

Used by ``tests/ik/test_fallback_audit.py`` (a few hundred targets) and by
``benchmarks/ik_degenerate.py`` (the issue's 100,000).
"""

from __future__ import annotations

import collections
import dataclasses
import math
from collections.abc import Iterator
from typing import Any

import numpy as np
from numpy.typing import NDArray

import kinematica as km
from kinematica.dh.joints import Joint
from kinematica.ik.analytic import SOLVERS
from kinematica.ik.registry import ArmSample, SolverSpec
from kinematica.ik.structure import features

FloatArray = NDArray[np.float64]

#: Solutions reach their target to the default tolerances (m, rad).
TOL = 1e-10
#: The generating configuration is among the solutions when one is this close
#: (rad or m, modulo 2π), plus what round-off allows at its conditioning:
#: ROUNDOFF (m in units of the arm's size, or rad) / the Jacobian's relative
#: smallest singular value. A solution only within the tolerances would be off by
#: up to 1e-10 / that value.
FOUND_TOL = 1e-7
ROUNDOFF = 1e-12
#: The arm is singular at q when the smallest singular value of its scaled Jacobian
#: is below this fraction of the largest: there the answer within the tolerance is
#: an arc, or solutions merge, and q need not be returned.
SINGULAR_REL = 1e-6
#: Twists this close to 0, ±π/2 or π are special; jittered arms move them by up to
#: JITTER_TWIST (rad), and lengths and offsets of 0 become ±JITTER_LENGTH (m).
SPECIAL_TOL = 1e-12
JITTER_TWIST = 5e-10
JITTER_LENGTH = 1e-10
#: A fold target puts one revolute joint within FOLD of a special angle (rad).
FOLD = 1e-9

_SPECIAL = (0.0, math.pi / 2, -math.pi / 2, math.pi, -math.pi)
COUNTS = ("targets", "bad_fk", "missing_closed", "missing_numeric", "unreachable", "not_found",
          "out_of_limits")  # fmt: skip


@dataclasses.dataclass
class Case:
    """One audited target that failed: enough to reproduce it."""

    what: str
    spec: str
    kind: str
    note: str
    arm: ArmSample
    q: FloatArray
    status: str
    message: str


def jitter(arm: ArmSample, rng: np.random.Generator) -> ArmSample:
    """``arm`` with its special twists and zero lengths moved within the tolerances."""

    def twist(alpha: float) -> float:
        if min(abs(alpha - s) for s in _SPECIAL) <= SPECIAL_TOL:
            return alpha + float(rng.uniform(-JITTER_TWIST, JITTER_TWIST))
        return alpha

    def zero(v: float) -> float:
        if abs(v) <= SPECIAL_TOL and rng.random() < 0.5:
            return JITTER_LENGTH * float(rng.choice([-1.0, 1.0]))
        return v

    rows: list[Joint] = []
    for j in arm.links:
        fields: dict[str, float] = {"alpha": twist(j.alpha), "a": zero(j.a)}
        if isinstance(j, km.Revolute):
            fields["d"] = zero(j.d)
        rows.append(dataclasses.replace(j, **fields))  # type: ignore[arg-type]
    return dataclasses.replace(arm, links=tuple(rows), note=f"{arm.note} jittered".strip())


def robot_of(arm: ArmSample, name: str) -> km.Robot:
    """The robot of a sample arm, its limits dropped (the audit ignores them)."""
    rows = [dataclasses.replace(j, qlim=None) for j in arm.links]
    conv = arm.convention
    return km.Robot.from_dh(rows, convention=conv, base=arm.base, tool=arm.tool, name=name)


def arms(
    spec: SolverSpec, rng: np.random.Generator, count: int
) -> Iterator[tuple[km.Robot, ArmSample]]:
    """``count`` arms of ``spec``'s family: generic, degenerate, jittered by turns."""
    made = 0
    while made < count:
        arm = spec.sample_arm(rng, made % 2 == 1)
        if made % 4 >= 2:
            jittered = jitter(arm, rng)
            robot = robot_of(jittered, spec.kind)
            if spec.handles(features(robot.chain)):
                made += 1
                yield robot, jittered
                continue
        made += 1
        yield robot_of(arm, spec.kind), arm


def configurations(robot: km.Robot, rng: np.random.Generator, count: int) -> FloatArray:
    """``(count, n)`` random q; a third with one revolute joint within FOLD of a special angle."""
    n = robot.dof
    prismatic = robot.is_prismatic
    q = np.where(prismatic, rng.uniform(-0.5, 0.5, (count, n)), rng.uniform(-3.1, 3.1, (count, n)))
    revolute = np.flatnonzero(~prismatic)
    for i in range(count):
        if i % 3 == 2 and revolute.size:
            j = int(rng.choice(revolute))
            q[i, j] = float(rng.choice(_SPECIAL[:4])) + float(rng.uniform(-FOLD, FOLD))
    return q


def conditioning(robot: km.Robot, q: FloatArray, position: bool, size: float) -> FloatArray:
    """``(N,)`` smallest / largest singular value of the scaled Jacobian at each q.

    NaN where the arm is redundant for the target (more joints than counted rows):
    its solutions are never a finite set.
    """
    J = robot.jacobian(q).copy()
    J[:, :3] /= size
    if position:
        J = J[:, :3]
    rows, n = J.shape[-2:]
    if n > rows:
        return np.full(len(q), np.nan)
    sv = np.linalg.svd(J, compute_uv=False)
    return sv[:, n - 1] / sv[:, 0]


def _distance(robot: km.Robot, a: FloatArray, b: FloatArray) -> FloatArray:
    d = a - b
    d = np.where(robot.is_prismatic, d, np.abs(np.remainder(d + math.pi, 2 * math.pi) - math.pi))
    return np.max(np.abs(d), axis=-1)


def audit_arm(
    robot: km.Robot, q: FloatArray, position: bool, spec: SolverSpec | None = None
) -> tuple[collections.Counter[str], list[tuple[str, int, Any]]]:
    """Counts of :data:`COUNTS` for the targets ``fk(q)``, and the failures ``(what, i, one)``.

    A family solving at a parameter (``spec.parameter``) is given each q's own
    value (0 where it is undefined: there every value solves).
    """
    T = robot.fk(q)
    targets = np.ascontiguousarray(T[:, :3, 3]) if position else T
    extra = {}
    if spec is not None and spec.parameter is not None and spec.parameter_of is not None:
        extra = {spec.parameter: np.nan_to_num(spec.parameter_of(robot.chain, q))}
    res = robot.ik(targets, respect_limits=False, **extra)
    size = features(robot.chain).size
    cond = conditioning(robot, q, position, size)
    counts: collections.Counter[str] = collections.Counter(targets=len(q))
    bad: list[tuple[str, int, Any]] = []
    for i in range(len(q)):
        status = str(res.status[i])
        if status in ("unreachable", "not_found", "out_of_limits"):
            counts[status] += 1
            bad.append((status, i, res[i]))
            continue
        one = res[i]
        if one.count:
            F = robot.fk(one.solutions)
            err = np.linalg.norm(F[:, :3, 3] - targets[i][:3, 3] if not position else
                                 F[:, :3, 3] - targets[i], axis=-1)  # fmt: skip
            if not position:
                err = np.maximum(err, km.rotation_angle(F[:, :3, :3], targets[i][:3, :3]))
            if (err > TOL).any():
                counts["bad_fk"] += 1
                bad.append(("bad_fk", i, one))
                continue
        if status == "ok" and cond[i] >= SINGULAR_REL:
            allowed = FOUND_TOL + ROUNDOFF / cond[i]
            if not one.count or _distance(robot, one.solutions, q[i]).min() > allowed:
                what = "missing_closed" if one.method.startswith("analytic") else "missing_numeric"
                counts[what] += 1
                bad.append((what, i, one))
    return counts, bad


def run(
    arms_per_case: int, targets_per_arm: int, seed: int = 0, keep: int = 20
) -> tuple[dict[tuple[str, str], collections.Counter[str]], list[Case]]:
    """The audit over every family and target kind: counts per ``(family, kind)``, failures."""
    out: dict[tuple[str, str], collections.Counter[str]] = {}
    cases: list[Case] = []
    for spec in SOLVERS:
        for kind in spec.targets:
            rng = np.random.default_rng([seed, SOLVERS.index(spec), len(kind)])
            total: collections.Counter[str] = collections.Counter()
            for robot, arm in arms(spec, rng, arms_per_case):
                q = configurations(robot, rng, targets_per_arm)
                counts, bad = audit_arm(robot, q, kind == "position", spec)
                total.update(counts)
                for what, i, one in bad:
                    if len(cases) < keep:
                        cases.append(Case(what, spec.kind, kind, arm.note, arm, q[i],
                                          str(one.status), one.message))  # fmt: skip
            out[(spec.kind, kind)] = total
    return out, cases
