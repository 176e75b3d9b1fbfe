"""Inverse kinematics over a compiled chain: closed forms by structure, or numeric."""

# ruff: noqa: F401 (the imports are the public names; kinematica._lazy makes __all__)

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

__getattr__, __dir__, __all__ = exports(__name__)
