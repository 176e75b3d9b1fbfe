"""DH rows: one revolute or prismatic joint and the link that follows it.

A row holds the four Denavit-Hartenberg parameters of one joint. The joint
variable ``q`` is added to ``theta`` (revolute) or to ``d`` (prismatic), after
the row's constant ``offset``: a slide's ``q2 + 90°`` is ``Revolute(offset=pi/2)``.

In the standard (Paul, distal) convention row ``i`` holds ``theta_i, d_i,
a_i, alpha_i``; in the modified (Craig, proximal) convention it holds
``a_(i-1), alpha_(i-1), theta_i, d_i`` as Craig's tables are written, and the
``a``/``alpha`` fields carry ``a_(i-1)``/``alpha_(i-1)``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

from kinematica.errors import KinematicaError

__all__ = ["Convention", "Joint", "JointType", "Prismatic", "Revolute", "check_convention"]

Convention = Literal["standard", "modified"]
JointType = Literal["R", "P"]

_CONVENTION_ALIASES: dict[str, Convention] = {
    "standard": "standard",
    "dh": "standard",
    "paul": "standard",
    "distal": "standard",
    "modified": "modified",
    "mdh": "modified",
    "craig": "modified",
    "proximal": "modified",
}


def check_convention(convention: str) -> Convention:
    """Return the canonical convention name for ``convention`` or raise.

    Args:
        convention: ``"standard"`` or ``"modified"`` (aliases: dh, paul, distal;
            mdh, craig, proximal), case-insensitive.

    Raises:
        KinematicaError: If the name is not a known convention.
    """
    key = str(convention).strip().lower()
    if key not in _CONVENTION_ALIASES:
        raise KinematicaError(
            f"unknown DH convention {convention!r}: expected 'standard' (Paul, distal) "
            "or 'modified' (Craig, proximal)"
        )
    return _CONVENTION_ALIASES[key]


def _finite(name: str, value: float) -> float:
    v = float(value)
    if not math.isfinite(v):
        raise KinematicaError(f"DH parameter {name} must be a finite number, got {value!r}")
    return v


def _limits(qlim: tuple[float, float] | None) -> tuple[float, float] | None:
    if qlim is None:
        return None
    lo, hi = (float(v) for v in qlim)
    if math.isnan(lo) or math.isnan(hi) or not lo < hi:
        raise KinematicaError(f"joint limits must be two numbers lo < hi, got {qlim!r}")
    return (lo, hi)


@dataclass(frozen=True)
class Revolute:
    """A revolute joint: ``theta = q + offset``; ``d``, ``a``, ``alpha`` fixed.

    Attributes:
        d: Link offset along z (metres).
        a: Link length along x (metres); ``a_(i-1)`` in the modified convention.
        alpha: Link twist about x (radians); ``alpha_(i-1)`` in the modified convention.
        offset: Constant added to the joint variable (radians).
        qlim: Joint limits ``(lo, hi)`` in radians, or ``None`` for a joint that
            turns freely (taken as ``(-pi, pi)``).
        name: Optional joint name.
    """

    d: float = 0.0
    a: float = 0.0
    alpha: float = 0.0
    offset: float = 0.0
    qlim: tuple[float, float] | None = None
    name: str | None = None

    def __post_init__(self) -> None:
        for key in ("d", "a", "alpha", "offset"):
            object.__setattr__(self, key, _finite(key, getattr(self, key)))
        object.__setattr__(self, "qlim", _limits(self.qlim))

    @property
    def type(self) -> JointType:
        """``"R"``."""
        return "R"

    @property
    def theta(self) -> float:
        """The constant part of theta: the offset (radians)."""
        return self.offset


@dataclass(frozen=True)
class Prismatic:
    """A prismatic joint: ``d = q + offset``; ``theta``, ``a``, ``alpha`` fixed.

    Attributes:
        theta: Joint angle about z (radians).
        a: Link length along x (metres); ``a_(i-1)`` in the modified convention.
        alpha: Link twist about x (radians); ``alpha_(i-1)`` in the modified convention.
        offset: Constant added to the joint variable (metres).
        qlim: Joint limits ``(lo, hi)`` in metres, or ``None`` (unbounded).
        name: Optional joint name.
    """

    theta: float = 0.0
    a: float = 0.0
    alpha: float = 0.0
    offset: float = 0.0
    qlim: tuple[float, float] | None = None
    name: str | None = None

    def __post_init__(self) -> None:
        for key in ("theta", "a", "alpha", "offset"):
            object.__setattr__(self, key, _finite(key, getattr(self, key)))
        object.__setattr__(self, "qlim", _limits(self.qlim))

    @property
    def type(self) -> JointType:
        """``"P"``."""
        return "P"

    @property
    def d(self) -> float:
        """The constant part of d: the offset (metres)."""
        return self.offset


Joint = Revolute | Prismatic
