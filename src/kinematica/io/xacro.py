"""Expanding xacro files into URDF, in a child process with limits.

xacro evaluates the expressions of the file it expands (Python, with a thin
guard), reads the files it includes and, through ``$(env NAME)`` and
``$(optenv NAME)``, the environment. So kinematica expands xacro only when
asked (a ``.xacro`` file, or ``xacro=True`` for a ``.urdf`` holding xacro),
and never in its own process: the ``xacro`` package runs in a child Python
(:mod:`kinematica.io._xacro_child`) that

- is stopped after :data:`XACRO_TIME_LIMIT` seconds (a loop or a huge number
  in an expression cannot hang the caller);
- may create at most :data:`XACRO_MAX_NODES` XML nodes by macro calls and
  loops (a "macro bomb", each macro calling the one before twice, stops there
  at once instead of doubling thirty times) and use at most
  :data:`XACRO_MAX_MEMORY` bytes of memory;
- may write at most the URDF size limit of expanded text;
- starts with an empty environment, and refuses ``$(env ...)`` and
  ``$(optenv ...)`` by name, unless ``env=True`` (``xacro_env=True`` on the
  loaders, ``--xacro-env`` on the command line) hands it the caller's;
- runs isolated (``python -I``): nothing from the file's folder is imported.

Includes are still read (the file's folder is the child's working
directory): expand only files you trust as far as reading goes.
"""

from __future__ import annotations

import importlib.util
import os
import sys
from pathlib import Path
from typing import Final

from kinematica.errors import RobotFileError

__all__ = [
    "XACRO_HINT",
    "XACRO_MAX_MEMORY",
    "XACRO_MAX_NODES",
    "XACRO_TIME_LIMIT",
    "expand_xacro",
]

#: Seconds a xacro expansion may take. Real descriptions (a humanoid with its
#: includes) expand in one or two seconds.
XACRO_TIME_LIMIT: Final = 10.0

#: XML nodes (elements and the text between them) a xacro expansion may create
#: by calling macros and unrolling loops. A URDF holds about one node per 40
#: bytes: a six-axis arm's 300 to 900, a PR2's (400 kB) about 10,000; this
#: allows some 1.2 MB of URDF. xacro's time grows with the square of the nodes
#: it adds to one element (30,000 take one to two seconds), so a far larger
#: limit would let a macro bomb run into the time limit instead of being named.
XACRO_MAX_NODES: Final = 30_000

#: Bytes of memory (address space) the expanding child process may use.
XACRO_MAX_MEMORY: Final = 2 * 2**30

#: How to get plain URDF from a xacro file, for messages.
XACRO_HINT: Final = (
    "load it with xacro=True (--xacro on the command line) to expand it with the xacro "
    "package, or expand it first: `xacro FILE > FILE.urdf`"
)

_CHILD = Path(__file__).with_name("_xacro_child.py")


def _xacro_dir() -> str | None:
    """The folder the installed ``xacro`` package is imported from, or None."""
    try:
        spec = importlib.util.find_spec("xacro")
    except (ImportError, ValueError):  # ValueError: sys.modules["xacro"] is None
        return None
    if spec is None or spec.origin is None:
        return None
    return str(Path(spec.origin).resolve().parent.parent)


def expand_xacro(path: str | os.PathLike[str], *, max_bytes: int, env: bool = False) -> bytes:
    """The URDF text that the ``xacro`` package makes of file ``path``, within limits.

    Args:
        path: The xacro file.
        max_bytes: Largest expanded text accepted, in bytes.
        env: Let xacro read the environment (``$(env ...)``, ``$(optenv ...)``,
            ROS package paths for ``$(find ...)``).

    Returns:
        The expanded URDF, UTF-8.

    Raises:
        RobotFileError: the ``xacro`` package is not installed, xacro reports
            an error, or the expansion goes past a limit (time, nodes, memory,
            size); one line naming the file.
    """
    p = Path(path).resolve()
    source = str(path)
    where = _xacro_dir()
    if where is None:
        raise RobotFileError(
            "a xacro file, and expanding it needs the xacro package "
            "(pip install 'kinematica[xacro]'); or expand it first: `xacro FILE > FILE.urdf`",
            path=source,
        )
    import subprocess  # only here: reading a plain URDF starts no process

    limit = float(XACRO_TIME_LIMIT)
    command = [
        sys.executable,
        "-I",
        str(_CHILD),
        str(p),
        where,
        str(max_bytes),
        str(XACRO_MAX_NODES),
        str(XACRO_MAX_MEMORY),
        "1" if env else "0",
    ]
    try:
        done = subprocess.run(
            command,
            capture_output=True,
            timeout=limit,
            env=dict(os.environ) if env else {},
            cwd=p.parent,
            check=False,
        )
    except subprocess.TimeoutExpired as exc:
        raise RobotFileError(
            f"xacro did not finish expanding the file within {limit:g} s: refused "
            "(an expression or a macro that runs without end?)",
            path=source,
        ) from exc
    except OSError as exc:
        raise RobotFileError(f"cannot run xacro: {exc.strerror or exc}", path=source) from exc
    if done.returncode != 0:
        lines = done.stderr.decode("utf-8", "replace").strip().splitlines()
        detail = lines[-1].strip() if lines else _signal(done.returncode)
        raise RobotFileError(f"xacro could not expand the file: {detail}", path=source)
    if len(done.stdout) > max_bytes:  # the child checks too; this holds whatever it did
        raise RobotFileError(
            f"the expanded URDF is larger than the limit of {max_bytes} bytes", path=source
        )
    return done.stdout


def _signal(code: int) -> str:
    """Why a child that printed nothing stopped."""
    if code < 0:
        return f"the expansion was stopped by signal {-code} (a limit of time or memory)"
    return f"the expansion failed with exit status {code}"
