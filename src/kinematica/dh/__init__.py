"""Denavit-Hartenberg rows, link matrices, conversion between conventions, extraction."""

from kinematica.dh.axes import AxisFrame, ChainGeometry, ExtractedTable, FrameRule, NamedFrame
from kinematica.dh.convert import convert_table
from kinematica.dh.extract import FK_CHECK_TOL, extract_dh
from kinematica.dh.joints import (
    Convention,
    Joint,
    JointType,
    Prismatic,
    Revolute,
    check_convention,
)
from kinematica.dh.lines import AXIS_ANGLE_TOL, AXIS_LENGTH_TOL, LinePair, length_tol, line_pair
from kinematica.dh.link import link_matrix

__all__ = [
    "AXIS_ANGLE_TOL",
    "AXIS_LENGTH_TOL",
    "FK_CHECK_TOL",
    "AxisFrame",
    "ChainGeometry",
    "Convention",
    "ExtractedTable",
    "FrameRule",
    "Joint",
    "JointType",
    "LinePair",
    "NamedFrame",
    "Prismatic",
    "Revolute",
    "check_convention",
    "convert_table",
    "extract_dh",
    "length_tol",
    "line_pair",
    "link_matrix",
]
