"""A serial chain as the DH extraction sees it: joint axes, named frames, results.

Plain data shared by :mod:`kinematica.dh.extract` and the layers that feed it
(a URDF chain, a DH robot's own frames): each joint's axis at q = 0 with the
joint's own frame, the tip pose, the named frames around the chain, and what
the extraction gives back.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from kinematica.dh.joints import Convention, Joint, JointType
from kinematica.errors import KinematicaError

__all__ = ["AxisFrame", "ChainGeometry", "ExtractedTable", "FrameRule", "NamedFrame"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class AxisFrame:
    """One joint at q = 0.

    Attributes:
        kind: ``"R"`` or ``"P"``.
        direction: ``(3,)`` unit axis (the sense of positive motion), chain base frame.
        frame: ``(4, 4)`` the joint's own frame in the chain base frame; its
            origin is on the axis (a URDF joint frame).
        name: The joint's name.
        qlim: Joint limits ``(lo, hi)`` (rad or m), or ``None``.
    """

    kind: JointType
    direction: FloatArray
    frame: FloatArray
    name: str | None = None
    qlim: tuple[float, float] | None = None


@dataclass(frozen=True)
class NamedFrame:
    """A named frame of the description (a URDF link), pose ``(4, 4)`` in the chain base frame."""

    name: str
    pose: FloatArray


@dataclass(frozen=True)
class ChainGeometry:
    """A serial chain at q = 0, as the DH extraction sees it.

    Attributes:
        joints: The movable joints, base to tip.
        tip: ``(4, 4)`` tip pose in the chain base frame at q = 0.
        before: Named frames before joint 1, nearest to joint 1 first.
        after: Named frames after joint n, nearest to joint n first.
        dh_frames: ``"standard"`` or ``"modified"`` when the description says
            its joint frames are DH frames of that convention (a URDF
            kinematica wrote), else ``None``: how to read frames that obey
            both conventions' rules.
    """

    joints: tuple[AxisFrame, ...]
    tip: FloatArray
    before: tuple[NamedFrame, ...] = ()
    after: tuple[NamedFrame, ...] = ()
    dh_frames: str | None = None

    def __post_init__(self) -> None:
        if not self.joints:
            raise KinematicaError("a chain needs at least one movable joint")
        if self.dh_frames not in (None, "standard", "modified"):
            raise KinematicaError(
                f"dh_frames must be 'standard', 'modified' or None, got {self.dh_frames!r}"
            )

    @property
    def size(self) -> float:
        """The chain's size (m): the path from joint 1 through every joint to the tip.

        The scale the line geometry's length tolerance is relative to
        (:func:`kinematica.dh.lines.length_tol`).
        """
        points = [j.frame[:3, 3] for j in self.joints] + [self.tip[:3, 3]]
        return float(sum(np.linalg.norm(b - a) for a, b in itertools.pairwise(points)))


@dataclass(frozen=True)
class FrameRule:
    """Which rule placed DH frame ``S_frame``, in words.

    Attributes:
        frame: The frame index, 0..n.
        rule: A short key: ``"frame"`` (a frame of the description kept),
            ``"rule 5"`` (S_0 built on axis 1), ``"skew"``, ``"intersecting"``,
            ``"parallel"``, ``"collinear"`` (how axes i, i+1 lie: rules 6-7),
            ``"rule 9"`` (S_n built at the tip), ``"craig"`` (the modified
            convention's S_0 = S_1, or S_n built at joint n).
        text: One sentence saying how the frame was placed.
    """

    frame: int
    rule: str
    text: str

    def __str__(self) -> str:
        return f"S{self.frame}: {self.text}"


@dataclass(frozen=True)
class ExtractedTable:
    """The result of :func:`extract_dh`.

    Attributes:
        rows: The DH rows (offsets make q = 0 the chain's home pose).
        convention: ``"standard"`` or ``"modified"``.
        base: ``(4, 4)`` pose of ``S_0`` in the chain base frame.
        tool: ``(4, 4)`` pose of the tip in ``S_n``.
        rules: One :class:`FrameRule` per frame ``S_0..S_n``.
        fk_error: How far the table (rows, base, tool) is from the chain it was
            read off: the largest difference of any entry of the tool pose T
            (m for the translation, unitless for the rotation) between the
            table's FK and the chain's own (about its joint axes as given, not
            as the rules idealised them), over q = 0 and
            :data:`~kinematica.dh.extract.FK_CHECK_SAMPLES` configurations
            spread within the joint limits (seeded).
        frames: ``(n+1, 4, 4)`` the frames ``S_0..S_n`` at q = 0, chain base frame.
    """

    rows: tuple[Joint, ...]
    convention: Convention
    base: FloatArray
    tool: FloatArray
    rules: tuple[FrameRule, ...]
    fk_error: float
    frames: FloatArray = field(repr=False)
