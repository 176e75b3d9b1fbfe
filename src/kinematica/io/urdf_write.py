"""Writing a serial chain as URDF text, and URDF's roll-pitch-yaw of a rotation.

The text holds the kinematic part only (links without geometry, joints with
origin, axis and limits). Numbers are written with the shortest decimal that
reads back to the same float, so reading the file back reproduces every joint
origin to the last bit of its roll-pitch-yaw.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike

from kinematica.io.spec import FrameSpec
from kinematica.io.urdf_model import DH_FRAMES_NOTE, UrdfChain

__all__ = ["rpy_from_matrix", "urdf_text"]


def rpy_from_matrix(T: ArrayLike) -> tuple[float, float, float]:
    """URDF roll, pitch, yaw (rad) of a rotation: ``R = Rz(yaw) · Ry(pitch) · Rx(roll)``.

    Stable everywhere, gimbal lock included: yaw comes from the first column;
    roll and pitch from ``Rz(-yaw) · R``, whose second row is ``(0, cos r,
    -sin r)`` and first column ``(cos p, 0, -sin p)``, entries of size 1. In
    gimbal lock (pitch = ±90°) yaw is 0.

    Args:
        T: ``(3, 3)`` rotation or ``(4, 4)`` transform.

    Returns:
        ``(roll, pitch, yaw)``, roll and yaw in (-π, π], pitch in [-π/2, π/2].
    """
    R = np.asarray(T, dtype=float)[:3, :3]
    yaw = math.atan2(R[1, 0], R[0, 0])
    c, s = math.cos(yaw), math.sin(yaw)
    M = np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]]) @ R
    roll = math.atan2(-M[1, 2], M[1, 1])
    pitch = math.atan2(-M[2, 0], M[0, 0])
    return roll, pitch, yaw


def _num(v: float) -> str:
    v = float(v) + 0.0  # no "-0"
    return str(int(v)) if v.is_integer() and abs(v) < 1e15 else repr(v)


def _vec(values: Sequence[float]) -> str:
    return " ".join(_num(v) for v in values)


def _xyz_rpy(origin: FrameSpec) -> tuple[str, str]:
    if origin.matrix is None:
        return _vec(origin.xyz), _vec(origin.rpy or (0.0, 0.0, 0.0))
    return _vec(origin.xyz), _vec(rpy_from_matrix(origin.as_matrix()))


def urdf_text(chain: UrdfChain, comment: str | None = None) -> str:
    """The URDF text of a serial chain.

    Args:
        chain: The chain; its joints' origins may be given as ``rpy`` or as a
            matrix (written as roll-pitch-yaw).
        comment: A comment put at the top of ``<robot>`` (e.g. where the model
            comes from). A chain whose link frames are DH frames
            (``chain.dh_frames``) says so in a second comment
            (:data:`~kinematica.io.urdf_model.DH_FRAMES_NOTE`), which reading
            the file back finds.

    Returns:
        The XML document, ending with a newline. A revolute joint without
        limits is written ``continuous``; a prismatic joint without limits
        gets a ``<limit>`` with effort and velocity only.
    """
    root = ET.Element("robot", name=chain.name)
    if comment:
        root.append(ET.Comment(" " + " ".join(comment.replace("--", "- -").split()) + " "))
    if chain.dh_frames is not None:
        root.append(ET.Comment(f" {DH_FRAMES_NOTE.format(convention=chain.dh_frames)} "))
    for link in (chain.base, *(j.child for j in chain.joints)):
        ET.SubElement(root, "link", name=link)
    for j in chain.joints:
        jtype = "continuous" if j.type == "revolute" and j.limits is None else j.type
        elem = ET.SubElement(root, "joint", name=j.name, type=jtype)
        ET.SubElement(elem, "parent", link=j.parent)
        ET.SubElement(elem, "child", link=j.child)
        xyz, rpy = _xyz_rpy(j.origin)
        ET.SubElement(elem, "origin", xyz=xyz, rpy=rpy)
        if j.movable:
            ET.SubElement(elem, "axis", xyz=_vec(j.axis))
        if jtype in ("revolute", "prismatic"):
            limit = {"effort": "0", "velocity": "0"}
            if j.limits is not None:
                limit = {"lower": _num(j.limits[0]), "upper": _num(j.limits[1]), **limit}
            ET.SubElement(elem, "limit", limit)
    ET.indent(root)
    return '<?xml version="1.0"?>\n' + ET.tostring(root, encoding="unicode") + "\n"
