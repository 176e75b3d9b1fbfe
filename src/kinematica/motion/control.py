"""Resolved-rate control: joint velocities from the Jacobian, step by step.

At each step of length ``dt`` the controller asks for a tool twist ``v``
(base frame, rows ``vx vy vz ωx ωy ωz`` or the subset ``axes`` selects):
either a given one (``twist=``) or ``gain · e`` towards a target pose, with
``e = km.se3_error(T, target)`` (position error in m, rotation vector in rad,
both in the base frame). The joints then move at

    q̇ = J⁺_λ v + (I − J⁺J) q̇₀,   J⁺_λ = Jᵀ (J Jᵀ + λ² I)⁻¹

(Whitney's resolved-rate motion; damped least squares, Wampler / Nakamura &
Hanafusa, when ``λ > 0``; Liégeois' projection of a secondary objective
``q̇₀`` into the null space of the redundant arm). ``q`` is integrated by
Euler steps, ``q ← q + q̇·dt``.

Damping laws (``damping=``): a number is a constant ``λ``; the variable laws
switch damping on only near a singularity, so elsewhere the motion is the
exact pseudo-inverse's:

- ``"manipulability"`` (Nakamura & Hanafusa's variable damping, on Yoshikawa's
  ``w`` of the controlled rows): ``λ² = λmax² (1 − (w/w0)²)`` for ``w < w0``;
- ``"min_singular"`` (Chiaverini's singular region, on the smallest singular
  value ``σ``): ``λ² = λmax² (1 − (σ/ε)²)`` for ``σ < ε``.

``threshold`` is ``w0`` or ``ε``; ``lambda_max`` is ``λmax``.

Limits: ``qd_max`` scales the whole ``q̇`` down (its direction kept) until every
joint is within its speed; with ``respect_limits`` a joint's rate is then
clipped so that the step ends inside its limits (a joint at a limit stops
there, the others go on). The null-space objectives: ``"limits"`` climbs away
from the limits (Liégeois: ``q̇₀ = −k (q − q_mid) / (n·range²)``),
``"manipulability"`` climbs Yoshikawa's ``w`` along its gradient (from the
Hessian, :func:`kinematica.motion.manipulability_gradient`), or any callable
``q -> q̇₀``.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.arguments import check_count, check_size
from kinematica.errors import DimensionError, KinematicaError
from kinematica.motion.trajectory import JointTrajectory
from kinematica.robot.velocity import Axes, manipulability_gradient, selected_rows
from kinematica.spatial import check_transform, se3_error

if TYPE_CHECKING:
    from kinematica.robot import Robot

__all__ = [
    "DEFAULT_STEPS",
    "MARGIN_RATE",
    "MAX_STEPS",
    "DampingLaw",
    "RateControl",
    "damping_factor",
    "resolved_rate",
]

FloatArray = NDArray[np.float64]

#: Steps when neither ``steps`` nor ``duration`` is given.
DEFAULT_STEPS = 2000
#: Most steps a run takes (``steps``, or ``duration / dt``): it keeps q, q̇ and the
#: error of every step, ~100 MB for 7 joints.
MAX_STEPS = 1_000_000

#: With ``min_manipulability``: the fraction of the margin ``w − w_min`` one step may
#: use up (to first order). Each step then keeps a half of what is left, so ``w``
#: tends to ``w_min`` and does not cross it (a velocity damper on ``w``).
MARGIN_RATE = 0.5

#: Variable damping laws (see the module docstring).
DampingLaw = Literal["manipulability", "min_singular"]
NullSpace = Literal["limits", "manipulability"] | Callable[[FloatArray], ArrayLike]


@dataclass(frozen=True)
class RateControl:
    """A resolved-rate run: the samples of the motion and what the controller saw.

    Sample ``k`` is at ``t[k] = k·dt``; ``qd[k]`` is the joint rate commanded
    there, held until the next sample (``q[k+1] = q[k] + qd[k]·dt``); the last
    sample's ``qd`` is the rate the controller would command next (0 once a
    target is reached).

    Attributes:
        t: ``(m,)`` times (s).
        q: ``(m, n)`` joint values (rad, m).
        qd: ``(m, n)`` commanded joint rates (rad/s, m/s).
        qdd: ``(m, n)`` central differences of ``qd`` (the command is piecewise
            constant; these are its average changes).
        error: ``(m, 2)`` position (m) and rotation (rad) error to the target at
            each sample (NaN without a target), of the controlled rows.
        manipulability: ``(m,)`` Yoshikawa's ``w`` of the controlled rows.
        damping: ``(m,)`` the ``λ`` used at each sample.
        reached: True when the target was reached within ``tol`` (the run stops
            there; a moving target is tracked to the end and judged there);
            False when the steps ran out first; None for a twist.
    """

    t: FloatArray
    q: FloatArray
    qd: FloatArray
    qdd: FloatArray
    error: FloatArray
    manipulability: FloatArray
    damping: FloatArray
    reached: bool | None

    @property
    def trajectory(self) -> JointTrajectory:
        """The motion as a :class:`JointTrajectory` (for export, plots, animation)."""
        return JointTrajectory(self.t, self.q, self.qd, self.qdd)


def damping_factor(
    law: DampingLaw | float | None, w: float, sigma_min: float, threshold: float, lambda_max: float
) -> float:
    """``λ`` of a damping law at a configuration with measures ``w`` and ``σmin``.

    Args:
        law: ``None`` (0), a constant ``λ``, ``"manipulability"`` or ``"min_singular"``.
        w: Yoshikawa's manipulability of the controlled rows.
        sigma_min: Their smallest singular value.
        threshold: ``w0`` (manipulability) or ``ε`` (min_singular).
        lambda_max: ``λmax``.

    Returns:
        ``λ >= 0``.
    """
    if law is None:
        return 0.0
    if not isinstance(law, str):
        return float(law)
    x = w if law == "manipulability" else sigma_min
    if x >= threshold:
        return 0.0
    return lambda_max * math.sqrt(1.0 - (x / threshold) ** 2)


def _positive(value: float, name: str) -> float:
    v = float(value)
    if not (math.isfinite(v) and v > 0.0):
        raise KinematicaError(f"{name} must be a positive number, got {value!r}", arg=name)
    return v


def _check_damping(damping: DampingLaw | float | None) -> None:
    if damping is None or damping in ("manipulability", "min_singular"):
        return
    if isinstance(damping, str) or not (
        isinstance(damping, int | float) and math.isfinite(damping) and damping >= 0
    ):
        raise KinematicaError(
            "damping must be None, a constant λ >= 0, 'manipulability' or 'min_singular', "
            f"got {damping!r}",
            arg="damping",
        )


def _steps(steps: int | None, duration: float | None, dt: float) -> int:
    if steps is not None and duration is not None:
        raise KinematicaError("give steps or duration, not both", arg="steps")
    if duration is not None:
        d = _positive(duration, "duration")
        check_size(d / dt, MAX_STEPS, "duration/dt", f"steps ({d:g} s every {dt!r} s)",
                   arg="duration")  # fmt: skip
        return max(1, round(d / dt))
    if steps is None:
        return DEFAULT_STEPS
    return check_count(steps, "steps", lo=1, hi=MAX_STEPS)


def _limits_gradient(robot: Robot) -> Callable[[FloatArray], FloatArray]:
    """Liégeois' ``−∇`` of ``Σ ((q − q_mid)/range)² / 2n`` over joints with limits."""
    has = robot.has_limits
    lo, hi = robot.qlim[:, 0], robot.qlim[:, 1]
    mid = np.where(has, (lo + hi) / 2.0, 0.0)
    inv_range2 = np.where(has, 1.0 / np.where(has, hi - lo, 1.0) ** 2, 0.0)
    n = robot.dof

    def grad(q: FloatArray) -> FloatArray:
        out: FloatArray = -(q - mid) * inv_range2 / n
        return out

    return grad


def _nullspace(
    robot: Robot, nullspace: NullSpace | None, axes: Axes
) -> Callable[[FloatArray], FloatArray] | None:
    if nullspace is None:
        return None
    if nullspace == "limits":
        return _limits_gradient(robot)
    if nullspace == "manipulability":
        return lambda q: manipulability_gradient(robot, q, axes)
    if callable(nullspace):
        user = nullspace

        def call(q: FloatArray) -> FloatArray:
            out = np.asarray(user(q), dtype=float)
            if out.shape != (robot.dof,) or not np.all(np.isfinite(out)):
                raise DimensionError(
                    f"nullspace must return {robot.dof} finite joint rates, got shape {out.shape}"
                )
            return out

        return call
    raise KinematicaError(
        f"nullspace must be None, 'limits', 'manipulability' or a function of q, got {nullspace!r}",
        arg="nullspace",
    )


def _twist_source(
    twist: ArrayLike | Callable[[float], ArrayLike], m: int
) -> Callable[[float], FloatArray]:
    def check(v: ArrayLike) -> FloatArray:
        a = np.asarray(v, dtype=float)
        if a.shape != (m,) or not np.all(np.isfinite(a)):
            raise DimensionError(
                f"twist must be {m} finite numbers (the controlled rows), got shape {a.shape}"
            )
        return a

    if callable(twist):
        source = twist
        return lambda t: check(source(t))
    fixed = check(twist)
    return lambda t: fixed


def _target_source(
    target: ArrayLike | Callable[[float], ArrayLike],
) -> Callable[[float], FloatArray]:
    if callable(target):
        source = target
        return lambda t: check_transform(source(t), "target")
    fixed = check_transform(target, "target")
    return lambda t: fixed


def resolved_rate(
    robot: Robot,
    q0: ArrayLike,
    *,
    target: ArrayLike | Callable[[float], ArrayLike] | None = None,
    twist: ArrayLike | Callable[[float], ArrayLike] | None = None,
    dt: float = 0.01,
    steps: int | None = None,
    duration: float | None = None,
    gain: float = 5.0,
    axes: Axes = "all",
    damping: DampingLaw | float | None = "min_singular",
    threshold: float = 0.05,
    lambda_max: float = 0.05,
    qd_max: ArrayLike | None = None,
    respect_limits: bool = True,
    nullspace: NullSpace | None = None,
    nullspace_gain: float = 1.0,
    min_manipulability: float | None = None,
    tol: float = 1e-10,
) -> RateControl:
    """Drive the tool toward a pose, or along a twist, by resolved-rate control.

    See the module docstring for the control law, the damping laws and the
    limits.

    Args:
        robot: The robot.
        q0: ``(n,)`` start configuration (rad, m).
        target: A ``(4, 4)`` goal pose (base frame), or a function ``t -> (4, 4)``
            for a moving goal. Exactly one of ``target`` and ``twist``.
        twist: The tool twist to follow (base frame; m/s then rad/s, only the
            rows ``axes`` selects), or a function ``t -> twist``.
        dt: Step (s).
        steps: Number of steps (default :data:`DEFAULT_STEPS`); or ``duration`` (s).
        duration: Length of the run (s), instead of ``steps``.
        gain: Proportional gain toward ``target`` (1/s): the error shrinks by
            about ``gain·dt`` per step (``gain·dt`` = 1 is a Newton step).
        axes: The rows controlled: ``"all"`` (default: the full pose), ``"trans"``
            (the tool position, orientation free), ``"rot"``, ``"task"`` or indices.
        damping: ``None`` (plain pseudo-inverse), a constant ``λ``,
            ``"manipulability"`` or ``"min_singular"`` (default).
        threshold: ``w0`` or ``ε`` of the damping law (units of the measure).
        lambda_max: ``λmax`` of the damping law.
        qd_max: Joint speed limits, one number or ``(n,)`` (rad/s, m/s); None: none.
        respect_limits: Clip each step at the joint limits (default True).
        nullspace: Secondary objective in the null space: ``"limits"``,
            ``"manipulability"``, a function ``q -> q̇₀``, or None.
        nullspace_gain: Its gain ``k`` (``q̇₀`` is scaled by it).
        min_manipulability: Keep Yoshikawa's ``w`` of the controlled rows above
            this: each rate is changed least so that ``∇w·q̇`` (from the
            Hessian) uses at most :data:`MARGIN_RATE` of the margin per step.
            Damping alone bounds the rates near a singularity but still creeps
            toward it; this stops the approach. None: no floor.
        tol: A target is reached when the position error is at most ``tol``
            metres and the rotation error at most ``tol`` radians (on the
            controlled rows); the run then stops.

    Returns:
        The :class:`RateControl` run (``.trajectory`` for export).

    Raises:
        KinematicaError: Bad arguments (each names its argument).
    """
    if (target is None) == (twist is None):
        raise KinematicaError("give exactly one of target and twist", arg="target")
    dt = _positive(dt, "dt")
    gain = _positive(gain, "gain")
    tol = _positive(tol, "tol")
    threshold = _positive(threshold, "threshold")
    lambda_max = _positive(lambda_max, "lambda_max")
    _check_damping(damping)
    count = _steps(steps, duration, dt)
    rows = selected_rows(robot, axes)
    m, n = len(rows), robot.dof
    q = robot.check_q(q0, "q0").copy()
    if q.shape != (n,):
        raise DimensionError(f"q0 must be one configuration of {n} joint values, got {q.shape}")
    # only a joint's own limits bind: a free revolute joint turns on past ±π
    lo = np.where(robot.has_limits, robot.qlim[:, 0], -np.inf)
    hi = np.where(robot.has_limits, robot.qlim[:, 1], np.inf)
    secondary = _nullspace(robot, nullspace, axes)  # reads the robot's own limits
    w_min = (
        0.0 if min_manipulability is None else _positive(min_manipulability, "min_manipulability")
    )
    if not respect_limits:  # asked to ignore them: no warning per step beyond them
        robot = robot.with_limits([None] * n)
    speed = None
    if qd_max is not None:
        speed = np.broadcast_to(np.asarray(qd_max, dtype=float), (n,))
        if not np.all(np.isfinite(speed) & (speed > 0)):
            raise KinematicaError(
                f"qd_max must be positive speeds, one or {n} values", arg="qd_max"
            )
    goal = None if target is None else _target_source(target)
    stop = not callable(target)  # a moving target is tracked for the whole run
    follow = None if twist is None else _twist_source(twist, m)
    pos_rows = [i for i, r in enumerate(rows) if r < 3]
    rot_rows = [i for i, r in enumerate(rows) if r >= 3]

    qs, qds, errs, ws, lams = [], [], [], [], []
    reached: bool | None = None
    for k in range(count + 1):
        t = k * dt
        J = robot.jacobian(q)[rows, :]
        s = np.linalg.svd(J, compute_uv=False)
        w = float(np.prod(s))
        if goal is not None:
            e = se3_error(robot.fk(q), goal(t))[list(rows)]
            err = (
                float(np.linalg.norm(e[pos_rows])) if pos_rows else 0.0,
                float(np.linalg.norm(e[rot_rows])) if rot_rows else 0.0,
            )
            v = gain * e
            done = stop and err[0] <= tol and err[1] <= tol
        else:
            assert follow is not None
            err, v, done = (math.nan, math.nan), follow(t), False
        lam = damping_factor(damping, w, float(s[-1]), threshold, lambda_max)
        if done:
            qd = np.zeros(n)
        else:
            qd = _rates(J, v, lam, secondary, q, nullspace_gain)
            if min_manipulability is not None:
                qd = _keep_above(qd, manipulability_gradient(robot, q, axes), w, w_min, dt)
            if speed is not None:
                worst = float(np.max(np.abs(qd) / speed))
                if worst > 1.0:
                    qd = qd / worst
            if respect_limits:
                qd = np.clip(qd, (lo - q) / dt, (hi - q) / dt)
        qs.append(q.copy())
        qds.append(qd)
        errs.append(err)
        ws.append(w)
        lams.append(lam)
        if done:
            reached = True
            break
        if k < count:
            q = q + qd * dt
            if respect_limits:  # q + ((hi - q) / dt) * dt may round an ulp past hi: land on it
                q = np.clip(q, lo, hi)
    if goal is not None and not stop:  # tracking: on target at the end?
        reached = errs[-1][0] <= tol and errs[-1][1] <= tol
    elif goal is not None and reached is None:
        reached = False
    t_out = dt * np.arange(len(qs), dtype=np.float64)
    qd_out = np.array(qds)
    qdd = np.gradient(qd_out, dt, axis=0) if len(qs) > 1 else np.zeros_like(qd_out)
    return RateControl(
        t=t_out,
        q=np.array(qs),
        qd=qd_out,
        qdd=qdd,
        error=np.array(errs, dtype=float),
        manipulability=np.array(ws),
        damping=np.array(lams),
        reached=reached,
    )


def _rates(
    J: FloatArray,
    v: FloatArray,
    lam: float,
    secondary: Callable[[FloatArray], FloatArray] | None,
    q: FloatArray,
    k0: float,
) -> FloatArray:
    """``J⁺_λ v + (I − J⁺J)·k0·q̇₀(q)``."""
    if lam > 0.0:
        m = J.shape[0]
        qd: FloatArray = J.T @ np.linalg.solve(J @ J.T + lam * lam * np.eye(m), v)
    else:
        qd = np.linalg.pinv(J) @ v
    if secondary is not None:
        z = k0 * secondary(q)
        qd = qd + z - np.linalg.pinv(J) @ (J @ z)
    return qd


def _keep_above(qd: FloatArray, grad: FloatArray, w: float, w_min: float, dt: float) -> FloatArray:
    """``q̇`` changed least (in norm) so that ``∇w·q̇ >= −MARGIN_RATE·(w − w_min)/dt``."""
    need = -MARGIN_RATE * (w - w_min) / dt
    have = float(grad @ qd)
    gg = float(grad @ grad)
    if have >= need or gg == 0.0:
        return qd
    out: FloatArray = qd + (need - have) / gg * grad
    return out
