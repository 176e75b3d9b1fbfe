"""Inverse kinematics over a compiled chain: closed forms by structure, or numeric."""

from kinematica.ik.options import IKOptions, Method
from kinematica.ik.registry import ClosedForm, SolverSpec
from kinematica.ik.result import IKBatchResult, IKResult
from kinematica.ik.solve import closed_form, solve_ik, structure_of
from kinematica.ik.status import IKStatus
from kinematica.ik.structure import Features, features
from kinematica.ik.targets import POSITION_TOL, PROJECTION_TOL, ROTATION_TOL, Tolerance

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
