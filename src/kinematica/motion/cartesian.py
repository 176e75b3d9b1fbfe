"""Cartesian paths: a line or an arc of poses, followed on one IK branch.

The tool moves along a straight line (or the circular arc through ``via``)
while its orientation turns by slerp. At every sample, inverse kinematics
gives every solution and the one nearest the previous configuration is kept
(revolute joints unwrapped, so no 2π jump either). Each segment between two
samples is then inspected; nothing changes silently:

- ``"singularity"``: a sample is singular (:func:`singularities`), or the
  determinant of the arm's square Jacobian changes sign between two samples
  (the path crosses a singular surface: bisection in the path parameter finds
  the crossing and names it);
- ``"unreachable"``: the pose has no IK solution (the path leaves the workspace);
- ``"joint_limit"``: the continuation lies outside a joint limit;
- ``"branch_change"``: the nearest solution is not the continuation of the
  previous one (a joint jump that refining the segment does not shrink);
- ``"near_singularity"``, ``"speed_jump"``, ``"end_branch"``: a passage near a
  singular set, a joint rate that jumps, an end on another branch than ``q1``
  (:mod:`kinematica.motion.path_checks`).

A segment whose largest joint step exceeds :data:`MAX_JOINT_STEP` is refined by
bisection until every sub-step is below it (continuous, fast motion) or the
refinement reaches :data:`MAX_DEPTH` levels (a jump: ``"branch_change"``).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.arguments import check_count, check_flag, check_size
from kinematica.errors import DimensionError, KinematicaError
from kinematica.ik.result import IKResult
from kinematica.motion.cartesian_timed import time_cartesian
from kinematica.motion.cartesian_types import CartesianPath, PathEvent
from kinematica.motion.path_checks import (
    RawEvent,
    end_branch,
    near_singular_passages,
    speed_jumps,
)
from kinematica.motion.trajectory import DEFAULT_DT
from kinematica.robot.singularities import singularities, singularity_plan
from kinematica.spatial import (
    check_transform,
    make_transform,
    matrix_from_quat,
    quat_from_matrix,
    quat_slerp,
    wrap_angle,
)
from kinematica.spatial.checks import as_batch_array, as_float_array

if TYPE_CHECKING:
    from kinematica.robot import Robot

__all__ = [
    "MAX_DEPTH",
    "MAX_JOINT_STEP",
    "MAX_STEPS",
    "CartesianPath",
    "PathEvent",
    "cartesian_path",
    "follow",
    "path_samples",
]

FloatArray = NDArray[np.float64]

#: Largest joint step (rad or m) between two path samples accepted without refining.
MAX_JOINT_STEP = 0.2
#: Most samples of a path (each is an IK solve).
MAX_STEPS = 100_000
#: Bisection levels when refining a segment or locating a singular crossing.
MAX_DEPTH = 40
#: Three points closer than this (m) to one line define no circle.
COLLINEAR_TOL = 1e-9


class _Geometry:
    """Pose at path parameter s: position on a line or arc, orientation by slerp."""

    def __init__(self, T0: FloatArray, T1: FloatArray, via: FloatArray | None) -> None:
        self.p0, self.p1 = T0[:3, 3], T1[:3, 3]
        self.q0, self.q1 = quat_from_matrix(T0[:3, :3]), quat_from_matrix(T1[:3, :3])
        self.arc: tuple[FloatArray, float, FloatArray, FloatArray, float] | None = None
        if via is not None:
            u, v = via - self.p0, self.p1 - self.p0
            w = np.cross(u, v)
            ww = float(w @ w)
            if np.sqrt(ww) < COLLINEAR_TOL * max(1.0, float(u @ u + v @ v)):
                raise KinematicaError(
                    "via lies on the line from T0 to T1 (or repeats an end): "
                    "no circle passes through the three points"
                )
            c = self.p0 + (float(u @ u) * np.cross(v, w) + float(v @ v) * np.cross(w, u)) / (
                2.0 * ww
            )
            r = float(np.linalg.norm(self.p0 - c))
            e1 = (self.p0 - c) / r
            e2 = np.cross(w / np.sqrt(ww), e1)
            d1 = self.p1 - c
            total = float(np.arctan2(d1 @ e2, d1 @ e1)) % (2.0 * np.pi)
            self.arc = (c, r, e1, e2, total)

    def __call__(self, s: FloatArray) -> FloatArray:
        s = np.asarray(s, dtype=float)
        if self.arc is None:
            p = self.p0 + s[..., None] * (self.p1 - self.p0)
        else:
            c, r, e1, e2, total = self.arc
            ang = s[..., None] * total
            p = c + r * (np.cos(ang) * e1 + np.sin(ang) * e2)
        # Exact ends: the first and last pose are T0 and T1 to round-off.
        R = matrix_from_quat(quat_slerp(self.q0, self.q1, s))
        return make_transform(R, p)


class _Follower:
    """Nearest-solution continuation of one robot along one path."""

    def __init__(
        self, robot: Robot, geometry: Callable[[FloatArray], FloatArray], position_only: bool
    ) -> None:
        self.robot = robot
        self.position_only = position_only
        self.geo = geometry
        self.revolute = ~robot.is_prismatic
        self.limited = robot.has_limits
        self.qlim = robot.qlim
        plan = singularity_plan(robot)
        self.rows = plan.rows
        self.square = len(plan.rows) == robot.dof and plan.rank == robot.dof

    def solve(self, s: float, q_prev: FloatArray | None) -> tuple[str, FloatArray | None, str]:
        """``(status, q, detail)``: status ``ok``, ``unreachable`` or ``joint_limit``."""
        T = self.geo(np.array(s))
        target = T[:3, 3] if self.position_only else T
        res = self.robot.ik(target, q0=q_prev, respect_limits=True)
        assert isinstance(res, IKResult)  # one target, one result
        within, outside = res.solutions, res.out_of_limits
        if within.shape[0] == 0 and outside.shape[0] == 0:
            return "unreachable", None, res.message
        if q_prev is None:
            if within.shape[0] == 0:
                return "joint_limit", None, self._over(outside[0])
            return "ok", within[0].copy(), ""
        cands = np.vstack([within, outside])
        cont = self._unwrap(cands, q_prev)
        dist = np.linalg.norm(cont - q_prev, axis=1)
        best = int(np.argmin(dist))
        q = cont[best]
        over = self._outside(q)
        if best >= within.shape[0] or over.any():
            return "joint_limit", None, self._over(q)
        return "ok", q, ""

    def _unwrap(self, cands: FloatArray, q_prev: FloatArray) -> FloatArray:
        """Revolute values moved by multiples of 2π next to ``q_prev``."""
        near = q_prev + wrap_angle(cands - q_prev)
        out: FloatArray = np.where(self.revolute, near, cands)
        return out

    def _outside(self, q: FloatArray) -> NDArray[np.bool_]:
        lo, hi = self.qlim[:, 0], self.qlim[:, 1]
        return self.limited & ((q < lo - 1e-12) | (q > hi + 1e-12))

    def _over(self, q: FloatArray) -> str:
        joints = [f"q{i + 1}" for i in np.flatnonzero(self._outside(q))]
        return ", ".join(joints) if joints else "the nearest solution is outside the limits"

    def det(self, q: FloatArray) -> float | None:
        """Determinant of the square task Jacobian (its sign flips across singularities)."""
        if not self.square:
            return None
        return float(np.linalg.det(self.robot.jacobian(q)[self.rows, :]))

    def inspect(
        self, sa: float, qa: FloatArray, sb: float, qb: FloatArray, depth: int = 0
    ) -> list[tuple[str, float, tuple[str, ...]]]:
        """Events strictly inside the segment ``(sa, sb)``: crossings and jumps."""
        da, db = self.det(qa), self.det(qb)
        crossing = da is not None and db is not None and da * db < 0.0
        if not crossing and np.max(np.abs(qb - qa)) <= MAX_JOINT_STEP:
            return []
        if depth >= MAX_DEPTH:
            if np.max(np.abs(qb - qa)) > MAX_JOINT_STEP:
                return [("branch_change", sb, ())]
            return [("singularity", sb, ("rank",))]  # a sign change no sample pins down
        sm = 0.5 * (sa + sb)
        status, qm, _ = self.solve(sm, qa)
        if qm is None:
            return [(status, sm, ())]
        names = singularities(self.robot, qm)
        if names:
            return [("singularity", sm, tuple(names))]
        return self.inspect(sa, qa, sm, qm, depth + 1) + self.inspect(sm, qm, sb, qb, depth + 1)


def _as_pose(T: ArrayLike, name: str) -> FloatArray:
    out: FloatArray = check_transform(T, name=name)
    if out.shape != (4, 4):
        raise DimensionError(f"{name} must be one pose (4, 4), got shape {out.shape}")
    return out


def cartesian_path(
    robot: Robot,
    T0: ArrayLike,
    T1: ArrayLike,
    steps: int = 50,
    q0: ArrayLike | None = None,
    via: ArrayLike | None = None,
    s: ArrayLike | None = None,
    position_only: bool | None = None,
    q1: ArrayLike | None = None,
    *,
    vmax: ArrayLike | None = None,
    amax: ArrayLike | None = None,
    tcp_speed: float | None = None,
    tcp_angular_speed: float | None = None,
    dt: float = DEFAULT_DT,
) -> CartesianPath:
    """Follow a straight line (or an arc through ``via``) from ``T0`` to ``T1``.

    Given any of ``vmax``, ``amax``, ``tcp_speed``, ``tcp_angular_speed``, the
    path is timed by the robot (:mod:`kinematica.motion.cartesian_timed`): the
    fastest timing, rest to rest, of the path through the ``steps`` samples within
    those limits, sampled every ``dt``.

    Args:
        robot: The robot.
        T0: ``(4, 4)`` start pose (base frame).
        T1: ``(4, 4)`` end pose.
        steps: Number of samples, both ends included (>= 2).
        q0: ``(n,)`` configuration whose branch the path starts on (the IK
            solution of ``T0`` nearest to it); the first solution if ``None``.
        via: ``(3,)`` point (or ``(4, 4)`` pose, its position) the arc passes
            through; a straight line if ``None``.
        s: ``(m,)`` increasing path parameters in [0, 1] instead of ``steps``
            uniform ones (e.g. a time scaling ``s(t)``).
        position_only: Follow the tool position only (the orientation in
            ``poses`` is then not imposed). By default, True for arms whose
            whole mobility is positional (3R anthropomorphic, planar 2R: the
            rows :func:`singularities` judges are the position rows).
        q1: ``(n,)`` configuration the path is asked to end on (the IK solution
            of ``T1`` nearest to it): an ``"end_branch"`` event says when the
            continuation ends elsewhere (the same pose, another branch).
        vmax: Joint velocity limits (rad/s, m/s; as for
            :func:`~kinematica.motion.optimal.time_optimal`).
        amax: Joint acceleration limits (rad/s², m/s²).
        tcp_speed: Largest linear speed of the tool (m/s).
        tcp_angular_speed: Largest angular speed of the tool (rad/s).
        dt: Largest sample spacing (s) of a timed path.

    Returns:
        The :class:`CartesianPath`, with its ``events``; timed (``t``, ``qd``,
        ``qdd`` set) when limits are given.

    Raises:
        DimensionError: Poses that are not rigid transforms, bad shapes.
        ArgumentError: ``steps`` not a whole number from 2 to MAX_STEPS, or
            ``s`` longer than MAX_STEPS.
        KinematicaError: ``s`` not increasing within [0, 1], or ``via``
            collinear with the ends.
    """
    A, B = _as_pose(T0, "T0"), _as_pose(T1, "T1")
    if via is not None:
        v = as_float_array(via, "via")
        v = _as_pose(v, "via")[:3, 3] if v.shape == (4, 4) else v
        if v.shape != (3,) or not np.all(np.isfinite(v)):
            raise DimensionError(f"via must be a point (3,) or a pose (4, 4), got {via!r}")
        via = v
    ss = path_samples(steps, s)
    geo = _Geometry(A, B, None if via is None else np.asarray(via))
    path = follow(robot, geo, ss, q0, position_only, q1)
    timing = (vmax, amax, tcp_speed, tcp_angular_speed, dt)
    if any(v is not None for v in timing[:4]):
        return time_cartesian(robot, geo, path, timing)
    return path


def path_samples(steps: int, s: ArrayLike | None) -> FloatArray:
    """``(m,)`` path parameters: ``steps`` uniform ones, or ``s`` checked."""
    if s is None:
        return np.linspace(0.0, 1.0, check_count(steps, "steps", lo=2, hi=MAX_STEPS))
    ss = as_float_array(s, "s")
    ok = ss.ndim == 1 and ss.size >= 2 and np.all(np.isfinite(ss))
    if not ok or ss[0] < 0 or ss[-1] > 1 or np.any(np.diff(ss) < 0):
        raise KinematicaError("s must hold >= 2 non-decreasing values within [0, 1]")
    check_size(ss.size, MAX_STEPS, "s", "samples")
    return ss


def _one_configuration(robot: Robot, q: ArrayLike | None, name: str) -> FloatArray | None:
    """``q`` checked as one configuration ``(n,)``, or None."""
    if q is None:
        return None
    qa = as_batch_array(robot.check_q(q, name), name, (robot.dof,))
    if qa.ndim != 1:
        raise DimensionError(f"{name} must be one configuration ({robot.dof},), got {qa.shape}")
    return qa


def follow(
    robot: Robot,
    geometry: Callable[[FloatArray], FloatArray],
    ss: FloatArray,
    q0: ArrayLike | None,
    position_only: bool | None,
    q1: ArrayLike | None = None,
) -> CartesianPath:
    """Follow the poses ``geometry(s)`` at the samples ``ss`` on one IK branch.

    Args:
        robot: The robot.
        geometry: Path parameter ``(...)`` to poses ``(..., 4, 4)`` (base frame).
        ss: ``(m,)`` non-decreasing path parameters in [0, 1].
        q0: ``(n,)`` configuration whose branch the path starts on, or ``None``.
        position_only: As :func:`cartesian_path`'s (``None``: from the arm).
        q1: ``(n,)`` configuration whose branch the path should end on (at
            ``geometry(1)``), or ``None``: see :func:`cartesian_path`.

    Returns:
        The :class:`CartesianPath`, with its ``events``.
    """
    q_start = _one_configuration(robot, q0, "q0")
    q_end = _one_configuration(robot, q1, "q1")
    if position_only is None:
        position_only = singularity_plan(robot).rows == (0, 1, 2)
    position_only = check_flag(position_only, "position_only")
    follower = _Follower(robot, geometry, bool(position_only))
    poses = geometry(ss)
    m, n = ss.size, robot.dof
    q = np.full((m, n), np.nan)
    raw: list[tuple[str, int, float, tuple[str, ...], str]] = []
    last: FloatArray | None = q_start
    last_ok = False  # whether sample i-1 was solved (the segment is then inspected)
    for i, si in enumerate(ss):
        status, qi, why = follower.solve(float(si), last)
        if qi is None:
            names = tuple(why.split(", ")) if status == "joint_limit" else ()
            raw.append((status, i, float(si), names, why))
            last_ok = False
            continue
        if last_ok and last is not None:
            for kind, se, names in follower.inspect(float(ss[i - 1]), last, float(si), qi):
                raw.append((kind, i, se, names, ""))
        here = singularities(robot, qi)
        if here:
            raw.append(("singularity", i, float(si), tuple(here), ""))
        q[i] = qi
        last, last_ok = qi, True
    checks = near_singular_passages(robot, ss, q) + speed_jumps(robot, ss, q)
    if q_end is not None:
        end = geometry(np.array(1.0))
        checks += end_branch(robot, end, q, ss, q_end, bool(position_only))
    return CartesianPath(ss, poses, q, _with_checks(_merge(raw), checks))


def _with_checks(events: tuple[PathEvent, ...], checks: list[RawEvent]) -> tuple[PathEvent, ...]:
    """The events and the checks' findings, in path order.

    A near-singular run that reaches a singularity of its name is told by that
    singularity alone.
    """
    extra = []
    for kind, i, stop, s, names, message in checks:
        met = any(
            e.kind == "singularity"
            and set(names) <= set(e.names)
            and i <= e.stop
            and e.index <= stop
            for e in events
        )
        if not (kind == "near_singularity" and met):
            extra.append(PathEvent(kind, i, stop, s, names, message))
    return tuple(sorted((*events, *extra), key=lambda e: e.index))


def _merge(raw: list[tuple[str, int, float, tuple[str, ...], str]]) -> tuple[PathEvent, ...]:
    """One event per run of consecutive samples with the same kind and names."""
    out: list[PathEvent] = []
    for kind, i, s, names, why in raw:
        prev = out[-1] if out else None
        if prev and prev.kind == kind and prev.names == names and i - prev.stop <= 1:
            out[-1] = PathEvent(kind, prev.index, i, prev.s, names, prev.message)
            continue
        out.append(PathEvent(kind, i, i, s, names, _message(kind, i, s, names, why)))
    return tuple(out)


def _message(kind: str, i: int, s: float, names: tuple[str, ...], why: str) -> str:
    where = f"at sample {i} (s = {s:.6g})"
    if kind == "singularity":
        return f"{' + '.join(names)} singularity {where}"
    if kind == "unreachable":
        return f"the path leaves the workspace {where}: {why}"
    if kind == "joint_limit":
        return f"joint limit {where}: {why}"
    return f"branch change {where}: the joints would jump to another IK branch"
