"""Exceptions raised by kinematica.

Every error a user can cause derives from :class:`KinematicaError`, so a caller
(or the command line) can catch one type and print one clear line. Messages say
what was expected and what was found, and where: file, joint, key.
"""

from __future__ import annotations

__all__ = [
    "ArgumentError",
    "ConventionWarning",
    "DimensionError",
    "KinematicaError",
    "KinematicaWarning",
    "RobotFileError",
    "UnitWarning",
    "UnknownRobotError",
    "UnreachableError",
    "located",
]


def located(
    message: str, *, path: str | None = None, joint: int | None = None, key: str | None = None
) -> str:
    """``message`` prefixed with where it applies: ``"arm.yaml, joint 2, key 'alpha': ..."``.

    Args:
        message: What is wrong.
        path: The file, or ``None``.
        joint: The 1-based joint number, or ``None``.
        key: The key, or ``None``.
    """
    where = []
    if path is not None:
        where.append(str(path))
    if joint is not None:
        where.append(f"joint {joint}")
    if key is not None:
        where.append(f"key '{key}'")
    return f"{', '.join(where)}: {message}" if where else message


class KinematicaError(Exception):
    """Base class of every error raised on purpose by kinematica.

    The message speaks of the Python API; the structured fields let another face
    (the command line) say the same in its own words, with no parsing of the text.

    Attributes:
        message: What is wrong, without the suggestion; when ``arg`` is given it begins
            with that argument's name (``"tol must be a positive number"``).
        arg: The argument the error is about (``"tol"``, ``"q0"``, ``"target"``),
            or ``None``.
        suggest: ``(argument, value)`` that would help, or ``None``: ``str(error)``
            then ends with ``"; use method='numeric'"``.
    """

    def __init__(
        self,
        message: str = "",
        *,
        arg: str | None = None,
        suggest: tuple[str, object] | None = None,
    ) -> None:
        self.message = message
        self.arg = arg
        self.suggest = suggest
        text = message if suggest is None else f"{message}; use {suggest[0]}={suggest[1]!r}"
        super().__init__(text)


class ArgumentError(KinematicaError, ValueError):
    """A function was called with an argument of the wrong type or value.

    For example ``Revolute(d=None)``, ``Revolute(qlim=(1, 2, 3))`` or
    ``load(None)``. It is a ``ValueError`` too, as NumPy and SciPy raise for
    bad arguments.
    """


class DimensionError(KinematicaError, ValueError):
    """An array has the wrong shape, or holds NaN/inf where numbers are needed."""


class RobotFileError(KinematicaError, ValueError):
    """A robot file (or a description given as data) is malformed.

    Attributes:
        path: The file the error is in, or ``None`` for in-memory data.
        joint: The 1-based joint number the error is in, or ``None``.
        key: The key the error is at (e.g. ``"theta"``), or ``None``.
    """

    def __init__(
        self,
        message: str,
        *,
        path: str | None = None,
        joint: int | None = None,
        key: str | None = None,
    ) -> None:
        self.path = path
        self.joint = joint
        self.key = key
        super().__init__(located(message, path=path, joint=joint, key=key))


class UnknownRobotError(KinematicaError, LookupError):
    """A robot name is neither a built-in model nor an existing file."""


class UnreachableError(KinematicaError):
    """A target pose cannot be reached by the robot."""


class MissingDependencyError(KinematicaError, ImportError):
    """An optional dependency needed for this feature is not installed."""


class KinematicaWarning(UserWarning):
    """Something was computed, but part of the input looks wrong.

    For example rows of a batch holding NaN (their results are NaN), or a
    value implausible for its unit (``alpha: 90`` in a file in radians).
    """


class LimitWarning(KinematicaWarning):
    """A joint value beyond the joint's own limits, with its parts for other units.

    The message speaks the library's units (rad, m); :meth:`in_units` says the same
    in a caller's (the command line's degrees, a robot file's millimetres).

    Attributes:
        name: The argument (``"q"``, ``"q0"``).
        joint: The joint's 0-based index.
        value: Its value (rad or m).
        limits: ``(lower, upper)`` (rad or m).
        prismatic: Whether the joint is prismatic (a length).
        where: Which row of a batch (``" in row (3,)"``), or ``""``.
        more: How many configurations are beyond their limits, or ``""``.
    """

    def __init__(
        self,
        *,
        name: str,
        joint: int,
        value: float,
        limits: tuple[float, float],
        prismatic: bool,
        where: str = "",
        more: str = "",
    ) -> None:
        self.name, self.joint, self.value, self.limits = name, joint, value, limits
        self.prismatic, self.where, self.more = prismatic, where, more
        super().__init__(self.in_units())

    def in_units(self, per_rad: float = 1.0, angle: str = "rad", per_m: float = 1.0,
                 length: str = "m") -> str:  # fmt: skip
        """The message with angles times ``per_rad`` in ``angle``, lengths times ``per_m``."""
        scale, unit = (per_m, length) if self.prismatic else (per_rad, angle)
        lo, hi = (v * scale for v in self.limits)
        return (
            f"{self.name}: joint {self.joint + 1} = {self.value * scale:.6g} {unit}{self.where} "
            f"is outside its limits [{lo:.6g}, {hi:.6g}] {unit}{self.more}"
        )


class UnitWarning(KinematicaWarning):
    """A number valid as such but implausible in its unit, most likely a unit slip.

    Degrees where radians are meant (``alpha: 90`` in a file in radians,
    ``robot.fk([30, 40, -30, 10, 60, -20])``: joint angles beyond a full turn),
    radians where degrees are meant, millimetres where metres are meant. The
    value is used as given.
    """


class ConventionWarning(KinematicaWarning):
    """No DH convention was given: the table is read as standard (Paul, distal).

    One rule for ``Robot.from_dh(rows)`` and a robot file without ``convention``:
    the common convention is assumed, and said, because a modified (Craig) table
    read as standard gives another arm without any error.
    """
