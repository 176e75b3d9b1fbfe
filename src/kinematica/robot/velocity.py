"""Velocity kinematics: analytic Jacobian, manipulability, condition number.

All are functions of the geometric Jacobian ``J = robot.jacobian(q)``
(``(..., 6, n)``, base frame: rows ``vx, vy, vz`` of the tool origin, then
``ωx, ωy, ωz``).
"""

from __future__ import annotations

import warnings
from collections.abc import Sequence
from typing import TYPE_CHECKING, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.errors import KinematicaError, KinematicaWarning
from kinematica.spatial import euler_from_matrix, euler_rate_matrix, gimbal_locked

if TYPE_CHECKING:
    from kinematica.robot.kinematics import RobotKinematics

__all__ = [
    "Axes",
    "ManipulabilityMethod",
    "analytic_jacobian",
    "condition_number",
    "manipulability",
    "manipulability_gradient",
    "selected_rows",
    "task_rows",
]

FloatArray = NDArray[np.float64]

#: Which rows of the Jacobian a measure uses: all six, the translational
#: (``vx, vy, vz``) or the rotational (``ωx, ωy, ωz``) ones, or explicit indices.
#: ``"task"``: the rows :func:`kinematica.robot.singularities.singularities` judges (position rows
#: for arms whose whole mobility shows in the tool position, else all six).
Axes = Literal["all", "trans", "rot", "task"] | Sequence[int]

#: A manipulability measure over the singular values ``σ1 >= ... >= σr`` of the
#: selected rows: ``"yoshikawa"`` ``σ1···σr`` (the ellipsoid's volume measure),
#: ``"inverse_condition"`` ``σr/σ1`` (isotropy, 1 for a sphere, unit-free) and
#: ``"min_singular"`` ``σr`` (the slowest direction's speed per unit joint rate).
ManipulabilityMethod = Literal["yoshikawa", "inverse_condition", "min_singular"]

_METHODS = ("yoshikawa", "inverse_condition", "min_singular")

_ROWS = {"all": (0, 1, 2, 3, 4, 5), "trans": (0, 1, 2), "rot": (3, 4, 5)}


def task_rows(axes: Axes) -> tuple[int, ...]:
    """The Jacobian row indices that ``axes`` names.

    Raises:
        KinematicaError: ``axes`` is neither a name nor indices in 0..5.
    """
    if isinstance(axes, str):
        if axes not in _ROWS:
            raise KinematicaError(
                f"axes must be 'all', 'trans', 'rot', 'task' or row indices 0-5, got {axes!r}"
            )
        return _ROWS[axes]
    try:
        rows = tuple(int(r) for r in axes)
    except (TypeError, ValueError, OverflowError):  # not indices: say what is expected below
        rows = ()
    if not rows or any(r < 0 or r > 5 for r in rows) or len(set(rows)) != len(rows):
        raise KinematicaError(f"axes must be distinct Jacobian row indices 0-5, got {axes!r}")
    return rows


def selected_rows(robot: RobotKinematics, axes: Axes) -> tuple[int, ...]:
    """The Jacobian row indices ``axes`` names for ``robot`` (``"task"`` included)."""
    if isinstance(axes, str) and axes == "task":
        from kinematica.robot.singularities import task_plan_rows

        return tuple(task_plan_rows(robot))
    return task_rows(axes)


def _singular_values(robot: RobotKinematics, q: ArrayLike, axes: Axes) -> FloatArray:
    """``(..., min(m, n))`` singular values of the selected rows of ``J(q)``, descending.

    The core's (:func:`kinematica.core.singular_values`) where ``min(m, n) <= 6``, as
    every Jacobian's rows are; rows of a batch holding NaN/inf (robot.jacobian
    warned of them) come out NaN.
    """
    from kinematica.core import singular_values

    J = robot.jacobian(q)[..., selected_rows(robot, axes), :]
    return singular_values(J)


def manipulability(
    robot: RobotKinematics,
    q: ArrayLike,
    axes: Axes = "all",
    method: ManipulabilityMethod = "yoshikawa",
) -> FloatArray:
    """Manipulability: by default Yoshikawa's, the volume measure of the velocity ellipsoid.

    ``w = σ1 · σ2 · ... · σr`` over the singular values of the selected rows
    ``Jt`` of the geometric Jacobian (``r = min(m, n)`` for ``m`` rows). With
    ``m <= n`` (e.g. a 6R or 7R arm with ``axes="all"``) that is Yoshikawa's
    ``sqrt(det(Jt Jtᵀ))``, computed as ``|det Jt|`` when ``Jt`` is square (a
    6R arm's six rows: an LU factorisation rather than an SVD, ten times
    faster, as reachability maps need); with fewer joints than rows it is
    ``sqrt(det(Jtᵀ Jt))``, the volume of the ellipsoid in the motions the arm
    has. ``w = 0`` exactly where those rows lose rank.

    The classic textbook values use the rows of the arm's task: a planar 2R
    arm's ``l1·l2·|sin q2|`` and an anthropomorphic arm's
    ``l2·l3·|sin q3|·|l2 cos q2 + l3 cos(q2+q3)|`` come from ``axes="trans"``.
    With ``"all"`` on a 6R arm, rows in m/rad and rad/rad are mixed: ``w``
    then depends on the length unit (it is still zero exactly at singularities).

    ``method`` picks another measure of the same singular values ``σ1 >= ... >= σr``:
    ``"inverse_condition"`` gives ``σr/σ1`` (1 for an isotropic arm, 0 at a
    singularity, independent of the arm's size), ``"min_singular"`` gives
    ``σr``, the tool's speed along its slowest direction per unit joint rate.

    Args:
        robot: The robot.
        q: ``(..., n)`` joint values (rad, m).
        axes: ``"all"`` (default), ``"trans"``, ``"rot"``, ``"task"`` (the
            rows the singularity test judges) or row indices.
        method: ``"yoshikawa"`` (default), ``"inverse_condition"`` or ``"min_singular"``.

    Returns:
        ``(...)`` manipulability, >= 0.
    """
    if method not in _METHODS:
        raise KinematicaError(
            f"method must be 'yoshikawa', 'inverse_condition' or 'min_singular', got {method!r}",
            arg="method",
        )
    if method == "yoshikawa":
        J = robot.jacobian(q)[..., selected_rows(robot, axes), :]
        if J.shape[-2] == J.shape[-1]:
            # A square Jt: σ1···σn = |det Jt| (an LU, a tenth of an SVD's time).
            with np.errstate(invalid="ignore"):
                square: FloatArray = np.abs(np.linalg.det(J))
            return square
    s = _singular_values(robot, q, axes)
    if method == "min_singular":
        return s[..., -1].copy()
    if method == "inverse_condition":
        with np.errstate(divide="ignore", invalid="ignore"):
            inv: FloatArray = np.where(s[..., 0] > 0.0, s[..., -1] / s[..., 0], 0.0)
        return inv
    out: FloatArray = np.prod(s, axis=-1)
    return out


def manipulability_gradient(robot: RobotKinematics, q: ArrayLike, axes: Axes = "all") -> FloatArray:
    """Gradient of Yoshikawa's manipulability with respect to the joints.

    ``∂w/∂q_j = w · tr(Jt⁺ · ∂Jt/∂q_j)`` (the derivative of ``log det``; Haviland
    & Corke's eq. for the manipulability Jacobian), with ``∂Jt/∂q_j`` from the
    Hessian (:func:`kinematica.robot.differential.hessian`) and ``Jt`` the
    selected rows. It points towards larger ``w``: the null-space objective of
    :func:`kinematica.motion.resolved_rate` climbs it. Where the rows lose rank
    ``w`` has a kink (as ``|x|`` at 0) and the gradient returned is 0.

    Args:
        robot: The robot.
        q: ``(..., n)`` joint values (rad, m).
        axes: Rows, as for :func:`manipulability`.

    Returns:
        ``(..., n)``, units of ``w`` per rad (or per m).
    """
    from kinematica.robot.differential import hessian

    rows = selected_rows(robot, axes)
    Jt = robot.jacobian(q)[..., rows, :]
    H = hessian(robot, q)[..., rows, :, :]
    w = np.prod(np.linalg.svd(Jt, compute_uv=False), axis=-1)
    out: FloatArray = w[..., None] * np.einsum("...ia,...aij->...j", np.linalg.pinv(Jt), H)
    return out


def condition_number(robot: RobotKinematics, q: ArrayLike, axes: Axes = "all") -> FloatArray:
    """Condition number ``σmax / σmin`` of the selected rows of the Jacobian.

    1 for an isotropic arm, growing towards a singularity, ``inf`` at one.
    With ``axes="all"`` the rows mix m/rad and rad/rad (see
    :func:`manipulability`).

    Args:
        robot: The robot.
        q: ``(..., n)`` joint values.
        axes: ``"all"`` (default), ``"trans"``, ``"rot"`` or row indices.

    Returns:
        ``(...)`` condition numbers in ``[1, inf]``.
    """
    s = _singular_values(robot, q, axes)
    with np.errstate(divide="ignore", invalid="ignore"):
        out: FloatArray = np.where(s[..., -1] > 0.0, s[..., 0] / s[..., -1], np.inf)
    return out


def analytic_jacobian(robot: RobotKinematics, q: ArrayLike, euler: str = "ZYZ") -> FloatArray:
    """Analytic Jacobian: the rates of the pose ``(x, y, z, a, b, c)``.

    ``J_a = blockdiag(I, E⁻¹) · J``, where ``J`` is the geometric Jacobian in
    the base frame and ``E`` the Euler-rate matrix (``ω = E · (ȧ, ḃ, ċ)``,
    :func:`kinematica.spatial.euler_rate_matrix`) at the tool's Euler angles
    ``km.to_pose(robot.fk(q), euler)[..., 3:]``. So ``d pose / dt = J_a · q̇``,
    the derivative of :func:`kinematica.to_pose` along the motion.

    Representation singularity: where the tool orientation is in gimbal lock
    for ``euler`` (exactly where :func:`kinematica.gimbal_locked` is True),
    the angle rates are undefined. Those configurations get NaN in rows 3-5
    (the position rows stay valid) and a :class:`KinematicaWarning` says how
    many; ``km.gimbal_locked(robot.fk(q)[..., :3, :3], euler)`` is the mask.
    Pick another sequence to get finite rates there.

    Args:
        robot: The robot.
        q: ``(..., n)`` joint values (rad, m).
        euler: Euler sequence, scipy naming (``"ZYZ"`` intrinsic, ``"xyz"``
            extrinsic, ...), or ``"exp"`` for exponential coordinates (the
            rotation vector's rates, no representation singularity below π:
            :func:`kinematica.robot.differential.exp_jacobian`).

    Returns:
        ``(..., 6, n)``: rows 0-2 m/rad (or m/m), rows 3-5 rad/rad.
    """
    if isinstance(euler, str) and euler == "exp":
        from kinematica.robot.differential import exp_jacobian

        return exp_jacobian(robot, q)
    J = robot.jacobian(q)
    R = robot.fk(q)[..., :3, :3]
    locked = np.asarray(gimbal_locked(R, euler))
    angles = euler_from_matrix(R, euler)
    E = euler_rate_matrix(angles, euler)
    E = np.where(locked[..., None, None], np.eye(3), E)  # placeholder, replaced by NaN below
    Ja = J.copy()
    Ja[..., 3:, :] = np.linalg.solve(E, J[..., 3:, :])
    if locked.any():
        Ja[..., 3:, :] = np.where(locked[..., None, None], np.nan, Ja[..., 3:, :])
        warnings.warn(
            f"analytic Jacobian: {int(locked.sum())} configuration(s) in gimbal lock for "
            f"Euler sequence {euler!r}; their angle-rate rows are NaN "
            "(use another sequence there)",
            KinematicaWarning,
            stacklevel=3,
        )
    return Ja
