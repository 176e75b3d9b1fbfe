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
- xacro is expanded only when asked: a ``.xacro`` file, or ``xacro=True`` for a
  ``.urdf`` holding xacro (elements in the ``xacro`` namespace, ``${...}`` or
  ``$(...)`` in attributes); otherwise such a file is refused with the option
  to give. kinematica's own expander runs no code from the file, reads only
  files inside its folder and its packages, and not the environment; the
  ``xacro`` package is used only with ``trust_xacro=True``
  (:mod:`kinematica.io.xacro`). A file that merely declares ``xmlns:xacro`` (as
  many generated URDFs do) is plain URDF.
"""

from __future__ import annotations

import math
import os
import stat
import warnings
from collections.abc import Mapping
from pathlib import Path
from typing import Any, Final

from kinematica.errors import KinematicaWarning, RobotFileError
from kinematica.io.spec import FrameSpec
from kinematica.io.urdf_model import (
    JOINT_TYPES,
    MOVABLE_TYPES,
    UrdfJoint,
    UrdfModel,
    dh_frames_note,
)
from kinematica.io.xacro import XACRO_HINT, xacro_to_urdf
from kinematica.io.xml_parse import local_name as _local
from kinematica.io.xml_parse import parse_xml

__all__ = ["URDF_MAX_BYTES", "parse_urdf", "read_urdf"]

#: Largest URDF file read, in bytes (real arm descriptions are a few tens of kB;
#: humanoids with inline meshes lists stay under a few MB).
URDF_MAX_BYTES = 16 * 2**20


#: Largest size of a joint origin's coordinate or a prismatic limit, in metres.
#: The largest machines a URDF describes (cranes, gantries) measure tens of
#: metres; a million metres leaves four orders of margin and keeps every
#: product of lengths the kinematics form (squares, cross products) far from
#: overflow, which 1e154 m reaches.
URDF_MAX_LENGTH: Final = 1e6

#: Largest size of an origin's roll, pitch or yaw, or of a revolute limit, in
#: radians (1,591 turns). Files hold a few turns at most; an angle this large
#: is still known to 2e-12 rad (one unit in the last place), so its rotation is
#: as exact as the rest of the model, which a 1e16 rad angle is not at all.
URDF_MAX_ANGLE: Final = 1e4

#: An ``<axis xyz>`` is a direction and is normalised; its components may be at
#: most this large and its length at least the inverse. Beyond, the numbers are
#: not a direction anyone writes (1e200 1e200 0) or are too small to hold one.
URDF_AXIS_SCALE: Final = 1e6


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
    return parse_xml(data, source, hint=XACRO_HINT)


def _numbers(
    text: str | None, count: int, default: tuple[float, ...], what: str, bound: float, unit: str
) -> list[float]:
    """``count`` finite numbers of at most ``bound`` in size from an attribute's text."""
    if text is None:
        return list(default)
    try:
        values = [float(p) for p in text.split()]
    except ValueError:
        values = []
    if len(values) == count and all(-bound <= v <= bound for v in values):
        return values  # NaN fails both comparisons
    shown = text.strip()[:60]
    if len(values) != count:
        raise ValueError(f'{what}="{shown}" must be {count} numbers')
    if not all(math.isfinite(v) for v in values):
        raise ValueError(f'{what}="{shown}" holds NaN or inf')
    big = next(v for v in values if abs(v) > bound)
    raise ValueError(f'{what}="{shown}" holds {big:g}: the accepted range is ±{bound:g}{unit}')


def _axis(axis_elem: Any, jtype: str) -> tuple[float, float, float]:
    """The unit axis of a joint: ``<axis xyz>`` (any length within the scale) normalised."""
    text = None if axis_elem is None else axis_elem.get("xyz")
    axis = _numbers(text, 3, (1, 0, 0), "axis xyz", URDF_AXIS_SCALE, "")
    norm = math.hypot(*axis)  # hypot neither overflows nor underflows
    if jtype not in MOVABLE_TYPES:
        return (axis[0] / norm, axis[1] / norm, axis[2] / norm) if norm > 0.0 else (1.0, 0.0, 0.0)
    if norm == 0.0:
        raise ValueError(f"has a zero axis (axis xyz={' '.join(map(str, axis))!r})")
    if norm < 1.0 / URDF_AXIS_SCALE:
        raise ValueError(
            f'has axis xyz="{(text or "").strip()[:60]}" of length {norm:.3g}: a direction '
            f"needs a length of at least {1.0 / URDF_AXIS_SCALE:g} (a near-zero axis has none)"
        )
    return (axis[0] / norm, axis[1] / norm, axis[2] / norm)


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


def _missing_limits_warning(names: list[str], source: str | None) -> None:
    """Warn of revolute and prismatic joints without ``<limit>`` (read as free), by name."""
    if not names:
        return
    where = f"{source}: " if source else ""
    listed = ", ".join(repr(n) for n in names)
    warnings.warn(
        f"{where}joint{'s' if len(names) > 1 else ''} {listed} "
        f"{'have' if len(names) > 1 else 'has'} no <limit>, which the URDF specification "
        "requires of revolute and prismatic joints: read as free (no joint limits)",
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
    parts: dict[str, Any] = {}  # the first child element of each tag, in one pass
    counts = {"parent": 0, "child": 0}
    for e in elem:
        tag = _local(e.tag)
        parts.setdefault(tag, e)
        if tag in counts:
            counts[tag] += 1
    links = {}
    for role in ("parent", "child"):
        link = parts[role].get("link") if counts[role] == 1 else None
        if not link:
            raise ValueError(f'needs exactly one <{role} link="..."/>')
        links[role] = link
    first = parts.get

    origin_elem = first("origin")
    xyz_text = None if origin_elem is None else origin_elem.get("xyz")
    rpy_text = None if origin_elem is None else origin_elem.get("rpy")
    xyz = _numbers(xyz_text, 3, (0, 0, 0), "origin xyz", URDF_MAX_LENGTH, " m")
    rpy = _numbers(rpy_text, 3, (0, 0, 0), "origin rpy", URDF_MAX_ANGLE, " rad")
    unit = _axis(first("axis"), jtype)
    limits = None
    limit_elem = first("limit")
    if jtype in ("revolute", "prismatic") and limit_elem is not None:
        lower, upper = limit_elem.get("lower"), limit_elem.get("upper")
        if lower is not None or upper is not None:
            bound, unit_name = (
                (URDF_MAX_ANGLE, " rad") if jtype == "revolute" else (URDF_MAX_LENGTH, " m")
            )
            lo = _numbers(lower, 1, (0.0,), "limit lower", bound, unit_name)[0]
            hi = _numbers(upper, 1, (0.0,), "limit upper", bound, unit_name)[0]
            if _no_limits(jtype, lo, hi):
                limits = None  # "no limits given" (the reader warns)
            elif not lo < hi:
                raise ValueError(
                    f"has limits lower={lo:g} >= upper={hi:g}: the joint cannot move "
                    "(make it fixed, or give lower < upper)"
                )
            else:
                limits = (lo, hi)
    mimic_elem = first("mimic")
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
    return _model(_parse_xml(raw, source), source, dh_frames_note(raw))


def _model(root: Any, source: str | None, dh_frames: str | None = None) -> UrdfModel:
    """The model of a parsed ``<robot>`` tree."""
    if _local(root.tag) != "robot":
        raise RobotFileError(
            f"not a URDF: the root element is <{_local(root.tag)}>, expected <robot>", path=source
        )
    why = _is_xacro(root)
    if why is not None:
        raise RobotFileError(f"a xacro file, not plain URDF: {why}; {XACRO_HINT}", path=source)
    # dicts, not lists, for the duplicate checks: a file may hold 100,000 links
    links: dict[str, None] = {}
    for elem in root:
        if _local(elem.tag) != "link":
            continue
        name = elem.get("name")
        if not name:
            raise RobotFileError(f"link number {len(links) + 1} has no name", path=source)
        if name in links:
            raise RobotFileError(f"two links are named {name!r}", path=source)
        links[name] = None
    joints: dict[str, UrdfJoint] = {}
    unlimited: list[str] = []
    for elem in root:
        if _local(elem.tag) != "joint":
            continue
        name = elem.get("name")
        if not name:
            raise RobotFileError(f"joint number {len(joints) + 1} has no name", path=source)
        if name in joints:
            raise RobotFileError(f"two joints are named {name!r}", path=source)
        try:
            joints[name] = _joint(elem)
        except ValueError as exc:
            raise RobotFileError(f"joint {name!r} {exc}", path=source) from exc
        _zero_limits_warning(elem, source)
        if elem.get("type") in ("revolute", "prismatic") and not any(
            _local(e.tag) == "limit" for e in elem
        ):
            unlimited.append(name)
    _missing_limits_warning(unlimited, source)
    if not links:
        raise RobotFileError("the URDF has no <link>", path=source)
    return UrdfModel(
        name=root.get("name") or Path(source or "robot").stem,
        links=tuple(links),
        joints=tuple(joints.values()),
        source=source,
        dh_frames=dh_frames,
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


def read_urdf(
    path: str | os.PathLike[str],
    *,
    max_bytes: int = URDF_MAX_BYTES,
    xacro: bool = False,
    xacro_env: bool = False,
    trust_xacro: bool = False,
    packages: Mapping[str, str | os.PathLike[str]] | None = None,
    xacro_args: Mapping[str, str] | None = None,
) -> UrdfModel:
    """Read a URDF file, or a xacro file expanded into URDF.

    Args:
        path: The file.
        max_bytes: Size limit in bytes of the file, and of its expansion;
            larger files are refused unread.
        xacro: Expand xacro in a ``.urdf`` file too (a ``.xacro`` file is
            always expanded). Without it, a ``.urdf`` holding xacro is refused.
        xacro_env: Let xacro read the environment (``$(env ...)``,
            ``$(optenv ...)``); refused otherwise.
        trust_xacro: Expand with the ``xacro`` package, which runs the file's
            code (in a child process with limits); by default kinematica's own
            expander, which runs none (see :mod:`kinematica.io.xacro`).
        packages: ROS package name -> folder, for ``$(find pkg)`` in xacro
            files (``ROS_PACKAGE_PATH``, ``AMENT_PREFIX_PATH`` and the file's
            own ``package.xml`` find the others).
        xacro_args: Values of the xacro file's ``<xacro:arg>`` (as xacro's
            ``name:=value``), over their defaults.

    Returns:
        The links and joints, checked to form one tree.

    Raises:
        RobotFileError: missing, not a regular file, too large, not valid or
            hostile XML, xacro not asked for or failing (refused constructs,
            missing packages, limits), or a malformed URDF (the message names
            the joint or link).
    """
    p = Path(path)
    source = str(p)
    data = _read_bytes(p, max_bytes)
    root = _parse_xml(data, source)  # hostile XML is refused before xacro sees it
    if p.name.lower().endswith(".xacro") or (xacro and _is_xacro(root) is not None):
        expanded = xacro_to_urdf(
            p,
            max_bytes=max_bytes,
            env=xacro_env,
            trust=trust_xacro,
            packages=packages,
            args=xacro_args,
        )
        return parse_urdf(expanded, source=source)
    return _model(root, source, dh_frames_note(data))
