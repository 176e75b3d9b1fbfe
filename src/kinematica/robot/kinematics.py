"""A robot's forward kinematics: poses, link matrices, Jacobians and joint axes."""

from __future__ import annotations

import warnings
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.arguments import check_choice, check_flag
from kinematica.dh import link_matrix
from kinematica.errors import (
    DimensionError,
    KinematicaError,
    KinematicaWarning,
    LimitWarning,
    UnitWarning,
)
from kinematica.io.plausible import check_angle
from kinematica.robot.description import RobotDescription

__all__ = ["RobotKinematics"]

FloatArray = NDArray[np.float64]
_FLOAT64 = np.dtype(np.float64)
#: The frames a Jacobian is expressed in.
_FRAMES = ("base", "tool", "spatial")
#: What the core says of one configuration (kinematica._core.Chain.fk): QState in
#: cpp/include/kinematica/chain.hpp. Beyond a turn: a revolute joint with no limits of
#: its own beyond 2π (PLAUSIBLE_ANGLE), which batches check here.
_NOT_FINITE, _OUTSIDE_LIMITS, _BEYOND_TURN = 1, 2, 3
#: Rows of a batch read at a time when looking for the first configuration beyond the
#: limits (the core counts them; only the first is named).
_SCAN_ROWS = 4096
#: Configurations a warning of NaN/inf rows names (it says how many there are in all).
_SHOWN_ROWS = 5


class RobotKinematics(RobotDescription):
    """A robot's description with its forward kinematics (see :class:`~kinematica.Robot`)."""

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
            return self._analytic_jacobian(q, euler)
        if frame == "spatial":
            return self._spatial_jacobian(q, workers)
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

    def _analytic_jacobian(self, q: ArrayLike, euler: str) -> FloatArray:
        """``jacobian(q, euler=...)``: :class:`~kinematica.robot.robot.Robot`'s (velocity layer)."""
        raise NotImplementedError

    def _spatial_jacobian(self, q: ArrayLike, workers: int | None) -> FloatArray:
        """``jacobian(q, frame="spatial")``: :class:`~kinematica.robot.robot.Robot`'s."""
        raise NotImplementedError

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
