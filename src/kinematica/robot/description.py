"""A robot's description: its DH table, joint limits, base and tool, and the values it takes.

:class:`RobotDescription` holds what :class:`~kinematica.robot.robot.Robot` is made
of (an immutable dataclass: the DH rows, convention, base, tool, the chain compiled
for the core), its structure, the check of joint values and the robots derived from
it. Its subclasses add the kinematics (:mod:`kinematica.robot.kinematics`), the IK
(:mod:`kinematica.robot.inverse`) and the rest (:mod:`kinematica.robot.robot`).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING, Self

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.core import Chain
from kinematica.dh import (
    Convention,
    Joint,
    Prismatic,
    Revolute,
    check_convention,
    convert_table,
    given_convention,
)
from kinematica.errors import DimensionError, KinematicaError
from kinematica.io.plausible import PLAUSIBLE_ANGLE
from kinematica.robot.frames import rigid_frame, short
from kinematica.robot.transforms import ChainTransforms, dh_frames

if TYPE_CHECKING:
    from kinematica.io import RobotSpec

__all__ = ["RobotDescription"]

FloatArray = NDArray[np.float64]
_FLOAT64 = np.dtype(np.float64)


@dataclass(frozen=True, eq=False)
class RobotDescription:
    """A serial arm's description (see :class:`~kinematica.robot.robot.Robot`)."""

    links: tuple[Joint, ...]
    convention: Convention = "standard"
    name: str = "robot"
    base: FloatArray = field(default_factory=lambda: np.eye(4))
    tool: FloatArray = field(default_factory=lambda: np.eye(4))
    description: str | None = None
    chain: Chain = field(init=False, repr=False)
    source_spec: RobotSpec | None = field(default=None, compare=False, repr=False)
    transforms: ChainTransforms | None = field(default=None, compare=False, repr=False)
    _single: tuple[int] = field(init=False, repr=False, compare=False)
    _fk_one: Callable[[FloatArray], tuple[FloatArray, int]] = field(
        init=False, repr=False, compare=False
    )
    _jacobian_one: Callable[[FloatArray, bool], tuple[FloatArray, int]] = field(
        init=False, repr=False, compare=False
    )
    _turn: FloatArray | None = field(init=False, repr=False, compare=False)
    _own: NDArray[np.bool_] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        links = tuple(self.links)
        if not links:
            raise KinematicaError("a robot needs at least one joint")
        for i, link in enumerate(links, start=1):
            if not isinstance(link, Revolute | Prismatic):
                raise KinematicaError(
                    f"joint {i}: expected kinematica.Revolute or kinematica.Prismatic, "
                    f"got {type(link).__name__}"
                )
        object.__setattr__(self, "links", links)
        object.__setattr__(self, "convention", check_convention(self.convention))
        base = rigid_frame(self.base, "base")
        tool = rigid_frame(self.tool, "tool")
        base.flags.writeable = False
        tool.flags.writeable = False
        object.__setattr__(self, "base", base)
        object.__setattr__(self, "tool", tool)
        if self.transforms is None:
            chain = Chain.from_dh(links, self.convention, base, tool)
        else:
            if self.transforms.frame_offsets.shape[0] != len(links):
                raise KinematicaError(
                    f"transforms describe {self.transforms.frame_offsets.shape[0]} joints, "
                    f"the DH table {len(links)}"
                )
            chain = self.transforms.compile(links, base, tool)
        object.__setattr__(self, "chain", chain)
        # the single-call path of fk and jacobian: the core's entry points, looked up once
        object.__setattr__(self, "_single", (len(links),))
        object.__setattr__(self, "_fk_one", chain.core.fk)
        object.__setattr__(self, "_jacobian_one", chain.core.jacobian)
        # revolute joints with no limits of their own: a value beyond a full turn is
        # most likely degrees given to the radian API (limits would say it otherwise)
        free = np.array([isinstance(j, Revolute) and j.qlim is None for j in links], dtype=bool)
        turn = np.where(free, PLAUSIBLE_ANGLE, np.inf) if free.any() else None
        object.__setattr__(self, "_turn", turn)
        # the joints with limits of their own (has_limits): read-only, made once
        own = np.array([link.qlim is not None for link in links], dtype=bool)
        own.flags.writeable = False
        object.__setattr__(self, "_own", own)

    @classmethod
    def from_dh(
        cls,
        rows: Iterable[Joint],
        *,
        convention: str | None = None,
        name: str = "robot",
        base: ArrayLike | None = None,
        tool: ArrayLike | None = None,
        description: str | None = None,
    ) -> Self:
        """A robot from its DH rows.

        Args:
            rows: ``Revolute(d=, a=, alpha=, offset=, qlim=)`` and
                ``Prismatic(theta=, a=, alpha=, offset=, qlim=)`` rows, base to tip.
            convention: ``"standard"`` or ``"modified"`` (aliases accepted);
                ``None`` reads standard with a ConventionWarning (as a robot file
                without ``convention``).
            name: Display name.
            base: ``(4, 4)`` pose of frame 0 in the world frame; identity if ``None``.
            tool: ``(4, 4)`` pose of the tool in frame n; identity if ``None``.
            description: Free text.

        Returns:
            The robot.
        """
        return cls(
            links=tuple(rows),
            convention=given_convention(convention),
            name=name,
            base=rigid_frame(base, "base"),
            tool=rigid_frame(tool, "tool"),
            description=description,
        )

    @property
    def dof(self) -> int:
        """Number of joints n."""
        return len(self.links)

    @cached_property
    def joint_names(self) -> tuple[str, ...]:
        """Each joint's name: its own (a URDF's joint names), else ``"q1"``, ``"q2"``..."""
        return tuple(
            link.name if link.name else f"q{i}" for i, link in enumerate(self.links, start=1)
        )

    @property
    def joint_types(self) -> str:
        """One letter per joint, e.g. ``"RRPRRR"``."""
        return "".join(link.type for link in self.links)

    @property
    def is_prismatic(self) -> NDArray[np.bool_]:
        """``(n,)`` True where the joint is prismatic."""
        return self.chain.prismatic.copy()

    @property
    def qlim(self) -> FloatArray:
        """``(n, 2)`` joint limits: ``(-π, π)`` for free revolute joints, ±inf for prismatic."""
        return self.chain.qlim.copy()

    @property
    def has_limits(self) -> NDArray[np.bool_]:
        """``(n,)`` True where the joint has limits of its own (not the default)."""
        return self._own.copy()

    def dh_table(self, q: ArrayLike | None = None) -> FloatArray:
        """The DH parameters ``theta, d, a, alpha`` of every row at ``q``.

        Args:
            q: ``(n,)`` joint values; zeros if ``None``.

        Returns:
            ``(n, 4)`` rows (rad, m), in the robot's own convention.
        """
        qq = np.zeros(self.dof) if q is None else self.check_q(q)
        if qq.ndim != 1:
            raise DimensionError(f"dh_table takes one configuration (n,), got shape {qq.shape}")
        rows = []
        for link, qi in zip(self.links, qq, strict=True):
            if isinstance(link, Revolute):
                rows.append((qi + link.offset, link.d, link.a, link.alpha))
            else:
                rows.append((link.theta, qi + link.offset, link.a, link.alpha))
        return np.array(rows, dtype=float)

    def check_q(self, q: ArrayLike, name: str = "q") -> FloatArray:
        """Validate joint values: shape ``(..., n)``, real numbers (NaN/inf pass).

        Args:
            q: ``(..., n)`` joint values.
            name: Name used in messages.

        Returns:
            ``q`` as a float array.

        Raises:
            DimensionError: On a wrong last dimension or values that are not
                real numbers.
        """
        if type(q) is np.ndarray and q.dtype is _FLOAT64 and q.ndim and q.shape[-1] == self.dof:
            return q  # already what the slow path below would return: a cheap single call
        try:
            raw = np.asarray(q)
        except (TypeError, ValueError) as exc:
            raise DimensionError(f"{name} must be numbers, got {q!r}") from exc
        if raw.dtype is _FLOAT64 and raw.shape == self._single:
            return raw  # a list of n floats: the common case, checked in full
        if raw.dtype.kind not in "iuf":
            raise DimensionError(f"{name} must be numbers, got {short(q)}")
        if raw.ndim == 0 or raw.shape[-1] != self.dof:
            found = "a scalar" if raw.ndim == 0 else f"{raw.shape[-1]} (shape {raw.shape})"
            raise DimensionError(
                f"{name} must hold {self.dof} joint values for {self.name} "
                f"({self.joint_types}), got {found}"
            )
        return raw.astype(np.float64, copy=False)

    def to_convention(self, convention: str) -> Self:
        """The same robot written in another DH convention.

        Base and tool absorb the regrouped ``a``/``alpha`` so that ``fk(q)`` is
        unchanged for every ``q`` (the intermediate frames move; the end pose does not).
        """
        target = check_convention(convention)
        rows, base, tool = convert_table(self.links, self.convention, target, self.base, self.tool)
        transforms = self.transforms
        if transforms is not None:  # the same chain, seen from the new DH frames 0 and n
            transforms = transforms.rebased(
                (self.base, self.tool), (base, tool), dh_frames(rows, target)
            )
        return dataclasses.replace(
            self, links=rows, convention=target, base=base, tool=tool, transforms=transforms
        )

    def with_tool(self, tool: ArrayLike | None) -> Self:
        """The same robot with another tool transform (``(4, 4)`` or ``None``)."""
        return dataclasses.replace(self, tool=rigid_frame(tool, "tool"))

    def with_base(self, base: ArrayLike | None) -> Self:
        """The same robot with another base transform (``(4, 4)`` or ``None``)."""
        return dataclasses.replace(self, base=rigid_frame(base, "base"))

    def with_limits(self, qlim: Sequence[Sequence[float] | None] | FloatArray) -> Self:
        """The same robot with other joint limits (``(n, 2)``; ``None`` rows free)."""
        try:
            rows = list(qlim)
        except TypeError:  # a number, None: not rows
            raise DimensionError(
                f"qlim must have {self.dof} rows (lo, hi) or None, got {short(qlim)}"
            ) from None
        if len(rows) != self.dof:
            raise DimensionError(f"qlim must have {self.dof} rows, got {len(rows)}")
        # Each joint checks its own pair (two numbers lo < hi, or None).
        links = tuple(
            dataclasses.replace(link, qlim=lim) for link, lim in zip(self.links, rows, strict=True)
        )
        return dataclasses.replace(self, links=links)

    def __repr__(self) -> str:
        return f"Robot({self.name!r}, {self.joint_types}, convention={self.convention!r})"
