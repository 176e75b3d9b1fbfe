"""The robot: an immutable description of a serial arm and its kinematics.

A :class:`Robot` holds a DH table (standard or modified), joint limits and the
base and tool transforms. It has no state: ``robot.fk(q)`` is a pure function
of ``q``. All batch computations take ``q`` of shape ``(..., n)``.
"""

from __future__ import annotations

import dataclasses
import warnings
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.arguments import check_choice, check_flag
from kinematica.core import Chain
from kinematica.dh import (
    Convention,
    Joint,
    Prismatic,
    Revolute,
    check_convention,
    convert_table,
    given_convention,
    link_matrix,
)
from kinematica.errors import (
    DimensionError,
    KinematicaError,
    KinematicaWarning,
    LimitWarning,
    UnitWarning,
)
from kinematica.io.plausible import PLAUSIBLE_ANGLE, check_angle
from kinematica.robot.frames import rigid_frame, short
from kinematica.robot.save import write_robot_file
from kinematica.robot.transforms import ChainTransforms, dh_frames

# The IK layer and the DH rules load when a method first needs them: a robot that only
# answers FK (`kinematica fk`) never imports them.
if TYPE_CHECKING:
    import os

    from kinematica.ik import IKBatchResult, IKOptions, IKResult, Tolerance
    from kinematica.ik.direct import DirectParameter
    from kinematica.ik.parameter import Parameter
    from kinematica.ik.registry import TargetKind
    from kinematica.ik.solvers import PoseSolver
    from kinematica.io import RobotSpec
    from kinematica.robot.decoupling import Decoupling
    from kinematica.robot.dh_rules import DHExtraction
    from kinematica.robot.self_motion import SelfMotion

__all__ = ["Robot"]

FloatArray = NDArray[np.float64]
_FLOAT64 = np.dtype(np.float64)
#: Coordinates a pose fixes: an arm of more joints is redundant, and only such an arm's IK
#: needs the redundancy layer (kinematica.ik.redundancy), loaded for it alone.
_POSE_DOF = 6
#: The frames a Jacobian is expressed in.
_FRAMES = ("base", "tool", "spatial")
#: Where a position target is placed (the orientation is free).
_IDENTITY = np.eye(4)
#: What the core says of one configuration (kinematica._core.Chain.fk): QState in
#: cpp/include/kinematica/chain.hpp. Beyond a turn: a revolute joint with no limits of
#: its own beyond 2π (PLAUSIBLE_ANGLE), which batches check here.
_NOT_FINITE, _OUTSIDE_LIMITS, _BEYOND_TURN = 1, 2, 3
#: Rows of a batch read at a time when looking for the first configuration beyond the
#: limits (the core counts them; only the first is named).
_SCAN_ROWS = 4096
#: Configurations a warning of NaN/inf rows names (it says how many there are in all).
_SHOWN_ROWS = 5


@dataclass(frozen=True, eq=False)
class Robot:
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
    _fast_ik: dict[tuple[str, str], PoseSolver | None] = field(
        init=False, repr=False, compare=False, default_factory=dict
    )
    _turn: FloatArray | None = field(init=False, repr=False, compare=False)

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
    ) -> Robot:
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

    # ---------------------------------------------------------------- structure
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
        return np.array([link.qlim is not None for link in self.links], dtype=bool)

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

    # --------------------------------------------------------------- kinematics
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

    def _report(self, qa: FloatArray, name: str, bad: int, outside: int) -> None:
        """Raise or warn about configurations holding NaN/inf or beyond the limits."""
        if bad and qa.ndim == 1:
            index = int(np.flatnonzero(~np.isfinite(qa))[0])
            raise DimensionError(f"{name} holds NaN or inf at index ({index},)")
        if bad:
            rows = self._first_bad_rows(qa, _SHOWN_ROWS)
            shown = ", ".join(map(str, rows)) + (" ..." if bad > len(rows) else "")
            warnings.warn(
                f"{name}: {bad} row(s) hold NaN or inf, their results are NaN: {shown}",
                KinematicaWarning,
                stacklevel=3,
            )
        if outside:
            warnings.warn(self._limits_message(qa, name, outside), stacklevel=3)

    def _first_bad_rows(self, qa: FloatArray, count: int) -> list[tuple[int, ...]]:
        """The indices of the first ``count`` configurations holding NaN/inf.

        Read a block of rows at a time, and only as far as the ``count``-th: a batch of a
        million bad rows costs no more than one of a few (no Python object per row).
        """
        rows = qa.reshape(-1, self.dof)
        found: list[int] = []
        for start in range(0, len(rows), _SCAN_ROWS):
            block = rows[start : start + _SCAN_ROWS]
            hit = np.flatnonzero(~np.isfinite(block).all(axis=-1))[: count - len(found)]
            found += (start + hit).tolist()
            if len(found) == count:
                break
        return [tuple(int(i) for i in np.unravel_index(r, qa.shape[:-1])) for r in found]

    def _check_turns(self, qa: FloatArray, name: str = "q") -> None:
        """Warn (:class:`UnitWarning`) of a free revolute joint beyond a full turn."""
        if self._turn is None:
            return
        with np.errstate(invalid="ignore"):  # NaN and inf are reported apart
            beyond = (np.abs(qa) > self._turn) & np.isfinite(qa)
        if not beyond.any():
            return
        first = tuple(int(i) for i in np.argwhere(beyond)[0])
        where = f" (row {first[:-1]})" if qa.ndim > 1 else ""
        warnings.warn(
            f"{name}: joint {first[-1] + 1}{where} = {check_angle(float(qa[first]))}",
            UnitWarning,
            stacklevel=3,
        )

    def _limits_message(self, qa: FloatArray, name: str, count: int) -> KinematicaWarning:
        """Which joint of which configuration lies beyond its own limits, and how many do.

        ``count``: the configurations beyond their limits, as the core counted them.
        The first is looked for a block of rows at a time, so that a batch whose first
        rows are outside is not read whole.
        """
        own = self.has_limits
        lo, hi = self.qlim[:, 0], self.qlim[:, 1]
        more = f" ({count} configurations outside the limits)" if count > 1 else ""
        rows = qa.reshape(-1, self.dof)
        for start in range(0, len(rows), _SCAN_ROWS):
            block = rows[start : start + _SCAN_ROWS]
            beyond = own & ((block < lo) | (block > hi))
            hit = np.flatnonzero(beyond.any(axis=-1))
            if hit.size:
                row, j = start + int(hit[0]), int(np.flatnonzero(beyond[hit[0]])[0])
                break
        else:  # not expected: the core and this test read the same limits
            return KinematicaWarning(f"{name}: outside the joint limits{more}")
        index = tuple(int(i) for i in np.unravel_index(row, qa.shape[:-1])) if qa.ndim > 1 else ()
        where = f" in row {index}" if qa.ndim > 1 else ""
        return LimitWarning(
            name=name, joint=j, value=float(qa[(*index, j)]), limits=(float(lo[j]), float(hi[j])),
            prismatic=self.links[j].type == "P", where=where, more=more,
        )  # fmt: skip

    def fk(
        self, q: ArrayLike, all_frames: bool = False, *, workers: int | None = None
    ) -> FloatArray:
        """Forward kinematics: the tool pose in the base frame.

        Args:
            q: ``(..., n)`` joint values (rad for revolute, m for prismatic joints).
            all_frames: Return every frame ``0T0 (base), 0T1, ..., 0Tn (with tool)``.
            workers: Threads for a batch (None: the library default, see
                :func:`kinematica.core.resolve_workers`).

        A batch whose rows hold NaN/inf still returns the other rows; those
        rows come out NaN, with a :class:`KinematicaWarning` naming them. A
        single configuration with NaN/inf raises :class:`DimensionError`. A
        configuration beyond a joint's own limits is computed, with a
        :class:`KinematicaWarning` naming the joint and the limit; a revolute
        joint with no limits of its own beyond a full turn (2π rad), with a
        :class:`~kinematica.errors.UnitWarning` (degrees given for radians?).

        Returns:
            ``(..., 4, 4)`` pose ``T = base · 0A1 · ... · (n-1)An · tool``, or
            ``(..., n+1, 4, 4)`` with ``all_frames``.
        """
        if all_frames is not False and all_frames is not True:
            all_frames = check_flag(all_frames, "all_frames")
        qa = q if type(q) is np.ndarray and q.dtype is _FLOAT64 else self.check_q(q)
        if qa.shape == self._single:
            try:  # one configuration, already what the core reads: one call
                T, state = self._fk_one(qa) if not all_frames else self.chain.core.fk_frames(qa)
            except ValueError:  # not contiguous: the general path copies it
                pass
            else:
                if state == _BEYOND_TURN:
                    self._check_turns(qa)
                elif state:
                    self._report(qa, "q", state == _NOT_FINITE, state == _OUTSIDE_LIMITS)
                return T
        qa = self.check_q(qa)
        out, bad, outside, turns = self.chain.fk(qa, all_frames, workers)
        if bad or outside:
            self._report(qa, "q", bad, outside)
        if turns:
            self._check_turns(qa)
        return out

    def link_matrices(self, q: ArrayLike) -> FloatArray:
        """The link matrices ``i-1Ai`` of the DH table (no base, no tool).

        Args:
            q: ``(..., n)`` joint values.

        Returns:
            ``(..., n, 4, 4)``; their product is ``base⁻¹ · T · tool⁻¹``.
        """
        qa = self.check_q(q)
        bad = ~np.all(np.isfinite(qa), axis=-1)
        if bad.any():
            self._report(qa, "q", int(bad.sum()), 0)
            qa = np.where(bad[..., None], 0.0, qa)
        prismatic = self.chain.prismatic
        theta0 = np.array([link.theta for link in self.links])
        d0 = np.array([link.d for link in self.links])
        a = np.array([link.a for link in self.links])
        alpha = np.array([link.alpha for link in self.links])
        theta = np.where(prismatic, theta0, qa + theta0)
        d = np.where(prismatic, qa + d0, d0)
        A = link_matrix(theta, d, np.broadcast_to(a, theta.shape), alpha, self.convention)
        if bad.any():
            A[bad] = np.nan
        return A

    def jacobian(
        self,
        q: ArrayLike,
        frame: Literal["base", "tool", "spatial"] = "base",
        euler: str | None = None,
        *,
        workers: int | None = None,
    ) -> FloatArray:
        """Geometric Jacobian of the tool, or the analytic Jacobian of its pose.

        Rows 0-2 map joint rates to the linear velocity of the tool origin, rows
        3-5 to the angular velocity, both expressed in the base frame
        (``frame="base"``) or in the tool frame (``frame="tool"``, the body
        Jacobian). Column i is ``[z × (p - o); z]`` for a revolute joint with
        axis ``z`` through ``o``, ``[z; 0]`` for a prismatic one.
        ``frame="spatial"``: the spatial (world) Jacobian, rows 0-2 the velocity
        of the body point at the base origin, ``ṗ + p × ω`` (column i
        ``[o × z; z]``); see :func:`kinematica.robot.differential.spatial_from_base`.

        With ``euler`` (e.g. ``"ZYZ"``): the analytic Jacobian of the pose
        ``(x, y, z, a, b, c)`` instead, base frame only; NaN rotation rows in
        gimbal lock. See :func:`kinematica.robot.velocity.analytic_jacobian`.
        ``euler="exp"``: the rates of the position and the rotation vector
        (exponential coordinates), :func:`kinematica.robot.differential.exp_jacobian`.

        Args:
            q: ``(..., n)`` joint values.
            frame: ``"base"``, ``"tool"`` or ``"spatial"``.
            euler: An Euler sequence or ``"exp"`` for the analytic Jacobian, or None.
            workers: Threads for a batch (None: the library default).

        Returns:
            ``(..., 6, n)`` (m/rad or m/m in the top rows, rad/rad below); rows
            of a batch holding NaN/inf come out NaN, with a warning.
        """
        if frame.__class__ is not str or frame not in _FRAMES:  # the common case costs ~30 ns
            check_choice(frame, "frame", _FRAMES)
        if euler is not None:
            if frame != "base":
                raise KinematicaError(
                    "euler gives the analytic Jacobian of the pose in the base frame; "
                    f"the {frame} frame does not apply to it",
                    arg="euler",
                )
            from kinematica.robot.velocity import analytic_jacobian

            return analytic_jacobian(self, q, euler)
        if frame == "spatial":
            from kinematica.robot.differential import spatial_from_base

            return spatial_from_base(self.jacobian(q, workers=workers), self.fk(q)[..., :3, 3])
        qa = q if type(q) is np.ndarray and q.dtype is _FLOAT64 else self.check_q(q)
        if qa.shape == self._single:
            try:
                J, state = self._jacobian_one(qa, frame == "tool")
            except ValueError:  # not contiguous: the general path copies it
                pass
            else:
                if state == _NOT_FINITE:
                    self._report(qa, "q", 1, 0)
                elif state == _BEYOND_TURN:
                    self._check_turns(qa)
                return J
        qa = self.check_q(qa)
        J, bad, turns = self.chain.jacobian(qa, frame == "tool", workers)
        if bad:
            self._report(qa, "q", bad, 0)
        if turns:
            self._check_turns(qa)
        return J

    def joint_axes(self, q: ArrayLike | None = None) -> tuple[FloatArray, FloatArray]:
        """Each joint's axis as a line in the base frame.

        Args:
            q: ``(..., n)`` joint values; zeros if ``None``.

        Returns:
            ``(directions, points)``, each ``(..., n, 3)``: unit axis directions
            and one point on each axis (metres, base frame).
        """
        qa = np.zeros(self.dof) if q is None else self.check_q(q)
        if qa.ndim == 1 and not np.all(np.isfinite(qa)):
            self._report(qa, "q", 1, 0)
        axes = self.chain.joint_axes(qa)
        return axes[..., :3], axes[..., 3:]

    def ik(
        self,
        target: ArrayLike,
        *,
        method: Literal["auto", "analytic", "numeric"] = "auto",
        respect_limits: bool = True,
        q0: ArrayLike | None = None,
        mask: ArrayLike | None = None,
        seed: int | np.random.Generator | None = None,
        tol: float | tuple[float, float] | Tolerance | None = None,
        workers: int | None = None,
        precision: tuple[float, float] | None = None,
        fixed: Mapping[int | str, float] | None = None,
        arm_angle: ArrayLike | None = None,
        options: IKOptions | None = None,
    ) -> IKResult | IKBatchResult:
        """Every inverse-kinematics solution of a target, or an honest status.

        Args:
            target: A pose ``(4, 4)`` (tool in the base frame), a position
                ``(3,)`` (tool origin; orientation free), or batches of any
                shape ``(..., 4, 4)`` / ``(..., 3)``. A rotation orthonormal
                to within ``PROJECTION_TOL`` (2e-4: any copy with 4 decimals)
                is projected onto SO(3), with a note in the result.
            method: ``"auto"`` (closed form when the structure allows, else
                numeric, with a note saying why), ``"analytic"`` or ``"numeric"``.
                The numeric search is local: it gives one solution, where more may
                exist (``complete`` False).
            respect_limits: Keep solutions outside the joint limits apart
                (``out_of_limits``) rather than among ``solutions``.
            q0: ``(n,)`` or ``(..., n)``: the numeric initial guess, and the
                configuration solutions are sorted by distance to.
            mask: ``(6,)`` weights of the error components x, y, z, rx, ry, rz
                (numeric only); e.g. ``[1, 1, 1, 0, 0, 1]``.
            seed: Seed of the numeric restarts (a whole number or a Generator).
            tol: Acceptance tolerance: one number for both, or a pair
                (position m, rotation rad); default 1e-10 m and 1e-10 rad.
            workers: Threads for a batch (None: the library default).
            precision: For a pose target of an arm with fewer than 6 joints
                (over-determined): ``(position m, rotation entries)``, half a
                unit in the last digit its numbers were printed with; None: read
                from their digits. The closest configuration answers a target
                it reproduces to that precision (a note says which was assumed).
            fixed: ``{joint: value}``: every solution with that joint held at the
                value (rad or m; the joint by its 0-based index, its name, or
                ``"qN"``); the status is relative to it and ``result.parameter``
                names it. A value outside the joint's limits is an error unless
                ``respect_limits=False``. Without it, ``method="auto"`` on a
                7-joint arm holds a joint whose locked arm has a closed form (at
                q0's value, else the middle of its limits) and says which; see
                :mod:`kinematica.ik.redundancy`.
            arm_angle: For an SRS 7R arm (iiwa type): the arm angle (rad) of the
                solutions, one value or one per target; all 8 solutions at it
                (see :mod:`kinematica.ik.analytic.srs` and :meth:`arm_angle`).
            options: All of the above as one :class:`~kinematica.ik.IKOptions`
                (then give none of them as keywords).

        Returns:
            An :class:`IKResult` for one target, an :class:`IKBatchResult`
            (arrays with the targets' batch shape) for a batch. In a batch, a
            malformed target gets the status ``"invalid"``; the others are solved.
        """
        given = (q0, fixed, arm_angle)
        if options is not None and hasattr(options, "q0"):
            given = (options.q0, options.fixed, options.arm_angle)
        if given[0] is not None or given[1] is not None or given[2] is not None:
            from kinematica.robot.given import check_given  # degrees given for radians?

            check_given(self, *given)
        if (
            options is None
            and type(target) is np.ndarray
            and target.dtype is _FLOAT64
            and method.__class__ is str
            and (method == "auto" or method == "numeric")
            and respect_limits is True
            and tol is None
            and q0 is None
            and mask is None
            and seed is None
            and workers is None
            and precision is None
        ):  # one target, every default: straight to the core (a rigid target to round-off)
            out: IKResult | None = None
            try:
                if fixed is None and arm_angle is None:
                    if target.shape == (4, 4):
                        out = self._fast(target, "pose", method)
                    elif target.shape == (3,):
                        pose = _IDENTITY.copy()
                        pose[0, 3], pose[1, 3], pose[2, 3] = target.tolist()
                        out = self._fast(pose, "position", method)
                elif method == "auto" and target.shape == (4, 4):
                    # one pose at one value of a redundant arm's parameter
                    if arm_angle is None:
                        out = self._direct.fixed(target, fixed)
                    elif fixed is None:
                        out = self._direct.arm_angle(target, arm_angle)
            except ValueError:  # a view the core does not read (not C-contiguous): copied below
                out = None
            if out is not None:
                return out
        from kinematica.ik.options import IKOptions

        if options is None:
            options = IKOptions(
                method, tol, respect_limits, q0, mask, seed, workers, precision, fixed, arm_angle
            )
        elif not isinstance(options, IKOptions):
            raise KinematicaError(
                f"options must be an IKOptions, got {type(options).__name__}", arg="options"
            )
        elif not (
            isinstance(method, str)
            and method == "auto"
            and respect_limits is True
            and all(v is None for v in (tol, q0, mask, seed, workers, precision, fixed, arm_angle))
        ):
            raise KinematicaError(
                "give the IK settings either as options= or as keywords, not both",
                arg="options",
            )
        check_choice(options.method, "method", ("auto", "analytic", "numeric"))
        check_flag(options.respect_limits, "respect_limits")
        if options.fixed is None and options.arm_angle is None and not self._holds(options):
            # no joint to hold: solve_arm would hand the target to solve_ik, as here, with
            # the redundancy layer loaded for nothing
            from kinematica.ik.solve import solve_ik

            return solve_ik(self.chain, target, options)
        from kinematica.ik.redundancy import solve_arm

        return solve_arm(self.chain, target, options, self.joint_names)

    def arm_angle(self, q: ArrayLike) -> FloatArray:
        """The arm angle (rad) of configurations of an SRS 7R arm (iiwa type).

        The parameter of ``ik(T, arm_angle=...)``: the angle about the line from
        the shoulder centre to the wrist centre from the plane through that line
        and axis 1 to the plane of the elbow (:mod:`kinematica.ik.analytic.srs`).

        Args:
            q: ``(..., 7)`` joint angles (rad).

        Returns:
            ``(...)`` angles in (-π, π]; NaN where undefined (the elbow stretched
            or folded onto the shoulder-wrist line, or that line along axis 1).

        Raises:
            KinematicaError: The arm is not an SRS 7R arm.
        """
        from kinematica.ik.analytic.srs import arm_angle

        return arm_angle(self.chain, self.check_q(q))

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

    @cached_property
    def _direct(self) -> DirectParameter:
        """The one-pose paths at one value of a redundant arm's parameter."""
        from kinematica.ik.direct import DirectParameter

        return DirectParameter(self.chain, self.joint_names)

    def _holds(self, options: IKOptions) -> bool:
        """True when ``auto`` may hold a joint of this arm (a redundant arm's pose targets).

        :func:`~kinematica.ik.redundancy.solve_arm`'s own test, made without loading
        the redundancy layer: ``auto`` without a mask, and one joint more than a pose fixes.
        """
        return options.method == "auto" and options.mask is None and self.dof == _POSE_DOF + 1

    def _fast(
        self, pose: FloatArray, kind: TargetKind, method: Literal["auto", "numeric"]
    ) -> IKResult | None:
        """``ik`` of one rigid target with every default; None: the general path explains it."""
        key = (kind, method)
        if key in self._fast_ik:
            fast = self._fast_ik[key]
        else:
            fast = None  # a redundant arm solved at a parameter: no solver of its own
            if (
                method == "numeric"
                or kind != "pose"
                or self.dof != _POSE_DOF + 1
                or not self._at_parameter()
            ):
                from kinematica.ik.solvers import pose_solver

                fast = pose_solver(self.chain, kind, method=method)
            self._fast_ik[key] = fast
        if fast is None:  # at auto's parameter value, else the general path
            return self._direct.auto(pose)
        if not fast.direct:
            return None  # the general path completes or explains it
        return fast.rigid(self.chain.core, pose)  # None: the general path explains it

    def _at_parameter(self) -> bool:
        """True when ``auto`` holds a parameter of this (redundant) arm for a pose target."""
        from kinematica.ik.redundancy import choose

        return choose(self.chain) is not None

    # ------------------------------------------------------------ derived models
    def to_convention(self, convention: str) -> Robot:
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

    def with_tool(self, tool: ArrayLike | None) -> Robot:
        """The same robot with another tool transform (``(4, 4)`` or ``None``)."""
        return dataclasses.replace(self, tool=rigid_frame(tool, "tool"))

    def with_base(self, base: ArrayLike | None) -> Robot:
        """The same robot with another base transform (``(4, 4)`` or ``None``)."""
        return dataclasses.replace(self, base=rigid_frame(base, "base"))

    def with_limits(self, qlim: Sequence[Sequence[float] | None] | FloatArray) -> Robot:
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

    def _repr_html_(self) -> str:
        """The DH table with units and limits, as HTML (Jupyter)."""
        from kinematica.robot.display import robot_html

        return robot_html(self)

    def save(self, path: str | os.PathLike[str]) -> None:
        """Write this robot as a robot file; see :func:`kinematica.write_robot_file`."""
        write_robot_file(self, path)

    # ---------------------------------------------------------------- URDF, DH rules
    def to_dh(self, convention: str = "standard") -> DHExtraction:
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

    # ------------------------------------------- motion (thin, over kinematica.motion)
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
