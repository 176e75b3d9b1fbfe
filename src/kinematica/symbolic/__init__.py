"""Symbolic derivations for teaching: DH products in sympy, short notation, reports.

Needs sympy (``pip install 'kinematica[symbolic]'``); ``import kinematica`` does
not import it. Every function takes a :class:`~kinematica.Robot` (numbers stay
numbers), a built-in name or a robot-file path (named parameters stay symbols)::

    from kinematica import symbolic

    symbolic.link_matrices("arm6-dh")       # [0A1, 1A2, ...] in q1 ... q6, l1 ... l4
    symbolic.short(symbolic.position("anthropomorphic-3r"))   # c1*(L2*c2 + L3*c23), ...
    symbolic.jacobian("anthropomorphic-3r")                    # (6, 3) geometric Jacobian
    print(symbolic.report("arm6-dh", format="markdown", lang="es"))
"""

from __future__ import annotations

try:
    import sympy as _sympy  # noqa: F401
except ImportError as exc:  # pragma: no cover - depends on the installation
    raise ImportError(
        "kinematica.symbolic needs sympy: pip install 'kinematica[symbolic]'"
    ) from exc

from kinematica.symbolic.jacobian import jacobian
from kinematica.symbolic.kinematics import (
    Factor,
    factors,
    fk,
    frames,
    lambdify,
    link_factors,
    link_matrices,
    orientation,
    position,
)
from kinematica.symbolic.model import (
    ANGLE_SNAP_TOL,
    SymbolicError,
    SymbolicRobot,
    SymbolicRow,
    symbolic_robot,
)
from kinematica.symbolic.notation import short, tidy
from kinematica.symbolic.report import report

__all__ = [
    "ANGLE_SNAP_TOL",
    "Factor",
    "SymbolicError",
    "SymbolicRobot",
    "SymbolicRow",
    "factors",
    "fk",
    "frames",
    "jacobian",
    "lambdify",
    "link_factors",
    "link_matrices",
    "orientation",
    "position",
    "report",
    "short",
    "symbolic_robot",
    "tidy",
]
