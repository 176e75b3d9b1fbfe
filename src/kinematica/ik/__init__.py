"""Inverse kinematics over a compiled chain: closed forms by structure, or numeric."""

from typing import TYPE_CHECKING

from kinematica._lazy import exports

if TYPE_CHECKING:  # the names below load on first use (kinematica._lazy)
    from kinematica.ik.options import IKOptions, Method
    from kinematica.ik.registry import ClosedForm, SolverSpec
    from kinematica.ik.result import IKBatchResult, IKResult
    from kinematica.ik.solve import solve_ik
    from kinematica.ik.solvers import closed_form, structure_of
    from kinematica.ik.status import IKStatus
    from kinematica.ik.structure import Features, features
    from kinematica.ik.targets import PROJECTION_TOL
    from kinematica.ik.tolerance import POSITION_TOL, ROTATION_TOL, Tolerance

__getattr__, __dir__ = exports(
    __name__,
    {
        "IKOptions": "kinematica.ik.options",
        "Method": "kinematica.ik.options",
        "ClosedForm": "kinematica.ik.registry",
        "SolverSpec": "kinematica.ik.registry",
        "IKBatchResult": "kinematica.ik.result",
        "IKResult": "kinematica.ik.result",
        "closed_form": "kinematica.ik.solvers",
        "solve_ik": "kinematica.ik.solve",
        "structure_of": "kinematica.ik.solvers",
        "IKStatus": "kinematica.ik.status",
        "Features": "kinematica.ik.structure",
        "features": "kinematica.ik.structure",
        "POSITION_TOL": "kinematica.ik.tolerance",
        "PROJECTION_TOL": "kinematica.ik.targets",
        "ROTATION_TOL": "kinematica.ik.tolerance",
        "Tolerance": "kinematica.ik.tolerance",
    },
)

__all__ = [
    "POSITION_TOL",
    "PROJECTION_TOL",
    "ROTATION_TOL",
    "ClosedForm",
    "Features",
    "IKBatchResult",
    "IKOptions",
    "IKResult",
    "IKStatus",
    "Method",
    "SolverSpec",
    "Tolerance",
    "closed_form",
    "features",
    "solve_ik",
    "structure_of",
]
