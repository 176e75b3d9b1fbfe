"""The solver list's families: the joint types each takes, and the modules imported.

:data:`kinematica.ik.analytic.FAMILIES` says which joint types (``"RRRRRR"``, ...)
each family's specs may handle, so that :func:`solvers_for` imports only the
modules an arm can need. These tests hold that statement to the specs'
predicates, on every family's sample arms (generic and degenerate) and the
built-in robots: no spec handles an arm whose joint types its family does not
take, each family takes exactly the joint types its specs handle there, and
:func:`solvers_for` gives :data:`SOLVERS`' own specs in their order, so that the
first spec handling an arm is the same through either.
"""

from __future__ import annotations

import importlib

import numpy as np
import pytest

import kinematica as km
from kinematica.ik.analytic import FAMILIES, PARAMETERS, SOLVERS, solvers_at, solvers_for
from kinematica.ik.registry import SolverSpec
from kinematica.ik.structure import Features, features

#: Sample arms per spec and kind (generic, degenerate): every predicate tests the
#: joint types first, and a family's sample arms cover each joint types it handles.
ARMS = 3


def _own(module: str) -> tuple[SolverSpec, ...]:
    """The specs a family's module declares."""
    found = importlib.import_module(f"kinematica.ik.analytic.{module}")
    return getattr(found, "SPECS", None) or (found.SPEC,)


def _takes(spec: SolverSpec) -> bool:
    return next(takes for module, takes in FAMILIES if spec in _own(module))


@pytest.fixture(scope="module")
def arms() -> list[Features]:
    """Features of every spec's sample arms and of every built-in robot."""
    out = []
    for k, spec in enumerate(SOLVERS):
        for degenerate in (False, True):
            rng = np.random.default_rng([k, degenerate])
            for _ in range(ARMS):
                arm = spec.sample_arm(rng, degenerate)
                robot = km.Robot.from_dh(
                    arm.links, convention=arm.convention, base=arm.base, tool=arm.tool
                )
                out.append(features(robot.chain))
    return out + [features(km.load(name).chain) for name in km.builtin_names()]


def test_solvers_is_every_family_in_order() -> None:
    assert tuple(s for module, _ in FAMILIES for s in _own(module)) == SOLVERS
    assert len({module for module, _ in FAMILIES}) == len(FAMILIES)


def test_each_family_takes_exactly_the_joint_types_its_specs_handle(
    arms: list[Features],
) -> None:
    seen = {f.joint_types for f in arms}
    for module, takes in FAMILIES:
        handled = {f.joint_types for f in arms for s in _own(module) if s.handles(f)}
        assert handled, module  # its samples are its own arms
        assert handled == {t for t in seen if takes(t)}, module


def test_solvers_for_gives_the_specs_of_the_families_taking_the_arm(
    arms: list[Features],
) -> None:
    for types in sorted({f.joint_types for f in arms}):
        assert list(solvers_for(types)) == [s for s in SOLVERS if _takes(s)(types)]
    for f in arms:
        first = next((s for s in SOLVERS if s.handles(f)), None)
        assert next((s for s in solvers_for(f.joint_types) if s.handles(f)), None) is first


def test_each_family_solves_at_the_parameter_it_is_listed_with() -> None:
    for module, _ in FAMILIES:
        assert {s.parameter for s in _own(module)} == {PARAMETERS.get(module)}, module
    assert set(PARAMETERS) <= {module for module, _ in FAMILIES}
    for types in ("RRRRRR", "RRRRRRR", "RRR"):
        for parameter in (None, "arm_angle"):
            specs = [s for s in solvers_for(types) if s.parameter == parameter]
            assert list(solvers_at(types, parameter)) == specs
