"""Denavit-Hartenberg rows, link matrices, conversion between conventions, extraction."""

from typing import TYPE_CHECKING

from kinematica._lazy import exports

if TYPE_CHECKING:  # the names below load on first use (kinematica._lazy)
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
        given_convention,
    )
    from kinematica.dh.lines import AXIS_ANGLE_TOL, AXIS_LENGTH_TOL, LinePair, length_tol, line_pair
    from kinematica.dh.link import link_matrix

__getattr__, __dir__ = exports(
    __name__,
    {
        "AxisFrame": "kinematica.dh.axes",
        "ChainGeometry": "kinematica.dh.axes",
        "ExtractedTable": "kinematica.dh.axes",
        "FrameRule": "kinematica.dh.axes",
        "NamedFrame": "kinematica.dh.axes",
        "convert_table": "kinematica.dh.convert",
        "FK_CHECK_TOL": "kinematica.dh.extract",
        "extract_dh": "kinematica.dh.extract",
        "Convention": "kinematica.dh.joints",
        "Joint": "kinematica.dh.joints",
        "JointType": "kinematica.dh.joints",
        "Prismatic": "kinematica.dh.joints",
        "Revolute": "kinematica.dh.joints",
        "check_convention": "kinematica.dh.joints",
        "given_convention": "kinematica.dh.joints",
        "AXIS_ANGLE_TOL": "kinematica.dh.lines",
        "AXIS_LENGTH_TOL": "kinematica.dh.lines",
        "LinePair": "kinematica.dh.lines",
        "length_tol": "kinematica.dh.lines",
        "line_pair": "kinematica.dh.lines",
        "link_matrix": "kinematica.dh.link",
    },
)

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
    "given_convention",
    "length_tol",
    "line_pair",
    "link_matrix",
]
