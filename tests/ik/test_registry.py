"""Every closed-form solver, held to the same contract through its ``sample_arm``.

Parametrised over :data:`kinematica.ik.analytic.SOLVERS`: a new solver is tested
by adding it there. On generic and degenerate arms of each family: the solver
takes the arm; every solution reaches the target by forward kinematics; the
configuration that made a pose is among the solutions where the answer is a
finite set; a batch gives what single calls give (solutions, statuses,
messages); a malformed row is reported and leaves the others as they were; a
target far outside the reach is unreachable with a proven gap. A family that
solves at a parameter (``spec.parameter``, e.g. the arm angle of SRS 7R arms) is
given each generating configuration's own value (``spec.parameter_of``).
"""

from __future__ import annotations

import dataclasses
import math
import zlib

import numpy as np
import pytest

import kinematica as km
from kinematica.ik.analytic import SOLVERS
from kinematica.ik.registry import SolverSpec
from kinematica.ik.structure import features

#: Arms per family and kind of geometry, targets per arm.
ARMS, TARGETS = 4, 12
#: Solutions reach their target to the default tolerances (m, rad).
TOL = 1e-10
#: The configuration that made a pose is found to this (rad or m, modulo 2π).
FOUND_TOL = 1e-7

pytestmark = pytest.mark.filterwarnings("ignore::kinematica.KinematicaWarning")


def _robot(spec: SolverSpec, rng: np.random.Generator, degenerate: bool) -> km.Robot:
    arm = spec.sample_arm(rng, degenerate)
    return km.Robot.from_dh(
        arm.links, convention=arm.convention, base=arm.base, tool=arm.tool, name=spec.kind
    )


def _targets(robot: km.Robot, kind: str, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    # within the limits; a slide without limits within a metre
    lo, hi = robot.qlim[:, 0], robot.qlim[:, 1]
    lo, hi = np.where(np.isfinite(lo), lo, -1.0), np.where(np.isfinite(hi), hi, 1.0)
    q = rng.uniform(lo, hi, (TARGETS, robot.dof))
    T = robot.fk(q)
    return q, (T if kind == "pose" else np.ascontiguousarray(T[:, :3, 3]))


def _found(q: np.ndarray, rows: np.ndarray, prismatic: np.ndarray) -> bool:
    d = rows - q
    d = np.where(prismatic, d, np.abs(np.remainder(d + math.pi, 2 * math.pi) - math.pi))
    return bool(rows.size) and float(np.min(np.max(np.abs(d), axis=-1))) <= FOUND_TOL


def _same(a: km.ik.IKResult, b: km.ik.IKResult) -> None:
    assert a.status == b.status and a.message == b.message
    assert a.branches == b.branches and a.free_joints == b.free_joints
    np.testing.assert_array_equal(a.solutions, b.solutions)
    np.testing.assert_array_equal(a.out_of_limits, b.out_of_limits)


def _parameter(spec: SolverSpec, robot: km.Robot, q: np.ndarray) -> dict[str, np.ndarray]:
    """The keyword a parametrised family needs: the configurations' own values."""
    if spec.parameter is None:
        return {}
    assert spec.parameter_of is not None
    return {spec.parameter: spec.parameter_of(robot.chain, q)}


def _cases() -> list[tuple[SolverSpec, str, bool]]:
    return [(s, kind, deg) for s in SOLVERS for kind in s.targets for deg in (False, True)]


@pytest.mark.parametrize(
    ("spec", "kind", "degenerate"),
    _cases(),
    ids=[f"{s.kind}-{k}-{'degenerate' if d else 'generic'}" for s, k, d in _cases()],
)
def test_solver_contract(spec: SolverSpec, kind: str, degenerate: bool) -> None:
    rng = np.random.default_rng(zlib.crc32(f"{spec.kind}/{kind}/{degenerate}".encode()))
    for _ in range(ARMS):
        robot = _robot(spec, rng, degenerate)
        assert spec.handles(features(robot.chain)), robot.dh_table()
        q, targets = _targets(robot, kind, rng)
        extra = _parameter(spec, robot, q)
        batch = robot.ik(targets, **extra)
        assert batch.method.startswith("analytic:"), batch.method
        for i in range(TARGETS):
            one = robot.ik(targets[i], **{k: v[i] for k, v in extra.items()})
            _same(batch[i], one)
            for sol in one.solutions:  # each solution reaches the target, by FK
                T = robot.fk(sol)
                if kind == "pose":
                    assert np.linalg.norm(T[:3, 3] - targets[i][:3, 3]) <= TOL
                    assert km.rotation_angle(T[:3, :3], targets[i][:3, :3]) <= TOL
                else:
                    assert np.linalg.norm(T[:3, 3] - targets[i]) <= TOL
            if one.status == "ok" and one.complete and not one.near_singular:  # q is in it
                rows = np.concatenate([one.solutions, one.out_of_limits])
                assert _found(q[i], rows, robot.is_prismatic), (q[i], one.message)
            assert one.status != "unreachable", one.message  # made by FK: reachable
        # a malformed row is reported, the others are as before
        bad = targets.copy()
        bad[1] = np.nan
        marred = robot.ik(bad, **extra)
        assert marred.status[1] == "invalid" and (1,) in marred.errors
        for i in (0, *range(2, TARGETS)):
            _same(marred[i], batch[i])


@pytest.mark.parametrize("spec", SOLVERS, ids=[s.kind for s in SOLVERS])
def test_far_targets_are_unreachable_with_a_gap(spec: SolverSpec) -> None:
    rng = np.random.default_rng(zlib.crc32(spec.kind.encode()))
    robot = _robot(spec, rng, False)
    if np.any(robot.is_prismatic & ~np.isfinite(robot.qlim).all(axis=1)):
        pytest.skip("a slide without limits reaches any distance: no gap to prove")
    kind = spec.targets[0]
    q, targets = _targets(robot, kind, rng)
    far = targets.copy()
    if kind == "pose":
        far[:, :3, 3] *= 1e3
        far[:, :3, 3] += 1e3
    else:
        far = far * 1e3 + 1e3
    res = robot.ik(far, **_parameter(spec, robot, q))
    assert np.all(res.status == "unreachable"), res.message
    assert np.all(res.gap > 1.0)


def test_arms_no_solver_describes_name_their_meeting_axes() -> None:
    # the first and last three axes meeting: the Panda (shoulder); an iiwa whose elbow
    # axis passes through the shoulder (d3 = 0: no SRS arm, the iiwa itself is one)
    assert km.classify(km.load("panda")).summary.endswith("redundant, spherical shoulder")
    assert km.classify(km.load("iiwa14")).kind == "srs-7R"
    iiwa = km.load("iiwa14")
    no_upper_arm = [
        dataclasses.replace(j, d=0.0) if i == 2 else j for i, j in enumerate(iiwa.links)
    ]
    both = km.classify(km.Robot.from_dh(no_upper_arm, convention="standard"))
    assert both.summary.endswith("redundant, spherical shoulder, spherical wrist")
    assert both.summary_es.endswith("redundante, con hombro esférico, con muñeca esférica")
    # a 5R arm whose first three axes meet (no solver of its own)
    rows = [km.Revolute(d=0.3, alpha=math.pi / 2), km.Revolute(alpha=-math.pi / 2)]
    rows += [km.Revolute(d=0.3, alpha=math.pi / 2), km.Revolute(a=0.3), km.Revolute(a=0.2)]
    five = km.classify(km.Robot.from_dh(rows, convention="standard"))
    assert five.kind == "general"
    assert five.summary == "5 joints (RRRRR), first three axes meet (shoulder)"
