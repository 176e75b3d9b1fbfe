"""Every public function taking arrays takes float64 arrays however they are laid out.

A row of a packed record array, or ``np.frombuffer(..., offset=1)``, is a float64 array
whose data is not aligned; a byte-swapped ``'>f8'`` one reads as the same numbers. The
core copies such an array once, where it reads it; each function must answer exactly
as it does for the same values in an ordinary array (the audit of issue 34 found 22 of
34 raising ``ValueError: q must be C-contiguous and aligned``).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

import kinematica as km

Layout = Callable[[Any], np.ndarray]


def plain(a: Any) -> np.ndarray:
    return np.array(a, dtype=np.float64)


def unaligned(a: Any) -> np.ndarray:
    """The values of ``a`` in a writeable float64 array starting one byte into its buffer."""
    src = np.ascontiguousarray(a, dtype=np.float64)
    buf = bytearray(src.nbytes + 1)
    out = np.frombuffer(buf, dtype=np.float64, count=src.size, offset=1).reshape(src.shape)
    out[...] = src
    assert not out.flags.aligned
    return out


def packed_field(a: Any) -> np.ndarray:
    """The values of ``a`` as the field of one row of a packed record array (offset 1)."""
    src = np.asarray(a, dtype=np.float64)
    rec = np.zeros(2, dtype=[("flag", "u1"), ("x", "f8", src.shape)])
    rec["x"][1] = src
    out = rec[1]["x"]
    assert not out.flags.aligned
    return out


def swapped(a: Any) -> np.ndarray:
    return np.asarray(a, dtype=np.float64).astype(">f8")


LAYOUTS = {"unaligned": unaligned, "packed record": packed_field, "big-endian": swapped}

PUMA = km.load("puma560")
IIWA = km.load("iiwa14")
Q6 = [0.1, -0.5, 0.3, 0.7, 0.4, -0.2]
Q6B = [[0.1, -0.5, 0.3, 0.7, 0.4, -0.2], [0.3, 0.2, -0.4, 0.1, 0.9, 0.5]]
Q7 = [0.3, 0.5, -0.2, -1.2, 0.4, 0.9, 0.2]
T6 = PUMA.fk(Q6)
T6B = PUMA.fk(Q6B)
T7 = IIWA.fk(Q7)
R = T6[:3, :3]
QUAT = [0.1, 0.2, 0.3, 0.927361849549570]
#: Readings near the middle of the PUMA's limits, and what a tracker would measure there.
QC = np.mean(PUMA.qlim, axis=1) + np.random.default_rng(0).uniform(-0.3, 0.3, (12, 6))
BOX = [[-0.3, -0.3, 0.0], [0.3, 0.3, 0.3]]


def _fields(result: Any) -> tuple[Any, ...]:
    """What a result says, as arrays and plain values, for an exact comparison."""
    if isinstance(result, np.ndarray | np.generic):
        return (np.asarray(result),)
    if isinstance(result, tuple):
        return tuple(x for r in result for x in _fields(r))
    if isinstance(result, list):  # names: singularities of each configuration
        return (np.array(repr(result)),)
    if isinstance(result, km.Robot):
        return (result.base, result.tool, result.fk(Q6 if result.dof == 6 else Q7))
    names = ("solutions", "status", "count", "q", "t", "qd", "values", "points", "errors",
             "radii", "axes", "near", "center", "manipulability", "sd", "index", "positions",
             "fitted", "covariance")  # fmt: skip
    found = tuple(np.asarray(getattr(result, n)) for n in names if hasattr(result, n))
    assert found, f"nothing to compare in {type(result).__name__}"
    return found


#: Each public function, called with every array argument passed through a layout.
CALLS: dict[str, Callable[[Layout], Any]] = {
    "Robot.fk": lambda c: PUMA.fk(c(Q6)),
    "Robot.fk batch": lambda c: PUMA.fk(c(Q6B)),
    "Robot.fk all_frames": lambda c: PUMA.fk(c(Q6B), all_frames=True),
    "Robot.jacobian": lambda c: PUMA.jacobian(c(Q6)),
    "Robot.jacobian batch": lambda c: PUMA.jacobian(c(Q6B), frame="tool"),
    "Robot.ik": lambda c: PUMA.ik(c(T6)),
    "Robot.ik batch": lambda c: PUMA.ik(c(T6B)),
    "Robot.ik position": lambda c: PUMA.ik(c(T6[:3, 3])),
    "Robot.ik numeric q0": lambda c: PUMA.ik(c(T6), method="numeric", q0=c(Q6), seed=0),
    "Robot.ik redundant": lambda c: IIWA.ik(c(T7), arm_angle=c([0.2])),
    "Robot.joint_axes": lambda c: PUMA.joint_axes(c(Q6B)),
    "Robot.link_matrices": lambda c: PUMA.link_matrices(c(Q6)),
    "Robot.dh_table": lambda c: PUMA.dh_table(c(Q6)),
    "Robot.check_q": lambda c: PUMA.check_q(c(Q6B)),
    "Robot.arm_angle": lambda c: IIWA.arm_angle(c(Q7)),
    "Robot.singularities": lambda c: PUMA.singularities(c(Q6B)),
    "Robot.self_motion": lambda c: IIWA.self_motion(c(T7), "q1", samples=5),
    "Robot.with_tool": lambda c: PUMA.with_tool(c(T6)),
    "Robot.with_base": lambda c: PUMA.with_base(c(T6)),
    "analytic_jacobian": lambda c: km.analytic_jacobian(PUMA, c(Q6)),
    "condition_number": lambda c: km.condition_number(PUMA, c(Q6B)),
    "manipulability": lambda c: km.manipulability(PUMA, c(Q6B)),
    "hessian": lambda c: km.hessian(PUMA, c(Q6)),
    "jacobian_dot": lambda c: km.jacobian_dot(PUMA, c(Q6), c(Q6)),
    "ellipsoid": lambda c: km.ellipsoid(PUMA, c(Q6)),
    "cartesian_path": lambda c: km.cartesian_path(PUMA, c(T6), c(T6B[1]), steps=4, q0=c(Q6)),
    "cartesian_via_path": lambda c: km.cartesian_via_path(PUMA, c(T6B), steps=4, q0=c(Q6)),
    "resolved_rate": lambda c: km.resolved_rate(PUMA, c(Q6), target=c(T6B[1]), steps=5),
    "joint_trajectory": lambda c: km.joint_trajectory(c(Q6), c(Q6B[1]), 1.0, dt=0.25),
    "via_trajectory": lambda c: km.via_trajectory(c(Q6B), "cubic", times=c([0.0, 1.0]), dt=0.25),
    "to_pose": lambda c: km.to_pose(c(T6B)),
    "from_pose": lambda c: km.from_pose(c(km.to_pose(T6B))),
    "inv_transform": lambda c: km.inv_transform(c(T6B)),
    "compose": lambda c: km.compose(c(T6), c(T6B)),
    "se3_error": lambda c: km.se3_error(c(T6), c(T6B[1])),
    "check_transform": lambda c: km.check_transform(c(T6B)),
    "check_rotation": lambda c: km.check_rotation(c(R)),
    "make_transform": lambda c: km.make_transform(c(R), c([1.0, 2.0, 3.0])),
    "transl": lambda c: km.transl(c([1.0, 2.0]), c([0.5, 0.1]), 0.0),
    "rotx": lambda c: km.rotx(c([0.1, 0.2])),
    "roty": lambda c: km.roty(c([0.1, 0.2])),
    "rotz": lambda c: km.rotz(c([0.1, 0.2])),
    "wrap_angle": lambda c: km.wrap_angle(c([4.0, -7.0, 0.5])),
    "euler_from_matrix": lambda c: km.euler_from_matrix(c(R), "ZYX"),
    "matrix_from_euler": lambda c: km.matrix_from_euler(c([0.1, 0.2, 0.3]), "ZYX"),
    "gimbal_locked": lambda c: km.gimbal_locked(c(R)),
    "rotvec_from_matrix": lambda c: km.rotvec_from_matrix(c(R)),
    "matrix_from_rotvec": lambda c: km.matrix_from_rotvec(c([0.1, 0.2, 0.3])),
    "axis_angle_from_matrix": lambda c: km.axis_angle_from_matrix(c(R)),
    "matrix_from_axis_angle": lambda c: km.matrix_from_axis_angle(c([0.0, 0.6, 0.8]), c([0.4])),
    "rotation_angle": lambda c: km.rotation_angle(c(R), c(T6B[1][:3, :3])),
    "quat_from_matrix": lambda c: km.quat_from_matrix(c(R)),
    "matrix_from_quat": lambda c: km.matrix_from_quat(c(QUAT)),
    "quat_conjugate": lambda c: km.quat_conjugate(c(QUAT)),
    "quat_multiply": lambda c: km.quat_multiply(c(QUAT), c(QUAT)),
    "quat_slerp": lambda c: km.quat_slerp(c(QUAT), c([0.0, 0.0, 0.0, 1.0]), c([0.25, 0.5])),
    "link_matrix": lambda c: km.link_matrix(c([0.1, 0.2]), c([0.3, 0.0]), c([0.5, 0.1]), 0.2),
    "time_optimal": lambda c: km.time_optimal(c(Q6B), vmax=c([1.0] * 6), amax=2.0, grid=50),
    "reachability": lambda c: km.reachability(PUMA, c(BOX), 0.3, orientations=c(R[None])),
    "base_placement": lambda c: km.base_placement(PUMA, c(T6B), c(BOX), resolution=0.3, yaw=2),
    "calibrate": lambda c: km.calibrate(PUMA, c(QC), c(PUMA.fk(QC))),
    "Robot.wrist_center": lambda c: PUMA.wrist_center(c(T6B)),
}


@pytest.mark.parametrize("layout", sorted(LAYOUTS))
@pytest.mark.parametrize("name", sorted(CALLS))
def test_any_float64_layout_gives_the_same_answer(name: str, layout: str) -> None:
    call = CALLS[name]
    expected = _fields(call(plain))
    found = _fields(call(LAYOUTS[layout]))
    assert len(found) == len(expected)
    for a, b in zip(found, expected, strict=True):
        np.testing.assert_array_equal(a, b)


def test_the_layouts_hold_the_values() -> None:
    for make in LAYOUTS.values():
        np.testing.assert_array_equal(make(T6B), T6B)


def test_every_public_function_taking_arrays_is_listed() -> None:
    """The functions of ``km.__all__`` that take arrays, and the Robot's methods that do."""
    takes_no_array = {"builtin_names", "classify", "load", "read_robot_file",
                      "robot_from_spec", "spec_from_robot", "urdf_to_dh", "workspace",
                      "write_robot_file"}  # fmt: skip
    functions = {
        name
        for name in km.__all__
        if callable(getattr(km, name)) and not isinstance(getattr(km, name), type)
    }
    listed = {name.split(" ")[0] for name in CALLS}
    assert functions - takes_no_array - listed == set()
    robot = {"fk", "jacobian", "ik", "joint_axes", "link_matrices", "dh_table", "check_q",
             "arm_angle", "singularities", "self_motion", "with_tool", "with_base"}  # fmt: skip
    assert {f"Robot.{m}" for m in robot} <= listed
    assert len(listed) >= 50
