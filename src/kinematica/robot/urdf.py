"""URDF in: a Robot from any serial chain of a URDF file.

The chain's joint axes get DH frames by the rules (:mod:`kinematica.robot.dh_rules`):
that table describes the robot. Its kinematics are the file's own transforms
(:class:`~kinematica.robot.transforms.ChainTransforms`), so its FK equals the
URDF's to round-off whatever its axes (nearly parallel ones included).
"""

from __future__ import annotations

import dataclasses
import os
from collections.abc import Mapping

import numpy as np
from numpy.typing import NDArray

from kinematica.dh import check_convention
from kinematica.io import UrdfChain, UrdfModel, read_urdf
from kinematica.robot.dh_rules import DHExtraction, dh_from_chain
from kinematica.robot.robot import Robot
from kinematica.robot.transforms import ChainTransforms, align_z
from kinematica.spatial import inv_transform

__all__ = ["chain_transforms", "robot_from_urdf", "urdf_to_dh"]

FloatArray = NDArray[np.float64]


def chain_transforms(chain: UrdfChain, frames: FloatArray) -> ChainTransforms:
    """The chain's own transforms, relative to its DH frames ``frames`` (n+1, 4, 4) at q = 0.

    Between consecutive movable joints the origins (fixed joints included) are
    multiplied as the file gives them; each joint's frame is turned so that its
    axis is z (:func:`~kinematica.robot.transforms.align_z`), the turn undone in
    the next transform. Frames are in the chain's base link frame.
    """
    local = np.eye(4)  # from the frame after the last motion (or the base link) on
    rel: list[FloatArray] = []
    align: list[FloatArray] = []
    for j in chain.joints:
        local = local @ j.origin.as_matrix()
        if j.movable:
            axis = np.array(j.axis, dtype=float)
            R = np.eye(4)
            R[:3, :3] = align_z(axis / np.linalg.norm(axis))
            rel.append(local)
            align.append(R)
            local = np.eye(4)
    n = len(rel)
    first = rel[0] @ align[0]  # joint 1's frame in the base link frame
    between = np.array([align[i].T @ rel[i + 1] @ align[i + 1] for i in range(n - 1)])
    between = between.reshape(n - 1, 4, 4)
    tip_from_last = align[-1].T @ local  # the tip link from the frame after the last motion
    S0, Sn = frames[0], frames[-1]
    start = inv_transform(S0) @ first
    motion = np.empty((n, 4, 4))  # the frames joints move in at q = 0, base link frame
    motion[0] = first
    for i in range(1, n):
        motion[i] = motion[i - 1] @ between[i - 1]
    offsets = np.array([inv_transform(F) @ S for F, S in zip(motion, frames[1:], strict=True)])
    # end · tool = tip_from_last with tool = Sn⁻¹ tip: end = tip_from_last tip⁻¹ Sn
    tip = motion[-1] @ tip_from_last
    end = tip_from_last @ inv_transform(tip) @ Sn
    return ChainTransforms(start, between, end, offsets)


def urdf_to_dh(
    urdf: str | os.PathLike[str] | UrdfModel,
    *,
    base: str | None = None,
    tip: str | None = None,
    convention: str = "standard",
    xacro: bool = False,
    xacro_env: bool = False,
    trust_xacro: bool = False,
    packages: Mapping[str, str | os.PathLike[str]] | None = None,
    xacro_args: Mapping[str, str] | None = None,
) -> DHExtraction[Robot]:
    """Read a URDF and extract the DH table of its chain from ``base`` to ``tip``.

    Args:
        urdf: A ``.urdf`` file (``.xacro`` too, expanded without running its code), or
            a parsed :class:`~kinematica.io.UrdfModel`.
        base: Base link; default the root link.
        tip: Tip link; default the single leaf at the end of movable joints
            (the error lists the leaves when there are several).
        convention: ``"standard"`` or ``"modified"``.
        xacro: Expand xacro in a ``.urdf`` file too (see
            :func:`~kinematica.io.read_urdf`; ``.xacro`` files always are).
        xacro_env: Let xacro read the environment.
        trust_xacro: Expand xacro with the ``xacro`` package, which runs the
            file's code; by default kinematica's own expander, which runs none.
        packages: ROS package name -> folder, for ``$(find pkg)`` in xacro.
        xacro_args: Values of the xacro file's ``<xacro:arg>``.

    Returns:
        The :class:`DHExtraction`: ``.robot`` (its DH table the extracted one,
        its FK the URDF's own transforms, exactly), ``.rules`` (which rule
        placed each frame), ``.fk_error`` (how well the DH table alone
        reproduces the URDF's FK).

    Raises:
        RobotFileError: the file cannot be read, is hostile or malformed, or
            the chain holds a joint kinematica cannot model (the message names
            the file, the joint or link, and the problem).
    """
    check_convention(convention)
    if isinstance(urdf, UrdfModel):
        model = urdf
    else:
        model = read_urdf(
            urdf,
            xacro=xacro,
            xacro_env=xacro_env,
            trust_xacro=trust_xacro,
            packages=packages,
            xacro_args=xacro_args,
        )
    chain = model.chain(base, tip)
    source = f"URDF {chain.source}" if chain.source else "URDF"
    ext = dh_from_chain(
        chain,
        convention,
        make=Robot.from_dh,
        description=f"{source}, chain {chain.base} -> {chain.tip}",
    )
    exact = dataclasses.replace(ext.robot, transforms=chain_transforms(chain, ext.frames))
    return dataclasses.replace(ext, robot=exact)


def robot_from_urdf(
    urdf: str | os.PathLike[str] | UrdfModel,
    *,
    base: str | None = None,
    tip: str | None = None,
    convention: str = "standard",
    xacro: bool = False,
    xacro_env: bool = False,
    trust_xacro: bool = False,
    packages: Mapping[str, str | os.PathLike[str]] | None = None,
    xacro_args: Mapping[str, str] | None = None,
) -> Robot:
    """The robot of a URDF chain (see :func:`urdf_to_dh`)."""
    ext = urdf_to_dh(
        urdf,
        base=base,
        tip=tip,
        convention=convention,
        xacro=xacro,
        xacro_env=xacro_env,
        trust_xacro=trust_xacro,
        packages=packages,
        xacro_args=xacro_args,
    )
    return ext.robot
