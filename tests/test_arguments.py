"""Every error of the API is a KinematicaError; argument errors are ValueErrors too."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

import kinematica as km
from kinematica.errors import ArgumentError, DimensionError, KinematicaError


@pytest.mark.parametrize(
    ("make", "match"),
    [
        (lambda: km.Revolute(d=None), r"Revolute: DH parameter d must be a real number, got None"),
        (lambda: km.Revolute(a="0.3"), r"DH parameter a must be a real number, got '0.3'"),
        (lambda: km.Revolute(alpha=1j), r"DH parameter alpha must be a real number, got 1j"),
        (lambda: km.Revolute(offset=np.complex128(1)), r"DH parameter offset must be a real"),
        (lambda: km.Revolute(d=True), r"DH parameter d must be a real number, got True"),
        (lambda: km.Revolute(d=[0.1, 0.2]), r"DH parameter d must be a real number"),
        (lambda: km.Revolute(d=np.inf), r"DH parameter d must be a finite number, got inf"),
        (lambda: km.Revolute(qlim=(1, 2, 3)), r"joint limits must be two numbers .*3 values"),
        (lambda: km.Revolute(qlim=5), r"two numbers lo < hi \(or None\), got 5"),
        (lambda: km.Revolute(qlim="ab"), r"joint limits must be two numbers .*got 'ab'"),
        (lambda: km.Revolute(qlim=np.array(1.0)), r"joint limits must be two numbers"),
        (lambda: km.Revolute(qlim=(None, 1)), r"each joint limit must be a real number, got None"),
        (lambda: km.Revolute(qlim=(2, 1)), r"joint limits must be two numbers lo < hi .*\(2, 1\)"),
        (lambda: km.Revolute(name=3), r"Revolute: name must be text or None, got 3"),
        (lambda: km.Prismatic(theta=None, name="slide"), r"Prismatic 'slide': DH parameter theta"),
        (lambda: km.Prismatic(qlim=[0]), r"Prismatic: joint limits .*got 1 values"),
    ],
)
def test_bad_joint_rows_are_argument_errors(make: Callable[[], object], match: str) -> None:
    with pytest.raises(ArgumentError, match=match) as info:
        make()
    assert isinstance(info.value, KinematicaError) and isinstance(info.value, ValueError)


def test_limits_may_be_any_pair_of_numbers() -> None:
    assert km.Revolute(qlim=np.array([-1, 1])).qlim == (-1.0, 1.0)
    assert km.Prismatic(qlim=[0, np.float32(0.5)]).qlim == (0.0, 0.5)
    assert km.Prismatic(qlim=(-np.inf, np.inf)).qlim == (-np.inf, np.inf)
    assert km.Revolute(d=np.float64(0.1), a=np.int64(2)).a == 2.0


@pytest.mark.parametrize(
    ("call", "error", "match"),
    [
        (lambda: km.load(None), ArgumentError, "load takes a built-in robot name or"),
        (lambda: km.robot_from_spec(None), ArgumentError, "expected a RobotSpec, got NoneType"),
        (lambda: km.spec_from_robot("puma560"), ArgumentError, "expected a Robot, got str"),
        (lambda: km.read_robot_file(3), ArgumentError, "expected a path"),
        (lambda: km.rotx("a"), DimensionError, "angle must be an array of numbers"),
        (lambda: km.rotz(None), DimensionError, "angle must be an array of numbers"),
        (lambda: km.wrap_angle("a"), DimensionError, "angle must be an array of numbers"),
        (lambda: km.inv_transform(None), DimensionError, "T must be an array of numbers, got None"),
        (lambda: km.inv_transform(np.eye(3)), DimensionError, r"got \(3, 3\)"),
        (lambda: km.make_transform(np.eye(4)), DimensionError, r"R must have shape \(\.\.\., 3,"),
        (lambda: km.make_transform(None, [1, 2]), DimensionError, r"p must have shape"),
        (
            lambda: km.make_transform(np.zeros((2, 3, 3)), np.zeros((3, 3))),
            DimensionError,
            "do not broadcast",
        ),
        (lambda: km.transl([1, 2], [1, 2, 3]), DimensionError, "x, y and z do not broadcast"),
        (lambda: km.compose(np.eye(4), np.eye(3)), DimensionError, "transform 2 must have shape"),
        (
            lambda: km.compose(np.zeros((2, 4, 4)), np.zeros((3, 4, 4))),
            DimensionError,
            "transform 2: batch shapes do not broadcast",
        ),
    ],
)
def test_bad_arguments_raise_kinematica_errors(
    call: Callable[[], object], error: type[KinematicaError], match: str
) -> None:
    with pytest.raises(error, match=match) as info:
        call()
    assert isinstance(info.value, ValueError)


def test_save_to_a_bad_place_is_a_robot_file_error(tmp_path: Path) -> None:
    robot = km.load("planar-3r")
    with pytest.raises(km.RobotFileError, match=r"unknown file type '\.txt'"):
        robot.save(tmp_path / "x.txt")
    with pytest.raises(km.RobotFileError, match="cannot write the file"):
        robot.save(tmp_path / "missing" / "x.yaml")
    with pytest.raises(ArgumentError, match="expected a path"):
        robot.save(None)  # type: ignore[arg-type]


def test_elementary_operations_still_let_nan_through() -> None:
    # NaN in, NaN out, as numpy does: only non-numbers and wrong shapes are errors.
    assert np.isnan(km.rotx(np.nan)).sum() == 4
    assert np.isnan(km.wrap_angle(np.nan))
    assert np.isnan(km.transl(np.nan)[0, 3])
