"""The package map: where ``$(find pkg)`` looks, in which order, and what it says when
a package is nowhere (issue 35, item 2)."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

import kinematica as km
from kinematica.io.packages import CRAWL_DEPTH, PackageMap, parse_package_option

ROBOT = """<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="$(find {package})/urdf/arm.xacro"/>
  <link name="base"/>
  <xacro:arm parent="base"/>
</robot>
"""

ARM = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="arm" params="parent">
    <link name="l1">
      <visual><geometry><mesh filename="package://{package}/meshes/l1.stl"/></geometry></visual>
    </link>
    <joint name="j1" type="revolute">
      <parent link="${{parent}}"/><child link="l1"/>
      <origin xyz="0 0 {length}"/><axis xyz="0 0 1"/>
      <limit lower="-1" upper="1" effort="1" velocity="1"/>
    </joint>
    <link name="l2"/>
    <joint name="j2" type="revolute">
      <parent link="l1"/><child link="l2"/>
      <origin xyz="0.5 0 0"/><axis xyz="0 1 0"/>
      <limit lower="-1" upper="1" effort="1" velocity="1"/>
    </joint>
  </xacro:macro>
</robot>
"""


def package(folder: Path, name: str | None, length: float = 0.3) -> Path:
    """A package folder: ``package.xml`` naming ``name`` (none if None) and ``urdf/arm.xacro``."""
    (folder / "urdf").mkdir(parents=True)
    if name is not None:
        (folder / "package.xml").write_text(
            f'<?xml version="1.0"?>\n<package format="2"><name>{name}</name></package>\n'
        )
    (folder / "urdf" / "arm.xacro").write_text(ARM.format(package=name, length=length))
    return folder


def robot_file(folder: Path, needs: str) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / "robot.urdf.xacro"
    path.write_text(ROBOT.format(package=needs))
    return path


def height(robot: km.Robot) -> float:
    """The z of the tool at q = 0: the length of the package the arm came from."""
    return float(robot.fk(np.zeros(robot.dof))[2, 3])


@pytest.fixture
def clean_env(monkeypatch: pytest.MonkeyPatch) -> pytest.MonkeyPatch:
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    monkeypatch.delenv("AMENT_PREFIX_PATH", raising=False)
    return monkeypatch


def test_a_given_folder(tmp_path: Path, clean_env: pytest.MonkeyPatch) -> None:
    folder = package(tmp_path / "somewhere" / "arm_pkg", None, length=0.7)  # no package.xml
    path = robot_file(tmp_path / "robot", "arm_pkg")
    assert height(km.load(path, packages={"arm_pkg": folder})) == pytest.approx(0.7, abs=1e-15)
    assert height(km.load(path, packages={"arm_pkg": str(folder)})) == pytest.approx(0.7)


def test_the_files_own_package_and_its_siblings(tmp_path: Path, clean_env) -> None:
    src = tmp_path / "ws" / "src"
    own = package(src / "own_description", "own_description", length=0.4)
    package(src / "sibling_pkg", "sibling_pkg", length=0.9)
    path = robot_file(own / "robots", "own_description")
    assert height(km.load(path)) == pytest.approx(0.4)
    path.write_text(ROBOT.format(package="sibling_pkg"))
    assert height(km.load(path)) == pytest.approx(0.9)
    # a package of the same repository, a level further (repo/moveit_configs/arm_config)
    nested = package(src / "moveit_configs" / "arm_config", "arm_config", length=0.5)
    path.write_text(ROBOT.format(package="arm_config"))
    assert height(km.load(path)) == pytest.approx(0.5)
    config = robot_file(nested / "config", "sibling_pkg")  # and back, from the nested one
    assert height(km.load(config)) == pytest.approx(0.9)


def test_ros_package_path_is_searched(tmp_path: Path, clean_env) -> None:
    deep = tmp_path / "ros" / "a" / "b" / "c"  # CRAWL_DEPTH levels below the entry: found
    assert CRAWL_DEPTH == 4
    package(deep / "deep_pkg", "deep_pkg", length=0.2)
    package(tmp_path / "ros" / "a" / "b" / "c" / "d" / "too_deep_pkg", "too_deep_pkg")
    path = robot_file(tmp_path / "robot", "deep_pkg")
    clean_env.setenv("ROS_PACKAGE_PATH", f"{tmp_path / 'nowhere'}:{tmp_path / 'ros'}")
    assert height(km.load(path)) == pytest.approx(0.2)
    pmap = PackageMap(environ={"ROS_PACKAGE_PATH": str(tmp_path / "ros")})
    assert pmap.find("deep_pkg") == (deep / "deep_pkg").resolve()
    assert pmap.find("too_deep_pkg") is None  # one level past the crawl's depth


def test_ament_prefix_path_share_folders(tmp_path: Path, clean_env) -> None:
    package(tmp_path / "install" / "share" / "ament_pkg", "ament_pkg", length=0.6)
    path = robot_file(tmp_path / "robot", "ament_pkg")
    clean_env.setenv("AMENT_PREFIX_PATH", str(tmp_path / "install"))
    assert height(km.load(path)) == pytest.approx(0.6)


def test_the_order_given_own_ros_ament(tmp_path: Path, clean_env) -> None:
    src = tmp_path / "ws" / "src"
    own = package(src / "pkg", "pkg", length=0.2)
    ros = package(tmp_path / "ros" / "pkg", "pkg", length=0.3)
    package(tmp_path / "install" / "share" / "pkg", "pkg", length=0.4)
    given = package(tmp_path / "given", None, length=0.1)
    env = {
        "ROS_PACKAGE_PATH": str(tmp_path / "ros"),
        "AMENT_PREFIX_PATH": str(tmp_path / "install"),
    }
    start = own / "robots" / "r.xacro"
    assert PackageMap({"pkg": given}, start=start, environ=env).find("pkg") == given.resolve()
    assert PackageMap(start=start, environ=env).find("pkg") == own.resolve()
    assert PackageMap(environ=env).find("pkg") == ros.resolve()
    only_ament = {"AMENT_PREFIX_PATH": env["AMENT_PREFIX_PATH"]}
    assert PackageMap(environ=only_ament).find("pkg") == (tmp_path / "install/share/pkg").resolve()
    assert PackageMap(environ={}).find("pkg") is None


def test_a_package_name_never_walks_out_of_a_folder(tmp_path: Path, clean_env) -> None:
    # AMENT_PREFIX_PATH joins <prefix>/share/<name>: "../.." would be <prefix>'s parent
    (tmp_path / "install" / "share").mkdir(parents=True)
    env = {"AMENT_PREFIX_PATH": str(tmp_path / "install")}
    for name in ("..", "../..", "../../etc", ".", "a/b", "x.y"):
        assert PackageMap(environ=env).find(name) is None, name
    path = robot_file(tmp_path / "robot", "../..")
    clean_env.setenv("AMENT_PREFIX_PATH", env["AMENT_PREFIX_PATH"])
    with pytest.raises(km.RobotFileError, match=re.escape("needs the ROS package '../..'")):
        km.load(path)


def test_a_missing_package_is_one_line_saying_how_to_give_it(tmp_path: Path, clean_env) -> None:
    path = robot_file(tmp_path / "robot", "nowhere_pkg")
    with pytest.raises(km.RobotFileError) as info:
        km.load(path)
    message = str(info.value)
    assert "\n" not in message
    for part in (str(path), "line 3", "'nowhere_pkg'", "--package nowhere_pkg=DIR", "packages="):
        assert part in message, message


def test_mesh_names_of_a_missing_package_do_not_fail_the_load(tmp_path: Path, clean_env) -> None:
    # package://arm_pkg/meshes/l1.stl names a package that is nowhere: kinematics needs no mesh
    folder = package(tmp_path / "pkgs" / "x", None)
    (folder / "urdf" / "arm.xacro").write_text(ARM.format(package="no_such_mesh_pkg", length=0.3))
    path = robot_file(tmp_path / "robot", "arm_pkg")
    assert km.load(path, packages={"arm_pkg": folder}).dof == 2


def test_files_outside_the_packages_are_not_read(tmp_path: Path, clean_env) -> None:
    folder = package(tmp_path / "pkgs" / "arm_pkg", None)
    path = robot_file(tmp_path / "robot", "arm_pkg")
    text = ROBOT.format(package="arm_pkg").replace(
        '<link name="base"/>', f'<xacro:include filename="{tmp_path / "pkgs" / "other.xacro"}"/>'
    )
    (tmp_path / "pkgs" / "other.xacro").write_text('<robot xmlns:xacro="x:xacro"/>')
    path.write_text(text)
    with pytest.raises(km.RobotFileError, match="outside the folders"):
        km.load(path, packages={"arm_pkg": folder})
    # the same file, inside the package's folder, is read
    (folder / "other.xacro").write_text('<robot xmlns:xacro="x:xacro"/>')
    path.write_text(
        text.replace(str(tmp_path / "pkgs" / "other.xacro"), str(folder / "other.xacro"))
    )
    with pytest.raises(km.RobotFileError, match="parent link 'base' is not defined"):  # read
        km.load(path, packages={"arm_pkg": folder})


def test_the_option_and_argument_forms(tmp_path: Path) -> None:
    assert parse_package_option("abc_pkg=/x/y") == ("abc_pkg", "/x/y")
    assert parse_package_option(" a = b=c ") == ("a", "b=c")
    for bad in ("abc", "=dir", "name=", "na me=dir", "../x=dir"):
        with pytest.raises(ValueError, match="--package"):
            parse_package_option(bad)
    with pytest.raises(km.RobotFileError, match="is not a folder"):
        PackageMap({"pkg": tmp_path / "missing"})
    with pytest.raises(km.RobotFileError, match="not a ROS package name"):
        PackageMap({"a/b": tmp_path})
    with pytest.raises(km.KinematicaError, match="packages: only for URDF"):
        km.load("puma560", packages={"pkg": tmp_path})
