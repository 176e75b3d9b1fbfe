"""Denavit-Hartenberg rows, link matrices and conversion between conventions."""

from kinematica.dh.chain import DHChain
from kinematica.dh.convert import convert_table
from kinematica.dh.joints import (
    Convention,
    Joint,
    JointType,
    Prismatic,
    Revolute,
    check_convention,
)
from kinematica.dh.link import link_matrix

__all__ = [
    "Convention",
    "DHChain",
    "Joint",
    "JointType",
    "Prismatic",
    "Revolute",
    "check_convention",
    "convert_table",
    "link_matrix",
]
