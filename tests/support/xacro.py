"""Test helpers for xacro: rtb-data's descriptions and their package map, and the canonical
form of a URDF tree that compares kinematica's expansion with the xacro package's.

The canonical form keeps every element's tag, attributes and text (whitespace
collapsed) and its children in order; it drops comments and the layout, which the
two expanders write differently and which carry no meaning in a URDF.
"""

from __future__ import annotations

import hashlib
import json
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any

from support import DATA

XACRO_DIR = DATA / "xacro"
RTB = XACRO_DIR / "rtb-data"
REFERENCE = XACRO_DIR / "reference"

_KUKA = ("kr3", "kr5", "kr6", "kr10", "kr16", "kr120", "kr150", "kr210")

#: The ROS package names rtb-data's files use, and the folders holding them here (rtb-data
#: keeps them without package.xml files, so they are given as the user would give them).
RTB_PACKAGES: dict[str, Path] = {
    "abb_irb140": RTB / "abb_irb140_description",
    "kuka_resources": RTB / "kuka_description/kuka_resources",
    "kuka_lbr_iiwa_support": RTB / "kuka_description/kuka_lbr_iiwa",
    "qut_frankie_description": RTB / "qut_frankie_description",
    **{f"kuka_{k}_support": RTB / f"kuka_description/kuka_{k}" for k in _KUKA},
}

#: rtb-data's robot descriptions (the files that are robots, not the macros they include).
RTB_ROBOTS: tuple[str, ...] = tuple(
    sorted(
        str(p.relative_to(RTB))
        for p in RTB.rglob("*.xacro")
        if not p.name.endswith("_macro.xacro")
        and not p.name.startswith("common_")
        and p.name
        not in ("panda_arm.xacro", "hand.xacro", "frankie_arm.xacro", "frankieOmni_arm.xacro")
    )
)


def canonical(elem: ET.Element) -> tuple[Any, ...]:
    """The tree of ``elem`` as nested tuples: tag, sorted attributes, text, children."""
    text = " ".join((elem.text or "").split())
    return (elem.tag, tuple(sorted(elem.attrib.items())), text, tuple(map(canonical, elem)))


def digest(elem: ET.Element) -> str:
    """The sha256 of the canonical form of a tree (JSON of the nested tuples)."""
    return hashlib.sha256(json.dumps(canonical(elem)).encode()).hexdigest()
