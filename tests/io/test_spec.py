"""Bounded parameters (design templates) and rebuilding a spec with other values."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from support.helpers import PROPERTY

import kinematica as km
from kinematica.errors import RobotFileError
from kinematica.io import (
    RobotSpec,
    dump_robot_dict,
    parse_robot_dict,
    read_robot_file,
    with_parameters,
    write_robot_file,
)
from kinematica.io.spec import CONVENTION_ALIASES

DEG = math.pi / 180


def _template() -> dict[str, Any]:
    """A 3R arm whose lengths, limits and tool follow two design variables."""
    return {
        "name": "design 3R",
        "convention": "standard",
        "units": {"angle": "deg", "length": "mm"},
        "parameters": {
            "h": 300,
            "l1": {"value": 400, "min": 100, "max": 900},
            "l2": "1000 - l1",  # the total length is fixed
            "reach": {"min": 10, "max": 30},  # value left out: the midpoint
            "lim": "90 + reach",
        },
        "joints": [
            {"theta": "q1", "d": "h", "a": 0, "alpha": 90},
            {"theta": "q2", "d": 0, "a": "l1", "alpha": 0, "limits": ["-lim", "lim"]},
            {"theta": "q3", "d": 0, "a": "l2", "alpha": 0},
        ],
        "tool": {"xyz": ["reach", 0, 0]},
    }


def test_bounded_values_bounds_and_expressions() -> None:
    spec = parse_robot_dict(_template())
    assert dict(spec.parameters) == {"h": 300, "l1": 400, "l2": 600, "reach": 20, "lim": 110}
    assert dict(spec.parameter_bounds) == {"l1": (100.0, 900.0), "reach": (10.0, 30.0)}
    assert [j.a for j in spec.joints] == [0.0, 0.4, 0.6]
    assert spec.joints[1].qlim == (-110 * DEG, 110 * DEG)
    assert spec.tool is not None and spec.tool.xyz == (0.02, 0.0, 0.0)


def test_with_parameters_re_evaluates_every_expression() -> None:
    spec = parse_robot_dict(_template(), source="t.yaml")
    new = with_parameters(spec, {"l1": 250.0, "reach": 30})
    # by hand: l2 = 1000 - 250 = 750 mm; lim = 90 + 30 = 120 deg; tool x = 30 mm
    assert [j.a for j in new.joints] == [0.0, 0.25, 0.75]
    assert new.joints[1].qlim == (-120 * DEG, 120 * DEG)
    assert new.tool is not None and new.tool.xyz == (0.03, 0.0, 0.0)
    assert new.parameters["l2"] == 750.0
    assert new.source == "t.yaml"
    assert new.parameter_bounds == spec.parameter_bounds
    # the original is untouched, and a plain-number parameter can be set too
    assert spec.joints[1].a == 0.4
    assert with_parameters(spec, {"h": 500}).joints[0].d == 0.5


def test_a_template_loads_as_the_robot_at_its_values(tmp_path: Path) -> None:
    path = tmp_path / "t.json"
    write_robot_file(parse_robot_dict(_template()), path)
    robot = km.load(path)
    T = robot.fk([0.0, 0.0, 0.0])
    # stretched along x: l1 + l2 + tool = 0.4 + 0.6 + 0.02 m, at height h = 0.3 m
    np.testing.assert_allclose(T[:3, 3], [1.02, 0.0, 0.3], atol=1e-15)


@pytest.mark.parametrize("suffix", [".json", ".toml", ".yaml"])
def test_bounds_survive_writing_and_reading(tmp_path: Path, suffix: str) -> None:
    spec = parse_robot_dict(_template())
    write_robot_file(spec, tmp_path / f"t{suffix}")
    again = read_robot_file(tmp_path / f"t{suffix}")
    assert again == spec
    assert dict(again.parameter_bounds) == dict(spec.parameter_bounds)
    assert dict(again.parameters) == dict(spec.parameters)
    assert dump_robot_dict(spec)["parameters"]["l1"] == {"value": 400, "min": 100, "max": 900}


@pytest.mark.parametrize(
    ("values", "match"),
    [
        ({"l2": 500}, r"parameters\.l2.*cannot set l2: it is the expression '1000 - l1'"),
        ({"l1": 950}, r"parameters\.l1.*950, is outside its bounds \[100, 900\]"),
        ({"l1": 99.999}, r"outside its bounds \[100, 900\]"),
        ({"l1": math.nan}, r"outside its bounds"),
        ({"l1": "400"}, r"the value set for l1 must be a number, found '400'"),
        ({"l1": True}, r"must be a number"),
        ({"l11": 400}, r"no parameter 'l11' \(did you mean 'l1'\?\) to set"),
    ],
)
def test_bad_values_to_set(values: dict[str, Any], match: str) -> None:
    spec = parse_robot_dict(_template(), source="t.yaml")
    with pytest.raises(RobotFileError, match=match):
        with_parameters(spec, values)


def test_a_file_without_parameters_has_none_to_set() -> None:
    data = _template()
    del data["parameters"]
    data["joints"] = [{"theta": "q1", "d": 0, "a": 1, "alpha": 0}]
    data["tool"] = None
    with pytest.raises(
        RobotFileError, match="no parameter 'l1' to set; the file's parameters: none"
    ):
        with_parameters(parse_robot_dict(data), {"l1": 1})
    assert with_parameters(parse_robot_dict(data), {}) == parse_robot_dict(data)


def test_values_at_the_bounds_are_accepted() -> None:
    spec = parse_robot_dict(_template())
    assert with_parameters(spec, {"l1": 100}).joints[1].a == 0.1
    assert with_parameters(spec, {"l1": 900}).joints[2].a == 0.1


def test_a_spec_built_in_code_has_no_parameters_to_set() -> None:
    spec = km.spec_from_robot(km.load("puma560"))
    with pytest.raises(RobotFileError, match="not read from a robot file"):
        with_parameters(spec, {"l1": 1})
    assert spec.document is None


@pytest.mark.parametrize(
    ("entry", "match"),
    [
        ({"value": 0.5, "max": 1}, r"parameters\.p.*needs min and max \(missing min\)"),
        ({"value": 0.5, "min": 1, "max": 1}, r"expected min < max, found min 1 and max 1"),
        ({"value": 2, "min": 0, "max": 1}, r"parameters\.p\.value.*value 2 is outside"),
        ({"value": 0.5, "min": 0, "max": 1, "step": 1}, r"parameters\.p\.step.*unknown key"),
        ({"value": "q1", "min": 0, "max": 1}, r"cannot use joint variables"),
        ({"value": "nope", "min": 0, "max": 1}, r"unknown name 'nope'"),
        ({"value": [1], "min": 0, "max": 1}, r"expected a number or an expression"),
    ],
)
def test_malformed_bounded_parameters(entry: dict[str, Any], match: str) -> None:
    data = _template()
    data["parameters"] = {"p": entry}
    with pytest.raises(RobotFileError, match=match):
        parse_robot_dict(data, source="t.yaml")


def test_pi_in_a_bound_taints_the_parameter_in_a_degrees_file() -> None:
    data = _template()
    data["parameters"]["tw"] = {"value": 1, "min": 0, "max": "pi"}
    data["joints"][0]["alpha"] = "tw"
    with pytest.raises(RobotFileError, match="defined with pi"):
        parse_robot_dict(data)


@given(l1=st.floats(min_value=100, max_value=900), reach=st.floats(min_value=10, max_value=30))
@PROPERTY
def test_rebuilt_robot_matches_a_hand_written_table(l1: float, reach: float) -> None:
    spec = parse_robot_dict(_template(), source="t.yaml")
    robot = km.robot_from_spec(with_parameters(spec, {"l1": l1, "reach": reach}))
    # the same arm written in code, in metres and radians
    by_hand = km.Robot.from_dh(
        [
            km.Revolute(d=0.3, alpha=math.pi / 2),
            km.Revolute(a=l1 / 1000, qlim=(-(90 + reach) * DEG, (90 + reach) * DEG)),
            km.Revolute(a=(1000 - l1) / 1000),
        ],
        tool=km.transl(reach / 1000, 0, 0),
        convention="standard",
    )
    q = np.random.default_rng(0).uniform(-2, 2, (5, 3))
    np.testing.assert_allclose(robot.fk(q), by_hand.fk(q), atol=1e-14)
    np.testing.assert_allclose(robot.qlim, by_hand.qlim, rtol=1e-15)


def test_spec_equality_ignores_document_and_bounds() -> None:
    a = parse_robot_dict(_template())
    b = RobotSpec(a.name, a.convention, a.joints, tool=a.tool)
    assert a == b


ROW = "  - {theta: q1, d: 0.3, a: 0.2, alpha: 90}\n  - {theta: q2, d: 0, a: 0.4, alpha: 0}\n"


@pytest.mark.parametrize("alias", sorted(CONVENTION_ALIASES))
def test_every_convention_alias_works_in_files_and_in_code(alias: str, tmp_path: Path) -> None:
    path = tmp_path / "arm.yaml"
    path.write_text(f"name: arm\nconvention: {alias.upper()}\njoints:\n{ROW}")
    from_file = km.load(path)
    rows = [km.Revolute(d=0.3, a=0.2, alpha=np.pi / 2), km.Revolute(a=0.4)]
    in_code = km.Robot.from_dh(rows, convention=alias)
    assert from_file.convention == in_code.convention == CONVENTION_ALIASES[alias]
    q = [0.3, -0.7]
    np.testing.assert_allclose(from_file.fk(q), in_code.fk(q), atol=1e-15)
