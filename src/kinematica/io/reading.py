"""Reading a whole file safely: a regular file, of at most so many bytes.

The type and size are checked before the file is opened: opening a FIFO would
wait for a writer, and reading ``/dev/zero`` would never end. Each reader
(robot files, trajectories, design checkpoints) states its own limit and
raises its own error, made from this module's one-line reasons.
"""

from __future__ import annotations

import stat
from collections.abc import Callable
from pathlib import Path

__all__ = ["ROBOT_FILE_SUFFIXES", "URDF_SUFFIXES", "file_kind", "os_reason", "read_limited"]

# Which reader a path goes to, known without importing the readers (``load`` of a
# built-in model imports neither the URDF reader nor the robot-file writer).

#: File extensions of robot files (:mod:`kinematica.io.robotfile` reads and writes them).
ROBOT_FILE_SUFFIXES = (".yaml", ".yml", ".json", ".toml")

#: File name endings read as URDF (:mod:`kinematica.io.urdf`; ``.xacro`` ones are
#: expanded first).
URDF_SUFFIXES = (".urdf", ".xacro")


def file_kind(mode: int) -> str | None:
    """What a file that is not a regular file is, or ``None`` for a regular file."""
    if stat.S_ISREG(mode):
        return None
    if stat.S_ISDIR(mode):
        return "a directory"
    if stat.S_ISFIFO(mode):
        return "a named pipe (FIFO)"
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "a device"
    if stat.S_ISSOCK(mode):
        return "a socket"
    return "a special file"


def os_reason(exc: Exception) -> str:
    """The short reason of an ``OSError`` (``"Permission denied"``), else its text."""
    return str(exc.strerror) if isinstance(exc, OSError) and exc.strerror else str(exc)


def read_limited(
    path: Path,
    max_bytes: int,
    what: str,
    error: Callable[[str], Exception],
    *,
    missing_ok: bool = False,
) -> bytes:
    """The bytes of the regular file ``path``, of at most ``max_bytes`` bytes.

    Args:
        path: The file.
        max_bytes: The most bytes read; a larger file is refused.
        what: What the file should be, for messages (``"robot file"``).
        error: Makes the exception raised from a one-line reason
            (``"is a device, not a robot file"``); the caller adds the path.
        missing_ok: Return ``b""`` for a file that does not exist.

    Raises:
        Whatever ``error`` makes: no such file, not a regular file, too large,
        or unreadable.
    """
    try:
        info = path.stat()
    except FileNotFoundError as exc:
        if missing_ok:
            return b""
        raise error("file not found") from exc
    except (OSError, ValueError) as exc:  # ValueError: a NUL byte in the path
        raise error(f"cannot read the file: {os_reason(exc)}") from exc
    kind = file_kind(info.st_mode)
    if kind is not None:
        raise error(f"is {kind}, not a {what}")
    limit = f"{what}s of at most {max_bytes:,} bytes are read"
    if info.st_size > max_bytes:
        raise error(f"the file is {info.st_size:,} bytes; {limit}")
    try:
        with path.open("rb") as f:
            data = f.read(max_bytes + 1)  # the file may have grown since stat
    except OSError as exc:
        raise error(f"cannot read the file: {os_reason(exc)}") from exc
    if len(data) > max_bytes:
        raise error(f"the file is {len(data):,} bytes or more; {limit}")
    return data
