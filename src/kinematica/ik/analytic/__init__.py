"""Closed-form IK solvers, chosen from the geometry of the joint axes.

:data:`SOLVERS` lists every solver's :class:`~kinematica.ik.registry.SolverSpec`
in the order they are tried: the specs of each family's module (its ``SPECS``, or
its one ``SPEC``), family by family. What a spec handles (the joint types first) and
the parameter it solves at are its own properties
(:attr:`~kinematica.ik.registry.SolverSpec.handles`,
:attr:`~kinematica.ik.registry.SolverSpec.parameter`).
"""

from __future__ import annotations

import importlib
from collections.abc import Iterator

from kinematica.ik.registry import SolverSpec

__all__ = ["SOLVERS", "solvers_at"]

#: Each family's module, in the order its specs are tried. Three-parallel first: an arm
#: with axes 2-3-4 parallel and a spherical wrist (axes 4, 5, 6 meeting: d5 = a5 = 0) is
#: a UR-type arm, whose solver handles it whole; an arm with a spherical wrist and a
#: spherical shoulder is the wrist's; the general 6R after every special family, which
#: keep theirs; position targets of any longer arm last.
_FAMILIES = (
    "parallel",
    "planar_arms",
    "cylindrical",
    "elbow_arms",
    "spherical_wrist",
    "spherical_shoulder",
    "srs",
    "general_6r",
    "arm_position",
)


def _specs(module: str) -> tuple[SolverSpec, ...]:
    """The specs a family's module declares (``SPECS``, or its one ``SPEC``)."""
    found = importlib.import_module(f"{__name__}.{module}")
    specs: tuple[SolverSpec, ...] = getattr(found, "SPECS", None) or (found.SPEC,)
    return specs


#: Every closed-form solver's spec, in the order they are tried.
SOLVERS: tuple[SolverSpec, ...] = tuple(spec for module in _FAMILIES for spec in _specs(module))


def solvers_at(parameter: str | None) -> Iterator[SolverSpec]:
    """The specs of :data:`SOLVERS` that solve at ``parameter`` (None: at none), in order."""
    return (spec for spec in SOLVERS if spec.parameter == parameter)
