"""Values that are valid numbers but implausible for their unit.

The usual slips of a DH table typed by hand: degrees where radians are meant
(``alpha: 90`` in a file in radians, ``Revolute(alpha=90)``), radians where
degrees are meant (``alpha: 1.5708`` in a file in degrees), millimetres where
metres are meant (``d: 300``). The value is still used as written: these are
warnings (:class:`~kinematica.errors.KinematicaWarning`), since a strange
value can be meant, but a wrong unit is far more often the cause.

Each check takes a value in radians or metres and returns the text of a
warning, or ``None`` when the value is plausible.
"""

from __future__ import annotations

import math
from typing import Final

__all__ = [
    "PLAUSIBLE_ANGLE",
    "PLAUSIBLE_LENGTH",
    "PLAUSIBLE_LIMIT",
    "RADIAN_LOOKALIKE_TOL",
    "check_angle",
    "check_degrees",
    "check_length",
    "check_limit",
]

#: Largest constant DH angle (a theta offset, a twist alpha, a base/tool rpy
#: angle) taken as plausible, in radians: one full turn. Above it the value is
#: almost always degrees written where radians are expected.
PLAUSIBLE_ANGLE: Final = 2.0 * math.pi

#: Largest revolute joint limit taken as plausible, in radians: two full turns
#: (some wrists turn ±720°; no joint of a serial arm turns further).
PLAUSIBLE_LIMIT: Final = 4.0 * math.pi

#: Largest DH length (``d``, ``a``) taken as plausible, in metres. The largest
#: industrial arms reach about 4 m; 20 m leaves room for cranes and gantries
#: and still catches millimetres written as metres (``d: 300``).
PLAUSIBLE_LENGTH: Final = 20.0

#: An angle written in degrees that lies within this many degrees of π/2, π,
#: 3π/2 or 2π (the numbers 1.5708, 3.1416, ...) is radians written where
#: degrees are expected: ``alpha: 1.57`` is 0.0008 from π/2.
RADIAN_LOOKALIKE_TOL: Final = 0.002

_QUARTER_TURNS: Final = {1: "pi/2", 2: "pi", 3: "3*pi/2", 4: "2*pi"}


def check_angle(value: float, unit: str = "rad") -> str | None:
    """A warning when a constant angle is more than one full turn.

    Args:
        value: The angle, in radians.
        unit: The unit it was written in, ``"rad"`` or ``"deg"`` (for the advice).

    Returns:
        The warning's text, or ``None``.
    """
    if abs(value) <= PLAUSIBLE_ANGLE:
        return None
    if unit == "deg":
        return f"{math.degrees(value):g}° is more than a full turn (360°)"
    return (
        f"{value:g} rad is more than a full turn (2π rad): is it in degrees? "
        f"({value:g}° is {math.radians(value):.6g} rad)"
    )


def check_limit(value: float, unit: str = "rad") -> str | None:
    """A warning when a revolute joint limit is more than two full turns.

    Args:
        value: The limit, in radians.
        unit: The unit it was written in, ``"rad"`` or ``"deg"``.

    Returns:
        The warning's text, or ``None``.
    """
    if abs(value) <= PLAUSIBLE_LIMIT:
        return None
    if unit == "deg":
        return f"a limit of {math.degrees(value):g}° is more than two full turns (720°)"
    return (
        f"a limit of {value:g} rad is more than two full turns (4π rad): is it in degrees? "
        f"({value:g}° is {math.radians(value):.6g} rad)"
    )


def check_degrees(value: float) -> str | None:
    """A warning when an angle written in degrees looks like radians.

    Args:
        value: The angle as written, in degrees.

    Returns:
        The warning's text when ``value`` is within
        :data:`RADIAN_LOOKALIKE_TOL` of π/2, π, 3π/2 or 2π (or their
        negatives), else ``None``.
    """
    k = round(value / (math.pi / 2.0))
    if abs(k) not in _QUARTER_TURNS or abs(value - k * math.pi / 2.0) > RADIAN_LOOKALIKE_TOL:
        return None
    sign = "-" if k < 0 else ""
    return (
        f"{value:g}° looks like {sign}{_QUARTER_TURNS[abs(k)]} in radians: "
        f"write {90 * k} for {90 * k}°, or set units.angle: rad if the file is in radians"
    )


def check_length(value: float, unit: str = "m") -> str | None:
    """A warning when a DH length is longer than :data:`PLAUSIBLE_LENGTH`.

    Args:
        value: The length, in metres.
        unit: The unit it was written in, ``"m"`` or ``"mm"``.

    Returns:
        The warning's text, or ``None``.
    """
    if abs(value) <= PLAUSIBLE_LENGTH:
        return None
    if unit == "mm":
        return f"{value * 1000:g} mm ({value:g} m) is longer than {PLAUSIBLE_LENGTH:g} m"
    return (
        f"{value:g} m is longer than {PLAUSIBLE_LENGTH:g} m: is it in millimetres? "
        f"({value:g} mm is {value / 1000:g} m)"
    )
