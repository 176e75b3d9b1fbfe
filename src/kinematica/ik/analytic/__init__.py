"""Closed-form IK solvers, chosen from the geometry of the joint axes.

:data:`SOLVERS` lists every solver's :class:`~kinematica.ik.registry.SolverSpec`
in the order they are tried. :func:`solvers_for` gives the same specs for one
arm's joint types, importing a family's module only when an arm of joint types
it takes first asks: the first ``robot.ik`` of a PUMA imports the spherical
wrist's module and the one tried before it, not the SRS, general 6R or planar ones.
"""

from __future__ import annotations

import importlib
import importlib.util
from collections.abc import Callable, Iterator
from typing import TYPE_CHECKING, Any

from kinematica.ik.registry import SolverSpec

if TYPE_CHECKING:
    SOLVERS: tuple[SolverSpec, ...]

__all__ = ["FAMILIES", "PARAMETERS", "SOLVERS", "solvers_at", "solvers_for"]

#: Each family's module, and the joint types (``"RRRRRR"``, ...) of every arm one of
#: its specs handles: each spec's predicate tests them before anything else
#: (tests/ik/analytic/test_init.py holds the two equal). In the order tried.
#: Three-parallel first: an arm with axes 2-3-4 parallel and a spherical wrist
#: (axes 4, 5, 6 meeting: d5 = a5 = 0) is a UR-type arm, whose solver handles it whole.
FAMILIES: tuple[tuple[str, Callable[[str], bool]], ...] = (
    ("parallel", lambda t: t == "RRRRRR"),
    ("planar_arms", lambda t: t in ("RR", "PR", "RRR", "PRR", "RRPR")),
    ("cylindrical", lambda t: t in ("RPP", "PRP", "RPPR", "PRPR")),
    ("elbow_arms", lambda t: t == "RRR"),
    ("spherical_wrist", lambda t: t in ("RRRRRR", "RRPRRR")),
    # an arm with a spherical wrist too is the wrist's
    ("spherical_shoulder", lambda t: t in ("RRRRRR", "RRRPRR")),
    # at an arm angle only (robot.ik(T, arm_angle=...))
    ("srs", lambda t: t == "RRRRRRR"),
    # any other 6R arm: after every special family, which keep theirs
    ("general_6r", lambda t: t == "RRRRRR"),
    # position targets of any longer arm: tried last
    ("arm_position", lambda t: len(t) > 3 and t[:2] == "RR"),
)
#: The parameter a family's specs solve at (:attr:`SolverSpec.parameter`), for the
#: families that have one: the search for a solver at a parameter (or without one)
#: imports no family of the other kind (tests/ik/analytic/test_init.py holds it).
PARAMETERS: dict[str, str] = {"srs": "arm_angle"}


def _specs(module: str) -> tuple[SolverSpec, ...]:
    """The specs a family's module declares (``SPECS``, or its one ``SPEC``)."""
    found = importlib.import_module(f"{__name__}.{module}")
    specs: tuple[SolverSpec, ...] = getattr(found, "SPECS", None) or (found.SPEC,)
    return specs


def solvers_for(joint_types: str) -> Iterator[SolverSpec]:
    """The specs that may handle an arm of these joint types, in the order they are tried.

    Args:
        joint_types: One letter per joint, ``"R"`` or ``"P"`` (``Features.joint_types``).

    Yields:
        The specs of the families that take such arms; a family's module is imported
        when the iteration reaches it (stop early, and the rest stay unimported).
    """
    for module, takes in FAMILIES:
        if takes(joint_types):
            yield from _specs(module)


def solvers_at(joint_types: str, parameter: str | None) -> Iterator[SolverSpec]:
    """:func:`solvers_for`'s specs that solve at ``parameter`` (None: at none).

    The families listed with another parameter in :data:`PARAMETERS` are not imported.
    """
    for module, takes in FAMILIES:
        if PARAMETERS.get(module) == parameter and takes(joint_types):
            yield from _specs(module)


def __getattr__(name: str) -> Any:
    """:data:`SOLVERS`, made (every family's module imported) when first asked for.

    A family's module by its name (``analytic.general_6r``) is imported then.
    """
    if name != "SOLVERS":
        if name.startswith("__") or importlib.util.find_spec(f"{__name__}.{name}") is None:
            raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
        return importlib.import_module(f"{__name__}.{name}")
    specs = tuple(spec for module, _ in FAMILIES for spec in _specs(module))
    globals()["SOLVERS"] = specs
    return specs
