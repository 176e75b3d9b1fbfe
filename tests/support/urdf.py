"""Test helpers for URDF: an independent reference FK, URDF text for random chains.

The reference reads the XML with the standard library (the test files are
trusted) and composes, joint by joint, ``Trans(xyz) · Rot(rpy)`` and the
joint's motion, with scipy's ``Rotation`` for the roll-pitch-yaw (extrinsic
x-y-z) and for the axis-angle rotation. It shares no code with kinematica.
"""

from __future__ import annotations

import math
import warnings
import xml.etree.ElementTree as ET
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest
from hypothesis import strategies as st
from numpy.typing import NDArray
from scipy.spatial.transform import Rotation

import kinematica as km
from kinematica.io import parse_urdf
from support import DATA

FloatArray = NDArray[np.float64]

URDF_DIR = DATA / "urdf"


def _vec(text: str | None, default: Sequence[float]) -> FloatArray:
    return np.array(default if text is None else [float(v) for v in text.split()], dtype=float)


def _origin(joint: ET.Element) -> FloatArray:
    o = joint.find("origin")
    xyz = _vec(None if o is None else o.get("xyz"), (0, 0, 0))
    rpy = _vec(None if o is None else o.get("rpy"), (0, 0, 0))
    T = np.eye(4)
    T[:3, :3] = Rotation.from_euler("xyz", rpy).as_matrix()  # extrinsic: Rz(y) Ry(p) Rx(r)
    T[:3, 3] = xyz
    return T


def _motion(joint: ET.Element, q: float) -> FloatArray:
    a = joint.find("axis")
    axis = _vec(None if a is None else a.get("xyz"), (1, 0, 0))
    axis = axis / np.linalg.norm(axis)
    M = np.eye(4)
    if joint.get("type") == "prismatic":
        M[:3, 3] = axis * q
    else:
        M[:3, :3] = Rotation.from_rotvec(axis * q).as_matrix()
    return M


@dataclass(frozen=True)
class ReferenceChain:
    """The joints of a URDF from ``base`` to ``tip``, as XML elements."""

    joints: tuple[ET.Element, ...]
    base: str
    tip: str

    @property
    def movable(self) -> list[ET.Element]:
        return [j for j in self.joints if j.get("type") != "fixed"]

    @property
    def dof(self) -> int:
        return len(self.movable)

    def fk(self, q: Sequence[float]) -> FloatArray:
        """Pose of the tip link in the base link frame, ``(4, 4)``."""
        T = np.eye(4)
        values = iter(q)
        for j in self.joints:
            T = T @ _origin(j)
            if j.get("type") != "fixed":
                T = T @ _motion(j, float(next(values)))
        return T

    def fk_batch(self, q: FloatArray) -> FloatArray:
        flat = q.reshape(-1, self.dof)
        return np.array([self.fk(row) for row in flat]).reshape(*q.shape[:-1], 4, 4)


def reference_chain(text: str, base: str | None = None, tip: str | None = None) -> ReferenceChain:
    """The chain from ``base`` (default the root) to ``tip`` (default the only leaf)."""
    root = ET.fromstring(text)
    joints = root.findall("joint")  # direct children only: not <transmission>'s joints
    by_child = {j.find("child").get("link"): j for j in joints}
    links = [link.get("name") for link in root.findall("link")]
    start = base or next(name for name in links if name not in by_child)
    if tip is None:
        parents = {j.find("parent").get("link") for j in joints}
        leaves = [name for name in links if name not in parents and name != start]
        assert len(leaves) == 1, leaves
        tip = leaves[0]
    path, link = [], tip
    while link != start:
        j = by_child[link]
        path.append(j)
        link = j.find("parent").get("link")
    return ReferenceChain(tuple(reversed(path)), start, tip)


def link_poses(chain: ReferenceChain) -> dict[str, FloatArray]:
    """Pose of every link of the chain at q = 0, in the base link frame."""
    poses, T = {chain.base: np.eye(4)}, np.eye(4)
    for j in chain.joints:
        T = T @ _origin(j)  # the joint's motion is the identity at q = 0
        poses[j.find("child").get("link")] = T
    return poses


def reference_file(name: str, base: str | None = None, tip: str | None = None) -> ReferenceChain:
    return reference_chain((URDF_DIR / name).read_text(), base, tip)


# ------------------------------------------------------------------ random chains
def _num(v: float) -> str:
    return repr(float(v))


def urdf_from_joints(joints: Sequence[dict[str, object]], name: str = "random") -> str:
    """URDF text of a chain ``base -> l1 -> ... -> tip`` from plain joint dicts.

    Each dict has ``type``, ``xyz``, ``rpy``, ``axis`` and optionally ``limits``.
    """
    lines = ['<?xml version="1.0"?>', f'<robot name="{name}">', '  <link name="base"/>']
    parent = "base"
    for i, j in enumerate(joints, start=1):
        child = "tip" if i == len(joints) else f"l{i}"
        lines.append(f'  <link name="{child}"/>')
        xyz = " ".join(_num(v) for v in j["xyz"])  # type: ignore[attr-defined]
        rpy = " ".join(_num(v) for v in j["rpy"])  # type: ignore[attr-defined]
        body = [
            f'    <parent link="{parent}"/>',
            f'    <child link="{child}"/>',
            f'    <origin xyz="{xyz}" rpy="{rpy}"/>',
        ]
        if j["type"] != "fixed":
            axis = " ".join(_num(v) for v in j["axis"])  # type: ignore[attr-defined]
            body.append(f'    <axis xyz="{axis}"/>')
        if j.get("limits") is not None:
            lo, hi = j["limits"]  # type: ignore[misc]
            body.append(f'    <limit lower="{lo!r}" upper="{hi!r}" effort="1" velocity="1"/>')
        lines += [f'  <joint name="j{i}" type="{j["type"]}">', *body, "  </joint>"]
        parent = child
    lines.append("</robot>")
    return "\n".join(lines) + "\n"


_SPECIAL = (0.0, math.pi / 2, -math.pi / 2, math.pi)


def _float(lo: float, hi: float) -> st.SearchStrategy[float]:
    return st.floats(lo, hi, allow_nan=False, allow_infinity=False, allow_subnormal=False)


# Angles: exact special values (parallel, perpendicular axes) or clearly generic ones.
# Angles within 1e-6 of a special value (nearly parallel axes) are left out here:
# DH cannot place their far-away common normal accurately (see test_dh_extract).
_angles = st.one_of(
    st.sampled_from(_SPECIAL),
    _float(-math.pi, math.pi).filter(
        lambda a: min(abs(a - s) for s in (*_SPECIAL, -math.pi)) > 1e-3
    ),
)
# Lengths: 0, generic, or tiny offsets (1e-10: axes that nearly meet or coincide).
_lengths = st.one_of(st.just(0.0), _float(-1.0, 1.0), st.sampled_from((1e-10, -1e-10, 3e-13)))
_axes = st.one_of(
    st.sampled_from([(0, 0, 1), (0, 1, 0), (1, 0, 0), (0, 0, -1), (-1, 0, 0)]),
    st.tuples(_float(-1, 1), _float(-1, 1), _float(-1, 1)).filter(
        # no direction within 1e-3 of a coordinate plane: nearly parallel axes again
        lambda v: math.sqrt(sum(c * c for c in v)) > 0.1 and all(abs(c) > 1e-3 for c in v)
    ),
)


@st.composite
def urdf_joint(draw: st.DrawFn, movable: bool = True) -> dict[str, object]:
    jtype = draw(st.sampled_from(["revolute", "revolute", "continuous", "prismatic"]))
    if not movable:
        jtype = "fixed"
    joint: dict[str, object] = {
        "type": jtype,
        "xyz": [draw(_lengths) for _ in range(3)],
        "rpy": [draw(_angles) for _ in range(3)],
        "axis": draw(_axes),
    }
    if jtype in ("revolute", "prismatic") and draw(st.booleans()):
        lo = draw(_float(-3.0, 2.0))
        joint["limits"] = (lo, lo + draw(_float(0.1, 3.0)))
    return joint


@st.composite
def urdf_chains(draw: st.DrawFn, min_dof: int = 1, max_dof: int = 7) -> list[dict[str, object]]:
    """Random serial chains: R/P/continuous joints, fixed joints between, degenerate geometry."""
    n = draw(st.integers(min_dof, max_dof))
    joints: list[dict[str, object]] = []
    for _ in range(n):
        if draw(st.integers(0, 4)) == 0:
            joints.append(draw(urdf_joint(movable=False)))
        joints.append(draw(urdf_joint()))
    if draw(st.booleans()):
        joints.append(draw(urdf_joint(movable=False)))
    return joints


def random_joint_values(chain: ReferenceChain, rng: np.random.Generator, batch: tuple[int, ...]):
    """Joint values ``(*batch, n)``: radians in (-π, π), metres in (-1, 1)."""
    scale = np.array([1.0 if j.get("type") == "prismatic" else math.pi for j in chain.movable])
    return rng.uniform(-1.0, 1.0, (*batch, chain.dof)) * scale


ARM = """<?xml version="1.0"?>
<robot name="arm">
  <link name="base"/>
  <link name="l1"/>
  <link name="l2"/>
  <link name="tool"/>
  <joint name="j1" type="revolute">
    <parent link="base"/><child link="l1"/>
    <origin xyz="0 0 0.3" rpy="0 0 0"/>
    <axis xyz="0 0 1"/>
    <limit lower="-2" upper="2" effort="1" velocity="1"/>
  </joint>
  <joint name="j2" type="prismatic">
    <parent link="l1"/><child link="l2"/>
    <origin xyz="0.1 0 0" rpy="1.5707963267948966 0 0"/>
    <axis xyz="1 0 0"/>
    <limit lower="0" upper="0.5" effort="1" velocity="1"/>
  </joint>
  <joint name="j3" type="fixed">
    <parent link="l2"/><child link="tool"/>
    <origin xyz="0 0 0.05"/>
  </joint>
</robot>
"""


def write(tmp_path: Path, text: str, name: str = "arm.urdf") -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


def one_line_error(path: Path, *patterns: str, **kwargs) -> str:
    with pytest.raises(km.RobotFileError) as info:
        km.load(path, **kwargs)
    message = str(info.value)
    assert "\n" not in message
    assert str(path) in message
    for pattern in patterns:
        assert pattern in message, message
    return message


# ------------------------------------------------------------------ hostile XML
BOMB = """<?xml version="1.0"?>
<!DOCTYPE robot [
  <!ENTITY a "aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa">
  <!ENTITY b "&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;">
  <!ENTITY c "&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;">
  <!ENTITY d "&c;&c;&c;&c;&c;&c;&c;&c;&c;&c;&c;&c;&c;&c;&c;&c;">
  <!ENTITY e "&d;&d;&d;&d;&d;&d;&d;&d;&d;&d;&d;&d;&d;&d;&d;&d;">
  <!ENTITY f "&e;&e;&e;&e;&e;&e;&e;&e;&e;&e;&e;&e;&e;&e;&e;&e;">
  <!ENTITY g "&f;&f;&f;&f;&f;&f;&f;&f;&f;&f;&f;&f;&f;&f;&f;&f;">
]>
<robot name="&g;"><link name="base"/></robot>
"""


# ------------------------------------------------------------------ broken URDF
def broken(old: str, new: str) -> str:
    assert old in ARM
    return ARM.replace(old, new, 1)


# ------------------------------------------------------------------ two joints
def two_joints(xyz: str, rpy: str, tip: str = "0 0 1") -> str:
    """A URDF of two revolute joints, the second placed by ``xyz`` and ``rpy``, then a tip."""
    return f"""<robot name="t"><link name="b"/><link name="l1"/><link name="l2"/><link name="tip"/>
    <joint name="j1" type="continuous"><parent link="b"/><child link="l1"/>
      <axis xyz="0 0 1"/></joint>
    <joint name="j2" type="continuous"><parent link="l1"/><child link="l2"/>
      <origin xyz="{xyz}" rpy="{rpy}"/><axis xyz="0 0 1"/></joint>
    <joint name="j3" type="fixed"><parent link="l2"/><child link="tip"/>
      <origin xyz="{tip}"/></joint></robot>"""


def dh_table(text: str) -> np.ndarray:
    """The DH table extracted from a URDF text (standard convention)."""
    return km.urdf_to_dh(parse_urdf(text)).robot.dh_table()


def extraction_rule(text: str, convention: str = "standard") -> str:
    """The rule DH extraction applied to joint 2's axis (parallel, intersecting, ...)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return km.urdf_to_dh(parse_urdf(text), convention=convention).rules[1].rule


#: Two segments made by a xacro macro (a property, ${pi/2}): what `.xacro` files hold.
XACRO = """<?xml version="1.0"?>
<robot name="xarm" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="len" value="0.4"/>
  <xacro:macro name="seg" params="i parent">
    <link name="l${i}"/>
    <joint name="j${i}" type="revolute">
      <parent link="${parent}"/><child link="l${i}"/>
      <origin xyz="0 0 ${len}" rpy="0 ${pi/2} 0"/>
      <axis xyz="0 0 1"/>
      <limit lower="-1" upper="1" effort="1" velocity="1"/>
    </joint>
  </xacro:macro>
  <link name="base"/>
  <xacro:seg i="1" parent="base"/>
  <xacro:seg i="2" parent="l1"/>
</robot>
"""
