"""Writing a file so that a failure or a kill never leaves it empty or cut short.

Every file kinematica writes (robot files, URDF, C++ headers, trajectories,
pictures, animations, pages, reports, the design log; a design checkpoint's
first line) is written to a temporary file in the
same folder, flushed to disk and renamed over the old one: a reader sees the
old file or the whole new one, never a part. A write that fails (a full disk,
a file-size limit, an exception while drawing) removes the temporary file and
leaves the old file as it was. The standard library has the pieces
(``tempfile.mkstemp``, ``os.fsync``, ``os.replace``) but not their combination.

A process killed while writing cannot remove its temporary file. Its name says whose
it is (``.arm.yaml.~km-<host>-<pid>-<random>.tmp.yaml``: a hash of the machine's
name and the writer's process id), and the next write of the same file removes
such leftovers: those of a process of this machine that no longer runs, and any
older than :data:`STALE_AGE` (a writer on another machine sharing the folder, or a
process id taken again since).
"""

from __future__ import annotations

import contextlib
import os
import re
import stat
import time
import zlib
from collections.abc import Iterator
from pathlib import Path

__all__ = ["STALE_AGE", "atomic_path", "unchanged", "write_failed", "write_text_atomic"]

#: Seconds after which a temporary file beside a file being written is a leftover
#: whoever wrote it: no write of one file lasts a day (the longest, an animation or a
#: design report, take minutes), while a process id may be taken again within hours.
STALE_AGE = 24 * 3600.0
#: What names a temporary file as ours, between the target's name and the writer's
#: machine, process id and mkstemp's random part.
_TAG = "~km"


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike[str]) -> Iterator[Path]:
    """A temporary path beside ``path`` to write; it replaces ``path`` when the block ends.

    The temporary file keeps ``path``'s suffix (``.png``, ``.gif``: writers that
    read the format from the name see the right one). On an exception inside
    the block, or while flushing and renaming, it is removed and the exception
    propagates: ``path`` is untouched. A new file gets the permissions an
    ``open(path, "w")`` would give it; a replaced one keeps its own. A symbolic
    link is followed (the file it names is replaced, the link kept); a device
    or FIFO (``/dev/stdout``) is written in place, as there is no file to keep.

    Raises:
        OSError: The folder does not exist or is not writable (nothing written).
    """
    p = Path(os.path.realpath(path))
    try:
        special = not stat.S_ISREG(p.stat().st_mode)
    except OSError:  # no such file yet
        special = False
    if special:
        yield p
        return
    import tempfile  # only when writing: importing it (shutil, random) slows any start

    _remove_leftovers(p)
    fd, name = tempfile.mkstemp(
        dir=p.parent, prefix=f".{p.name}.{_TAG}-{_host()}-{os.getpid()}-", suffix=f".tmp{p.suffix}"
    )
    os.close(fd)
    tmp = Path(name)
    try:
        yield tmp
        with open(tmp, "rb+") as f:
            os.fsync(f.fileno())
        os.chmod(tmp, _mode(p))
        os.replace(tmp, p)
    except BaseException:
        with contextlib.suppress(OSError):
            tmp.unlink()
        raise


def _host() -> str:
    """This machine, as 8 hex digits (a hash of its name: any name, no separator in it)."""
    return f"{zlib.crc32(os.uname().nodename.encode()):08x}"


def _remove_leftovers(p: Path) -> None:
    """Remove the temporary files of earlier writes of ``p`` that will never finish.

    Ours (``.NAME.~km-HOST-PID-RANDOM.tmpSUFFIX``) whose writer was a process of this
    machine that no longer runs, or older than :data:`STALE_AGE`; and any of the form
    before the writer was named (``.NAME.RANDOM.tmpSUFFIX``) older than that.
    """
    name, tail = re.escape(p.name), re.escape(f".tmp{p.suffix}")
    ours = re.compile(rf"\.{name}\.{_TAG}-([0-9a-f]{{8}})-([0-9]+)-[a-z0-9_]+{tail}")
    unnamed = re.compile(rf"\.{name}\.[a-z0-9_]{{8}}{tail}")
    head, host = f".{p.name}.", _host()
    now = time.time()
    try:
        entries = [e for e in os.scandir(p.parent) if e.name.startswith(head)]
    except OSError:
        return  # an unreadable folder: the write says what is wrong
    for entry in entries:
        found = ours.fullmatch(entry.name)
        if found is None and unnamed.fullmatch(entry.name) is None:
            continue
        with contextlib.suppress(OSError):  # gone meanwhile (its writer finished), or kept
            old = now - entry.stat(follow_symlinks=False).st_mtime > STALE_AGE
            dead = found is not None and found[1] == host and not _running(int(found[2]))
            if (old or dead) and entry.is_file(follow_symlinks=False):
                os.unlink(entry.path)


def _running(pid: int) -> bool:
    """Whether a process ``pid`` runs on this machine (any user's)."""
    if pid <= 0:
        return False  # no process has that id (0 would signal our own group)
    try:
        os.kill(pid, 0)
    except (ProcessLookupError, OverflowError):
        return False
    except PermissionError:  # another user's process
        return True
    return True


def write_text_atomic(path: str | os.PathLike[str], text: str) -> None:
    """Write ``text`` (UTF-8) to ``path`` atomically (see :func:`atomic_path`)."""
    with atomic_path(path) as tmp:
        tmp.write_text(text, encoding="utf-8")


def unchanged(path: str | os.PathLike[str]) -> str:
    """What a failed write left: ``"the old file is unchanged"`` or ``"nothing was written"``."""
    return "the old file is unchanged" if Path(path).exists() else "nothing was written"


def write_failed(path: str | os.PathLike[str], exc: OSError, what: str = "") -> str:
    """One line for a write that failed, saying what it left.

    For example ``"arm.csv: cannot write the trajectory (No space left on
    device); the old file is unchanged"``; ``what`` names the content.
    """
    reason = exc.strerror or str(exc) or type(exc).__name__
    return f"{path}: cannot write {what or 'the file'} ({reason}); {unchanged(path)}"


def _mode(p: Path) -> int:
    """The old file's permission bits, else what ``open(p, "w")`` would give a new one."""
    try:
        return stat.S_IMODE(p.stat().st_mode)
    except OSError:
        return 0o666 & ~_umask()


def _umask() -> int:
    """The process umask: read from /proc on Linux (setting it to read it races threads)."""
    try:
        for line in Path("/proc/self/status").read_text().splitlines():
            if line.startswith("Umask:"):
                return int(line.split()[1], 8)
    except (OSError, ValueError, IndexError):
        pass
    umask = os.umask(0o022)
    os.umask(umask)
    return umask
