"""DH tables read off joint axes by the DH rules, and robots written as URDF chains.

A :class:`~kinematica.Robot` stays a DH robot. A serial chain (from a URDF, or
a robot's own kinematics) has its joint axes placed in space at q = 0 and a DH
table extracted by the rules of the DH method (:func:`kinematica.dh.extract_dh`),
with base and tool transforms for what DH cannot say, and the table's distance
from the chain's FK measured (``fk_error``). The way out writes each DH frame as
a URDF link, so that extracting the table again gives the same rows. Nothing
here imports the Robot class: the caller passes its constructor (no import cycle).
"""

from __future__ import annotations

import dataclasses
import os
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Generic, TypeVar

import numpy as np
from numpy.typing import NDArray

from kinematica.dh import (
    AxisFrame,
    ChainGeometry,
    FrameRule,
    NamedFrame,
    extract_dh,
)
from kinematica.dh.joints import values_checked
from kinematica.dh.lines import frame_from, perpendicular_hint
from kinematica.errors import RobotFileError
from kinematica.io import UrdfChain, UrdfJoint, urdf_text
from kinematica.io.atomic import unchanged, write_text_atomic
from kinematica.io.spec import frame_of

if TYPE_CHECKING:
    from kinematica.robot.kinematics import RobotKinematics

__all__ = [
    "DHExtraction",
    "chain_from_robot",
    "dh_from_chain",
    "geometry_from_chain",
    "geometry_from_robot",
    "to_dh",
    "to_urdf",
]

FloatArray = NDArray[np.float64]


#: The robot class a table is extracted for (made by its ``from_dh``).
R = TypeVar("R", bound="RobotKinematics")


@dataclass(frozen=True)
class DHExtraction(Generic[R]):
    """A DH robot extracted from a chain's joint axes, and how.

    Attributes:
        robot: The DH robot. From :func:`kinematica.urdf_to_dh` it computes
            with the file's own transforms (its FK the file's); from
            :meth:`kinematica.Robot.to_dh`, with the table alone.
        rules: For each DH frame ``S_0..S_n``, the rule that placed it
            (:class:`~kinematica.dh.FrameRule`: ``.frame``, ``.rule``, ``.text``).
        fk_error: How far the DH table alone (rows, base, tool) is from the
            chain it was read off (the URDF as loaded, or the robot's own
            kinematics): the largest difference of any entry of the tool pose T
            (m, or unitless for the rotation), over q = 0 and
            :data:`~kinematica.dh.extract.FK_CHECK_SAMPLES` configurations
            spread within the joint limits (seeded). Round-off when DH
            describes the axes exactly; 5.9e-10 on rtb-data's AL5D URDF, whose
            rpy values write π as 3.141592653 (axes 5.9e-10 rad off parallel,
            taken as parallel).
        frames: ``(n+1, 4, 4)`` the DH frames ``S_0..S_n`` at q = 0, in the
            chain's base frame.
        source: What the chain was read from (``"arm.urdf: base_link -> tool0"``).
    """

    robot: R
    rules: tuple[FrameRule, ...]
    fk_error: float
    frames: FloatArray = field(repr=False)
    source: str | None = None

    def report(self) -> str:
        """The rules, one line per frame."""
        head = f"{self.robot.convention} DH frames of {self.robot.name}"
        if self.source:
            head += f" ({self.source})"
        return "\n".join([head + ":", *(f"  {r}" for r in self.rules)])


def geometry_from_chain(chain: UrdfChain) -> ChainGeometry:
    """The joint axes, tip pose and named frames of a chain at q = 0, base-link frame.

    Fixed joints are folded into the next origin; the link frames before the
    first movable joint and after the last one are kept by name (candidates
    for DH frames 0 and n), ROS-Industrial's ``base`` frame (the maker's) first.
    """
    pose = np.eye(4)
    before = [NamedFrame(chain.base, pose)]
    after: list[NamedFrame] = []
    joints: list[AxisFrame] = []
    for j in chain.joints:
        pose = pose @ j.origin.as_matrix()  # the child frame at q = 0 is the joint frame
        if j.movable:
            axis = pose[:3, :3] @ np.array(j.axis, dtype=float)
            joints.append(
                AxisFrame(
                    kind="R" if j.kind == "R" else "P",
                    direction=axis / np.linalg.norm(axis),
                    frame=pose,
                    name=j.name,
                    qlim=j.limits,
                )
            )
            after = []
        elif joints:
            after.append(NamedFrame(j.child, pose))
        else:
            before.append(NamedFrame(j.child, pose))
    nearest_first = list(reversed(before))
    if chain.maker_base:  # the maker's base frame first: DH frame 0 wherever it may be
        maker = np.eye(4)
        for j in chain.maker_base:
            maker = maker @ j.origin.as_matrix()
        nearest_first.insert(0, NamedFrame(chain.maker_base[-1].child, maker))
    return ChainGeometry(
        joints=tuple(joints),
        tip=pose,
        before=tuple(nearest_first),
        after=tuple(after),
        dh_frames=chain.dh_frames,
    )


def geometry_from_robot(robot: RobotKinematics) -> ChainGeometry:
    """The joint axes, tip and named frames of the robot's own kinematics at q = 0.

    For a DH robot, its table's (the chain :func:`chain_from_robot` writes). For
    a robot computing with a loaded chain's transforms (a URDF), that chain's:
    each joint's axis where the file puts it, its frame the DH frame on that
    axis moved onto it exactly (so that the rules choose as the table did), the
    tip the chain's home pose. Its DH rows describe such a robot only to their
    extraction's accuracy, so they are not the chain to measure a table against.
    Frames are in the robot's world frame.
    """
    t = robot.transforms
    if t is None:
        return geometry_from_chain(chain_from_robot(robot))
    motion = robot.base @ t.motion_frames()  # (n, 4, 4): z along each joint's axis
    dh = np.concatenate([robot.base[None], motion @ t.frame_offsets])  # S_0..S_n
    on_axis = dh[:-1] if robot.convention == "standard" else dh[1:]  # S on joint i's axis
    joints = []
    for M, S, link, name in zip(motion, on_axis, robot.links, _joint_names(robot), strict=True):
        h, p = M[:3, 2], M[:3, 3]
        foot = p + float((S[:3, 3] - p) @ h) * h
        frame = frame_from(perpendicular_hint(S, h), h, foot)
        joints.append(AxisFrame(link.type, h, frame, name=name, qlim=link.qlim))
    tip = motion[-1] @ t.end @ robot.tool
    identity = np.eye(4)
    before = [NamedFrame("base_link", identity)]
    if not np.array_equal(robot.base, identity):
        before.insert(0, NamedFrame("link0", robot.base))
    after = [NamedFrame("tool0", tip)]
    if robot.convention == "standard" and not np.array_equal(robot.tool, identity):
        after.insert(0, NamedFrame("flange", dh[-1]))
    return ChainGeometry(
        joints=tuple(joints),
        tip=tip,
        before=tuple(before),
        after=tuple(after),
        dh_frames=robot.convention,
    )


def _extraction(
    geometry: ChainGeometry,
    convention: str,
    make: Callable[..., R],
    name: str,
    description: str | None,
    source: str | None,
) -> DHExtraction[R]:
    """The DH robot of the chain ``geometry`` describes, and the table's ``fk_error``."""
    table = extract_dh(geometry, convention)
    robot = make(
        table.rows,
        convention=table.convention,
        name=name,
        base=table.base,
        tool=table.tool,
        description=description,
    )
    return DHExtraction(
        robot=robot,
        rules=table.rules,
        fk_error=table.fk_error,
        frames=table.frames,
        source=source,
    )


def dh_from_chain(
    chain: UrdfChain,
    convention: str = "standard",
    *,
    make: Callable[..., R],
    name: str | None = None,
    description: str | None = None,
) -> DHExtraction[R]:
    """The DH robot of a URDF chain, by the DH rules (frames placed on the joint axes).

    Args:
        chain: The serial chain.
        convention: ``"standard"`` or ``"modified"``.
        make: Builds the robot from the rows (``Robot.from_dh``).
        name: The robot's name; default the chain's.
        description: Free text for the robot.

    Returns:
        The robot (its DH table alone), its frames, the rule behind each and the
        table's ``fk_error`` against the chain as the file gives it.
    """
    where = f"{chain.source}: " if chain.source else ""
    return _extraction(
        geometry_from_chain(chain),
        convention,
        make,
        name or chain.name,
        description,
        f"{where}{chain.base} -> {chain.tip}",
    )


def _joint_names(robot: RobotKinematics) -> list[str]:
    names = [link.name for link in robot.links]
    if all(names) and len(set(names)) == len(names):
        return [str(n) for n in names]
    return [f"joint{i}" for i in range(1, robot.dof + 1)]


def chain_from_robot(robot: RobotKinematics) -> UrdfChain:
    """The robot as a URDF chain whose link frames are its DH frames.

    Links ``base_link`` (the world), ``link0`` (DH frame 0, when the base is
    not the identity), ``link1..linkn``, ``flange`` (standard convention, DH
    frame n, when the tool is not the identity) and ``tool0``. Every joint
    turns or slides about its frame's z axis. Extracting DH from this chain in
    the robot's own convention gives back its rows.
    """
    n = robot.dof
    A0 = robot.link_matrices(np.zeros(n))
    standard = robot.convention == "standard"
    names = _joint_names(robot)
    joints: list[UrdfJoint] = []
    parent = "base_link"
    if not np.array_equal(robot.base, np.eye(4)):
        joints.append(UrdfJoint("base_link-link0", "fixed", parent, "link0", frame_of(robot.base)))
        parent = "link0"
    for i, link in enumerate(robot.links):
        origin = (np.eye(4) if i == 0 else A0[i - 1]) if standard else A0[i]
        jtype = "prismatic" if link.type == "P" else "revolute"
        child = f"link{i + 1}"
        joints.append(
            UrdfJoint(names[i], jtype, parent, child, frame_of(origin), (0.0, 0.0, 1.0), link.qlim)
        )
        parent = child
    has_tool = not np.array_equal(robot.tool, np.eye(4))
    if standard and has_tool:
        joints.append(UrdfJoint(f"{parent}-flange", "fixed", parent, "flange", frame_of(A0[-1])))
        parent = "flange"
    last = robot.tool if has_tool or not standard else A0[-1]
    joints.append(UrdfJoint(f"{parent}-tool0", "fixed", parent, "tool0", frame_of(last)))
    return UrdfChain(
        name=robot.name,
        base="base_link",
        tip="tool0",
        joints=tuple(joints),
        dh_frames=robot.convention,
    )


def to_dh(robot: R, convention: str = "standard") -> DHExtraction[R]:
    """Extract the DH table of a robot's joint axes again, by the rules.

    The axes are the robot's own (:func:`geometry_from_robot`): a URDF's as
    loaded, not its DH table's. In the robot's own convention this gives back
    its rows (angles wrapped to (-π, π]); in the other convention, a table
    placed by the rules with the same FK. ``fk_error`` is the returned table's
    distance from the robot's own FK. See :func:`kinematica.dh.extract_dh`.
    """
    make = type(robot).from_dh
    ext = _extraction(
        geometry_from_robot(robot), convention, make, robot.name, robot.description, None
    )
    out = ext.robot
    with values_checked():  # derived values: the plausibility warnings are for typed ones
        links = [  # the robot's own joint names, even repeated or missing ones
            dataclasses.replace(new, name=old.name)
            for new, old in zip(out.links, robot.links, strict=True)
        ]
    named = make(
        links,
        convention=out.convention,
        name=out.name,
        base=out.base,
        tool=out.tool,
        description=out.description,
    )
    return dataclasses.replace(ext, robot=named)


def to_urdf(robot: RobotKinematics, path: str | os.PathLike[str] | None = None) -> str:
    """The robot as URDF text (links without geometry), saved to ``path`` if given.

    Raises:
        RobotFileError: ``path`` cannot be written.
    """
    text = urdf_text(
        chain_from_robot(robot),
        comment=f"{robot.name}: written by kinematica from its {robot.convention} DH table; "
        "Kinematics only (effort and velocity unknown: 0).",
    )
    if path is not None:
        p = Path(path)
        try:
            write_text_atomic(p, text)
        except OSError as exc:
            raise RobotFileError(
                f"cannot write the file: {exc.strerror or exc}; {unchanged(p)}", path=str(p)
            ) from exc
    return text
