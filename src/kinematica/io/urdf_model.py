"""The kinematic part of a URDF as plain data: links, joints, one serial chain.

:class:`UrdfModel` is what :mod:`kinematica.io.urdf` reads from a file, checked
as a tree (every joint's links exist, one root, no link with two parents, no
loop). :meth:`UrdfModel.chain` picks the serial chain from a base link to a tip
link and checks that every joint on it is one kinematica can model: revolute,
continuous, prismatic or fixed, and not a mimic joint. Nothing here computes
kinematics; the origins are kept as :class:`~kinematica.io.spec.FrameSpec`.
"""

from __future__ import annotations

import re
import warnings
from collections.abc import Sequence
from dataclasses import dataclass, field

from kinematica.errors import KinematicaWarning, RobotFileError
from kinematica.io._parse import MAX_JOINTS
from kinematica.io.spec import FrameSpec

__all__ = [
    "DH_FRAMES_NOTE",
    "JOINT_TYPES",
    "MOVABLE_TYPES",
    "UrdfChain",
    "UrdfJoint",
    "UrdfModel",
    "dh_frames_note",
]

#: Joint types of the URDF specification.
JOINT_TYPES = ("revolute", "continuous", "prismatic", "fixed", "floating", "planar")
#: The 1-DOF joint types a serial chain may hold (besides ``fixed``).
MOVABLE_TYPES = ("revolute", "continuous", "prismatic")

_SHOWN = 8  # names listed in a message before "..."
#: The maker's controller base frame of ROS-Industrial descriptions (REP-199): DH
#: frame 0 where it lies on axis 1 (UR publishes its DH table in it).
MAKER_BASE = "base"
#: The flange frame of ROS-Industrial descriptions (REP-199): where a chain ends when
#: its leaves are all frames fixed to the last moving link.
FLANGE = "tool0"
#: The comment a URDF kinematica writes from a DH table carries: which convention's
#: DH frames its link frames are. Where an arm's frames obey both conventions' rules
#: (all axes parallel, say), it tells the DH extraction how to read them, so that a
#: modified table written out and read back in either convention gives one table.
DH_FRAMES_NOTE = "each link frame is a {convention} DH frame"
# The phrase alone (no scan for the comment's start: linear on any file).
_NOTE = re.compile(DH_FRAMES_NOTE.format(convention="(standard|modified)").encode())


def dh_frames_note(data: bytes) -> str | None:
    """The convention a URDF's :data:`DH_FRAMES_NOTE` comment names, or ``None``."""
    found = _NOTE.search(data)
    return None if found is None else found.group(1).decode()


def _names(names: Sequence[str]) -> str:
    shown = ", ".join(repr(n) for n in names[:_SHOWN])
    return shown + (f", ... ({len(names)} in all)" if len(names) > _SHOWN else "")


@dataclass(frozen=True)
class UrdfJoint:
    """One ``<joint>`` of a URDF.

    Attributes:
        name: The joint's name.
        type: One of :data:`JOINT_TYPES`.
        parent: Name of the parent link.
        child: Name of the child link.
        origin: Pose of the joint frame in the parent link frame (m, rad);
            the child link frame is the joint frame moved by the joint.
        axis: Unit axis of rotation or translation, in the joint frame.
        limits: ``(lower, upper)`` in rad (revolute) or m (prismatic), or
            ``None`` (continuous joints, or no limits given).
        mimic: Name of the joint this one mimics, or ``None``.
    """

    name: str
    type: str
    parent: str
    child: str
    origin: FrameSpec = field(default_factory=FrameSpec)
    axis: tuple[float, float, float] = (1.0, 0.0, 0.0)
    limits: tuple[float, float] | None = None
    mimic: str | None = None

    @property
    def movable(self) -> bool:
        """True for revolute, continuous and prismatic joints."""
        return self.type in MOVABLE_TYPES

    @property
    def kind(self) -> str:
        """``"R"`` (revolute, continuous), ``"P"`` (prismatic) or ``""`` (others)."""
        return {"revolute": "R", "continuous": "R", "prismatic": "P"}.get(self.type, "")


@dataclass(frozen=True)
class UrdfChain:
    """A serial chain of a URDF, from a base link to a tip link.

    Attributes:
        name: The robot's name.
        base: Name of the base link (the world frame of the chain).
        tip: Name of the tip link.
        joints: The joints from ``base`` to ``tip`` in order, fixed ones
            included; each joint's parent is the previous joint's child.
        source: The file it was read from, or ``None``.
        maker_base: The fixed joints from ``base`` to ROS-Industrial's ``base``
            link (the maker's controller base frame, REP-199) when it hangs off
            the chain before its first movable joint; ``()`` otherwise.
        dh_frames: ``"standard"`` or ``"modified"`` when the description says
            its link frames are DH frames of that convention (a URDF kinematica
            wrote: :data:`DH_FRAMES_NOTE`), else ``None``.
    """

    name: str
    base: str
    tip: str
    joints: tuple[UrdfJoint, ...]
    source: str | None = None
    maker_base: tuple[UrdfJoint, ...] = ()
    dh_frames: str | None = None

    @property
    def movable(self) -> tuple[UrdfJoint, ...]:
        """The revolute, continuous and prismatic joints, base to tip."""
        return tuple(j for j in self.joints if j.movable)


@dataclass(frozen=True)
class UrdfModel:
    """The links and joints of a URDF, checked to form one tree.

    Attributes:
        name: The ``<robot name=...>``.
        links: Link names, in file order.
        joints: Joints, in file order.
        source: The file it was read from, or ``None``.
        dh_frames: The DH convention the file says its link frames follow
            (:data:`DH_FRAMES_NOTE`), or ``None``.

    Raises:
        RobotFileError: A joint names a link that does not exist, a link is
            the child of two joints, the joints form a loop, or there is more
            than one root link (or none).
    """

    name: str
    links: tuple[str, ...]
    joints: tuple[UrdfJoint, ...]
    source: str | None = None
    dh_frames: str | None = None
    _parent_joint: dict[str, UrdfJoint] = field(init=False, repr=False, compare=False)
    _link_set: frozenset[str] = field(init=False, repr=False, compare=False)

    def _error(self, message: str) -> RobotFileError:
        return RobotFileError(message, path=self.source)

    def __post_init__(self) -> None:
        links = frozenset(self.links)
        parent_joint: dict[str, UrdfJoint] = {}
        for j in self.joints:
            for role, link in (("parent", j.parent), ("child", j.child)):
                if link not in links:
                    raise self._error(
                        f"joint {j.name!r}: its {role} link {link!r} is not defined "
                        f'(no <link name="{link}">)'
                    )
            if j.parent == j.child:
                raise self._error(
                    f"joint {j.name!r} joins link {j.child!r} to itself: a URDF has no loops"
                )
            if j.child in parent_joint:
                other = parent_joint[j.child].name
                raise self._error(
                    f"link {j.child!r} is the child of two joints ({other!r} and {j.name!r}): "
                    "a URDF is a tree and has no loops"
                )
            parent_joint[j.child] = j
        roots = [name for name in self.links if name not in parent_joint]
        if len(roots) > 1:
            raise self._error(
                f"{len(roots)} root links (links that are no joint's child): {_names(roots)}; "
                "a URDF is one tree with one root"
            )
        if not roots:
            raise self._error(f"the joints form a loop: {self._loop(parent_joint)}")
        object.__setattr__(self, "_parent_joint", parent_joint)
        object.__setattr__(self, "_link_set", links)

    @staticmethod
    def _loop(parent_joint: dict[str, UrdfJoint]) -> str:
        link = next(iter(parent_joint))
        seen: dict[str, int] = {}  # link -> its place on the walk (a dict: the walk may be long)
        while link not in seen:
            seen[link] = len(seen)
            link = parent_joint[link].parent
        cycle = [*list(seen)[seen[link] :], link]
        shown = " <- ".join(repr(n) for n in cycle[:_SHOWN])
        if len(cycle) > _SHOWN:
            shown += f" <- ... ({len(cycle) - 1} links in the loop)"
        return shown + " (every link has a parent joint)"

    @property
    def root(self) -> str:
        """The root link: the one link that is no joint's child."""
        return next(name for name in self.links if name not in self._parent_joint)

    def _children(self) -> dict[str, list[UrdfJoint]]:
        children: dict[str, list[UrdfJoint]] = {name: [] for name in self.links}
        for j in self.joints:
            children[j.parent].append(j)
        return children

    def _path(self, base: str, tip: str) -> tuple[UrdfJoint, ...] | None:
        """The joints from ``base`` down to ``tip``, or None if tip is not below base."""
        parent_joint = self._parent_joint
        path: list[UrdfJoint] = []
        link = tip
        while link != base:
            if link not in parent_joint:
                return None
            joint = parent_joint[link]
            path.append(joint)
            link = joint.parent
        return tuple(reversed(path))

    def _check_link(self, link: str, what: str) -> None:
        if not isinstance(link, str) or link not in self._link_set:
            raise self._error(f"{what}: no link named {link!r}; links: {_names(self.links)}")

    def leaves(self, base: str | None = None) -> tuple[str, ...]:
        """Links below ``base`` (default: the root) that have no child joint."""
        start = self.root if base is None else base
        self._check_link(start, "base")
        children = self._children()
        out, stack = [], [start]
        while stack:
            link = stack.pop()
            below = children[link]
            if not below and link != start:
                out.append(link)
            stack.extend(j.child for j in reversed(below))
        return tuple(out)

    def chain(self, base: str | None = None, tip: str | None = None) -> UrdfChain:
        """The serial chain from link ``base`` to link ``tip``.

        Args:
            base: The base link; default the root link.
            tip: The tip link; default the single leaf below ``base`` reached
                through at least one movable joint (leaves hanging from the
                base by fixed joints only, such as ROS-Industrial's ``base``
                frame, are not candidates). When several leaves all hang by
                fixed joints off the same last moving link (a UR file's
                ``ee_link`` and ``tool0``), ``tool0`` if that link carries one,
                else the last moving link, with a warning saying which. Other
                cases of several candidates are an error that lists them.

        Returns:
            The chain.

        Raises:
            RobotFileError: unknown link names, ``tip`` not below ``base``, no
                single default tip, no movable joint on the chain or more than
                ``MAX_JOINTS`` (100), or a joint on it that is floating, planar
                or a mimic joint.
        """
        start = self.root if base is None else base
        self._check_link(start, "base")
        if tip is None:
            tip = self._default_tip(start)
        self._check_link(tip, "tip")
        path = self._path(start, tip)
        if path is None:
            raise self._error(
                f"tip link {tip!r} is not below base link {start!r}; "
                f"leaves below {start!r}: {_names(self.leaves(start))}"
            )
        for j in path:
            if j.type in ("floating", "planar"):
                dof = "6 DOF" if j.type == "floating" else "3 DOF"
                raise self._error(
                    f"joint {j.name!r} is {j.type} ({dof}): kinematica models serial chains "
                    "of 1-DOF joints; choose a base link below it (base= / --base)"
                )
            if j.mimic is not None:
                raise self._error(
                    f"joint {j.name!r} mimics joint {j.mimic!r}: mimic joints are not supported "
                    "on the chain; choose a tip link before it (tip= / --tip)"
                )
        movable = sum(j.movable for j in path)
        if not movable:
            raise self._error(f"no movable joint between links {start!r} and {tip!r}")
        if movable > MAX_JOINTS:
            raise self._error(
                f"the chain from link {start!r} to link {tip!r} has {movable} movable joints; "
                f"at most {MAX_JOINTS} are accepted (as in robot files); choose a shorter chain "
                "(base= / --base, tip= / --tip)"
            )
        return UrdfChain(
            name=self.name,
            base=start,
            tip=tip,
            joints=path,
            source=self.source,
            maker_base=self._maker_base(start, path),
            dh_frames=self.dh_frames,
        )

    def _maker_base(self, start: str, path: tuple[UrdfJoint, ...]) -> tuple[UrdfJoint, ...]:
        """Fixed joints from ``start`` to a side link :data:`MAKER_BASE` before joint 1."""
        before = [start]
        for j in path:
            if j.movable:
                break
            before.append(j.child)
        if MAKER_BASE not in self.links or MAKER_BASE in before:
            return ()
        side: list[UrdfJoint] = []
        link = MAKER_BASE
        while link not in before:
            joint = self._parent_joint.get(link)
            if joint is None or joint.movable:
                return ()
            side.append(joint)
            link = joint.parent
        prefix = path[: before.index(link)]
        return (*prefix, *reversed(side))

    def _common_flange(self, leaves: list[str], children: dict[str, list[UrdfJoint]]) -> str | None:
        """The tip when every leaf hangs by fixed joints off one last moving link, else None.

        The chain is then unambiguous (the leaves are frames on one rigid body): it ends
        at ``tool0``, the ROS-Industrial flange frame, where that body carries one, else
        at the last moving link itself. A warning says which.
        """
        owners = set()
        for leaf in leaves:
            link = leaf
            while link in self._parent_joint and not self._parent_joint[link].movable:
                link = self._parent_joint[link].parent
            owners.add(link)
        if len(owners) != 1:
            return None
        (last,) = owners
        rigid, stack = [], [last]  # the links fixed to the last moving link
        while stack:
            link = stack.pop()
            rigid.append(link)
            stack.extend(j.child for j in children[link] if not j.movable)
        tip = FLANGE if FLANGE in rigid else last
        why = (
            f"the ROS-Industrial flange frame {FLANGE!r}"
            if tip == FLANGE
            else f"the last moving link {last!r}"
        )
        where = f"{self.source}: " if self.source else ""
        warnings.warn(
            f"{where}leaf links {_names(leaves)} all hang by fixed joints off {last!r}, the "
            f"last moving link: the chain ends at {why}; choose another with tip= / --tip",
            KinematicaWarning,
            stacklevel=4,
        )
        return tip

    def _default_tip(self, base: str) -> str:
        children = self._children()
        candidates: list[str] = []
        stack: list[tuple[str, bool]] = [(base, False)]
        while stack:
            link, moved = stack.pop()
            below = children[link]
            if not below and link != base and moved:
                candidates.append(link)
            stack.extend((j.child, moved or j.movable) for j in reversed(below))
        if len(candidates) == 1:
            return candidates[0]
        if not candidates:
            raise self._error(f"no movable joint below link {base!r}")
        flange = self._common_flange(candidates, children)
        if flange is not None:
            return flange
        raise self._error(
            f"{len(candidates)} leaf links below {base!r} end a chain with movable joints: "
            f"{_names(candidates)}; choose one as the tip (tip= / --tip)"
        )
