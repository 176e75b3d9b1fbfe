"""Where a ROS package's files are, without ROS: the package map.

xacro files name other files by package: ``$(find kuka_resources)/urdf/x.xacro``
and ``package://kuka_kr6_support/meshes/...``. ROS answers from its package
index; kinematica answers from a :class:`PackageMap`, which looks for a package

1. in the folders the user gave (``packages={"name": "dir"}`` on the loaders,
   ``--package NAME=DIR`` on the command line);
2. in the package the file itself belongs to: the nearest ``package.xml``
   above the file names it (``<name>...</name>``), and around it: the folder
   holding that package and the one above are searched as ``ROS_PACKAGE_PATH``
   folders are (a repository or workspace of several packages);
3. in the folders of ``ROS_PACKAGE_PATH`` (ROS 1): each is searched, to
   :data:`CRAWL_DEPTH` levels, for a ``package.xml`` naming the package;
4. in ``<prefix>/share/<name>`` of each prefix of ``AMENT_PREFIX_PATH`` (ROS 2).

The first answer wins. Nothing here runs code or reads anything but
``package.xml`` files (of at most :data:`PACKAGE_XML_MAX_BYTES` bytes, parsed
with defusedxml) and folder listings.
"""

from __future__ import annotations

import os
import re
from collections.abc import Mapping
from pathlib import Path
from typing import Final

from kinematica.errors import RobotFileError

__all__ = [
    "CRAWL_DEPTH",
    "CRAWL_MAX_DIRS",
    "PACKAGE_XML_MAX_BYTES",
    "PackageMap",
    "missing_package",
    "parse_package_option",
]

#: Folder levels below a ``ROS_PACKAGE_PATH`` entry searched for packages (a
#: catkin workspace's ``src/group/package`` is three deep).
CRAWL_DEPTH: Final = 4
#: Folders listed at most when searching ``ROS_PACKAGE_PATH``, so that an entry
#: such as ``/`` cannot make a load crawl the whole disk.
CRAWL_MAX_DIRS: Final = 20_000
#: Largest ``package.xml`` read (real ones are 1-5 kB).
PACKAGE_XML_MAX_BYTES: Final = 256 * 1024

_NAME: Final = re.compile(r"[A-Za-z0-9_][A-Za-z0-9_\-]*")


def _package_name(folder: Path) -> str | None:
    """The ``<name>`` of ``folder/package.xml``, or None (no file, unreadable, hostile)."""
    from defusedxml import ElementTree as SafeET

    path = folder / "package.xml"
    try:
        if not path.is_file() or path.stat().st_size > PACKAGE_XML_MAX_BYTES:
            return None
        root = SafeET.fromstring(path.read_bytes(), forbid_dtd=True)
    except Exception:  # unreadable, not XML, hostile XML: not a package we can name
        return None
    name = root.find("name")
    text = None if name is None or name.text is None else name.text.strip()
    return text or None


def missing_package(name: str, source: str | None) -> RobotFileError:
    """The one-line error for a package no rule found."""
    return RobotFileError(
        f"needs the ROS package {name!r}, which was not found: give its folder with "
        f"--package {name}=DIR (packages={{{name!r}: DIR}} in Python), or add the folder "
        "holding it to ROS_PACKAGE_PATH",
        path=source,
    )


def parse_package_option(text: str) -> tuple[str, str]:
    """``NAME=DIR`` (the ``--package`` option) as ``(name, dir)``.

    Raises:
        ValueError: not of that form, with what is wrong.
    """
    name, sep, folder = text.partition("=")
    name = name.strip()
    if not sep or not folder.strip():
        raise ValueError(f"--package takes NAME=DIR, got {text!r}")
    if _NAME.fullmatch(name) is None:
        raise ValueError(f"--package {text!r}: {name!r} is not a ROS package name")
    return name, folder.strip()


def _crawl(tops: list[Path]) -> dict[str, Path]:
    """Packages in and below the folders ``tops`` (first found wins).

    At most :data:`CRAWL_DEPTH` levels deep and :data:`CRAWL_MAX_DIRS` folders, and
    never inside a package (as ROS's crawl).
    """
    found: dict[str, Path] = {}
    listed = 0
    for top in tops:
        queue = [(top, 0)]
        while queue and listed < CRAWL_MAX_DIRS:
            folder, depth = queue.pop(0)
            listed += 1
            name = _package_name(folder)
            if name is not None:  # a package: ROS does not look inside it for more
                found.setdefault(name, folder)
                continue
            if depth >= CRAWL_DEPTH:
                continue
            try:
                children = sorted(p for p in folder.iterdir() if p.is_dir())
            except OSError:
                continue
            queue += [(c, depth + 1) for c in children if not c.name.startswith(".")]
    return found


class PackageMap:
    """Finds ROS packages' folders by the rules of the module docstring.

    Args:
        packages: Package name -> folder, given by the user; tried first.
        start: The file being read; its own package (and its siblings) come next.
        environ: The variables ``ROS_PACKAGE_PATH`` and ``AMENT_PREFIX_PATH`` are
            read from (default ``os.environ``).

    Raises:
        RobotFileError: a folder given in ``packages`` does not exist.
    """

    def __init__(
        self,
        packages: Mapping[str, str | os.PathLike[str]] | None = None,
        *,
        start: Path | None = None,
        environ: Mapping[str, str] | None = None,
    ) -> None:
        self._given: dict[str, Path] = {}
        for name, folder in (packages or {}).items():
            if not isinstance(name, str) or _NAME.fullmatch(name) is None:
                raise RobotFileError(f"packages: {name!r} is not a ROS package name")
            path = Path(folder).expanduser()
            if not path.is_dir():
                raise RobotFileError(
                    f"packages: the folder of {name!r}, {str(path)!r}, is not a folder"
                )
            self._given[name] = path.resolve()
        self._start = start
        env = os.environ if environ is None else environ
        self._ros_path = [Path(p) for p in env.get("ROS_PACKAGE_PATH", "").split(os.pathsep) if p]
        self._ament = [Path(p) for p in env.get("AMENT_PREFIX_PATH", "").split(os.pathsep) if p]
        self._found: dict[str, Path | None] = {}
        self._crawled: dict[str, Path] | None = None
        self._own: dict[str, Path] | None = None

    def find(self, name: str) -> Path | None:
        """The folder of package ``name``, or None when no rule finds it.

        A name that is not a ROS package name (``../..``) is found nowhere: it is
        never joined to a folder.
        """
        if _NAME.fullmatch(name) is None or name in (".", ".."):
            return None
        if name in self._given:
            return self._given[name]
        if name not in self._found:
            self._found[name] = self._search(name)
        return self._found[name]

    def own_folder(self) -> Path | None:
        """The folder of the package the file belongs to (nearest ``package.xml`` above it)."""
        if self._start is None:
            return None
        for folder in Path(self._start).resolve().parents:
            if _package_name(folder) is not None:
                return folder
        return None

    def folders(self) -> list[Path]:
        """The package folders found so far (those the user gave included)."""
        return [*self._given.values(), *(p for p in self._found.values() if p is not None)]

    def known(self) -> dict[str, Path]:
        """Every package the rules can name now (for a child process that resolves by name)."""
        found = {**self._ament_packages(), **self._crawl(), **self._own_packages(), **self._given}
        return {k: v.resolve() for k, v in found.items()}

    def _search(self, name: str) -> Path | None:
        own = self._own_packages().get(name)
        if own is not None:
            return own.resolve()
        crawled = self._crawl().get(name)
        if crawled is not None:
            return crawled.resolve()
        for prefix in self._ament:
            share = prefix / "share" / name
            if share.is_dir():
                return share.resolve()
        return None

    def _own_packages(self) -> dict[str, Path]:
        """The file's own package, and the packages around it (its repository, workspace)."""
        if self._own is not None:
            return self._own
        self._own = {}
        own = self.own_folder()
        if own is None:
            return self._own
        name = _package_name(own)
        assert name is not None
        # the folder holding the package and the one above it, as ROS_PACKAGE_PATH folders
        self._own = _crawl([own.parent, own.parent.parent])
        self._own[name] = own
        return self._own

    def _crawl(self) -> dict[str, Path]:
        """Packages under the ``ROS_PACKAGE_PATH`` folders (first found wins), bounded."""
        if self._crawled is None:
            self._crawled = _crawl(self._ros_path)
        return self._crawled

    def _ament_packages(self) -> dict[str, Path]:
        found: dict[str, Path] = {}
        for prefix in reversed(self._ament):  # the first prefix wins
            try:
                shares = [p for p in (prefix / "share").iterdir() if p.is_dir()]
            except OSError:
                continue
            found.update({p.name: p for p in shares})
        return found
