"""A robot's joints as general transforms: how a URDF's FK stays exact.

A DH table can describe any serial chain, but not always to the last digit: a
file's axes 1e-9 or 1e-3 off parallel put the common normal far away, and a DH
table then reproduces the file's FK to 1e-10 or worse. A robot read from such a
description keeps its DH table as its description (``robot.links``, derivations,
``show``) and computes with :class:`ChainTransforms`, the file's own transforms,
compiled to the core's general chain (:meth:`kinematica.core.Chain.from_transforms`).

The transforms are written relative to the DH frames 0 and n, so that the
robot's ``base`` and ``tool`` keep their meaning::

    T = base · start · M1(q1) · between[0] · ... · Mn(qn) · end · tool

where ``Mi`` turns about, or slides along, the z axis of the frame it acts in.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from kinematica.core import Chain
from kinematica.dh import Convention, Joint, Prismatic, link_matrix
from kinematica.spatial import inv_transform

__all__ = ["ChainTransforms", "align_z", "dh_frames"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class ChainTransforms:
    """A serial chain's fixed transforms, relative to its DH frames 0 and n.

    Attributes:
        start: ``(4, 4)`` DH frame 0 to the frame joint 1 moves in (z: its axis).
        between: ``(n - 1, 4, 4)`` from the frame after each motion to the next
            joint's frame.
        end: ``(4, 4)`` from the frame after the last motion to DH frame n.
        frame_offsets: ``(n, 4, 4)`` DH frame i as seen from the frame after
            motion i (both move rigidly with joint i).
    """

    start: FloatArray
    between: FloatArray
    end: FloatArray
    frame_offsets: FloatArray

    def compile(self, links: Sequence[Joint], base: FloatArray, tool: FloatArray) -> Chain:
        """The core's chain of a robot with these transforms, DH rows (limits), base, tool."""
        prismatic = np.array([isinstance(j, Prismatic) for j in links], dtype=bool)
        lims = np.array(
            [j.qlim if j.qlim is not None else (-np.inf, np.inf) for j in links], dtype=float
        ).reshape(len(links), 2)
        return Chain.from_transforms(
            base @ self.start, self.between, self.end @ tool, self.frame_offsets,
            prismatic, lims, base,
        )  # fmt: skip

    def motion_frames(self) -> FloatArray:
        """``(n, 4, 4)`` the frames joints 1..n move in at q = 0, in DH frame 0."""
        n = self.frame_offsets.shape[0]
        frames = np.empty((n, 4, 4))
        frames[0] = self.start
        for i in range(1, n):
            frames[i] = frames[i - 1] @ self.between[i - 1]
        return frames

    def rebased(
        self,
        old: tuple[FloatArray, FloatArray],
        new: tuple[FloatArray, FloatArray],
        frames: FloatArray,
    ) -> ChainTransforms:
        """The same chain for another DH table: its (base, tool) and DH frames ``(n+1, 4, 4)``.

        ``old`` and ``new`` are the (base, tool) pairs; ``frames`` the new
        table's DH frames at q = 0 in the new DH frame 0 (:func:`dh_frames`).
        FK is unchanged: ``base' start' = base start``, ``end' tool' = end tool``.
        """
        (b0, t0), (b1, t1) = old, new
        start = inv_transform(b1) @ b0 @ self.start
        end = self.end @ t0 @ inv_transform(t1)
        moved = type(self)(start, self.between, end, self.frame_offsets).motion_frames()
        offsets = np.array([inv_transform(F) @ S for F, S in zip(moved, frames[1:], strict=True)])
        return type(self)(start, self.between, end, offsets)


def dh_frames(links: Sequence[Joint], convention: Convention) -> FloatArray:
    """``(n+1, 4, 4)`` the DH frames S0..Sn of a table at q = 0, in S0 (no base, no tool)."""
    n = len(links)
    A = link_matrix(
        np.array([j.theta for j in links]),
        np.array([j.d for j in links]),
        np.array([j.a for j in links]),
        np.array([j.alpha for j in links]),
        convention,
    )
    frames = np.empty((n + 1, 4, 4))
    frames[0] = np.eye(4)
    for i in range(n):
        frames[i + 1] = frames[i] @ A[i]
    return frames


def align_z(axis: FloatArray) -> FloatArray:
    """``(3, 3)`` a rotation taking the z axis onto the unit ``axis``.

    ``align_z(a) Rz(q) align_z(a)ᵀ`` is the rotation by q about ``a``: the
    identity for ``a = z`` (exactly), a half turn about x for ``a = -z``, else
    the shortest rotation (about ``z × a``, by the angle between them).
    """
    a = np.asarray(axis, dtype=float)
    v = np.array([-a[1], a[0], 0.0])  # z × a: sin θ times the unit rotation axis
    s = float(np.hypot(a[0], a[1]))
    if s == 0.0:
        return np.eye(3) if a[2] > 0.0 else np.diag([1.0, -1.0, -1.0])
    theta = float(np.arctan2(s, a[2]))
    U = np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]]) / s
    return np.eye(3) + np.sin(theta) * U + (1.0 - np.cos(theta)) * (U @ U)
