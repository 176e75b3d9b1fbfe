"""Expand one xacro file in a child process, within limits; run by :mod:`kinematica.io.xacro`.

Run as a script (``python -I _xacro_child.py FILE XACRO_DIR MAX_BYTES MAX_NODES
MAX_MEMORY ENV PACKAGES ARGS``), never imported by kinematica: it needs only the standard
library and the ``xacro`` package (found in ``XACRO_DIR``). It writes the
expanded URDF (UTF-8) to stdout and exits 0, or writes one line to stderr and
exits 2. The parent process bounds its time; here its memory (an address-space
limit), the elements it may create (every node a macro call or a loop clones
is counted, so a macro bomb stops at the limit instead of growing
exponentially) and its output are bounded. Unless ``ENV`` is ``1`` the
environment is empty and ``$(env ...)``, ``$(optenv ...)`` and their
``${env(...)}`` forms are refused by name. ``$(find pkg)`` is answered from
``PACKAGES``, a JSON object of package name -> folder (ROS is not needed);
``ARGS`` (JSON) gives the file's ``<xacro:arg>`` values.
"""

from __future__ import annotations

import json
import sys
import xml.dom.minidom
from types import ModuleType
from typing import Any

resource: ModuleType | None
try:
    import resource
except ImportError:  # not POSIX
    resource = None

_ENV_REFUSED = (
    "reads the environment variable {name!r}: refused, kinematica expands xacro without the "
    "environment unless asked (xacro_env=True, --xacro-env on the command line)"
)


class LimitExceededError(Exception):
    """The expansion went past one of its limits."""


def _count_clones(max_nodes: int) -> None:
    """Make every node minidom clones count towards ``max_nodes``."""
    clone = getattr(xml.dom.minidom, "_clone_node", None)
    if clone is None:  # another minidom: the time and memory limits still hold
        return
    made = 0

    def counted(node: Any, deep: bool, owner: Any) -> Any:
        nonlocal made
        made += 1
        if made > max_nodes:
            raise LimitExceededError(
                f"the expansion made more than {max_nodes} XML nodes: refused "
                "(a macro that calls itself or its callers many times over?)"
            )
        return clone(node, deep, owner)

    xml.dom.minidom._clone_node = counted  # type: ignore[attr-defined]


def _refuse_environment(substitution_args: Any, exception: type[Exception]) -> None:
    """Replace xacro's environment readers by ones that refuse, naming the variable."""

    def env(name: str, default: str | None = None) -> str:
        raise exception(_ENV_REFUSED.format(name=name))

    substitution_args._eval_env = env
    substitution_args._eval_optenv = env
    substitution_args._eval_dict["env"] = env
    substitution_args._eval_dict["optenv"] = env


def _find_in(substitution_args: Any, packages: dict[str, str], exception: type[Exception]) -> None:
    """Answer ``$(find pkg)`` from ``packages`` instead of ROS's package index."""

    def find(name: str) -> str:
        if name not in packages:
            raise exception(
                f"needs the ROS package {name!r}, which was not found: give its folder with "
                f"--package {name}=DIR (packages={{{name!r}: DIR}} in Python)"
            )
        return packages[name]

    substitution_args._eval_find = find
    substitution_args._eval_dict["find"] = find


def main(argv: list[str]) -> int:
    """Expand ``argv[0]``; see the module's docstring for the arguments."""
    path, xacro_dir, max_bytes, max_nodes, max_memory, allow_env, packages, args = argv
    sys.path.insert(0, xacro_dir)
    if resource is not None:  # POSIX; elsewhere the time and node limits still hold
        resource.setrlimit(resource.RLIMIT_AS, (int(max_memory), int(max_memory)))
    out, sys.stdout = sys.stdout, sys.stderr  # whatever xacro prints is not the URDF
    try:
        import xacro
        from xacro import substitution_args

        if allow_env != "1":
            _refuse_environment(substitution_args, substitution_args.SubstitutionException)
        _find_in(substitution_args, json.loads(packages), substitution_args.SubstitutionException)
        _count_clones(int(max_nodes))
        text = xacro.process_file(path, mappings=json.loads(args)).toxml()
    except MemoryError:
        sys.stderr.write(f"the expansion needed more than {int(max_memory)} bytes of memory\n")
        return 2
    except (Exception, SystemExit) as exc:  # xacro raises many types, and may exit
        cause: BaseException = exc
        while isinstance(getattr(cause, "exc", None), BaseException):  # xacro wraps its errors
            cause = cause.exc  # type: ignore[attr-defined]
        if isinstance(cause, MemoryError):
            sys.stderr.write(f"the expansion needed more than {int(max_memory)} bytes of memory\n")
            return 2
        detail = " ".join(str(cause).split()) or type(cause).__name__
        sys.stderr.write(detail + "\n")
        return 2
    data = text.encode("utf-8")
    if len(data) > int(max_bytes):
        sys.stderr.write(
            f"the expanded URDF is {len(data)} bytes, larger than the limit of {max_bytes} bytes\n"
        )
        return 2
    out.buffer.write(data)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
