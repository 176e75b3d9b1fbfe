"""Velocity and force ellipsoids of the tool, from the SVD of the Jacobian's rows.

With ``Jt = U Σ Vᵀ`` the selected rows of the geometric Jacobian (base frame):

- the **velocity ellipsoid** ``{Jt q̇ : |q̇| <= 1}`` has principal directions
  the columns of ``U`` and radii the singular values ``σ_k``;
- the **force ellipsoid** ``{F : |Jtᵀ F| <= 1}`` (tool wrenches a unit joint
  effort can balance) has the same directions and radii ``1/σ_k``.

Where the rows outnumber the joints, or the arm is singular, ``σ_k = 0``:
the velocity ellipsoid is flat along that direction and the force
ellipsoid infinite.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.errors import KinematicaError
from kinematica.robot.velocity import Axes, selected_rows

if TYPE_CHECKING:
    from kinematica.robot.kinematics import RobotKinematics

__all__ = ["Ellipsoid", "EllipsoidKind", "ellipsoid"]

FloatArray = NDArray[np.float64]

#: ``"velocity"`` (radii ``σ``) or ``"force"`` (radii ``1/σ``).
EllipsoidKind = Literal["velocity", "force"]


@dataclass(frozen=True)
class Ellipsoid:
    """Manipulability ellipsoids of a batch of configurations.

    Attributes:
        kind: ``"velocity"`` or ``"force"``.
        rows: The Jacobian rows it lives in (``(0, 1, 2)``: tool-origin velocity
            in m/s, or force in N; ``(3, 4, 5)``: angular velocity or moment).
        center: ``(..., 3)`` tool origin (m, base frame), where to draw it.
        directions: ``(..., m, m)`` unit principal directions as columns, in
            the base axes of those rows (the left singular vectors ``U``).
        radii: ``(..., m)`` semi-axis lengths along ``directions``: the singular
            values, descending, for velocity (per unit joint rate, 0 where the
            rows lose rank); their inverses, ascending, for force (``inf`` there).
    """

    kind: EllipsoidKind
    rows: tuple[int, ...]
    center: FloatArray
    directions: FloatArray
    radii: FloatArray

    def surface(self, resolution: int = 24) -> FloatArray:
        """Points on a 3-D ellipsoid for drawing, around :attr:`center`.

        Args:
            resolution: Points along each of the two angles (>= 3).

        Returns:
            ``(..., resolution, resolution, 3)`` (m, base frame, with the radii
            in the rows' own units added to the centre).

        Raises:
            KinematicaError: The ellipsoid is not 3-D, or an infinite radius.
        """
        if len(self.rows) != 3:
            raise KinematicaError(
                f"only a 3-D ellipsoid has a surface to draw; this one has {len(self.rows)} rows"
            )
        if resolution < 3:
            raise KinematicaError(f"resolution must be at least 3, got {resolution}")
        if not np.all(np.isfinite(self.radii)):
            raise KinematicaError("the ellipsoid has an infinite radius (a singular direction)")
        u = np.linspace(0.0, 2.0 * np.pi, resolution)
        v = np.linspace(0.0, np.pi, resolution)
        sphere = np.stack(
            [
                np.outer(np.cos(u), np.sin(v)),
                np.outer(np.sin(u), np.sin(v)),
                np.outer(np.ones_like(u), np.cos(v)),
            ],
            axis=-1,
        )
        scaled = self.directions * self.radii[..., None, :]  # columns U_k · r_k
        pts = np.einsum("...ij,uvj->...uvi", scaled, sphere)
        out: FloatArray = pts + self.center[..., None, None, :]
        return out


def ellipsoid(
    robot: RobotKinematics, q: ArrayLike, kind: EllipsoidKind = "velocity", axes: Axes = "trans"
) -> Ellipsoid:
    """The velocity or force ellipsoid of the tool at ``q``.

    Args:
        robot: The robot.
        q: ``(..., n)`` joint values (rad, m).
        kind: ``"velocity"`` (default) or ``"force"``.
        axes: Jacobian rows: ``"trans"`` (default, tool-origin velocity/force),
            ``"rot"``, ``"all"``, ``"task"`` or row indices.

    Returns:
        The :class:`Ellipsoid`.
    """
    if kind not in ("velocity", "force"):
        raise KinematicaError(f"kind must be 'velocity' or 'force', got {kind!r}", arg="kind")
    rows = selected_rows(robot, axes)
    J = robot.jacobian(q)[..., rows, :]
    m = len(rows)
    U, s, _ = np.linalg.svd(J, full_matrices=True)
    sigma = np.zeros((*s.shape[:-1], m))
    sigma[..., : s.shape[-1]] = s  # fewer joints than rows: the missing σ are 0
    if kind == "force":
        with np.errstate(divide="ignore"):
            radii = np.where(sigma > 0.0, 1.0 / np.where(sigma > 0.0, sigma, 1.0), np.inf)
    else:
        radii = sigma
    return Ellipsoid(
        kind=kind,
        rows=rows,
        center=robot.fk(q)[..., :3, 3],
        directions=U,
        radii=radii,
    )
