"""A DH table compiled into the arrays the kernels walk.

Both conventions are one product once the factors are regrouped (``Tras(x)``
and ``Rot(x)`` commute, as do ``Rot(z)`` and ``Tras(z)``)::

    T = S · Π_i [Rot(z, θi) · Tras(z, di) · Tras(x, ai*) · Rot(x, αi*)] · E

* standard: ``S = base``, ``(ai*, αi*) = (ai, αi)``, ``E = tool``;
* modified: ``S = base · Rot(x, α0) · Tras(x, a0)`` (row 1's ``a``/``alpha``),
  ``(ai*, αi*)`` are row ``i+1``'s ``a``/``alpha`` (zero after the last joint),
  ``E = tool``.

:class:`DHChain` holds that product as arrays (no computation here): the
kernels of :mod:`kinematica.kernels.fk` walk it.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from kinematica.dh.convert import rx_tx
from kinematica.dh.joints import Convention, Joint, Prismatic, Revolute, check_convention

__all__ = ["SNAP_TOL", "DHChain"]

FloatArray = NDArray[np.float64]

#: |cos| or |sin| of a constant angle below this is taken as exactly 0 (and the
#: other as exactly ±1): cos(pi/2) evaluates to 6.1e-17, not 0, and the exact
#: value keeps frames of twists of 0/±90/180 degrees exactly orthonormal.
SNAP_TOL = 1e-15


def _snap(v: float) -> float:
    if abs(v) < SNAP_TOL:
        return 0.0
    if abs(abs(v) - 1.0) < SNAP_TOL:
        return math.copysign(1.0, v)
    return v


def _readonly(a: FloatArray) -> FloatArray:
    a.flags.writeable = False
    return a


@dataclass(frozen=True, eq=False)
class DHChain:
    """A DH table compiled for the kernels.

    Attributes:
        links: ``(n, 10)`` one row per joint: prismatic (1.0) or revolute (0.0),
            constant θ (rad) and d (m), the regrouped ``ai*`` (m), cos and sin
            of the regrouped ``αi*``, cos and sin of the constant θ, and the
            joint's own limits (``±inf`` where it has none).
        ends: ``(3, 4, 4)``: the constant transform before the first joint, the
            tool (after the last link), and the robot's base (frame 0).
        frames_mid: True for the modified convention, where frame i sits after
            ``Rot(z)·Tras(z)`` of joint i rather than after the whole factor.
        qlim: ``(n, 2)`` joint limits (rad or m): ``(-π, π)`` for revolute joints
            without limits of their own, ``±inf`` for prismatic ones.
    """

    links: FloatArray
    ends: FloatArray
    frames_mid: bool
    qlim: FloatArray

    @classmethod
    def from_joints(
        cls,
        joints: Sequence[Joint],
        convention: Convention,
        base: FloatArray,
        tool: FloatArray,
    ) -> DHChain:
        """Compile a DH table with its base and tool transforms.

        Args:
            joints: The rows, base to tip.
            convention: ``"standard"`` or ``"modified"``.
            base: ``(4, 4)`` pose of frame 0 in the world (base) frame.
            tool: ``(4, 4)`` pose of the tool in frame n.
        """
        conv = check_convention(convention)
        a_row = [j.a for j in joints]
        alpha_row = [j.alpha for j in joints]
        base = np.array(base, dtype=float)
        if conv == "standard":
            a, alpha, start = a_row, alpha_row, base
        else:
            a, alpha = [*a_row[1:], 0.0], [*alpha_row[1:], 0.0]
            start = base @ rx_tx(alpha_row[0], a_row[0])
        links = np.array(
            [
                (
                    float(isinstance(j, Prismatic)),
                    j.theta,
                    j.d,
                    ai,
                    _snap(math.cos(al)),
                    _snap(math.sin(al)),
                    _snap(math.cos(j.theta)),
                    _snap(math.sin(j.theta)),
                    *(j.qlim if j.qlim is not None else (-math.inf, math.inf)),
                )
                for j, ai, al in zip(joints, a, alpha, strict=True)
            ],
            dtype=float,
        ).reshape(len(joints), 10)
        qlim = np.array(
            [
                j.qlim
                if j.qlim is not None
                else ((-math.pi, math.pi) if isinstance(j, Revolute) else (-math.inf, math.inf))
                for j in joints
            ],
            dtype=float,
        ).reshape(len(joints), 2)
        ends = np.stack([start, np.array(tool, dtype=float), base])
        return cls(
            links=_readonly(links),
            ends=_readonly(ends),
            frames_mid=conv == "modified",
            qlim=_readonly(qlim),
        )

    @cached_property
    def dof(self) -> int:
        """Number of joints."""
        return int(self.links.shape[0])

    @property
    def prismatic(self) -> NDArray[np.bool_]:
        """``(n,)`` True for prismatic joints."""
        return self.links[:, 0] != 0.0
