"""How well a robot does a task: reach, manipulability, conditioning, clearance.

For every target the robot's IK (``robot.ik`` on the whole task batch: closed
form where the arm's structure allows, numeric otherwise; joint limits
respected) gives its solutions. At each solution the *task Jacobian* is the
rows of the geometric Jacobian (base frame) that the task constrains: the three
position rows for position targets, all six for poses. With ``σ1 ≥ σ2 ≥ ...``
its singular values and ``r`` the arm's *generic rank* for those rows (the
largest rank over its configurations: 2 for a planar arm's position rows, so
that the plane's normal, where the arm never moves, does not make every
measure zero):

- manipulability ``w = σ1·σ2···σr`` (Yoshikawa's ``sqrt(det(J Jᵀ))`` for a
  full-rank square case), m^r for position rows;
- condition number ``κ = σ1 / σr`` (1 is isotropic; ``inf`` at a singularity);
- singularity clearance ``σr``, the smallest of the r singular values (how far
  the Jacobian is from losing rank, in the 2-norm).

A target's value is that of its best solution (the arm may choose its branch):
the largest ``w``, the smallest ``κ``, the largest ``σr``.

Only what is asked is computed (``measure_task(..., needs=)``): the manipulability
alone needs no singular value where ``r = min(m, n)``, since then ``w`` is
``|det J|`` (square rows) or ``√det(J Jᵀ)`` (:meth:`Chain.volumes`: an LU, a tenth
of an SVD); ``κ`` and ``σr`` need the singular values of every solution. ``w``
is computed that way whatever else is asked, so a target's manipulability does
not depend on the other measures asked with it.
"""

from __future__ import annotations

import math
from collections.abc import Collection
from dataclasses import dataclass
from typing import Final, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.design.task import Task
from kinematica.errors import KinematicaError
from kinematica.ik.result import IKBatchResult
from kinematica.robot import Robot

__all__ = [
    "IK_SEED",
    "RANK_TOL",
    "TASK_MEASURES",
    "TaskMeasures",
    "generic_rank",
    "measure_task",
    "task_singular_values",
    "total_length",
]

FloatArray = NDArray[np.float64]
Rows = Literal["position", "pose"]

#: A singular value counts towards the generic rank when it exceeds
#: ``RANK_TOL`` times the largest one (relative; units of the rows mix m and rad).
RANK_TOL: Final = 1e-9
#: Configurations drawn (within the limits, seeded) to find the generic rank.
RANK_SAMPLES: Final = 12
#: Seed of the numeric IK restarts, fixed so that a candidate's measures are a
#: pure function of the design (the same on every worker and in checkpoints).
IK_SEED: Final = 0
#: Most solutions of one target the core compares for equal singular values.
MAX_GROUP: Final = 16
#: Half-width (m) of the range sampled for a prismatic joint without limits.
_FREE_STROKE: Final = 1.0


_ROW_INDICES: Final = {"position": (0, 1, 2), "pose": (0, 1, 2, 3, 4, 5)}
#: The task measures, and those that need every solution's singular values.
TASK_MEASURES: Final = (
    "min_manipulability",
    "mean_manipulability",
    "worst_condition",
    "singularity_clearance",
)
_SINGULAR: Final = frozenset({"worst_condition", "singularity_clearance"})


def _singular_values(robot: Robot, q: ArrayLike, rows: Rows) -> FloatArray:
    """``(..., min(m, n))`` singular values of the task rows of ``J(q)``, largest first."""
    if rows not in _ROW_INDICES:
        raise KinematicaError(f"rows must be 'position' or 'pose', got {rows!r}")
    qa = robot.check_q(q)
    return robot.chain.singular_values(qa, _ROW_INDICES[rows])


def generic_rank(robot: Robot, rows: Rows = "position") -> int:
    """The largest rank of the task Jacobian over the robot's configurations.

    Estimated at :data:`RANK_SAMPLES` configurations drawn uniformly within
    the joint limits (a fixed seed): a rank reached at one random
    configuration is reached almost everywhere.

    Args:
        robot: The robot.
        rows: ``"position"`` (3 rows) or ``"pose"`` (6 rows).

    Returns:
        ``r``, at most ``min(3 or 6, n)``.
    """
    lim = robot.qlim.copy()
    lim[~np.isfinite(lim[:, 0]), 0] = -_FREE_STROKE
    lim[~np.isfinite(lim[:, 1]), 1] = _FREE_STROKE
    q = np.random.default_rng(0).uniform(lim[:, 0], lim[:, 1], (RANK_SAMPLES, robot.dof))
    s = _singular_values(robot, q, rows)
    top = s[:, :1]
    return int(np.max(np.sum(s > RANK_TOL * top, axis=-1), initial=0))


def task_singular_values(
    robot: Robot, q: ArrayLike, rows: Rows = "position", rank: int | None = None
) -> FloatArray:
    """The ``r`` largest singular values of the task Jacobian, largest first.

    Args:
        robot: The robot.
        q: ``(..., n)`` configurations (rad, m).
        rows: ``"position"``: the linear-velocity rows (m/rad, m/m);
            ``"pose"``: all six (angular rows in rad/rad).
        rank: ``r``; the robot's :func:`generic_rank` if ``None``.

    Returns:
        ``(..., r)`` singular values. Their product is the manipulability,
        ``σ1/σr`` the condition number, ``σr`` the clearance.
    """
    r = generic_rank(robot, rows) if rank is None else rank
    return np.ascontiguousarray(_singular_values(robot, q, rows)[..., :r])


def total_length(robot: Robot) -> float:
    """The sum of the DH table's constant lengths, and the tool offset (m).

    ``Σ|a_i|`` over every joint, ``Σ|d_i|`` over revolute joints, ``|d|``
    offsets of prismatic joints, and the length of the tool's translation: a
    proxy of the arm's mass and cost. The base placement is not a link.
    """
    total = 0.0
    for link in robot.links:
        constant_d = link.d if link.type == "R" else link.offset
        total += abs(link.a) + abs(constant_d)
    return total + float(np.linalg.norm(robot.tool[:3, 3]))


@dataclass(frozen=True)
class TaskMeasures:
    """A robot on a task, target by target (NaN where a target is not reached).

    Attributes:
        reached: ``(N,)`` True where IK found a solution within the joint limits.
        manipulability: ``(N,)`` best manipulability over the target's solutions.
        condition: ``(N,)`` best (smallest) condition number; None if not asked.
        clearance: ``(N,)`` best (largest) smallest singular value; None if not asked.
        gap: ``(N,)`` distance (m) outside the reach of an unreachable target
            when the solver knows it, else 0.
        rank: The generic rank ``r`` used.
    """

    reached: NDArray[np.bool_]
    manipulability: FloatArray
    condition: FloatArray | None
    clearance: FloatArray | None
    gap: FloatArray
    rank: int

    @property
    def violation(self) -> float:
        """The share of targets not reached, plus their mean gap (m): 0 when feasible."""
        return float(np.mean(~self.reached) + np.mean(self.gap))

    def summary(self) -> dict[str, float]:
        """The task-level values (over the reached targets; NaN if none).

        Returns:
            ``min_manipulability``, ``mean_manipulability``, ``worst_condition``
            and ``singularity_clearance`` (the last two only if measured), and
            ``reached`` (share of targets).
        """
        ok = self.reached
        if not ok.any():
            out = dict.fromkeys(TASK_MEASURES, math.nan)
            out["reached"] = 0.0
        else:
            out = {
                "min_manipulability": float(np.min(self.manipulability[ok])),
                "mean_manipulability": float(np.mean(self.manipulability[ok])),
                "worst_condition": math.nan
                if self.condition is None
                else float(np.max(self.condition[ok])),
                "singularity_clearance": math.nan
                if self.clearance is None
                else float(np.min(self.clearance[ok])),
                "reached": float(np.mean(ok)),
            }
        if self.condition is None:
            del out["worst_condition"]
        if self.clearance is None:
            del out["singularity_clearance"]
        return out


def measure_task(
    robot: Robot, task: Task, needs: Collection[str] | None = None, threads: int | None = None
) -> TaskMeasures:
    """Solve IK for every target of ``task`` and measure each reached one.

    Args:
        robot: The robot.
        task: Positions or poses in the robot's base frame.
        needs: The measures asked (names of :data:`TASK_MEASURES`; others are
            ignored); None: all. The manipulability is always measured; the
            condition number and the clearance only when asked.
        threads: Core threads of the batches (None: the library default; 1 on
            a Dask worker, which has one core).

    Returns:
        The per-target measures (see the module docs).
    """
    rows: Rows = task.kind
    n_targets = len(task)
    # positions as (N, 1, 3): three of them as (3, 3) would read as a rotation
    targets = task.targets[:, None, :] if rows == "position" else task.targets
    result = robot.ik(targets, seed=IK_SEED, workers=threads)
    assert isinstance(result, IKBatchResult)
    solutions = result.solutions.reshape(n_targets, -1, robot.dof)  # (N, k, n), NaN-padded
    k_max = solutions.shape[1]
    rank = generic_rank(robot, rows)
    reached = result.count.reshape(n_targets) > 0
    shape = (n_targets,)
    singular = needs is None or bool(_SINGULAR.intersection(needs))
    manip = np.full(shape, np.nan)
    cond = np.full(shape, np.nan) if singular else None
    clear = np.full(shape, np.nan) if singular else None
    if reached.any() and k_max > 0:
        # one core call over the padded (N·k, n) array, a target's solutions a group (a
        # wrist flip's values are copied); NaN rows (no solution) stay NaN below, and the
        # reductions over a target's solutions (fmax, fmin) skip them
        group = k_max if k_max <= MAX_GROUP else 1
        q = solutions.reshape(-1, robot.dof)
        idx = _ROW_INDICES[rows]
        full_rank = rank == min(len(idx), robot.dof)
        s = None
        if singular or not full_rank:
            s = robot.chain.singular_values(q, idx, threads, group).reshape(n_targets, k_max, -1)
        if full_rank:  # no twins looked for: comparing two Jacobians costs about an LU
            w = robot.chain.volumes(q, idx, threads).reshape(n_targets, k_max)
        else:
            assert s is not None
            w = np.prod(s[..., :rank], axis=-1)
            if rank == 0:  # no motion the task sees: every measure 0 (NaN rows kept NaN)
                w = np.where(np.isnan(s[..., 0]), np.nan, 0.0)
        manip = np.fmax.reduce(w, axis=1)
        manip[~reached] = np.nan
        if s is not None and cond is not None and clear is not None:
            # no motion the task sees (rank 0): every measure 0 (NaN rows kept NaN)
            smallest = s[..., rank - 1] if rank > 0 else np.where(np.isnan(s[..., 0]), np.nan, 0.0)
            with np.errstate(divide="ignore", invalid="ignore"):
                kappa = s[..., 0] / smallest
            kappa[smallest == 0.0] = np.inf
            cond[:] = np.fmin.reduce(kappa, axis=1)
            clear[:] = np.fmax.reduce(smallest, axis=1)
            cond[~reached] = np.nan
            clear[~reached] = np.nan
    raw_gap = result.gap.reshape(n_targets)
    gap = np.where(reached | ~np.isfinite(raw_gap), 0.0, raw_gap)
    return TaskMeasures(reached, manip, cond, clear, np.maximum(gap, 0.0), rank)
