"""The command line's xacro options: ``--package NAME=DIR`` and ``--trust-xacro``."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from support.cli import run, script
from support.xacro import RTB, RTB_PACKAGES

import kinematica as km
import kinematica.io.xacro as xacro_module

KR6 = RTB / "kuka_description/kuka_kr6/urdf/kr6r900sixx.xacro"
PACKAGES = [
    "--package",
    f"kuka_kr6_support={RTB_PACKAGES['kuka_kr6_support']}",
    "--package",
    f"kuka_resources={RTB_PACKAGES['kuka_resources']}",
]


def test_show_a_xacro_file_with_its_packages(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = run(capsys, "show", str(KR6), *PACKAGES, "--json")
    assert code == 0, err
    shown = json.loads(out)
    assert shown["joints"] == "RRRRRR"
    # the same arm as the built-in kr6: FK through the command line at one configuration
    q = ["10", "-80", "95", "20", "-30", "45"]
    code, out, err = run(capsys, "fk", str(KR6), *PACKAGES, "--q", *q, "--json")
    assert code == 0, err
    T = np.array(json.loads(out)["T"])
    expected = km.load("kr6").fk(np.radians([float(v) for v in q]))
    np.testing.assert_allclose(T, expected, atol=1e-12)


def test_a_missing_package_names_the_option(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = run(capsys, "show", str(KR6), PACKAGES[0], PACKAGES[1])
    assert code == 2 and out == ""
    assert len(err.strip().splitlines()) == 1
    assert "'kuka_resources'" in err and "--package kuka_resources=DIR" in err


@pytest.mark.parametrize("bad", ["kuka_resources", "=dir", "kuka resources=dir"])
def test_a_malformed_package_option_is_a_usage_error(
    capsys: pytest.CaptureFixture[str], bad: str
) -> None:
    code, _, err = run(capsys, "show", str(KR6), "--package", bad)
    assert code == 2
    assert "--package" in err and "Traceback" not in err


def test_package_is_only_for_urdf(capsys: pytest.CaptureFixture[str]) -> None:
    code, _, err = run(capsys, "show", "puma560", "--package", f"x={RTB}")
    assert code == 2
    assert "packages" in err and "only for URDF" in err


@pytest.mark.skipif(xacro_module._xacro_dir() is None, reason="the xacro package is not installed")
def test_trust_xacro_expands_with_the_xacro_package(capsys: pytest.CaptureFixture[str]) -> None:
    # the real script, as a user runs it: the xacro package in its child, $(find) from --package
    done = script("show", str(KR6), *PACKAGES, "--trust-xacro", "--json")
    assert done.returncode == 0, done.stderr
    assert json.loads(done.stdout)["joints"] == "RRRRRR"
    code, out, _ = run(capsys, "show", str(KR6), *PACKAGES, "--json")
    assert code == 0 and json.loads(out) == json.loads(done.stdout)


def test_the_help_explains_both_options(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run(capsys, "show", "--help")
    assert code == 0
    text = " ".join(out.split())
    assert "--trust-xacro" in text and "RUNS the file's code" in text
    assert "--package NAME=DIR" in text and "ROS_PACKAGE_PATH" in text


def test_xacro_arguments_on_the_command_line(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    path = tmp_path / "arm.urdf.xacro"
    path.write_text(
        '<robot name="$(arg name)" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:arg name="name" default="arm"/><xacro:arg name="length" default="0.5"/>'
        '<link name="base"/><link name="l1"/><joint name="j1" type="revolute">'
        '<parent link="base"/><child link="l1"/><origin xyz="0 0 $(arg length)"/>'
        '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
        "</robot>"
    )
    # the robot's name is an argument used before it is declared: xacro too needs it given
    argv = ["--xacro-arg", "length:=0.75", "--xacro-arg", "name:=tall"]
    code, out, err = run(capsys, "fk", str(path), "--q", "0", *argv, "--json")
    assert code == 0, err
    assert json.loads(out)["T"][2][3] == 0.75
    code, _, err = run(capsys, "show", str(path), "--xacro-arg", "length=0.75")
    assert code == 2 and "NAME:=VALUE" in err
