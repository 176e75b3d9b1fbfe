"""kinematica: kinematics of serial robot manipulators."""

from kinematica.errors import (
    DimensionError,
    KinematicaError,
    RobotFileError,
    UnknownRobotError,
    UnreachableError,
)

__version__ = "0.1.0"

__all__ = [
    "DimensionError",
    "KinematicaError",
    "RobotFileError",
    "UnknownRobotError",
    "UnreachableError",
    "__version__",
]
