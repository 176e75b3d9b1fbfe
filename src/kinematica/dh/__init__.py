"""Denavit-Hartenberg rows, link matrices, conversion between conventions, extraction."""

# ruff: noqa: F401 (the imports are the public names; kinematica._lazy makes __all__)

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

__getattr__, __dir__, __all__ = exports(__name__)
