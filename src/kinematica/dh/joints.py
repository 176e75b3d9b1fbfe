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
import warnings
from collections.abc import Iterable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass
from typing import Literal

import numpy as np

from kinematica.errors import ArgumentError, KinematicaError, UnitWarning
from kinematica.io import plausible
from kinematica.io.spec import (
    CONVENTION_ALIASES,
    Convention,
    convention_names,
    missing_convention,
)

__all__ = [
    "Convention",
    "Joint",
    "JointType",
    "Prismatic",
    "Revolute",
    "check_convention",
    "given_convention",
    "values_checked",
]

JointType = Literal["R", "P"]


def check_convention(convention: str) -> Convention:
    """Return the canonical convention name for ``convention`` or raise.

    Args:
        convention: ``"standard"`` or ``"modified"`` (aliases: dh, paul, distal;
            mdh, craig, proximal), case-insensitive.

    Raises:
        KinematicaError: If the name is not a known convention.
    """
    key = str(convention).strip().lower()
    if key not in CONVENTION_ALIASES:
        raise KinematicaError(
            f"unknown DH convention {convention!r}: expected {convention_names()}"
        )
    return CONVENTION_ALIASES[key]


def given_convention(convention: str | None) -> Convention:
    """:func:`check_convention`, with ``None`` read as standard and said (ConventionWarning).

    The rule of ``Robot.from_dh`` (and of robot files): see
    :func:`kinematica.io.spec.missing_convention`.
    """
    if convention is None:
        return missing_convention(stacklevel=3)  # the warning points at from_dh's caller
    return check_convention(convention)


# Inside `values_checked()`, joints skip the plausibility warnings.
_CHECKED: ContextVar[bool] = ContextVar("kinematica_dh_values_checked", default=False)


@contextmanager
def values_checked() -> Iterator[None]:
    """Build joints without warning about implausible values.

    For joints built from a robot file, whose reader has already warned with
    the file, joint and key (see :mod:`kinematica.io.plausible`).
    """
    token = _CHECKED.set(True)
    try:
        yield
    finally:
        _CHECKED.reset(token)


def _number(owner: str, name: str, value: object) -> float:
    """``value`` as a float, or an ArgumentError naming ``owner`` and ``name``."""
    if isinstance(value, bool | str | bytes | complex | np.complexfloating) or value is None:
        raise ArgumentError(f"{owner}: {name} must be a real number, got {value!r}")
    try:
        v = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError) as exc:
        raise ArgumentError(f"{owner}: {name} must be a real number, got {value!r}") from exc
    return v


def _finite(owner: str, name: str, value: object) -> float:
    v = _number(owner, f"DH parameter {name}", value)
    if not math.isfinite(v):
        raise ArgumentError(f"{owner}: DH parameter {name} must be a finite number, got {value!r}")
    return v


def _limits(owner: str, qlim: object) -> tuple[float, float] | None:
    if qlim is None:
        return None
    expected = f"{owner}: joint limits must be two numbers lo < hi (or None)"
    if isinstance(qlim, str | bytes) or not isinstance(qlim, Iterable):
        raise ArgumentError(f"{expected}, got {qlim!r}")
    try:
        pair = tuple(qlim)
    except TypeError as exc:  # e.g. a 0-d array
        raise ArgumentError(f"{expected}, got {qlim!r}") from exc
    if len(pair) != 2:
        raise ArgumentError(f"{expected}, got {len(pair)} values: {qlim!r}")
    lo, hi = (_number(owner, "each joint limit", v) for v in pair)
    if math.isnan(lo) or math.isnan(hi) or not lo < hi:
        raise ArgumentError(f"{expected}, got {qlim!r}")
    return (lo, hi)


def _check(joint: Revolute | Prismatic, angles: tuple[str, ...], lengths: tuple[str, ...]) -> None:
    """Validate a joint's fields in place, and warn about implausible values."""
    kind = type(joint).__name__
    if joint.name is not None and not isinstance(joint.name, str):
        raise ArgumentError(f"{kind}: name must be text or None, got {joint.name!r}")
    owner = kind if joint.name is None else f"{kind} {joint.name!r}"
    for key in (*angles, *lengths):
        object.__setattr__(joint, key, _finite(owner, key, getattr(joint, key)))
    object.__setattr__(joint, "qlim", _limits(owner, joint.qlim))
    if _CHECKED.get():
        return
    found = [(key, plausible.check_angle(getattr(joint, key))) for key in angles]
    found += [(key, plausible.check_length(getattr(joint, key))) for key in lengths]
    if isinstance(joint, Revolute) and joint.qlim is not None:
        found += [("qlim", plausible.check_limit(max(joint.qlim, key=abs)))]
    for key, message in found:
        if message is not None:
            # stacklevel: _check <- __post_init__ <- __init__ <- the caller.
            warnings.warn(
                f"{owner}: {key}={getattr(joint, key)!r}: {message}",
                UnitWarning,
                stacklevel=4,
            )


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
        _check(self, angles=("alpha", "offset"), lengths=("d", "a"))

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
        _check(self, angles=("theta", "alpha"), lengths=("a", "offset"))

    @property
    def type(self) -> JointType:
        """``"P"``."""
        return "P"

    @property
    def d(self) -> float:
        """The constant part of d: the offset (metres)."""
        return self.offset


Joint = Revolute | Prismatic
