"""Expanding xacro files into URDF: safely by default, with the ``xacro`` package if trusted.

A xacro file is a program: the ``xacro`` package evaluates its expressions with
Python's ``eval`` behind a guard that a file can get around
(``${python.vars(python.type(f))['__globals__']...}`` reaches ``os.system``).
So kinematica expands xacro in one of two ways:

- **By default, with its own expander** (:mod:`kinematica.io.xacro_expand`):
  properties, macros, includes, conditionals, arguments and ``load_yaml``, with
  expressions parsed by Python's ``ast`` and evaluated by a whitelist walker of its
  own (arithmetic, comparisons, math functions, strings, lists; no ``eval``, no
  attribute of a Python object). It
  runs no code from the file, reads only files inside the file's folder and its
  packages' folders, and reads no environment variable unless ``env=True``.
  Anything else is refused with an error naming the file, the line and the
  expression.
- **With the ``xacro`` package, only when the caller trusts the file**
  (``trust_xacro=True`` on the loaders, ``--trust-xacro`` on the command line):
  for files that use what kinematica's expander refuses. The file's code then
  runs, in a child Python (:mod:`kinematica.io._xacro_child`) that

  - is stopped after :data:`XACRO_TIME_LIMIT` seconds;
  - may create at most :data:`XACRO_MAX_NODES` XML nodes by macro calls and
    loops (a "macro bomb" stops there at once) and use at most
    :data:`XACRO_MAX_MEMORY` bytes of memory;
  - may write at most the URDF size limit of expanded text;
  - starts with an empty environment, and refuses ``$(env ...)`` and
    ``$(optenv ...)`` by name, unless ``env=True``;
  - runs isolated (``python -I``): nothing from the file's folder is imported;
  - resolves ``$(find pkg)`` through the same package map.

  These limits bound its time and memory; they do not stop its code: trust
  only files you would run.

Both resolve ``$(find pkg)`` through a :class:`~kinematica.io.packages.PackageMap`.
"""

from __future__ import annotations

import importlib.util
import json
import os
import sys
from collections.abc import Mapping
from pathlib import Path
from typing import Final

from kinematica.errors import RobotFileError

__all__ = [
    "XACRO_HINT",
    "XACRO_MAX_MEMORY",
    "XACRO_MAX_NODES",
    "XACRO_TIME_LIMIT",
    "expand_xacro",
    "xacro_to_urdf",
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
    "load it with xacro=True (--xacro on the command line) to expand it, "
    "or expand it first: `xacro FILE > FILE.urdf`"
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


def xacro_to_urdf(
    path: str | os.PathLike[str],
    *,
    max_bytes: int,
    env: bool = False,
    trust: bool = False,
    packages: Mapping[str, str | os.PathLike[str]] | None = None,
    args: Mapping[str, str] | None = None,
) -> bytes:
    """The URDF text xacro file ``path`` expands to: by kinematica's expander, or trusted.

    Args:
        path: The xacro file.
        max_bytes: Largest file and expanded text accepted, in bytes.
        env: Allow ``$(env ...)`` and ``$(optenv ...)``.
        trust: Expand with the ``xacro`` package, running the file's code
            (see the module docstring); otherwise kinematica's own expander.
        packages: Package name -> folder, for ``$(find pkg)``; the rules of
            :class:`~kinematica.io.packages.PackageMap` find the others.
        args: Values of the file's ``<xacro:arg>`` (``name:=value`` on xacro's
            command line), over their defaults.

    Raises:
        RobotFileError: one line naming the file (and the line and expression
            for kinematica's expander): a refused or malformed construct, a
            missing package, a limit passed, or (trusted) xacro's error.
    """
    from kinematica.io.packages import PackageMap

    pmap = PackageMap(packages, start=Path(path))
    if trust:
        return expand_xacro(path, max_bytes=max_bytes, env=env, packages=pmap.known(), args=args)
    from xml.etree import ElementTree

    from kinematica.io.xacro_expand import expand

    root = expand(
        path,
        max_bytes=max_bytes,
        max_nodes=XACRO_MAX_NODES,
        time_limit=XACRO_TIME_LIMIT,
        env=env,
        packages=pmap,
        args=args,
    )
    text: bytes = ElementTree.tostring(root, encoding="utf-8")
    if len(text) > max_bytes:
        raise RobotFileError(
            f"the expanded URDF is larger than the limit of {max_bytes} bytes", path=str(path)
        )
    return text


def expand_xacro(
    path: str | os.PathLike[str],
    *,
    max_bytes: int,
    env: bool = False,
    packages: Mapping[str, Path] | None = None,
    args: Mapping[str, str] | None = None,
) -> bytes:
    """The URDF text that the ``xacro`` package makes of file ``path``, within limits.

    This runs the file's code (in a child process with limits): only for trusted
    files; :func:`xacro_to_urdf` chooses.

    Args:
        path: The xacro file.
        max_bytes: Largest expanded text accepted, in bytes.
        env: Let xacro read the environment (``$(env ...)``, ``$(optenv ...)``).
        packages: Package name -> folder, answering ``$(find pkg)``.
        args: Values of the file's ``<xacro:arg>``.

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
            "trust_xacro=True (--trust-xacro) expands with the xacro package, which is not "
            "installed (pip install 'kinematica[xacro]'); without it kinematica's own expander "
            "is used",
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
        json.dumps({k: str(v) for k, v in (packages or {}).items()}),
        json.dumps(dict(args or {})),
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
