"""Robot descriptions in and out: robot files, built-in models, expressions.

The bottom layer of kinematica: it imports only :mod:`kinematica.errors`, the
standard library and numpy (and defusedxml, lazily, to read URDF), and hands
neutral descriptions to the layers above: a :class:`RobotSpec` (a DH table)
or a :class:`UrdfModel` (links and joints of a URDF).
"""

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

__getattr__, __dir__ = exports(
    __name__,
    {
        "builtin_names": "kinematica.io.builtin",
        "builtin_path": "kinematica.io.builtin",
        "read_builtin": "kinematica.io.builtin",
        "Affine": "kinematica.io.expr",
        "Expression": "kinematica.io.expr",
        "ExpressionError": "kinematica.io.expr",
        "evaluate": "kinematica.io.expr",
        "parse_expression": "kinematica.io.expr",
        "ROBOT_FILE_SUFFIXES": "kinematica.io.reading",
        "dump_robot_dict": "kinematica.io.robotfile",
        "dumps_robot_file": "kinematica.io.robotfile",
        "load_robot_text": "kinematica.io.robotfile",
        "parse_robot_dict": "kinematica.io.robotfile",
        "read_robot_file": "kinematica.io.robotfile",
        "write_robot_file": "kinematica.io.robotfile",
        "FrameSpec": "kinematica.io.spec",
        "JointSpec": "kinematica.io.spec",
        "RobotSpec": "kinematica.io.spec",
        "with_parameters": "kinematica.io.template",
        "URDF_MAX_BYTES": "kinematica.io.urdf",
        "URDF_SUFFIXES": "kinematica.io.reading",
        "parse_urdf": "kinematica.io.urdf",
        "read_urdf": "kinematica.io.urdf",
        "UrdfChain": "kinematica.io.urdf_model",
        "UrdfJoint": "kinematica.io.urdf_model",
        "UrdfModel": "kinematica.io.urdf_model",
        "rpy_from_matrix": "kinematica.io.urdf_write",
        "urdf_text": "kinematica.io.urdf_write",
    },
)

__all__ = [
    "ROBOT_FILE_SUFFIXES",
    "URDF_MAX_BYTES",
    "URDF_SUFFIXES",
    "Affine",
    "Expression",
    "ExpressionError",
    "FrameSpec",
    "JointSpec",
    "RobotSpec",
    "UrdfChain",
    "UrdfJoint",
    "UrdfModel",
    "builtin_names",
    "builtin_path",
    "dump_robot_dict",
    "dumps_robot_file",
    "evaluate",
    "load_robot_text",
    "parse_expression",
    "parse_robot_dict",
    "parse_urdf",
    "read_builtin",
    "read_robot_file",
    "read_urdf",
    "rpy_from_matrix",
    "urdf_text",
    "with_parameters",
    "write_robot_file",
]
