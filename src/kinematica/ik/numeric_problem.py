"""The numeric IK problem: settings, limits and tolerances, compiled once.

:class:`LMProblem` is what the Levenberg-Marquardt kernels
(:mod:`~kinematica.ik.numeric_batch`, :mod:`~kinematica.ik.numeric_single`)
need; :class:`Setup` adds what the public entry point
(:mod:`kinematica.ik.numeric`) needs around them: the restart range, the
default first guess, the reach bound. Both are pure functions of an immutable
robot and the settings, and are cached per robot.
"""

from __future__ import annotations

import math
import weakref
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from kinematica.dh import DHChain, Prismatic
from kinematica.robot import Robot

__all__ = [
    "FULL_TURN",
    "LAMBDA_DOWN",
    "LAMBDA_INIT",
    "LAMBDA_MAX",
    "LAMBDA_MIN",
    "LAMBDA_UP",
    "PRISMATIC_SPAN",
    "SCALE_FLOOR",
    "STALL_FACTOR",
    "STALL_WINDOW",
    "TWO_PI",
    "LMProblem",
    "Sampler",
    "SearchResult",
    "Setup",
    "compile_setup",
]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
BoolArray = NDArray[np.bool_]
#: ``sample(count)``: ``(count, n)`` random configurations for restarts.
Sampler = Callable[[int], FloatArray]

TWO_PI = 2.0 * math.pi

#: Initial damping, relative to the mean diagonal of the normal matrix: about
#: as strong as the Jacobian itself, a safe first step from a distant guess.
LAMBDA_INIT = 1.0
#: Damping factor after an accepted step (towards Gauss-Newton) ...
LAMBDA_DOWN = 0.1
#: ... and after a rejected one (towards short gradient steps).
LAMBDA_UP = 5.0
#: Smallest relative damping: negligible next to any singular value that
#: matters (so the last steps converge quadratically), yet it keeps the normal
#: matrix positive definite in floating point, rank-deficient Jacobian or not.
LAMBDA_MIN = 1e-12
#: Damping at which an attempt has stalled: even tiny gradient steps no longer
#: reduce the error (a local minimum, or the error is at round-off level).
LAMBDA_MAX = 1e8
#: Progress check: every STALL_WINDOW steps the squared error must have
#: dropped below STALL_FACTOR times its value at the previous check (the error
#: norm must halve), else the attempt has stalled and a restart is better.
STALL_WINDOW = 8
STALL_FACTOR = 0.25
#: Mean diagonal below which the normal matrix is treated as zero (every
#: column blocked, or a fresh row): its damping is then taken as absolute.
SCALE_FLOOR = 1e-300
#: Half-width (m) of the range restarts sample for a prismatic joint with no
#: limits; with one finite limit, the range is 2·PRISMATIC_SPAN from it.
PRISMATIC_SPAN = 1.0
#: A revolute range at least this wide (rad) is a full turn: wrapped, never clamped.
FULL_TURN = 2.0 * math.pi - 1e-12


@dataclass(frozen=True, eq=False)
class LMProblem:
    """Everything the kernels need about one call, prepared once.

    Attributes:
        chain: The robot's compiled DH chain (its regrouped link parameters).
        rows: ``(m,)`` indices in ``(x, y, z, rx, ry, rz)`` of the error
            components that count (mask weight > 0).
        weight: ``(m,)`` square roots of their weights: LM minimises
            ``½ Σ w_i e_i²``.
        check: ``(m,)`` scale of each component in the convergence test,
            ``max(w_i, 1)``: converged means the scaled norms are within the
            tolerances, hence so are both the plain and the weighted norms.
        is_position: ``(m,)`` True for rows 0-2 (metres), False for 3-5 (rad).
        wrap_base: ``(n,)`` start of each revolute joint's 2π window
            ``[wrap_base, wrap_base + 2π)``; unused for prismatic joints.
        lower: ``(n,)`` clamp bounds (−inf where none).
        upper: ``(n,)`` clamp bounds (+inf where none).
        tol_position: Convergence tolerance on the position error (m).
        tol_angle: Convergence tolerance on the rotation error (rad).
        max_iterations: Steps per attempt.
    """

    chain: DHChain
    rows: IntArray
    weight: FloatArray
    check: FloatArray
    is_position: BoolArray
    wrap_base: FloatArray
    lower: FloatArray
    upper: FloatArray
    tol_position: float
    tol_angle: float
    max_iterations: int

    @property
    def prismatic(self) -> BoolArray:
        """``(n,)`` True for prismatic joints."""
        return self.chain.prismatic

    @property
    def dof(self) -> int:
        """Number of joints n."""
        return self.chain.dof

    @property
    def orientation(self) -> bool:
        """True if any rotation component counts."""
        return not bool(np.all(self.is_position))

    @property
    def exact(self) -> bool:
        """True if only some rotation components count.

        The rotation error ``Δω`` then need not vanish at a solution, and its
        rows use the exact derivative ``dΔω = −J_r⁻¹(Δω) J_ω dq`` (``J_r`` the
        right Jacobian of SO(3)): with ``J_ω`` alone convergence is linear at
        best (measured: twice the steps, half the first attempts succeed).
        With every rotation component counted ``Δω → 0``, where ``J_r⁻¹ → I``,
        and the plain rows do as well for less.
        """
        counted = int(np.count_nonzero(~self.is_position))
        return 0 < counted < 3

    @property
    def weighted(self) -> bool:
        """True if some counted component has a weight other than 1."""
        return bool(np.any(self.weight != 1.0))

    @property
    def clamped(self) -> bool:
        """True if some joint has a clamp bound."""
        return bool(np.any(np.isfinite(self.lower) | np.isfinite(self.upper)))

    def project(self, q: FloatArray) -> FloatArray:
        """Wrap revolute angles into their window, then clamp into the limits.

        A revolute angle beyond its upper limit (after wrapping into
        ``[lower, lower + 2π)``) goes to the nearer limit around the circle.

        Args:
            q: ``(n, R)`` joint values, one column per row.

        Returns:
            ``(n, R)`` projected joint values.
        """
        revolute = ~self.prismatic[:, None]
        base = self.wrap_base[:, None]
        q = np.where(revolute, base + np.mod(q - base, TWO_PI), q)
        lo, hi = self.lower[:, None], self.upper[:, None]
        over = q > hi
        if over.any():
            to_lower = revolute & (q - hi > lo + TWO_PI - q)
            q = np.where(over, np.where(to_lower, lo, hi), q)
        return np.maximum(q, lo)


@dataclass(frozen=True)
class SearchResult:
    """Per-target outcome of a search.

    Attributes:
        q: ``(N, n)`` the converged configuration, or the best failed one.
        converged: ``(N,)`` True where an attempt met the tolerances.
        iterations: ``(N,)`` evaluations spent on the target, all rows summed.
        attempts: ``(N,)`` attempts started (1 + restarts used).
    """

    q: FloatArray
    converged: BoolArray
    iterations: IntArray
    attempts: IntArray


@dataclass(frozen=True, eq=False)
class Setup:
    """What a call needs about the robot and its settings, compiled once.

    Attributes:
        problem: The kernels' problem.
        limits: ``(n, 2)`` the robot's joint limits, for the final check.
        respect_limits: Whether solutions must lie within ``limits``.
        sample_lo: ``(n,)`` lower ends of the range restarts sample uniformly.
        sample_hi: ``(n,)`` upper ends.
        middle: ``(n,)`` the default first guess, the middle of that range.
        reach: Upper bound on the tool origin's distance from the base origin (m).
        base_origin: ``(3,)`` the base origin.
        counted_position: ``(3,)`` 1 for the counted position components, else 0.
    """

    problem: LMProblem
    limits: FloatArray
    respect_limits: bool
    sample_lo: FloatArray
    sample_hi: FloatArray
    middle: FloatArray
    reach: float
    base_origin: FloatArray
    counted_position: FloatArray


# Compiled set-ups per robot (a Robot is immutable, so a set-up is a pure
# function of it and the settings): compiling costs as much as a few LM steps,
# which matters for single solves. The cache forgets a robot when it dies.
_SETUPS: weakref.WeakKeyDictionary[Robot, dict[tuple[object, ...], Setup]] = (
    weakref.WeakKeyDictionary()
)
_SETUPS_PER_ROBOT = 8


def compile_setup(
    robot: Robot,
    weights: FloatArray,
    respect_limits: bool,
    tol_position: float,
    tol_angle: float,
    max_iterations: int,
) -> Setup:
    """The compiled set-up, from the cache when this robot has seen these settings."""
    key = (weights.tobytes(), respect_limits, tol_position, tol_angle, max_iterations)
    per_robot = _SETUPS.setdefault(robot, {})
    setup = per_robot.get(key)
    if setup is None:
        if len(per_robot) >= _SETUPS_PER_ROBOT:
            per_robot.pop(next(iter(per_robot)))
        setup = per_robot[key] = _compile(
            robot, weights, respect_limits, tol_position, tol_angle, max_iterations
        )
    return setup


def _compile(
    robot: Robot,
    weights: FloatArray,
    respect_limits: bool,
    tol_position: float,
    tol_angle: float,
    max_iterations: int,
) -> Setup:
    prismatic = robot.is_prismatic
    revolute = ~prismatic
    limits = robot.qlim
    lo, hi = limits.T
    free = (revolute & (hi - lo >= FULL_TURN)) | (not respect_limits)
    rows = np.flatnonzero(weights > 0)
    lower = np.where(free, -np.inf, lo)
    upper = np.where(free, np.inf, hi)
    problem = LMProblem(
        chain=DHChain.from_joints(robot.links, robot.convention, robot.base, robot.tool),
        rows=rows,
        weight=np.sqrt(weights[rows]),
        check=np.maximum(weights[rows], 1.0),
        is_position=rows < 3,
        wrap_base=np.where(prismatic | (not respect_limits), -math.pi, lo),
        lower=lower,
        upper=upper,
        tol_position=tol_position,
        tol_angle=tol_angle,
        max_iterations=max_iterations,
    )

    # Restarts sample each joint's limits (revolute: one turn at most; all of
    # it when the limits are ignored); a prismatic joint without limits
    # ±PRISMATIC_SPAN, with one limit 2·PRISMATIC_SPAN from it.
    s_lo = np.where(revolute & (not respect_limits), -math.pi, lo)
    s_hi = np.where(revolute & (not respect_limits), math.pi, hi)
    s_hi = np.where(revolute, np.minimum(s_hi, s_lo + 2.0 * math.pi), s_hi)
    span = PRISMATIC_SPAN
    sample_lo = np.where(
        np.isfinite(s_lo), s_lo, np.where(np.isfinite(s_hi), s_hi - 2 * span, -span)
    )
    sample_hi = np.where(
        np.isfinite(s_hi), s_hi, np.where(np.isfinite(s_lo), s_lo + 2 * span, span)
    )

    # The tool origin is never farther from the base origin than the sum of
    # the chain's translations: |a| and |d| of every row (d over its limits
    # for a prismatic joint) and the tool offset. Leaving position components
    # out only shortens a distance, so the bound holds under any mask.
    reach = float(np.linalg.norm(robot.tool[:3, 3]))
    for link, q_lo, q_hi in zip(robot.links, lower, upper, strict=True):
        reach += abs(link.a)
        if isinstance(link, Prismatic):
            reach += max(abs(link.offset + q_lo), abs(link.offset + q_hi))
        else:
            reach += abs(link.d)
    counted = np.zeros(3)
    counted[rows[rows < 3]] = 1.0

    setup = Setup(
        problem=problem,
        limits=limits,
        respect_limits=respect_limits,
        sample_lo=sample_lo,
        sample_hi=sample_hi,
        middle=0.5 * (sample_lo + sample_hi),
        reach=reach,
        base_origin=robot.base[:3, 3].copy(),
        counted_position=counted,
    )
    for part in (problem, setup):
        for value in vars(part).values():
            if isinstance(value, np.ndarray):
                value.flags.writeable = False
    return setup
