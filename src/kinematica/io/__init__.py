"""Robot descriptions in and out: robot files, built-in models, expressions.

The bottom layer of kinematica: it imports only :mod:`kinematica.errors`, the
standard library and numpy, and hands a neutral :class:`RobotSpec` to the
robot layer above.
"""

from kinematica.io.builtin import builtin_names, builtin_path, read_builtin
from kinematica.io.expr import Affine, Expression, ExpressionError, evaluate, parse_expression
from kinematica.io.robotfile import (
    ROBOT_FILE_SUFFIXES,
    dump_robot_dict,
    load_robot_text,
    parse_robot_dict,
    read_robot_file,
    write_robot_file,
)
from kinematica.io.spec import FrameSpec, JointSpec, RobotSpec
from kinematica.io.template import with_parameters

__all__ = [
    "ROBOT_FILE_SUFFIXES",
    "Affine",
    "Expression",
    "ExpressionError",
    "FrameSpec",
    "JointSpec",
    "RobotSpec",
    "builtin_names",
    "builtin_path",
    "dump_robot_dict",
    "evaluate",
    "load_robot_text",
    "parse_expression",
    "parse_robot_dict",
    "read_builtin",
    "read_robot_file",
    "with_parameters",
    "write_robot_file",
]
