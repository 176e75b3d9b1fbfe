"""Robot descriptions in and out: robot files, built-in models, expressions.

The bottom layer of kinematica: it imports only :mod:`kinematica.errors`, the
standard library and numpy (and defusedxml, lazily, to read URDF), and hands
neutral descriptions to the layers above: a :class:`RobotSpec` (a DH table)
or a :class:`UrdfModel` (links and joints of a URDF).
"""

# ruff: noqa: F401 (the imports are the public names; kinematica._lazy makes __all__)

from typing import TYPE_CHECKING

from kinematica._lazy import exports

if TYPE_CHECKING:  # the names below load on first use (kinematica._lazy)
    from kinematica.io.builtin import builtin_names, builtin_path, read_builtin
    from kinematica.io.expr import Affine, Expression, ExpressionError, evaluate, parse_expression
    from kinematica.io.reading import ROBOT_FILE_SUFFIXES, URDF_SUFFIXES
    from kinematica.io.robotfile import (
        dump_robot_dict,
        dumps_robot_file,
        load_robot_text,
        parse_robot_dict,
        read_robot_file,
        write_robot_file,
    )
    from kinematica.io.spec import FrameSpec, JointSpec, RobotSpec
    from kinematica.io.template import with_parameters
    from kinematica.io.urdf import URDF_MAX_BYTES, parse_urdf, read_urdf
    from kinematica.io.urdf_model import UrdfChain, UrdfJoint, UrdfModel
    from kinematica.io.urdf_write import rpy_from_matrix, urdf_text

__getattr__, __dir__, __all__ = exports(__name__)
