"""The robot: an immutable description of a serial arm and its kinematics.

A :class:`Robot` holds a DH table (standard or modified), joint limits and the
base and tool transforms. It has no state: ``robot.fk(q)`` is a pure function
of ``q``. All batch computations take ``q`` of shape ``(..., n)``. Its parts, each
a module: the description (:mod:`kinematica.robot.description`), the forward
kinematics (:mod:`kinematica.robot.kinematics`), the IK
(:mod:`kinematica.robot.inverse`); here, the rest (the Jacobian in other frames and
coordinates, the decoupling, files, URDF and DH rules, singularities, self-motion).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.dh import Convention, Joint
from kinematica.robot.inverse import RobotIK
from kinematica.robot.save import write_robot_file
from kinematica.robot.transforms import ChainTransforms

if TYPE_CHECKING:
    import os

    from kinematica.ik.parameter import Parameter
    from kinematica.io import RobotSpec
    from kinematica.robot.decoupling import Decoupling
    from kinematica.robot.dh_rules import DHExtraction
    from kinematica.robot.self_motion import SelfMotion

__all__ = ["Robot"]

FloatArray = NDArray[np.float64]
#: The frames a Jacobian is expressed in.
_FRAMES = ("base", "tool", "spatial")


class Robot(RobotIK):
    """A serial manipulator described by its DH table.

    Build one with :meth:`from_dh` or :func:`kinematica.load`.

    Attributes:
        links: The DH rows, base to tip (:class:`Revolute` / :class:`Prismatic`).
        convention: ``"standard"`` (Paul, distal) or ``"modified"`` (Craig, proximal).
        name: A display name.
        base: ``(4, 4)`` pose of DH frame 0 in the world (base) frame.
        tool: ``(4, 4)`` pose of the tool in the last DH frame.
        description: Free text (source of the model, notes).
        chain: The table compiled for the core (derived).
        source_spec: The description the robot was read from (robot file or
            built-in model), or ``None``; :meth:`save` writes it back as it
            was written, for every part that still describes this robot.
        transforms: For a robot read from a URDF, the file's own transforms
            (:class:`~kinematica.robot.transforms.ChainTransforms`): FK, Jacobians
            and IK use them, exactly, and the DH rows describe the robot (to the
            extraction's reported accuracy). ``None`` for a DH robot.
    """

    def __reduce__(self) -> tuple[Callable[..., Robot], tuple[object, ...]]:
        """Pickle the description alone (Dask workers): the core's chain is rebuilt from it."""
        return (
            _unpickle,
            (
                self.links,
                self.convention,
                self.name,
                self.base,
                self.tool,
                self.description,
                self.source_spec,
                self.transforms,
            ),
        )

    def _analytic_jacobian(self, q: ArrayLike, euler: str) -> FloatArray:
        """The analytic Jacobian (see :func:`kinematica.robot.velocity.analytic_jacobian`)."""
        from kinematica.robot.velocity import analytic_jacobian

        return analytic_jacobian(self, q, euler)

    def _spatial_jacobian(self, q: ArrayLike, workers: int | None) -> FloatArray:
        """The spatial Jacobian (see :func:`kinematica.robot.differential.spatial_from_base`)."""
        from kinematica.robot.differential import spatial_from_base

        return spatial_from_base(self.jacobian(q, workers=workers), self.fk(q)[..., :3, 3])

    def wrist_center(self, T: ArrayLike) -> FloatArray:
        """The wrist centre p_m of tool poses (seed 002's ``p - d6·R·z``).

        Args:
            T: ``(..., 4, 4)`` tool poses in the base (world) frame.

        Returns:
            ``(..., 3)`` the point where axes 4-6 meet, world frame (m).

        Raises:
            KinematicaError: The last three axes do not meet in one point.
        """
        from kinematica.robot.decoupling import wrist_center

        return wrist_center(self, T)

    def decouple(self, T: ArrayLike) -> Decoupling:
        """Seed 002's kinematic decoupling of a pose, step by step.

        p_m, the arm solutions of joints 1-3 for it, R03 and R36 = R03ᵀ·R06 of each,
        and the wrist solutions q4-q6 of each (see :mod:`kinematica.robot.decoupling`).

        Args:
            T: ``(4, 4)`` tool pose in the base (world) frame.

        Returns:
            A :class:`~kinematica.robot.decoupling.Decoupling`.

        Raises:
            KinematicaError: Not a 6-joint DH arm with a spherical wrist.
        """
        from kinematica.robot.decoupling import decouple

        return decouple(self, T)

    def _repr_html_(self) -> str:
        """The DH table with units and limits, as HTML (Jupyter)."""
        from kinematica.robot.display import robot_html

        return robot_html(self)

    def save(self, path: str | os.PathLike[str]) -> None:
        """Write this robot as a robot file; see :func:`kinematica.write_robot_file`."""
        write_robot_file(self, path)

    def to_dh(self, convention: str = "standard") -> DHExtraction[Robot]:
        """The DH table read off this robot's joint axes by the Denavit-Hartenberg rules.

        The axes are those the robot computes with: for a robot read from a
        URDF, the file's (not its DH rows'). In the robot's own convention it
        gives back the same rows; in the other, the frames the rules place.
        See :func:`kinematica.urdf_to_dh`.

        Returns:
            A ``DHExtraction``: ``.robot`` (the table alone), ``.rules`` (which
            rule placed each frame), ``.fk_error`` (the largest entry of T by
            which the table's FK misses this robot's, over q = 0 and
            configurations within the limits).
        """
        from kinematica.robot.dh_rules import to_dh

        return to_dh(self, convention)

    def to_urdf(self, path: str | os.PathLike[str] | None = None) -> str:
        """The robot as URDF text (each link frame a DH frame), written to ``path`` if given."""
        from kinematica.robot.dh_rules import to_urdf

        return to_urdf(self, path)

    def singularities(self, q: ArrayLike, detail: bool = False) -> Any:
        """Names of the singularities at ``q`` (``[]`` when regular).

        See :func:`kinematica.robot.singularities.singularities`.
        """
        from kinematica.robot.singularities import singularities

        return singularities(self, q, detail=detail)

    def self_motion(
        self,
        target: ArrayLike,
        parameter: int | str | Parameter,
        *,
        samples: int = 73,
        values: ArrayLike | None = None,
        max_jump: float | None = None,
        method: str = "auto",
    ) -> SelfMotion:
        """The solution families at the pose ``target`` swept over ``parameter`` (a joint).

        See :func:`kinematica.robot.self_motion.self_motion` (``max_jump`` None:
        its ``MAX_JUMP``).
        """
        from kinematica.robot.self_motion import MAX_JUMP, self_motion

        if values is not None:  # degrees given for radians? (as fk warns of q)
            from kinematica.robot.given import check_joint_values

            check_joint_values(self, parameter, values, "values")
        jump = MAX_JUMP if max_jump is None else max_jump
        return self_motion(
            self, target, parameter, samples=samples, values=values, max_jump=jump, method=method
        )

    def random_q(
        self, n: int | tuple[int, ...] = 1, seed: int | np.random.Generator | None = None
    ) -> FloatArray:
        """``(n, dof)`` configurations drawn uniformly within the joint limits.

        See :func:`kinematica.robot.sampling.random_q`.
        """
        from kinematica.robot.sampling import random_q

        return random_q(self, n, seed=seed)


def _unpickle(
    links: tuple[Joint, ...],
    convention: Convention,
    name: str,
    base: FloatArray,
    tool: FloatArray,
    description: str | None,
    source_spec: RobotSpec | None,
    transforms: ChainTransforms | None,
) -> Robot:
    """A pickled :class:`Robot` built again from its description."""
    return Robot(
        links,
        convention,
        name,
        base,
        tool,
        description,
        source_spec=source_spec,
        transforms=transforms,
    )
