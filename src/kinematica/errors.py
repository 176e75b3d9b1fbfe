"""Exceptions raised by kinematica.

Every error a user can cause derives from :class:`KinematicaError`, so a caller
(or the command line) can catch one type and print one clear line. Messages say
what was expected and what was found, and where: file, joint, key.
"""

from __future__ import annotations

__all__ = [
    "DimensionError",
    "KinematicaError",
    "KinematicaWarning",
    "RobotFileError",
    "UnknownRobotError",
    "UnreachableError",
]


class KinematicaError(Exception):
    """Base class of every error raised on purpose by kinematica."""


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
        where = []
        if path is not None:
            where.append(str(path))
        if joint is not None:
            where.append(f"joint {joint}")
        if key is not None:
            where.append(f"key '{key}'")
        super().__init__(f"{', '.join(where)}: {message}" if where else message)


class UnknownRobotError(KinematicaError, LookupError):
    """A robot name is neither a built-in model nor an existing file."""


class UnreachableError(KinematicaError):
    """A target pose cannot be reached by the robot."""


class KinematicaWarning(UserWarning):
    """Something was computed, but part of the input was unusable (e.g. NaN rows)."""
