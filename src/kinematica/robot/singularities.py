"""Singularities by name, read from the geometry of the joint axes.

An arm is singular where its Jacobian loses rank: some tool velocity (the
*lost direction*) cannot be produced at any joint rate. Where the structure
of the arm is known (:func:`kinematica.classify`), the rank losses have names,
tested on the joint axes as lines in space at ``q`` (``robot.joint_axes(q)``):

``"wrist"``
    Axes 4 and 6 aligned (the last three axes of a 6R arm: spherical wrists,
    and UR-type arms, whose axis 6 then lies parallel to axes 2-4; ``q5`` at
    0 or π). Measure: the sine of the angle between them, below
    :data:`WRIST_TOL`.
``"elbow"``
    Arm stretched or folded: the elbow point (wrist centre, the next axis of
    a planar group, or the tool point) is at its extreme distance from the
    shoulder axis, ``d|c - shoulder|/dq_elbow = 0``. Measure: that rate
    (m/rad), below :data:`ELBOW_TOL`.
``"shoulder"``
    Wrist centre on axis 1 (for arms with a shoulder offset, on the plane
    through axis 1 parallel to axis 2, where joint 1 moves it along the plane
    joints 2-3 already move it in). Measure: that distance (m), below
    :data:`SHOULDER_TOL`.
``"rank"``
    Any other rank loss (an unknown structure, or a loss beyond the named
    ones): a singular value of the Jacobian below :data:`RANK_TOL` times the
    largest one.

The Jacobian judged is the one of the arm's task: the position rows for an
arm whose whole mobility shows in the position of its tool (3R
anthropomorphic arms, planar 2R), all six rows otherwise. Its generic rank is
measured once per robot on a few configurations.

Each singularity carries its lost direction: a unit 6-vector ``u = (v, ω)``
in the base frame with ``uᵀ J(q) ≈ 0`` (ω = 0 when only position rows are
judged): the component of the tool twist ``(v_tool, ω)`` that no joint rate
changes.
"""

from __future__ import annotations

import dataclasses
import weakref
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.dh.lines import lines_parallel
from kinematica.ik.structure import arm_size
from kinematica.robot.sampling import generic_rank_samples
from kinematica.robot.structure import classify
from kinematica.spatial.checks import as_batch_array

if TYPE_CHECKING:
    from kinematica.robot.kinematics import RobotKinematics

__all__ = [
    "ELBOW_TOL",
    "RANK_TOL",
    "SHOULDER_TOL",
    "WRIST_TOL",
    "Singularity",
    "SingularityPlan",
    "jacobian_rank",
    "singularities",
    "singularity_measures",
    "singularity_plan",
    "task_plan_rows",
]

FloatArray = NDArray[np.float64]

#: Wrist: sine of the angle between axes 4 and 6 below which they are aligned.
WRIST_TOL = 1e-6
#: Elbow: rate of change (m/rad) of the elbow point's distance from the
#: shoulder axis with the elbow joint, below which the arm is stretched/folded.
ELBOW_TOL = 1e-6
#: Shoulder: distance (m) of the wrist centre from axis 1 (from the plane
#: through axis 1 parallel to axis 2, for arms with a shoulder offset).
SHOULDER_TOL = 1e-6
#: Rank: a singular value below this times the largest one is lost. Smaller
#: than the named tolerances produce near their boundary (σ there is ~1e-6 of
#: σmax), so a configuration just outside a named band is not called "rank".
RANK_TOL = 1e-8

_TOLS = {"wrist": WRIST_TOL, "elbow": ELBOW_TOL, "shoulder": SHOULDER_TOL}


@dataclass(frozen=True)
class Singularity:
    """One lost direction of the Jacobian, with its name.

    Attributes:
        name: ``"wrist"``, ``"elbow"``, ``"shoulder"`` or ``"rank"``.
        direction: ``(6,)`` unit ``(v, ω)`` in the base frame with
            ``direction @ robot.jacobian(q) ≈ 0``: the tool-twist component
            the arm cannot produce at ``q``.
        measure: The quantity that was below its tolerance: sine (wrist),
            m/rad (elbow), m (shoulder), σ/σmax (rank).
    """

    name: str
    direction: FloatArray
    measure: float

    def __str__(self) -> str:
        v = ", ".join(f"{x:.3g}" for x in self.direction)
        return f"{self.name} (lost direction v, ω = [{v}])"


@dataclass(frozen=True)
class SingularityPlan:
    """What to test on one robot, read once from its structure."""

    rows: tuple[int, ...]  # Jacobian rows judged
    rank: int  # their generic rank
    wrist: tuple[int, int, int] | None  # axes (4, 5, 6), 0-based
    shoulder_axis: int | None  # the first of the parallel shoulder/elbow pair
    elbow_point: tuple[str, int]  # ("axis", i) | ("wrist", -1) | ("tool", -1)
    shoulder_point: tuple[str, int] | None  # ("wrist"|"meet"|"tool", i)
    enabled: frozenset[str] = frozenset({"wrist", "elbow", "shoulder"})


_PLANS: weakref.WeakKeyDictionary[RobotKinematics, SingularityPlan] = weakref.WeakKeyDictionary()


def _generic_rank(J: FloatArray) -> int:
    s = np.linalg.svd(J, compute_uv=False)
    return int(np.max(np.sum(s > RANK_TOL * s[:, :1], axis=1)))


def singularity_plan(robot: RobotKinematics) -> SingularityPlan:
    """What to test on ``robot`` (its Jacobian rows, wrist, shoulder, elbow), cached."""
    if robot in _PLANS:
        return _PLANS[robot]
    st = classify(robot)
    n, types = robot.dof, robot.joint_types
    h, _ = robot.joint_axes()
    J = robot.jacobian(generic_rank_samples(robot))
    rank_all, rank_pos = _generic_rank(J), _generic_rank(J[:, :3])
    rows = (0, 1, 2) if rank_pos == rank_all else (0, 1, 2, 3, 4, 5)
    rank = rank_pos if rows == (0, 1, 2) else rank_all

    # which named singularities the class has: its solver's spec says (none: "general")
    named = st.spec.singular if st.spec is not None else frozenset()
    # axes 2, 3, 4 parallel (UR type): the elbow and shoulder points are set by the wrist
    three_parallel = types == "RRRRRR" and {(1, 2), (2, 3)} <= set(st.parallel)
    wrist = (n - 3, n - 2, n - 1) if "wrist" in named else None
    s_axis: int | None = None
    elbow_point: tuple[str, int] = ("tool", -1)
    shoulder_point: tuple[str, int] | None = None
    if "elbow" in named:
        for s in (0, 1):
            if s + 1 < n and types[s : s + 2] == "RR" and lines_parallel(h[s], h[s + 1]):
                if s == 1 and lines_parallel(h[0], h[1]):
                    continue
                s_axis = s
                break
    if s_axis is not None:
        # The elbow point: the last axis of the planar group (parallel revolute
        # axes, prismatic joints between them keep directions), else the wrist
        # centre, else the tool point.
        last = None
        for j in range(s_axis + 2, n):
            if types[j] == "P":
                continue
            if not lines_parallel(h[s_axis], h[j]):
                break
            last = j
        if last is not None:
            elbow_point = ("axis", last)
        elif st.wrist_center is not None and not three_parallel:
            elbow_point = ("wrist", -1)
        if s_axis == 1 and types[0] == "R" and "shoulder" in named:
            if st.wrist_center is not None:
                shoulder_point = ("wrist", -1)
            elif three_parallel:
                if st.features.meet(n - 2, n - 1):
                    shoulder_point = ("meet", n - 2)
            else:
                shoulder_point = ("tool", -1)
    plan = SingularityPlan(rows, rank, wrist, s_axis, elbow_point, shoulder_point)
    # A name whose test holds at generic configurations describes degenerate
    # geometry (e.g. coincident axes), not a singularity: it is not used.
    degenerate = {
        name
        for name, measure, _, _ in _named(robot, plan, generic_rank_samples(robot))
        if np.any(measure < _TOLS[name])
    }
    plan = dataclasses.replace(plan, enabled=plan.enabled - degenerate)
    _PLANS[robot] = plan
    return plan


def task_plan_rows(robot: RobotKinematics) -> tuple[int, ...]:
    """The Jacobian rows judged for ``robot`` (see the module docstring)."""
    return singularity_plan(robot).rows


def _unit(v: FloatArray) -> FloatArray:
    norm = np.linalg.norm(v, axis=-1, keepdims=True)
    return np.where(norm > 0.0, v / np.where(norm > 0.0, norm, 1.0), 0.0)


def _meet(h1: FloatArray, p1: FloatArray, h2: FloatArray, p2: FloatArray) -> FloatArray:
    """``(B, 3)`` point of line 1 closest to line 2 (the meeting point of axes that meet)."""
    w = p1 - p2
    b = np.sum(h1 * h2, axis=-1)
    d, e = np.sum(h1 * w, axis=-1), np.sum(h2 * w, axis=-1)
    den = 1.0 - b * b
    t = np.where(den > 1e-12, (b * e - d) / np.where(den > 1e-12, den, 1.0), 0.0)
    out: FloatArray = p1 + t[:, None] * h1
    return out


def _point(kind: tuple[str, int], h: FloatArray, p: FloatArray, tool: FloatArray) -> FloatArray:
    name, i = kind
    n = h.shape[1]
    if name == "axis":
        return p[:, i]
    if name == "wrist":  # axes 4 and 5 of the spherical wrist meet at its centre
        return _meet(h[:, n - 3], p[:, n - 3], h[:, n - 2], p[:, n - 2])
    if name == "meet":
        return _meet(h[:, i], p[:, i], h[:, i + 1], p[:, i + 1])
    return tool


def _covector(d: FloatArray, at: FloatArray, tool: FloatArray) -> FloatArray:
    """``(B, 6)``: a linear direction ``d`` lost at point ``at``, as a covector at the tool."""
    return np.concatenate([d, np.cross(at - tool, d)], axis=-1)


def _named(
    robot: RobotKinematics, plan: SingularityPlan, q: FloatArray
) -> list[tuple[str, FloatArray, FloatArray, FloatArray]]:
    """Per name: ``(name, measure (B,), geometric covector (B, 6), scale (B,))``.

    The scale is the largest value the measure takes at that configuration's
    geometry (1 for the wrist's sine, the elbow point's distance from the elbow
    axis for the elbow rate, the arm's size for the shoulder distance).
    """
    h, p = robot.joint_axes(q)
    tool = robot.fk(q)[:, :3, 3]
    out = []
    if plan.wrist is not None:
        a, m, b = plan.wrist
        sine = np.linalg.norm(np.cross(h[:, a], h[:, b]), axis=-1)
        lost = _unit(np.cross(h[:, a], h[:, m]))
        covector = np.concatenate([np.zeros_like(lost), lost], axis=-1)
        out.append(("wrist", sine, covector, np.ones_like(sine)))
    s = plan.shoulder_axis
    if s is not None:
        e = _point(plan.elbow_point, h, p, tool)
        rho = e - p[:, s]
        rho = rho - np.sum(rho * h[:, s], axis=-1, keepdims=True) * h[:, s]
        rho_hat = _unit(rho)
        rate = np.abs(np.sum(rho_hat * np.cross(h[:, s + 1], e - p[:, s + 1]), axis=-1))
        arm = np.linalg.norm(e - p[:, s + 1], axis=-1)  # |h × r| <= |r|: rate <= arm
        out.append(("elbow", rate, _covector(rho_hat, e, tool), arm))
        if plan.shoulder_point is not None:
            w = _point(plan.shoulder_point, h, p, tool)
            normal = _unit(np.cross(h[:, 0], h[:, 1]))
            dist = np.abs(np.sum((w - p[:, 0]) * normal, axis=-1))
            size = np.full_like(dist, arm_size(robot.chain))
            out.append(("shoulder", dist, _covector(h[:, 1], w, tool), size))
    return [item for item in out if item[0] in plan.enabled]


def _assign(
    found: list[tuple[str, float, FloatArray]], U: FloatArray, s: FloatArray, rank: int
) -> list[Singularity]:
    """Match named geometric directions to the lost subspace of one Jacobian.

    Each named direction is its geometric covector projected on the lost
    subspace (the smallest singular directions within the generic rank; the
    smallest one when a name is flagged just before σ drops below RANK_TOL).
    Two names can share one lost direction (a PUMA stretched with its wrist
    aligned loses one dimension only); lost directions no name accounts for
    are reported as ``"rank"``.
    """
    ratio = s / s[0] if s[0] > 0 else np.zeros_like(s)
    lost = int(np.sum(ratio[:rank] < RANK_TOL))
    k = max(lost, 1 if found else 0)
    basis = U[:, rank - k : rank]  # the k smallest directions within the generic rank
    out: list[Singularity] = []
    taken: list[FloatArray] = []
    for name, measure, g in found:
        d = basis @ (basis.T @ g)
        if len(taken) < k:  # a fresh dimension is left: keep the directions distinct
            for t in taken:
                d = d - (t @ d) * t
        norm = float(np.linalg.norm(d))
        d = d / norm if norm > 1e-9 else basis[:, -1].copy()
        d = d if d @ g >= 0 else -d
        taken.append(d)
        out.append(Singularity(name, d, float(measure)))
    for col in range(k):
        if len(taken) >= k:
            break
        d = basis[:, col].copy()
        for t in taken:
            d = d - (t @ d) * t
        norm = float(np.linalg.norm(d))
        if norm < 1e-6:
            continue
        taken.append(d / norm)
        out.append(Singularity("rank", d / norm, float(ratio[rank - k + col])))
    return out


def singularities(robot: RobotKinematics, q: ArrayLike, detail: bool = False) -> Any:
    """The singularities of ``robot`` at ``q``, by name.

    See the module docstring for the names, their tests and tolerances.

    Args:
        robot: The robot.
        q: ``(n,)`` joint values (rad, m), or a batch ``(..., n)``.
        detail: Return :class:`Singularity` objects (name, lost direction,
            measure) instead of names.

    Returns:
        For one configuration, a list: ``[]`` when regular, else names such
        as ``["wrist"]`` or ``["elbow", "wrist"]`` (``"rank"`` once, however
        many unnamed directions), or with ``detail`` one :class:`Singularity`
        per lost direction. For a batch, nested lists of the batch's shape.

    Raises:
        DimensionError: ``q`` has the wrong shape, or a row holds NaN or inf
            (the message names the first).
    """
    qa = as_batch_array(robot.check_q(q), "q", (robot.dof,))  # names cannot be NaN
    flat = qa.reshape(-1, robot.dof)
    plan = singularity_plan(robot)
    J = robot.jacobian(flat)[:, plan.rows, :]
    U, S, _ = np.linalg.svd(J)
    ratio = S / np.where(S[:, :1] > 0, S[:, :1], 1.0)
    lost = np.sum(ratio[:, : plan.rank] < RANK_TOL, axis=1) > 0
    named = _named(robot, plan, flat)
    flagged = lost.copy()
    for name, measure, _g, _s in named:
        flagged |= measure < _TOLS[name]
    results: list[Any] = []
    for b in range(flat.shape[0]):
        if not flagged[b]:
            results.append([])
            continue
        found = [(name, float(m[b]), g[b]) for name, m, g, _ in named if m[b] < _TOLS[name]]
        Ub = U[b]
        if len(plan.rows) == 3:  # position rows: embed (u, 0) in twist space
            Ub = np.vstack([Ub, np.zeros((3, 3))])
            found = [(nm, m, np.r_[g[:3], 0.0, 0.0, 0.0]) for nm, m, g in found]
        sing = _assign(found, Ub, S[b], plan.rank)
        if detail:
            results.append(sing)
        else:
            names = [x.name for x in sing]
            results.append(sorted(set(names), key=names.index))
    if qa.ndim == 1:
        return results[0]
    arr = np.empty(len(results), dtype=object)
    for i, r in enumerate(results):
        arr[i] = r
    return arr.reshape(qa.shape[:-1]).tolist()


def singularity_measures(
    robot: RobotKinematics, q: ArrayLike, relative: bool = False
) -> dict[str, FloatArray]:
    """The measure of each named singularity of ``robot`` at ``q`` (see the module docstring).

    Args:
        robot: The robot.
        q: ``(..., n)`` joint values.
        relative: Divide each by its largest value at that geometry: the elbow
            rate by the elbow point's distance from the elbow axis (the sine of
            the angle at the elbow point in the triangle shoulder axis, elbow
            axis, elbow point: 0 stretched or folded), the shoulder distance by
            the arm's size; the wrist's sine stays.

    Returns:
        Name -> ``(...)`` measure: the sine between axes 4 and 6 (``"wrist"``),
        the elbow rate (m/rad, ``"elbow"``), the shoulder distance (m,
        ``"shoulder"``); only the names the arm's structure has. Each is 0 on its
        singular set and grows away from it.
    """
    qa = robot.check_q(q)
    flat = qa.reshape(-1, robot.dof)
    out = {}
    for name, measure, _, scale in _named(robot, singularity_plan(robot), flat):
        m = measure / np.where(scale > 0.0, scale, 1.0) if relative else measure
        out[name] = m.reshape(qa.shape[:-1])
    return out


def jacobian_rank(robot: RobotKinematics, q: ArrayLike) -> Any:
    """Rank of the arm's task Jacobian at ``q`` (singular values above RANK_TOL·σmax).

    Args:
        robot: The robot.
        q: ``(..., n)`` joint values.

    Returns:
        ``(rank, generic)``: the rank, an int (or ``(...)`` int array for a
        batch), and the generic rank of the same rows (its value at regular
        configurations). The rows are the position rows for arms whose whole
        mobility shows in the tool position, all six otherwise.
    """
    qa = as_batch_array(robot.check_q(q), "q", (robot.dof,))  # a rank cannot be NaN
    plan = singularity_plan(robot)
    J = robot.jacobian(qa)[..., plan.rows, :]
    s = np.linalg.svd(J, compute_uv=False)
    rank = np.sum(s > RANK_TOL * s[..., :1], axis=-1)
    return (int(rank) if rank.ndim == 0 else rank), plan.rank
