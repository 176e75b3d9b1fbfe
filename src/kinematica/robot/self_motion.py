"""Self-motion: a redundant arm's solution families, swept over its parameter.

A 7-joint arm holding a pose moves along one-parameter families of
configurations. :func:`self_motion` holds the parameter (a joint, by default) at
``samples`` values across its span, solves the arm there (every solution the
registry's closed form gives, limits ignored), and links the solutions of
adjacent samples into families: a family keeps one branch label, and ends where
its next solution is farther than ``max_jump`` (:data:`MAX_JUMP`) away in joint
space, or where its branch has no solution. Each family says where along the
parameter it lies within every joint's limits.

A locked arm with no closed form is searched numerically, one configuration a
call: each configuration found at a sample seeds the search at its neighbours,
so a family found anywhere is followed as far as the search can carry it.

Branch labels are the locked arm's closed form's: at a value where the locked arm
has another structure (axes that become parallel or meet there), another closed
form names the same configurations differently, and the families change there.
A joint that sets the reach (an elbow) holds a pose at isolated values only: a
sweep over it finds nothing at almost every sample.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.arguments import check_count, check_size
from kinematica.errors import KinematicaError
from kinematica.ik import IKBatchResult, IKOptions, structure_of
from kinematica.ik.arm_angle import ARM_ANGLE_NAMES, arm_angle_parameter
from kinematica.ik.fixed import joint_parameter
from kinematica.ik.parameter import Parameter
from kinematica.ik.targets import parse_targets

if TYPE_CHECKING:
    from kinematica.core import Chain
    from kinematica.robot.kinematics import RobotKinematics

__all__ = [
    "MAX_JUMP",
    "MAX_SAMPLES",
    "Family",
    "SelfMotion",
    "families",
    "joint_jump",
    "self_motion",
]

FloatArray = NDArray[np.float64]
BoolArray = NDArray[np.bool_]

#: The largest change of any joint (rad, or m for a slide) between adjacent samples
#: along one family; a larger one ends the family and starts another. 73 samples
#: over a full turn are 0.087 rad apart: a family moving its joints by up to about
#: 6 times the parameter's step stays whole; one passing close to a singular set,
#: where joints turn fast, is split there.
MAX_JUMP = 0.5
#: Most parameter values a sweep takes (``samples`` or ``values``): each holds an IK
#: answer of up to a few hundred bytes and every family an ``(N, n)`` array, so a
#: million is a few hundred MB at most (``resolved_rate`` takes as many steps).
MAX_SAMPLES = 1_000_000
#: Two configurations of the search closer than this in every joint (rad, m) are one.
SAME_TOL = 1e-6


@dataclass(frozen=True, eq=False)
class Family:
    """One branch-continuous curve of solutions along the parameter.

    Attributes:
        branch: Its branch label (the same at every sample).
        q: ``(N, n)`` its configuration at each sample (rad, m); NaN rows where
            it has none.
        within: ``(N,)`` True where it has a configuration within every joint's
            own limits.
        feasible: The intervals ``(start, end)`` of parameter values (samples)
            over which it stays within the limits; ends are samples, so the
            true interval may reach up to one step beyond each.
    """

    branch: str
    q: FloatArray
    within: BoolArray
    feasible: tuple[tuple[float, float], ...]

    @property
    def present(self) -> BoolArray:
        """``(N,)`` True at the samples where the family has a configuration."""
        return np.asarray(np.isfinite(self.q).all(axis=1), dtype=bool)


@dataclass(frozen=True, eq=False)
class SelfMotion:
    """The solution families of a redundant arm at one pose, over its parameter.

    Attributes:
        parameter: The parameter's name (``"q7"``, a joint's name).
        unit: Its unit (``"rad"`` or ``"m"``).
        values: ``(N,)`` the parameter's values, in order.
        families: Every family, in order of first appearance.
        method: How each sample was solved (e.g. ``"analytic:spherical-wrist"``).
        max_jump: The largest joint change between adjacent samples of a family.
        qlim: ``(n, 2)`` each joint's own limits (±inf where none).
        joint_names: The joints' names.
    """

    parameter: str
    unit: str
    values: FloatArray
    families: tuple[Family, ...]
    method: str
    max_jump: float
    qlim: FloatArray
    joint_names: tuple[str, ...]

    def __len__(self) -> int:
        return len(self.families)

    def _repr_html_(self) -> str:
        """The families as an HTML table: branch, samples, feasible intervals (Jupyter)."""
        from kinematica.io.html_table import html_table, number

        rows = []
        for i, fam in enumerate(self.families, start=1):
            spans = ", ".join(f"[{number(a)}, {number(b)}]" for a, b in fam.feasible) or "none"
            rows.append([str(i), fam.branch, str(int(fam.present.sum())), spans])
        caption = (
            f"self-motion over {self.parameter} ({self.unit}): {len(self.families)} families, "
            f"{self.values.size} samples ({self.method})"
        )
        header = ["#", "branch", "samples", f"within limits ({self.parameter}, {self.unit})"]
        return html_table(header, rows, caption=caption)


def joint_jump(a: FloatArray, b: FloatArray, prismatic: BoolArray) -> FloatArray:
    """The largest change of any joint from ``a`` to ``b`` (``(..., n)``): turns wrapped.

    A revolute joint's change is taken modulo 2π into [0, π] (its angles are
    wrapped), a prismatic joint's as it is.
    """
    d = np.abs(np.asarray(b, dtype=float) - np.asarray(a, dtype=float))
    d = np.where(prismatic, d, np.abs(np.remainder(d + math.pi, 2.0 * math.pi) - math.pi))
    return np.asarray(d.max(axis=-1), dtype=float)


def families(
    values: FloatArray,
    solutions: FloatArray,
    branches: NDArray[np.str_],
    prismatic: BoolArray,
    limits: FloatArray,
    max_jump: float = MAX_JUMP,
) -> tuple[Family, ...]:
    """Link each sample's solutions into branch-continuous families.

    At each sample, a family of the previous one takes the nearest unclaimed
    solution of its branch (the pairs nearest first), if it lies within
    ``max_jump`` (:func:`joint_jump`); a family that takes none ends, a
    solution no family takes starts one.

    Args:
        values: ``(N,)`` the parameter's values.
        solutions: ``(N, k, n)`` the solutions at each sample, NaN-padded.
        branches: ``(N, k)`` their branch labels.
        prismatic: ``(n,)`` True for prismatic joints.
        limits: ``(n, 2)`` each joint's own limits (±inf where none).
        max_jump: See :data:`MAX_JUMP`.
    """
    N, _, n = solutions.shape
    done: list[tuple[str, dict[int, FloatArray]]] = []
    active: list[tuple[str, dict[int, FloatArray]]] = []
    for i in range(N):
        found = [
            (str(b), q)
            for q, b in zip(solutions[i], branches[i], strict=True)
            if np.isfinite(q).all()
        ]
        pairs = sorted(
            (float(joint_jump(fam[1][i - 1], q, prismatic)), f, s)
            for f, fam in enumerate(active)
            for s, (b, q) in enumerate(found)
            if b == fam[0]
        )
        taken_f: set[int] = set()
        taken_s: set[int] = set()
        for jump, f, s in pairs:
            if jump <= max_jump and f not in taken_f and s not in taken_s:
                taken_f.add(f)
                taken_s.add(s)
                active[f][1][i] = found[s][1]
        done.extend(fam for f, fam in enumerate(active) if f not in taken_f)
        active = [fam for f, fam in enumerate(active) if f in taken_f]
        active.extend((b, {i: q}) for s, (b, q) in enumerate(found) if s not in taken_s)
    done.extend(active)
    done.sort(key=lambda fam: min(fam[1]))
    out = []
    lo, hi = limits[:, 0], limits[:, 1]
    for branch, rows in done:
        q = np.full((N, n), np.nan)
        for i, row in rows.items():
            q[i] = row
        with np.errstate(invalid="ignore"):
            within = np.asarray(((q >= lo) & (q <= hi)).all(axis=1), dtype=bool)
        out.append(Family(branch, q, within, _intervals(values, within)))
    return tuple(out)


def _intervals(values: FloatArray, inside: BoolArray) -> tuple[tuple[float, float], ...]:
    """The runs of consecutive True samples, as ``(first value, last value)``."""
    edges = np.diff(np.concatenate([[0], inside.astype(np.int8), [0]]))
    starts, ends = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1) - 1
    return tuple((float(values[a]), float(values[b])) for a, b in zip(starts, ends, strict=True))


def self_motion(
    robot: RobotKinematics,
    target: ArrayLike,
    parameter: int | str | Parameter,
    *,
    samples: int = 73,
    values: ArrayLike | None = None,
    max_jump: float = MAX_JUMP,
    method: str = "auto",
) -> SelfMotion:
    """The solution families of ``robot`` at the pose ``target``, over ``parameter``.

    Args:
        robot: The arm (a redundant one: 7 joints for a pose).
        target: ``(4, 4)`` the tool pose in the base frame.
        parameter: A joint (0-based index, its name, or ``"qN"``), ``"arm_angle"``
            (an SRS arm's arm angle, swept over (-π, π]: :mod:`kinematica.ik.arm_angle`),
            or a :class:`~kinematica.ik.parameter.Parameter` object.
        samples: The number of values across the parameter's span (its limits),
            from 2 to :data:`MAX_SAMPLES`.
        values: ``(N,)`` the values to use instead (rad or m), in order; at most
            :data:`MAX_SAMPLES`.
        max_jump: See :data:`MAX_JUMP`.
        method: How each sample is solved: ``"auto"`` (the locked arm's closed
            form when the registry has one), ``"analytic"`` or ``"numeric"``.

    Returns:
        A :class:`SelfMotion`.

    Raises:
        KinematicaError: A bad parameter (``arg="parameter"``), samples, values,
            max_jump or target.
    """
    chain = robot.chain
    param: Parameter
    if isinstance(parameter, str) and parameter.strip().lower() in ARM_ANGLE_NAMES:
        found = arm_angle_parameter(chain)
        if found is None:
            raise KinematicaError(
                f"parameter: the arm angle is a parameter of SRS 7R arms (axes 1-3 and 5-7 "
                f"meeting) only; {robot.name}: {structure_of(chain)[1]}; sweep a joint instead",
                arg="parameter",
            )
        param = found
    elif isinstance(parameter, int | str | np.integer):
        param = joint_parameter(chain, parameter, robot.joint_names, arg="parameter")
    else:
        param = parameter
    targets = parse_targets(target)
    if not targets.single or targets.position:
        raise KinematicaError(
            "target: self-motion takes one pose (4, 4); a position leaves more than one "
            "parameter free",
            arg="target",
        )
    if not isinstance(max_jump, int | float) or not 0.0 < max_jump < math.inf:
        raise KinematicaError(
            f"max_jump must be a positive number (rad, m), got {max_jump!r}", arg="max_jump"
        )
    grid = _values(param.span(chain), samples, values)
    poses = np.broadcast_to(targets.poses[0], (grid.size, 4, 4))
    options = IKOptions(method=method, respect_limits=False)  # type: ignore[arg-type]
    res = param.solve(chain, poses, grid, options)
    assert isinstance(res, IKBatchResult)
    solutions, branches = res.solutions, res.branches
    if not res.complete:  # a search: one answer a call, carried from sample to sample
        solutions, branches = _continued(param, chain, targets.poses[0], grid, options, res)
    fams = families(grid, solutions, branches, chain.prismatic, chain.own_limits, float(max_jump))
    return SelfMotion(
        param.name, param.unit, grid, fams, res.method, float(max_jump),
        chain.own_limits.copy(), robot.joint_names,
    )  # fmt: skip


def _continued(
    param: Parameter,
    chain: Chain,
    target: FloatArray,
    grid: FloatArray,
    options: IKOptions,
    first: IKBatchResult,
) -> tuple[FloatArray, NDArray[np.str_]]:
    """Every configuration the search finds at each sample, seeded from the neighbours.

    The numeric search gives one configuration a call, from its first guess: each
    configuration found at a sample seeds the search at the next one (a sweep up
    the samples, then one down), so a family it found anywhere is followed as far
    as it goes. Two configurations within :data:`SAME_TOL` (every joint) are one.

    Returns:
        ``(N, k, n)`` solutions NaN-padded, and ``(N, k)`` their branch labels.
    """
    N = grid.size
    count = first.count.reshape(-1)
    found = [list(first.solutions.reshape(N, -1, chain.dof)[i, : count[i]]) for i in range(N)]
    label = str(first.labels[0]) if first.labels else ""
    for order in (range(1, N), range(N - 2, -1, -1)):
        for i in order:
            for seed in found[i - order.step]:
                res = param.solve(chain, target, float(grid[i]), replace(options, q0=seed))
                for q in res.solutions:
                    if all(joint_jump(q, other, chain.prismatic) > SAME_TOL for other in found[i]):
                        found[i].append(q)
    k = max(1, *(len(f) for f in found))
    solutions = np.full((N, k, chain.dof), np.nan)
    branches = np.full((N, k), "", dtype=f"<U{max(1, len(label))}")
    for i, rows in enumerate(found):
        if rows:
            solutions[i, : len(rows)] = rows
            branches[i, : len(rows)] = label
    return solutions, branches


def _values(span: tuple[float, float], samples: object, values: ArrayLike | None) -> FloatArray:
    """The parameter's values: ``values`` checked, else ``samples`` across ``span``."""
    if values is not None:
        try:
            v = np.asarray(values, dtype=float).reshape(-1)
        except (TypeError, ValueError):
            raise KinematicaError(f"values must be numbers, got {values!r}", arg="values") from None
        check_size(v.size, MAX_SAMPLES, "values", "parameter values")
        if v.size < 2 or not np.isfinite(v).all() or np.any(np.diff(v) <= 0):
            raise KinematicaError(
                "values must hold at least 2 finite numbers in increasing order", arg="values"
            )
        return v
    n = check_count(samples, "samples", lo=2, hi=MAX_SAMPLES)
    lo, hi = span
    if not (math.isfinite(lo) and math.isfinite(hi)):
        raise KinematicaError(
            "values: the parameter has no limits to sweep (a free slide); give values=",
            arg="values",
        )
    return np.linspace(lo, hi, n)
