"""The robot: an immutable description of a serial arm and its kinematics.

A :class:`Robot` holds a DH table (standard or modified), joint limits and the
base and tool transforms. It has no state: ``robot.fk(q)`` is a pure function
of ``q``. All batch computations take ``q`` of shape ``(..., n)``.
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from numbers import Real
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.dh import (
    Convention,
    DHChain,
    Joint,
    Prismatic,
    Revolute,
    check_convention,
    convert_table,
    link_matrix,
)
from kinematica.errors import DimensionError, KinematicaError, KinematicaWarning
from kinematica.robot.jacobian import jacobian

if TYPE_CHECKING:
    import os

    from kinematica.ik.result import IKBatchResult, IKResult
    from kinematica.io import RobotSpec
    from kinematica.robot.urdf import DHExtraction

__all__ = ["Robot"]

FloatArray = NDArray[np.float64]

#: Tolerance on a base/tool rotation part being orthonormal with det +1.
FRAME_TOL = 1e-9


def _check_frame(T: ArrayLike | None, what: str) -> FloatArray:
    if T is None:
        return np.eye(4)
    raw = np.asarray(T)
    if raw.dtype.kind not in "iuf":
        raise DimensionError(f"{what} must be a 4x4 matrix of real numbers, got {T!r}")
    M = np.array(raw, dtype=float)
    if M.shape != (4, 4):
        raise DimensionError(f"{what} must be a 4x4 homogeneous transform, got shape {M.shape}")
    if not np.all(np.isfinite(M)):
        raise DimensionError(f"{what} holds NaN or inf")
    if not np.allclose(M[3], [0.0, 0.0, 0.0, 1.0], atol=FRAME_TOL):
        raise DimensionError(f"{what} last row must be [0, 0, 0, 1], got {M[3].tolist()}")
    R = M[:3, :3]
    err = float(np.abs(R.T @ R - np.eye(3)).max())
    if err > FRAME_TOL or np.linalg.det(R) < 0:
        raise DimensionError(
            f"{what} rotation part is not a proper rotation (|RᵀR - I| = {err:.1e})"
        )
    M[3] = [0.0, 0.0, 0.0, 1.0]
    return M


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
        source_spec: The description the robot was read from (robot file or
            built-in model), or ``None``; :meth:`save` writes it back as it
            was written, for every part that still describes this robot.
    """

    links: tuple[Joint, ...]
    convention: Convention = "standard"
    name: str = "robot"
    base: FloatArray = field(default_factory=lambda: np.eye(4))
    tool: FloatArray = field(default_factory=lambda: np.eye(4))
    description: str | None = None
    _chain: DHChain = field(init=False, repr=False)
    source_spec: RobotSpec | None = field(default=None, compare=False, repr=False)

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
        base = _check_frame(self.base, "base")
        tool = _check_frame(self.tool, "tool")
        base.flags.writeable = False
        tool.flags.writeable = False
        object.__setattr__(self, "base", base)
        object.__setattr__(self, "tool", tool)
        object.__setattr__(self, "_chain", DHChain.from_joints(links, self.convention, base, tool))

    @classmethod
    def from_dh(
        cls,
        rows: Iterable[Joint],
        *,
        convention: str = "standard",
        name: str = "robot",
        base: ArrayLike | None = None,
        tool: ArrayLike | None = None,
        description: str | None = None,
    ) -> Robot:
        """A robot from its DH rows.

        Args:
            rows: ``Revolute(d=, a=, alpha=, offset=, qlim=)`` and
                ``Prismatic(theta=, a=, alpha=, offset=, qlim=)`` rows, base to tip.
            convention: ``"standard"`` or ``"modified"`` (aliases accepted).
            name: Display name.
            base: ``(4, 4)`` pose of frame 0 in the world frame; identity if ``None``.
            tool: ``(4, 4)`` pose of the tool in frame n; identity if ``None``.
            description: Free text.

        Returns:
            The robot.
        """
        return cls(
            links=tuple(rows),
            convention=check_convention(convention),
            name=name,
            base=_check_frame(base, "base"),
            tool=_check_frame(tool, "tool"),
            description=description,
        )

    # ---------------------------------------------------------------- structure
    @property
    def dof(self) -> int:
        """Number of joints n."""
        return len(self.links)

    @property
    def joint_types(self) -> str:
        """One letter per joint, e.g. ``"RRPRRR"``."""
        return "".join(link.type for link in self.links)

    @property
    def is_prismatic(self) -> NDArray[np.bool_]:
        """``(n,)`` True where the joint is prismatic."""
        return self._chain.prismatic.copy()

    @property
    def qlim(self) -> FloatArray:
        """``(n, 2)`` joint limits: ``(-π, π)`` for free revolute joints, ±inf for prismatic."""
        rows = []
        for link in self.links:
            if link.qlim is not None:
                rows.append(link.qlim)
            elif isinstance(link, Revolute):
                rows.append((-math.pi, math.pi))
            else:
                rows.append((-math.inf, math.inf))
        return np.array(rows, dtype=float)

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
    def check_q(self, q: ArrayLike, name: str = "q", *, bad_rows: bool = False) -> FloatArray:
        """Validate joint values: shape ``(..., n)``, finite real numbers.

        Args:
            q: ``(..., n)`` joint values.
            name: Name used in messages.
            bad_rows: For a batch, let rows holding NaN/inf through with a
                :class:`KinematicaWarning` naming them (their results are NaN)
                instead of raising.

        Raises:
            DimensionError: On a wrong last dimension, non-numbers, NaN or inf
                in a single configuration (or in a batch without ``bad_rows``).
        """
        try:
            raw = np.asarray(q)
        except (TypeError, ValueError) as exc:
            raise DimensionError(f"{name} must be numbers, got {q!r}") from exc
        if raw.dtype.kind not in "iuf":
            raise DimensionError(f"{name} must be numbers, got {q!r}")
        qa = raw.astype(float, copy=False)
        if qa.ndim == 0 or qa.shape[-1] != self.dof:
            found = "a scalar" if qa.ndim == 0 else f"{qa.shape[-1]} (shape {qa.shape})"
            raise DimensionError(
                f"{name} must hold {self.dof} joint values for {self.name} "
                f"({self.joint_types}), got {found}"
            )
        finite = np.isfinite(qa)
        if not finite.all():
            if bad_rows and qa.ndim >= 2:
                rows = [tuple(int(i) for i in r) for r in np.argwhere(~finite.all(axis=-1))]
                shown = ", ".join(map(str, rows[:5])) + (" ..." if len(rows) > 5 else "")
                warnings.warn(
                    f"{name}: {len(rows)} row(s) hold NaN or inf, their results are NaN: {shown}",
                    KinematicaWarning,
                    stacklevel=4,
                )
                return qa
            bad = np.argwhere(~finite)[0]
            raise DimensionError(f"{name} holds NaN or inf at index {tuple(int(i) for i in bad)}")
        return qa

    def _batch(self, q: ArrayLike) -> tuple[FloatArray, NDArray[np.bool_] | None]:
        """Validated ``q`` with unusable rows zeroed, and the mask of those rows."""
        qa = self.check_q(q, bad_rows=True)
        bad = ~np.all(np.isfinite(qa), axis=-1)
        if not bad.any():
            return qa, None
        return np.where(bad[..., None], 0.0, qa), bad

    def _single_q(self, q: ArrayLike) -> list[float] | None:
        """``q`` as a list of finite floats when it is one configuration, else None.

        The single-configuration fast path: checking a short list in Python costs
        far less than numpy's per-call overhead.
        """
        if isinstance(q, np.ndarray):
            if q.shape != (self.dof,) or q.dtype.kind not in "fiu":
                return None
            values = q.tolist()
        elif isinstance(q, list | tuple) and len(q) == self.dof:
            values = list(q)
            if not all(isinstance(v, Real) and not isinstance(v, bool) for v in values):
                return None
        else:
            return None
        floats = [float(v) for v in values]
        return floats if all(math.isfinite(v) for v in floats) else None

    def fk(self, q: ArrayLike, all_frames: bool = False) -> FloatArray:
        """Forward kinematics: the tool pose in the base frame.

        Args:
            q: ``(..., n)`` joint values (rad for revolute, m for prismatic joints).
            all_frames: Return every frame ``0T0 (base), 0T1, ..., 0Tn (with tool)``.

        A batch whose rows hold NaN/inf still returns the other rows; those
        rows come out NaN, with a :class:`KinematicaWarning` naming them. A
        single configuration with NaN/inf raises :class:`DimensionError`.

        Returns:
            ``(..., 4, 4)`` pose ``T = base · 0A1 · ... · (n-1)An · tool``, or
            ``(..., n+1, 4, 4)`` with ``all_frames``.
        """
        if not all_frames:
            single = self._single_q(q)
            if single is not None:
                return self._chain.fk_single(single)
        qa, bad = self._batch(q)
        flat = qa.reshape(-1, self.dof)
        out = self._chain.fk_batch(flat, all_frames)
        out = out.reshape(*qa.shape[:-1], *out.shape[1:])
        if bad is not None:
            out[bad] = np.nan
        return out

    def link_matrices(self, q: ArrayLike) -> FloatArray:
        """The link matrices ``i-1Ai`` of the DH table (no base, no tool).

        Args:
            q: ``(..., n)`` joint values.

        Returns:
            ``(..., n, 4, 4)``; their product is ``base⁻¹ · T · tool⁻¹``.
        """
        qa, bad = self._batch(q)
        prismatic = self._chain.prismatic
        theta0 = np.array([link.theta for link in self.links])
        d0 = np.array([link.d for link in self.links])
        a = np.array([link.a for link in self.links])
        alpha = np.array([link.alpha for link in self.links])
        theta = np.where(prismatic, theta0, qa + theta0)
        d = np.where(prismatic, qa + d0, d0)
        A = link_matrix(theta, d, np.broadcast_to(a, theta.shape), alpha, self.convention)
        if bad is not None:
            A[bad] = np.nan
        return A

    def jacobian(
        self, q: ArrayLike, frame: Literal["base", "tool"] = "base", euler: str | None = None
    ) -> FloatArray:
        """Geometric Jacobian ``(..., 6, n)`` of the tool; see :func:`jacobian`.

        With ``euler`` (e.g. ``"ZYZ"``): the analytic Jacobian of the pose
        ``(x, y, z, a, b, c)`` instead, base frame only; NaN rotation rows in
        gimbal lock. See :func:`kinematica.motion.analytic_jacobian`.
        """
        if euler is not None:
            if frame != "base":
                raise KinematicaError(
                    "euler= gives the analytic Jacobian of the pose in the base frame; "
                    f"frame={frame!r} does not apply to it"
                )
            from kinematica.motion.velocity import analytic_jacobian

            return analytic_jacobian(self, q, euler)
        return jacobian(self, q, frame)

    def joint_axes(self, q: ArrayLike | None = None) -> tuple[FloatArray, FloatArray]:
        """Each joint's axis as a line in the base frame.

        Args:
            q: ``(..., n)`` joint values; zeros if ``None``.

        Returns:
            ``(directions, points)``, each ``(..., n, 3)``: unit axis directions
            and one point on each axis (metres, base frame).
        """
        qa = np.zeros(self.dof) if q is None else self.check_q(q)
        F = self._chain.joint_frames(qa.reshape(-1, self.dof))[:, : self.dof]
        shape = (*qa.shape[:-1], self.dof, 3)
        return F[..., :3, 2].reshape(shape), F[..., :3, 3].reshape(shape)

    def ik(
        self,
        target: ArrayLike,
        *,
        method: Literal["auto", "analytic", "numeric"] = "auto",
        respect_limits: bool = True,
        q0: ArrayLike | None = None,
        mask: ArrayLike | None = None,
        seed: int | np.random.Generator | None = None,
    ) -> IKResult | IKBatchResult:
        """Every IK solution of a target; see :func:`kinematica.ik.solve_ik`.

        A pose ``(4, 4)`` or position ``(3,)`` gives an ``IKResult``; batches
        ``(N, 4, 4)`` / ``(N, 3)`` give an ``IKBatchResult``. (The one upward
        reference of this layer: a thin method over the ``ik`` layer, imported
        when called.)
        """
        from kinematica.ik.solve import solve_ik

        return solve_ik(
            self, target, method=method, respect_limits=respect_limits, q0=q0, mask=mask, seed=seed
        )

    # ------------------------------------------------------------ derived models
    def to_convention(self, convention: str) -> Robot:
        """The same robot written in another DH convention.

        Base and tool absorb the regrouped ``a``/``alpha`` so that ``fk(q)`` is
        unchanged for every ``q`` (the intermediate frames move, as seed 001 says).
        """
        target = check_convention(convention)
        rows, base, tool = convert_table(self.links, self.convention, target, self.base, self.tool)
        return dataclasses.replace(self, links=rows, convention=target, base=base, tool=tool)

    def with_tool(self, tool: ArrayLike | None) -> Robot:
        """The same robot with another tool transform (``(4, 4)`` or ``None``)."""
        return dataclasses.replace(self, tool=_check_frame(tool, "tool"))

    def with_base(self, base: ArrayLike | None) -> Robot:
        """The same robot with another base transform (``(4, 4)`` or ``None``)."""
        return dataclasses.replace(self, base=_check_frame(base, "base"))

    def with_limits(self, qlim: Sequence[Sequence[float] | None] | FloatArray) -> Robot:
        """The same robot with other joint limits (``(n, 2)``; ``None`` rows free)."""
        rows = list(qlim)
        if len(rows) != self.dof:
            raise DimensionError(f"qlim must have {self.dof} rows, got {len(rows)}")

        def pair(lim: Sequence[float] | FloatArray | None) -> tuple[float, float] | None:
            if lim is None:
                return None
            lo, hi = (float(v) for v in lim)
            return (lo, hi)

        links = tuple(
            dataclasses.replace(link, qlim=pair(lim))
            for link, lim in zip(self.links, rows, strict=True)
        )
        return dataclasses.replace(self, links=links)

    def __repr__(self) -> str:
        return f"Robot({self.name!r}, {self.joint_types}, convention={self.convention!r})"

    def save(self, path: str | os.PathLike[str]) -> None:
        """Write this robot as a robot file; see :func:`kinematica.write_robot_file`."""
        from kinematica.robot.load import write_robot_file

        write_robot_file(self, path)

    # ---------------------------------------------------------------- URDF, DH rules
    def to_dh(self, convention: str = "standard") -> DHExtraction:
        """The DH table read off this robot's joint axes by the rules of seed 000.

        In the robot's own convention it gives back the same rows; in the
        other, the frames the rules place. See :func:`kinematica.urdf_to_dh`.

        Returns:
            A ``DHExtraction``: ``.robot``, ``.rules`` (which rule placed each
            frame), ``.fk_error``.
        """
        from kinematica.robot.urdf import to_dh

        return to_dh(self, convention)

    def to_urdf(self, path: str | os.PathLike[str] | None = None) -> str:
        """The robot as URDF text (each link frame a DH frame), written to ``path`` if given."""
        from kinematica.robot.urdf import to_urdf

        return to_urdf(self, path)

    # ------------------------------------------- motion (thin, over kinematica.motion)
    def singularities(self, q: ArrayLike, detail: bool = False) -> Any:
        """Names of the singularities at ``q`` (``[]`` when regular).

        See :func:`kinematica.motion.singularities` (imported when called:
        the motion layer sits above this one).
        """
        from kinematica.motion.singularities import singularities

        return singularities(self, q, detail=detail)

    def random_q(
        self, n: int | tuple[int, ...] = 1, seed: int | np.random.Generator | None = None
    ) -> FloatArray:
        """``(n, dof)`` configurations drawn uniformly within the joint limits.

        See :func:`kinematica.motion.random_q`.
        """
        from kinematica.motion.sampling import random_q

        return random_q(self, n, seed=seed)
