"""SE(3)/SO(3) maths: rotations, homogeneous transforms, Euler angles, quaternions."""

from kinematica.spatial.transform import (
    compose,
    inv_transform,
    make_transform,
    rotx,
    roty,
    rotz,
    transl,
)

__all__ = [
    "compose",
    "inv_transform",
    "make_transform",
    "rotx",
    "roty",
    "rotz",
    "transl",
]
