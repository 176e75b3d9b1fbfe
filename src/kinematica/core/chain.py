"""A chain compiled for the core, and its forward kinematics, Jacobians and joint axes.

The core's chain is general: each joint is a fixed transform followed by a
rotation about, or a translation along, its z axis. A DH table of either
convention compiles to it exactly (:meth:`Chain.from_dh`), and so do the joints
of a URDF (:meth:`Chain.from_transforms`): the same walk serves both. The
entry points take joint values already validated as floats of shape ``(..., n)``
(the robot layer checks and explains bad input), flatten any batch shape, call
the core once, and restore the batch shape.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

import kinematica._core as _core
from kinematica.core.workers import resolve_workers
from kinematica.dh.joints import Convention, Joint, Prismatic, check_convention

__all__ = ["Chain"]

FloatArray = NDArray[np.float64]
BoolArray = NDArray[np.bool_]

#: What the core says of one configuration (kinematica._core.Chain.fk): QState in
#: cpp/include/kinematica/chain.hpp.
_NOT_FINITE, _OUTSIDE_LIMITS, _BEYOND_TURN = 1, 2, 3
_FLOAT64 = np.dtype(np.float64)


def _counts(state: int) -> tuple[int, int, int]:
    """``(bad, outside, turns)`` of one configuration from its core state."""
    return int(state == _NOT_FINITE), int(state == _OUTSIDE_LIMITS), int(state == _BEYOND_TURN)


def _readonly(a: NDArray[np.generic]) -> NDArray[np.generic]:
    a.flags.writeable = False
    return a


@dataclass(frozen=True, eq=False)
class Chain:
    """A serial chain compiled for the core.

    Attributes:
        core: The compiled chain (:class:`kinematica._core.Chain`).
        prismatic: ``(n,)`` True for prismatic joints.
        own_limits: ``(n, 2)`` each joint's own limits (rad or m), ``±inf`` where
            it has none.
        start: ``(4, 4)`` the transform before the first joint's motion (base frame).
        tool: ``(4, 4)`` the transform after the last joint's part.
        translations: ``(n, 3)`` the translation of each joint's fixed part in its
            own frame (m): a DH row's ``(a, 0, d)`` (see ``cpp/include/kinematica/chain.hpp``).
    """

    core: _core.Chain
    prismatic: BoolArray
    own_limits: FloatArray
    start: FloatArray
    tool: FloatArray
    translations: FloatArray

    @classmethod
    def from_dh(
        cls,
        joints: Sequence[Joint],
        convention: Convention,
        base: FloatArray,
        tool: FloatArray,
    ) -> Chain:
        """Compile a DH table with its base and tool transforms.

        Args:
            joints: The rows, base to tip.
            convention: ``"standard"`` or ``"modified"``.
            base: ``(4, 4)`` pose of frame 0 in the world (base) frame.
            tool: ``(4, 4)`` pose of the tool in frame n.
        """
        conv = check_convention(convention)
        prismatic = np.array([isinstance(j, Prismatic) for j in joints], dtype=bool)
        lims = np.array(
            [j.qlim if j.qlim is not None else (-math.inf, math.inf) for j in joints], dtype=float
        ).reshape(len(joints), 2)
        core = _core.Chain.from_dh(
            prismatic,
            np.array([j.theta for j in joints], dtype=float),
            np.array([j.d for j in joints], dtype=float),
            np.array([j.a for j in joints], dtype=float),
            np.array([j.alpha for j in joints], dtype=float),
            np.ascontiguousarray(lims[:, 0]),
            np.ascontiguousarray(lims[:, 1]),
            conv == "modified",
            np.asarray(base, dtype=float),
            np.asarray(tool, dtype=float),
        )
        return cls._of(core, prismatic, lims)

    @classmethod
    def from_transforms(
        cls,
        start: FloatArray,
        between: FloatArray,
        tool: FloatArray,
        frame_offsets: FloatArray,
        prismatic: BoolArray,
        own_limits: FloatArray,
        base: FloatArray,
    ) -> Chain:
        """Compile a chain of general transforms (the joints of a URDF).

        Args:
            start: ``(4, 4)`` the transform before the first joint's motion, in the
                base frame.
            between: ``(n - 1, 4, 4)`` the fixed transforms between motions.
            tool: ``(4, 4)`` the transform after the last motion.
            frame_offsets: ``(n, 4, 4)``: frame i of ``fk(all_frames=True)`` is
                the frame right after motion i times ``frame_offsets[i]``.
            prismatic: ``(n,)`` True for joints that slide along their z axis.
            own_limits: ``(n, 2)`` the joints' limits (``±inf`` where none).
            base: ``(4, 4)`` frame 0 of ``fk(all_frames=True)``.
        """
        prism = np.ascontiguousarray(prismatic, dtype=bool)
        lims = np.array(own_limits, dtype=float).reshape(len(prism), 2)
        core = _core.Chain.from_transforms(
            np.asarray(start, dtype=float),
            np.ascontiguousarray(between, dtype=float),
            np.asarray(tool, dtype=float),
            np.ascontiguousarray(frame_offsets, dtype=float),
            prism,
            np.ascontiguousarray(lims[:, 0]),
            np.ascontiguousarray(lims[:, 1]),
            np.asarray(base, dtype=float),
        )
        return cls._of(core, prism, lims)

    @classmethod
    def _of(cls, core: _core.Chain, prismatic: BoolArray, lims: FloatArray) -> Chain:
        return cls(
            core=core,
            prismatic=_readonly(prismatic.copy()),  # type: ignore[arg-type]
            own_limits=_readonly(lims.copy()),  # type: ignore[arg-type]
            start=_readonly(np.asarray(core.start)),  # type: ignore[arg-type]
            tool=_readonly(np.asarray(core.tool)),  # type: ignore[arg-type]
            translations=_readonly(np.asarray(core.translations)),  # type: ignore[arg-type]
        )

    def reversed(self) -> Chain:
        """The chain of the inverse transform: joints in reverse order, variables negated.

        With ``T(q) = start · Π_i [M_i(q_i) F_i] · tool`` (``F_i`` the joints'
        :attr:`fixed_parts`),

            T(q)⁻¹ = (tool⁻¹ F_n⁻¹) · M_n(-q_n) F_(n-1)⁻¹ ··· M_2(-q_2) F_1⁻¹ · M_1(-q_1) · start⁻¹

        (a joint's motion inverted is its motion by -q_i), so the reversed chain's
        ``fk(q')`` at ``q'_j = -q_(n+1-j)`` is ``fk(q)⁻¹``, built from the chain's
        own transforms (no DH table is re-read). Its limits are the joints' own
        mapped likewise (``[-hi, -lo]``), its frames are those of its motions (frame
        offsets are the identity) and its base is the identity. Built by the core
        (``Chain::reversed``, ``cpp/include/kinematica/chain_build.hpp``).
        """
        return Chain._of(self.core.reversed(), self.prismatic[::-1], -self.own_limits[::-1, ::-1])

    @cached_property
    def fixed_parts(self) -> FloatArray:
        """``(n, 4, 4)`` each joint's fixed part ``F_i = Rz(θ_i) Trans(t_i) Rx(α_i)``.

        What follows joint i's motion ``M_i`` (a rotation about, or a slide along,
        its z axis) in ``T(q) = start · Π_i [M_i(q_i) F_i] · tool``.
        """
        return _readonly(np.asarray(self.core.fixed_parts))  # type: ignore[return-value]

    def motion(self, joint: int, value: float) -> FloatArray:
        """``(4, 4)`` the motion ``M(value)`` of joint ``joint`` (0-based): ``Rz`` or ``Tz``."""
        M = np.eye(4)
        if self.prismatic[joint]:
            M[2, 3] = value
        else:
            c, s = math.cos(value), math.sin(value)
            M[:2, :2] = ((c, -s), (s, c))
        return M

    def locked(self, joint: int, value: float) -> Chain:
        """The chain of the other joints, with joint ``joint`` (0-based) held at ``value``.

        Its motion is folded into the neighbouring fixed transforms (the first
        joint's into ``start``, the last's into ``tool``): the n - 1 joint chain's
        FK at ``q`` without entry ``joint`` equals this chain's at ``q``, to round-off.
        Its frames (``fk(all_frames=True)``) are those right after each motion.
        Built by the core (``Chain::locked``, ``cpp/include/kinematica/chain_build.hpp``).

        Raises:
            ValueError: A chain of one joint (nothing would be left).
        """
        if self.dof < 2:
            raise ValueError("a chain of one joint has no joint left to solve once it is locked")
        keep = np.arange(self.dof) != joint
        return Chain._of(
            self.core.locked(joint, value), self.prismatic[keep], self.own_limits[keep]
        )

    @cached_property
    def memo(self) -> dict[object, object]:
        """What the layers above compute once for this chain (its IK plans...), by their keys.

        A chain is immutable: what is computed from it alone holds as long as it lives.
        """
        return {}

    @cached_property
    def dof(self) -> int:
        """Number of joints n."""
        return int(self.prismatic.shape[0])

    @cached_property
    def qlim(self) -> FloatArray:
        """``(n, 2)`` limits solutions are held to.

        A joint's own limits, else ``(-π, π)`` for a revolute joint and ±inf for a
        prismatic one.
        """
        return _readonly(np.asarray(self.core.qlim))  # type: ignore[return-value]

    # ------------------------------------------------------------ kinematics
    def fk(
        self, q: FloatArray, all_frames: bool = False, workers: int | None = None
    ) -> tuple[FloatArray, int, int, int]:
        """Tool poses (or every frame) of configurations ``q``.

        Args:
            q: ``(..., n)`` float joint values (rad, m).
            all_frames: Every frame ``0T0 (base), 0T1, ..., 0Tn (with tool)``.
            workers: Threads for a batch (None: the library default).

        Returns:
            ``(T, bad, outside, turns)``: ``(..., 4, 4)`` poses or ``(..., n+1, 4, 4)``
            frames; the number of configurations holding NaN/inf (their results
            are NaN); the number beyond some joint's own limits (computed all the
            same); the number with a revolute joint that has no limits of its own
            beyond a full turn. One configuration counts in the first of the three
            that applies.
        """
        if q.ndim == 1:
            if q.dtype is not _FLOAT64 or not q.flags.c_contiguous:
                q = np.ascontiguousarray(q, dtype=np.float64)
            T, state = self.core.fk_frames(q) if all_frames else self.core.fk(q)
            return T, *_counts(state)
        flat = self._flat(q)
        out, bad, outside, turns = self.core.fk_batch(flat, all_frames, resolve_workers(workers))
        return out.reshape(*q.shape[:-1], *out.shape[1:]), int(bad), int(outside), int(turns)

    def jacobian(
        self, q: FloatArray, tool_frame: bool = False, workers: int | None = None
    ) -> tuple[FloatArray, int, int]:
        """Geometric Jacobians ``(..., 6, n)`` of configurations ``q (..., n)``.

        Returns:
            ``(J, bad, turns)`` as for :meth:`fk`.
        """
        if q.ndim == 1:
            if q.dtype is not _FLOAT64 or not q.flags.c_contiguous:
                q = np.ascontiguousarray(q, dtype=np.float64)
            J, state = self.core.jacobian(q, tool_frame)
            bad, _, turns = _counts(state)
            return J, bad, turns
        flat = self._flat(q)
        J, bad, turns = self.core.jacobian_batch(flat, tool_frame, resolve_workers(workers))
        return J.reshape(*q.shape[:-1], 6, self.dof), int(bad), int(turns)

    def singular_values(
        self,
        q: FloatArray,
        rows: Sequence[int] = (0, 1, 2, 3, 4, 5),
        workers: int | None = None,
        group: int = 1,
    ) -> FloatArray:
        """Singular values of the Jacobians' ``rows`` (base frame) at ``q (..., n)``.

        One chain walk and one one-sided Jacobi SVD per configuration in the core
        (``cpp/include/kinematica/singular.hpp``); the Jacobians are not stored.

        Args:
            q: ``(..., n)`` float joint values (rad, m).
            rows: Distinct Jacobian row indices 0-5 (their order does not matter).
            workers: Threads for a batch (None: the library default).
            group: The configurations come in runs of ``group`` (1 to 16; the
                solutions of one target): a Jacobian equal to an earlier one of
                its run up to the signs of its columns (a wrist's two flips) has
                the same singular values, taken from it rather than computed.

        Returns:
            ``(..., min(len(rows), n))`` singular values, largest first; NaN for a
            configuration holding NaN/inf.
        """
        mask = 0
        for r in rows:
            mask |= 1 << int(r)
        flat = self._flat(q)
        S = self.core.jacobian_singular_values(flat, mask, group, resolve_workers(workers))
        return S.reshape(*q.shape[:-1], S.shape[-1])

    def volumes(
        self,
        q: FloatArray,
        rows: Sequence[int] = (0, 1, 2, 3, 4, 5),
        workers: int | None = None,
        group: int = 1,
    ) -> FloatArray:
        """The product of the singular values of the Jacobians' ``rows``, without them.

        Yoshikawa's manipulability ``σ1···σk`` (``k = min(m, n)``) as ``|det J|``
        for square rows, else the square root of the determinant of the Gram
        matrix of the shorter side (``cpp/include/kinematica/volume.hpp``: an LU,
        about a tenth of an SVD). Arguments as :meth:`singular_values`.

        Returns:
            ``(...)`` the products; NaN for a configuration holding NaN/inf.
        """
        mask = 0
        for r in rows:
            mask |= 1 << int(r)
        flat = self._flat(q)
        V = self.core.jacobian_singular_values(flat, mask, group, resolve_workers(workers), True)
        return V.reshape(q.shape[:-1])

    def joint_axes(self, q: FloatArray) -> FloatArray:
        """Each joint's axis as a line: ``(..., n, 6)`` unit direction, then a point.

        In the base frame (m).
        """
        axes = self.core.joint_axes(self._flat(q), resolve_workers(None))
        return axes.reshape(*q.shape[:-1], self.dof, 6)

    def _flat(self, q: FloatArray) -> FloatArray:
        return np.ascontiguousarray(q.reshape(-1, self.dof), dtype=np.float64)
