"""Reading URDF files, hardened: the kinematic part into a :class:`UrdfModel`.

Only what kinematics needs is read: ``<link name>`` and each ``<joint>``'s
type, parent, child, ``<origin xyz rpy>``, ``<axis xyz>``, ``<limit lower
upper>`` and ``<mimic joint>``; visuals, collisions, inertias, transmissions
and plugins are skipped. Each problem raises one
:class:`~kinematica.errors.RobotFileError` naming the file, the joint or link
and what is wrong.

A URDF may come from anywhere, so it is read defensively:

- the path must be a regular file (not a FIFO or a device: no hang) of at most
  :data:`URDF_MAX_BYTES` bytes;
- the XML is parsed with ``defusedxml``: entity declarations (the "billion
  laughs" bomb and its relatives), external entities and DTD-based tricks are
  refused with a clear error instead of being expanded;
- a xacro file (elements in the ``xacro`` namespace, ``${...}`` or ``$(...)``
  in attributes, or a ``.xacro`` name) is expanded with the ``xacro`` package
  when it is installed (``pip install 'kinematica[xacro]'``; xacro evaluates
  the file's expressions and reads its includes, so expand only files you
  trust), and otherwise refused with the command that expands it. A file that
  merely declares ``xmlns:xacro`` (as many generated URDFs do) is plain URDF.
"""

from __future__ import annotations

import contextlib
import io
import math
import os
import stat
import warnings
from pathlib import Path
from typing import Any

from kinematica.errors import KinematicaWarning, RobotFileError
from kinematica.io.spec import FrameSpec
from kinematica.io.urdf_model import JOINT_TYPES, MOVABLE_TYPES, UrdfJoint, UrdfModel

__all__ = ["URDF_MAX_BYTES", "URDF_SUFFIXES", "parse_urdf", "read_urdf"]

#: Largest URDF file read, in bytes (real arm descriptions are a few tens of kB;
#: humanoids with inline meshes lists stay under a few MB).
URDF_MAX_BYTES = 16 * 2**20

#: File name endings read as URDF (``.xacro`` ones are expanded first).
URDF_SUFFIXES = (".urdf", ".xacro")

_XACRO_HINT = (
    "expand it first: `xacro FILE > FILE.urdf` (pip install xacro), or install xacro "
    "(pip install 'kinematica[xacro]') and kinematica expands it when loading"
)


def _local(tag: object) -> str:
    """An element's tag without its ``{namespace}``."""
    return str(tag).rsplit("}", 1)[-1]


def _is_xacro(root: Any) -> str | None:
    """Why the tree needs xacro, or None when it is plain URDF."""
    for elem in root.iter():
        tag = str(elem.tag)
        if tag.startswith("{") and "xacro" in tag.split("}", 1)[0]:
            return f"it has xacro elements (<xacro:{_local(tag)}>)"
        for value in elem.attrib.values():
            if "${" in value or "$(" in value:
                return f"it uses xacro substitutions ({value.strip()[:40]!r})"
    return None


def _parse_xml(data: bytes, source: str | None) -> Any:
    """The XML root element, parsed by defusedxml (no entities, no external refs)."""
    import defusedxml
    from defusedxml import ElementTree as SafeET

    def fail(message: str) -> RobotFileError:
        return RobotFileError(message, path=source)

    try:
        return SafeET.fromstring(data, forbid_dtd=False, forbid_entities=True, forbid_external=True)
    except defusedxml.EntitiesForbidden as exc:
        raise fail(
            f"the XML declares an entity ({exc.name!r}): refused, since entity expansion is how "
            "XML bombs work and a URDF needs none"
        ) from exc
    except defusedxml.ExternalReferenceForbidden as exc:
        raise fail(
            f"the XML refers to an external resource ({exc.sysid or exc.pubid!r}): refused, "
            "a URDF is read on its own"
        ) from exc
    except defusedxml.DefusedXmlException as exc:
        raise fail(f"the XML uses a forbidden construct: {exc}") from exc
    except SafeET.ParseError as exc:
        line, column = getattr(exc, "position", (0, 0))
        what = str(exc).split(":")[0]
        if b"xacro:" in data:
            hint = f"not valid XML ({what}): it looks like a xacro file; {_XACRO_HINT}"
            raise fail(hint) from exc
        raise fail(f"not valid XML: {what} (line {line}, column {column + 1})") from exc
    except RecursionError as exc:  # pragma: no cover - expat does not recurse; defensive
        raise fail("the XML is nested too deeply") from exc


def _numbers(text: str | None, count: int, default: tuple[float, ...], what: str) -> list[float]:
    if text is None:
        return list(default)
    parts = text.split()
    try:
        values = [float(p) for p in parts]
    except ValueError:
        values = []
    if len(values) != count:
        raise ValueError(f'{what}="{text.strip()[:60]}" must be {count} numbers')
    if not all(math.isfinite(v) for v in values):
        raise ValueError(f'{what}="{text.strip()[:60]}" holds NaN or inf')
    return values


def _no_limits(jtype: str, lo: float, hi: float) -> bool:
    """True for ``<limit lower="0" upper="0">`` on a revolute joint: "no limits given".

    CAD exporters (and example-robot-data's ``double_pendulum.urdf``) write it for a
    joint without limits; Pinocchio reads it so. A joint that truly cannot move is
    written as fixed.
    """
    return jtype == "revolute" and lo == 0.0 and hi == 0.0


def _zero_limits_warning(elem: Any, source: str | None) -> None:
    """Warn that a joint's ``lower="0" upper="0"`` was read as no limits."""
    limit = next((e for e in elem if _local(e.tag) == "limit"), None)
    if limit is None or elem.get("type") != "revolute":
        return
    if limit.get("lower") is None and limit.get("upper") is None:
        return  # no bounds written: no limits, nothing to say
    try:
        lo = float(limit.get("lower") or 0.0)
        hi = float(limit.get("upper") or 0.0)
    except ValueError:
        return
    if _no_limits("revolute", lo, hi):
        where = f"{source}: " if source else ""
        warnings.warn(
            f"{where}joint {elem.get('name')!r} has limits lower=0 upper=0, what CAD "
            "exporters write for a joint without limits: read as no limits",
            KinematicaWarning,
            stacklevel=4,
        )


def _joint(elem: Any) -> UrdfJoint:
    """One ``<joint>`` element; raises ValueError with the problem (no joint name)."""
    jtype = elem.get("type")
    if jtype is None:
        raise ValueError("has no type")
    if jtype not in JOINT_TYPES:
        raise ValueError(f"has unknown type {jtype!r} (expected one of {', '.join(JOINT_TYPES)})")
    links = {}
    for role in ("parent", "child"):
        found = [e for e in elem if _local(e.tag) == role]
        if len(found) != 1 or not found[0].get("link"):
            raise ValueError(f'needs exactly one <{role} link="..."/>')
        links[role] = found[0].get("link")
    origin_elem = next((e for e in elem if _local(e.tag) == "origin"), None)
    xyz = _numbers(
        None if origin_elem is None else origin_elem.get("xyz"), 3, (0, 0, 0), "origin xyz"
    )
    rpy = _numbers(
        None if origin_elem is None else origin_elem.get("rpy"), 3, (0, 0, 0), "origin rpy"
    )
    axis_elem = next((e for e in elem if _local(e.tag) == "axis"), None)
    axis = _numbers(None if axis_elem is None else axis_elem.get("xyz"), 3, (1, 0, 0), "axis xyz")
    norm = math.sqrt(sum(v * v for v in axis))
    if jtype in MOVABLE_TYPES and norm == 0.0:
        raise ValueError(f"has a zero axis (axis xyz={' '.join(map(str, axis))!r})")
    unit = (axis[0] / norm, axis[1] / norm, axis[2] / norm) if norm > 0.0 else (1.0, 0.0, 0.0)
    limits = None
    limit_elem = next((e for e in elem if _local(e.tag) == "limit"), None)
    if jtype in ("revolute", "prismatic") and limit_elem is not None:
        lower, upper = limit_elem.get("lower"), limit_elem.get("upper")
        if lower is not None or upper is not None:
            lo = _numbers(lower, 1, (0.0,), "limit lower")[0]
            hi = _numbers(upper, 1, (0.0,), "limit upper")[0]
            if _no_limits(jtype, lo, hi):
                limits = None  # "no limits given" (the reader warns)
            elif not lo < hi:
                raise ValueError(
                    f"has limits lower={lo:g} >= upper={hi:g}: the joint cannot move "
                    "(make it fixed, or give lower < upper)"
                )
            else:
                limits = (lo, hi)
    mimic_elem = next((e for e in elem if _local(e.tag) == "mimic"), None)
    mimic = None if mimic_elem is None else (mimic_elem.get("joint") or "?")
    return UrdfJoint(
        name=elem.get("name") or "",
        type=jtype,
        parent=links["parent"],
        child=links["child"],
        origin=FrameSpec(xyz=(xyz[0], xyz[1], xyz[2]), rpy=(rpy[0], rpy[1], rpy[2])),
        axis=unit,
        limits=limits,
        mimic=mimic,
    )


def parse_urdf(data: bytes | str, *, source: str | None = None) -> UrdfModel:
    """Parse URDF text (plain URDF, not xacro) into a :class:`UrdfModel`.

    Args:
        data: The file's content (bytes, so the XML declaration picks the
            encoding, or text).
        source: Where it came from, for messages and ``UrdfModel.source``.

    Raises:
        RobotFileError: not valid or hostile XML, xacro, not a ``<robot>``, a
            malformed joint or link, or links and joints that are not one tree.
    """
    raw = data.encode("utf-8") if isinstance(data, str) else bytes(data)
    return _model(_parse_xml(raw, source), source)


def _model(root: Any, source: str | None) -> UrdfModel:
    """The model of a parsed ``<robot>`` tree."""
    if _local(root.tag) != "robot":
        raise RobotFileError(
            f"not a URDF: the root element is <{_local(root.tag)}>, expected <robot>", path=source
        )
    why = _is_xacro(root)
    if why is not None:
        raise RobotFileError(f"a xacro file, not plain URDF: {why}; {_XACRO_HINT}", path=source)
    links: list[str] = []
    for elem in root:
        if _local(elem.tag) != "link":
            continue
        name = elem.get("name")
        if not name:
            raise RobotFileError(f"link number {len(links) + 1} has no name", path=source)
        if name in links:
            raise RobotFileError(f"two links are named {name!r}", path=source)
        links.append(name)
    joints: list[UrdfJoint] = []
    for elem in root:
        if _local(elem.tag) != "joint":
            continue
        name = elem.get("name")
        if not name:
            raise RobotFileError(f"joint number {len(joints) + 1} has no name", path=source)
        if any(j.name == name for j in joints):
            raise RobotFileError(f"two joints are named {name!r}", path=source)
        try:
            joints.append(_joint(elem))
        except ValueError as exc:
            raise RobotFileError(f"joint {name!r} {exc}", path=source) from exc
        _zero_limits_warning(elem, source)
    if not links:
        raise RobotFileError("the URDF has no <link>", path=source)
    return UrdfModel(
        name=root.get("name") or Path(source or "robot").stem,
        links=tuple(links),
        joints=tuple(joints),
        source=source,
    )


def _read_bytes(p: Path, max_bytes: int) -> bytes:
    source = str(p)
    try:
        info = p.stat()
    except FileNotFoundError as exc:
        raise RobotFileError("file not found", path=source) from exc
    except OSError as exc:
        raise RobotFileError(f"cannot read the file: {exc.strerror or exc}", path=source) from exc
    if stat.S_ISDIR(info.st_mode):
        raise RobotFileError("is a directory, not a URDF file", path=source)
    if not stat.S_ISREG(info.st_mode):
        raise RobotFileError("not a regular file (a device, FIFO or socket)", path=source)
    too_big = f"larger than the URDF size limit of {max_bytes} bytes"
    if info.st_size > max_bytes:
        raise RobotFileError(f"the file is {info.st_size} bytes, {too_big}", path=source)
    try:
        with p.open("rb") as fh:
            data = fh.read(max_bytes + 1)
    except OSError as exc:
        raise RobotFileError(f"cannot read the file: {exc.strerror or exc}", path=source) from exc
    if len(data) > max_bytes:
        raise RobotFileError(f"the file is {too_big}", path=source)
    return data


def _expand_xacro(p: Path, why: str) -> bytes:
    """The URDF text that the ``xacro`` package makes of file ``p``."""
    try:
        import xacro
    except ImportError as exc:
        raise RobotFileError(f"a xacro file ({why}); {_XACRO_HINT}", path=str(p)) from exc
    captured = io.StringIO()
    try:
        with contextlib.redirect_stdout(captured), contextlib.redirect_stderr(captured):
            doc = xacro.process_file(str(p))
        text: str = doc.toxml()
    except (Exception, SystemExit) as exc:  # xacro raises many types, and may exit
        detail = " ".join(str(exc).split())
        if not detail:
            lines = captured.getvalue().strip().splitlines()
            detail = lines[-1] if lines else type(exc).__name__
        raise RobotFileError(f"xacro could not expand the file: {detail}", path=str(p)) from exc
    return text.encode("utf-8")


def read_urdf(path: str | os.PathLike[str], *, max_bytes: int = URDF_MAX_BYTES) -> UrdfModel:
    """Read a URDF file (or a xacro file, expanded with the ``xacro`` package).

    Args:
        path: The file.
        max_bytes: Size limit in bytes; larger files are refused unread.

    Returns:
        The links and joints, checked to form one tree.

    Raises:
        RobotFileError: missing, not a regular file, too large, not valid or
            hostile XML, xacro without the ``xacro`` package, or a malformed
            URDF (the message names the joint or link).
    """
    p = Path(path)
    source = str(p)
    data = _read_bytes(p, max_bytes)
    root = _parse_xml(data, source)  # hostile XML is refused before xacro sees it
    why = "a .xacro file" if p.name.lower().endswith(".xacro") else _is_xacro(root)
    if why is not None:
        expanded = _expand_xacro(p, why)
        return parse_urdf(expanded, source=source)
    return _model(root, source)
