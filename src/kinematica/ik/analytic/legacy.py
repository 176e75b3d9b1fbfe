"""TRANSITIONAL: the batched numpy solvers of the first release behind the new registry.

Each is being ported to a kernel (one source for single and batch); until
then this adapter runs it on a standard-DH robot equivalent to the chain
(the regrouped product of :mod:`kinematica.dh.chain` is a standard table with
the chain's start as its base) and hands its candidates to the common check.
This module goes when the last solver is ported.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.typing import NDArray

from kinematica.dh import DHChain, Prismatic, Revolute
from kinematica.ik.registry import ClosedForm, SolverSpec, TargetKind
from kinematica.ik.structure import Features
from kinematica.kernels.ik_check import INFO_FREE, INFO_GAP, INFO_NEAR, INFO_SINGULAR

__all__ = ["LEGACY_SPECS"]

FloatArray = NDArray[np.float64]


def _robot(chain: DHChain) -> Any:
    from kinematica.robot import Robot  # transitional upward import

    rows: list[Revolute | Prismatic] = []
    for row in chain.links:
        kind, theta, d, a = row[0], row[1], row[2], row[3]
        alpha = math.atan2(row[5], row[4])
        if kind:  # limits are the check's business, not the solvers'
            rows.append(Prismatic(theta=theta, a=a, alpha=alpha, offset=d))
        else:
            rows.append(Revolute(d=d, a=a, alpha=alpha, offset=theta))
    return Robot.from_dh(rows, convention="standard", base=chain.ends[0], tool=chain.ends[1])


def _wrap(chain: DHChain, solver: Any) -> ClosedForm:
    n = chain.dof

    def run(poses: FloatArray) -> tuple[FloatArray, FloatArray]:
        targets = poses[:, :3, 3] if solver.position_only else poses
        cand = solver.solve(np.ascontiguousarray(targets))
        info = np.zeros((len(poses), INFO_FREE + n))
        info[:, INFO_SINGULAR] = cand.singular
        info[:, INFO_NEAR] = 0.0
        info[:, INFO_GAP] = cand.gap
        info[:, INFO_FREE:] = cand.free
        return np.ascontiguousarray(cand.q, dtype=float), info

    return ClosedForm(
        name=solver.name,
        labels=tuple(solver.labels),
        params=np.empty(0),
        solve_one=None,
        solve_batch=None,
        position_only=bool(solver.position_only),
        legacy=run,
    )


def _builder(
    factory_name: str,
) -> Callable[[DHChain, Features, TargetKind], ClosedForm | None]:
    def build(chain: DHChain, features: Features, target: TargetKind) -> ClosedForm | None:
        from kinematica.ik.analytic import arm3r, parallel, planar

        factories = {
            "planar": planar.make_planar_solver,
            "arm3r": arm3r.make_arm3r_solver,
            "parallel": parallel.make_three_parallel_solver,
        }
        solver = factories[factory_name](_robot(chain))
        if solver is None:
            return None
        if solver.position_only != (target == "position") and not (
            target == "pose" and solver.position_only and chain.dof < 6
        ):
            return None
        return _wrap(chain, solver)

    return build


def _f(types: str, test: Callable[[Features], bool]) -> Callable[[Features], bool]:
    return lambda f: f.joint_types == types and test(f)


LEGACY_SPECS: tuple[SolverSpec, ...] = (
    SolverSpec(
        "planar-2R", "2R planar", _f("RR", lambda f: f.is_parallel(0, 1)), _builder("planar")
    ),
    SolverSpec(
        "planar-PR",
        "PR planar (prismatic then revolute)",
        _f("PR", lambda f: f.is_perpendicular(0, 1)),
        _builder("planar"),
    ),
    SolverSpec(
        "planar-3R", "3R planar", _f("RRR", lambda f: f.all_parallel(range(3))), _builder("planar")
    ),
    SolverSpec(
        "planar-PRR",
        "PRR planar (prismatic then two parallel revolute)",
        _f("PRR", lambda f: f.is_parallel(1, 2) and f.is_perpendicular(0, 1)),
        _builder("planar"),
    ),
    SolverSpec(
        "anthropomorphic-3R",
        "3R anthropomorphic (shoulder axes meet)",
        _f("RRR", lambda f: f.is_parallel(1, 2) and f.is_perpendicular(0, 1) and f.meet(0, 1)),
        _builder("arm3r"),
    ),
    SolverSpec(
        "elbow-3R",
        "3R elbow arm with shoulder offset",
        _f("RRR", lambda f: f.is_parallel(1, 2) and f.is_perpendicular(0, 1) and not f.meet(0, 1)),
        _builder("arm3r"),
    ),
    SolverSpec(
        "scara",
        "SCARA (RRPR, all axes parallel)",
        _f("RRPR", lambda f: f.all_parallel(range(4))),
        _builder("planar"),
    ),
    SolverSpec(
        "three-parallel-6R",
        "6R, three parallel axes (2-3-4), UR type",
        _f("RRRRRR", lambda f: {(1, 2), (2, 3)} <= set(f.parallel)),
        _builder("parallel"),
    ),
)
