"""Values implausible for their unit warn, naming file, joint and key; each threshold is pinned."""

from __future__ import annotations

import math
import warnings
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import kinematica as km
from kinematica.errors import KinematicaWarning
from kinematica.io import builtin_names, load_robot_text, parse_robot_dict, read_builtin
from kinematica.io.plausible import (
    PLAUSIBLE_ANGLE,
    PLAUSIBLE_LENGTH,
    PLAUSIBLE_LIMIT,
    RADIAN_LOOKALIKE_TOL,
    check_angle,
    check_degrees,
    check_length,
    check_limit,
)


def _arm(units: dict[str, str], **cells: Any) -> dict[str, Any]:
    """Two joints; joint 2's cells replaced by ``cells``."""
    joint2 = {"theta": "q2", "d": 0, "a": 0.3, "alpha": 0} | cells
    return {
        "convention": "standard",
        "units": units,
        "joints": [{"theta": "q1", "d": 0.2, "a": 0, "alpha": 0}, joint2],
    }


def _warnings(data: dict[str, Any], source: str | None = "arm.yaml") -> list[str]:
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        parse_robot_dict(data, source=source)
    return [str(w.message) for w in caught if issubclass(w.category, KinematicaWarning)]


RAD = {"angle": "rad", "length": "m"}
DEG = {"angle": "deg", "length": "m"}
MM = {"angle": "deg", "length": "mm"}


# --- the thresholds, each on both sides ------------------------------------------


def test_angle_threshold_is_one_full_turn() -> None:
    assert 2 * math.pi == PLAUSIBLE_ANGLE
    assert check_angle(6.28) is None  # just inside
    assert check_angle(-6.28) is None
    assert "more than a full turn" in (check_angle(6.29) or "")  # just outside
    assert "more than a full turn" in (check_angle(-6.29) or "")


def test_limit_threshold_is_two_full_turns() -> None:
    assert 4 * math.pi == PLAUSIBLE_LIMIT
    assert check_limit(math.radians(720)) is None  # ±720° wrists exist
    assert check_limit(12.56) is None
    assert "more than two full turns" in (check_limit(12.57) or "")


def test_length_threshold_is_20_m() -> None:
    assert PLAUSIBLE_LENGTH == 20.0
    assert check_length(19.99) is None
    assert check_length(-20.0) is None
    assert "longer than 20 m" in (check_length(20.01) or "")
    assert "is it in millimetres" in (check_length(300.0) or "")


@pytest.mark.parametrize("k", [1, 2, 3, 4, -1, -2, -3, -4])
def test_radian_lookalike_tolerance_both_sides(k: int) -> None:
    exact = k * math.pi / 2
    inside = exact + math.copysign(0.9 * RADIAN_LOOKALIKE_TOL, k)
    outside = exact + math.copysign(1.1 * RADIAN_LOOKALIKE_TOL, k)
    assert check_degrees(inside) is not None
    assert check_degrees(exact - math.copysign(0.9 * RADIAN_LOOKALIKE_TOL, k)) is not None
    assert check_degrees(outside) is None


@pytest.mark.parametrize("written", [1.5708, 1.57, 3.1416, 3.14, -1.5708, 4.7124, 6.2832])
def test_radians_typed_as_degrees_are_recognised(written: float) -> None:
    message = check_degrees(written)
    assert message is not None and "in radians" in message


@pytest.mark.parametrize("written", [0.0, 90.0, -90.0, 180.0, 1.0, 1.5, 1.6, 3.0, 10.0, 7.85398])
def test_plausible_degrees_pass(written: float) -> None:
    assert check_degrees(written) is None  # 7.85398 is 5π/2: beyond the quarter turns checked


# --- robot files ---------------------------------------------------------------


def test_alpha_90_in_a_radians_file_warns_with_file_joint_and_key() -> None:
    found = _warnings(_arm(RAD, alpha=90))
    assert len(found) == 1
    assert found[0].startswith("arm.yaml, joint 2, key 'alpha': 90 rad is more than a full turn")
    assert "set units.angle: deg" in found[0]


def test_alpha_1_5708_in_a_degrees_file_warns() -> None:
    (message,) = _warnings(_arm(DEG, alpha=1.5708))
    assert message.startswith("arm.yaml, joint 2, key 'alpha': 1.5708° looks like pi/2 in radians")
    assert "write 90" in message


def test_a_theta_offset_in_radians_in_a_degrees_file_warns() -> None:
    (message,) = _warnings(_arm(DEG, theta="q2 - 3.1416"))
    assert "joint 2, key 'theta'" in message and "looks like -pi in radians" in message


def test_d_300_in_a_metres_file_warns() -> None:
    (message,) = _warnings(_arm(DEG, d=300))
    assert message.startswith("arm.yaml, joint 2, key 'd': 300 m is longer than 20 m")
    assert "set units.length: mm" in message


def test_lengths_in_a_millimetre_file_are_judged_in_metres() -> None:
    assert _warnings(_arm(MM, d=300, a=19_990)) == []  # 0.3 m and 19.99 m
    (message,) = _warnings(_arm(MM, a=20_010))
    assert "joint 2, key 'a': 20010 mm (20.01 m) is longer than 20 m" in message


def test_prismatic_offset_is_a_length() -> None:
    (message,) = _warnings(_arm(DEG, theta=0, d="q2 + 500"))
    assert "joint 2, key 'd': 500 m is longer than 20 m" in message


def test_limits_in_degrees_in_a_radians_file_warn() -> None:
    (message,) = _warnings(_arm(RAD, limits=[-170, 170]))
    assert "joint 2, key 'limits': a limit of -170 rad is more than two full turns" in message
    assert _warnings(_arm(RAD, limits=["-2*pi", "2*pi"])) == []


def test_limits_in_radians_in_a_degrees_file_warn() -> None:
    (message,) = _warnings(_arm(DEG, limits=[-3.14, 3.14]))
    assert "joint 2, key 'limits'" in message and "looks like -pi in radians" in message
    assert _warnings(_arm(DEG, limits=[-400, 400])) == []


def test_base_and_tool_rpy_are_checked() -> None:
    data = _arm(RAD)
    data["tool"] = {"xyz": [0, 0, 0.1], "rpy": [0, 0, 90]}
    (message,) = _warnings(data)
    assert message.startswith("arm.yaml, key 'tool.rpy': 90 rad is more than a full turn")
    data = _arm(DEG)
    data["base"] = {"rpy": [1.5708, 0, 0]}
    (message,) = _warnings(data)
    assert "key 'base.rpy': 1.5708° looks like pi/2" in message


def test_a_plausible_file_gives_no_warning() -> None:
    assert _warnings(_arm(DEG, alpha=-90, d=0.4, limits=[-170, 170])) == []
    assert _warnings(_arm(RAD, alpha="pi/2", theta="q2 - pi", limits=[-3.1, 3.1])) == []


@pytest.mark.parametrize("name", builtin_names())
def test_no_builtin_model_warns(name: str) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error", KinematicaWarning)
        read_builtin(name)
        km.load(name)


def test_text_without_a_path_warns_with_joint_and_key() -> None:
    text = (
        "convention: standard\nunits: {angle: rad}\n"
        "joints:\n  - {theta: q1, d: 0, a: 1, alpha: 90}\n"
    )
    with pytest.warns(KinematicaWarning, match=r"^joint 1, key 'alpha': 90 rad"):
        load_robot_text(text, ".yaml")


def test_loading_a_file_warns_once_per_value(tmp_path: Path) -> None:
    # The file reader names file, joint and key; building the Robot does not
    # warn a second time about the same value.
    path = tmp_path / "arm.yaml"
    path.write_text(
        "convention: standard\nunits: {angle: rad}\njoints:\n"
        "  - {theta: q1, d: 0, a: 1, alpha: 90}\n"
    )
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        robot = km.load(path)
    messages = [str(w.message) for w in caught]
    assert messages == [
        f"{path}, joint 1, key 'alpha': 90 rad is more than a full turn (2π rad): is it in "
        "degrees? (90° is 1.5708 rad); set units.angle: deg if the file is in those units"
    ]
    assert robot.links[0].alpha == 90.0  # warned, not changed


# --- Python API ------------------------------------------------------------------


def test_revolute_alpha_90_warns() -> None:
    with pytest.warns(KinematicaWarning, match=r"Revolute: alpha=90\.0: 90 rad is more than a"):
        km.Revolute(alpha=90)


@pytest.mark.parametrize(
    ("make", "match"),
    [
        (lambda: km.Revolute(offset=-180), r"Revolute: offset=-180\.0: -180 rad"),
        (lambda: km.Revolute(d=300), r"Revolute: d=300\.0: 300 m is longer than 20 m"),
        (lambda: km.Revolute(a=431.8, name="j2"), r"Revolute 'j2': a=431\.8: 431\.8 m"),
        (lambda: km.Revolute(qlim=(-170, 170)), r"qlim=\(-170\.0, 170\.0\): a limit of -170 rad"),
        (lambda: km.Prismatic(theta=90), r"Prismatic: theta=90\.0: 90 rad"),
        (lambda: km.Prismatic(offset=500), r"Prismatic: offset=500\.0: 500 m"),
    ],
)
def test_joint_rows_warn_on_implausible_values(make: Any, match: str) -> None:
    with pytest.warns(KinematicaWarning, match=match):
        make()


def test_joint_rows_with_plausible_values_do_not_warn() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error", KinematicaWarning)
        km.Revolute(d=0.4, a=19.99, alpha=-np.pi / 2, offset=np.pi, qlim=(-4 * np.pi, 4 * np.pi))
        km.Prismatic(theta=-np.pi, alpha=2 * np.pi, offset=1.0, qlim=(0, 100))  # 100 m of travel


def test_robot_file_unit_slips_are_unit_warnings(tmp_path: Path) -> None:
    arm = tmp_path / "arm.toml"
    arm.write_text(
        'name = "r"\nconvention = "standard"\nunits = { angle = "rad", length = "m" }\n'
        'joints = [ { theta = "q1", d = 0, a = 0.3, alpha = 90 } ]\n'
    )
    with pytest.warns(km.UnitWarning, match="is it in degrees"):
        km.load(arm)
