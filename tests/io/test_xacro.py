"""xacro: expanded only when asked, by kinematica's expander (default) or, trusted, by the
xacro package in a child process; both bounded in time, nodes and size, and never reading
the environment unless asked."""

from __future__ import annotations

import sys
import time

import numpy as np
import pytest
from support.urdf import ARM, BOMB, XACRO, one_line_error, write

import kinematica as km
import kinematica.io.xacro as xacro_module
from kinematica.io import URDF_MAX_BYTES, parse_urdf, read_urdf
from kinematica.io.xacro import XACRO_MAX_NODES, expand_xacro
from kinematica.io.xacro_expand import MAX_DEPTH

# A chain of `count` segments by a recursive macro with a loop counter: what real descriptions
# do (a macro per part, called for each joint), some thousand nodes for 60 segments.
CHAIN = """<?xml version="1.0"?>
<robot name="chain" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="seg" params="i count">
    <link name="l${i}"><visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual></link>
    <joint name="j${i}" type="revolute">
      <parent link="l${i-1}"/><child link="l${i}"/>
      <origin xyz="0 0 0.1" rpy="0 0 0"/><axis xyz="0 1 0"/>
      <limit lower="-1" upper="1" effort="1" velocity="1"/>
    </joint>
    <xacro:if value="${i &lt; count}"><xacro:seg i="${i+1}" count="${count}"/></xacro:if>
  </xacro:macro>
  <link name="l0"/>
  <xacro:seg i="1" count="60"/>
</robot>
"""


def macro_bomb(levels: int = 28) -> str:
    """Each macro calls the one before twice: 2**levels links from a file of under 2 kB."""
    macros = ['<xacro:macro name="m0"><link name="x"/></xacro:macro>']
    macros += [
        f'<xacro:macro name="m{k}"><xacro:m{k - 1}/><xacro:m{k - 1}/></xacro:macro>'
        for k in range(1, levels)
    ]
    return (
        '<?xml version="1.0"?>\n<robot name="bomb" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        + "\n".join(macros)
        + f"\n<xacro:m{levels - 1}/>\n</robot>\n"
    )


ENV_NAME = ARM.replace('<robot name="arm">', '<robot name="$(env KM_XACRO_SECRET)">')
OPTENV_NAME = ARM.replace('<robot name="arm">', '<robot name="$(optenv KM_XACRO_SECRET unset)">')

needs_xacro = pytest.mark.skipif(
    xacro_module._xacro_dir() is None, reason="the xacro package is not installed"
)

#: The two ways of expanding: kinematica's expander, and the xacro package (trusted).
BOTH = pytest.mark.parametrize(
    "trust", [False, pytest.param(True, marks=needs_xacro, id="trusted")], ids=str
)


@BOTH
def test_a_xacro_file_is_expanded(tmp_path, trust):
    robot = km.load(write(tmp_path, XACRO, "arm.urdf.xacro"), trust_xacro=trust)
    assert robot.dof == 2
    assert [link.name for link in robot.links] == ["j1", "j2"]
    # two segments of 0.4 m along z, each turned 90 degrees about y
    T = robot.fk([0.0, 0.0])
    np.testing.assert_allclose(T[:3, 3], [0.4, 0.0, 0.4], atol=1e-15)


def test_a_urdf_holding_xacro_needs_the_option(tmp_path):
    path = write(tmp_path, XACRO, "arm.urdf")
    one_line_error(path, "xacro elements", "xacro=True", "--xacro")
    robot = km.load(path, xacro=True)
    assert [link.name for link in robot.links] == ["j1", "j2"]
    np.testing.assert_allclose(robot.fk([0.0, 0.0])[:3, 3], [0.4, 0.0, 0.4], atol=1e-15)
    # the option leaves plain URDF as it is
    assert km.load(write(tmp_path, ARM, "plain.urdf"), xacro=True).dof == 2
    with pytest.raises(km.KinematicaError, match="xacro: only for URDF files"):
        km.load("puma560", xacro=True)


@BOTH
def test_the_environment_is_read_only_when_asked(tmp_path, monkeypatch, trust):
    monkeypatch.setenv("KM_XACRO_SECRET", "s3cret-value")
    for text in (ENV_NAME, OPTENV_NAME):
        path = write(tmp_path, text, "arm.xacro")
        message = one_line_error(
            path, "'KM_XACRO_SECRET'", "refused", "xacro_env=True", trust_xacro=trust
        )
        assert "s3cret-value" not in message
        assert km.load(path, xacro_env=True, trust_xacro=trust).name == "s3cret-value"
    # a .urdf needs both options
    path = write(tmp_path, ENV_NAME, "arm.urdf")
    one_line_error(path, "'KM_XACRO_SECRET'", "refused", xacro=True, trust_xacro=trust)
    assert km.load(path, xacro=True, xacro_env=True, trust_xacro=trust).name == "s3cret-value"


@BOTH
def test_a_macro_bomb_is_refused_quickly(tmp_path, trust):
    text = macro_bomb()
    assert len(text) < 2000
    path = write(tmp_path, text, "bomb.xacro")
    # the node count stopped it, not the time limit (whose message names seconds): no
    # wall-clock bound here, which a loaded machine breaks
    one_line_error(path, f"more than {XACRO_MAX_NODES} XML", trust_xacro=trust)


@BOTH
def test_a_real_sized_expansion_is_within_the_node_limit(tmp_path, trust):
    # 60 segments clone about 1,500 nodes: 1,000 times fewer allowed would refuse it
    robot = km.load(write(tmp_path, CHAIN, "chain.xacro"), trust_xacro=trust)
    assert robot.dof == 60
    np.testing.assert_allclose(robot.fk(np.zeros(60))[:3, 3], [0.0, 0.0, 6.0], atol=1e-12)


def test_the_node_limit_is_what_stops_a_bomb(tmp_path, monkeypatch):
    # the 60-segment chain copies 60 macro bodies of 13 elements: refused under 779, read under 780
    path = write(tmp_path, CHAIN, "chain.xacro")
    monkeypatch.setattr(xacro_module, "XACRO_MAX_NODES", 779)
    one_line_error(path, "more than 779 XML elements")
    monkeypatch.setattr(xacro_module, "XACRO_MAX_NODES", 780)
    assert km.load(path).dof == 60


def test_a_huge_number_is_refused_at_once(tmp_path):
    text = XACRO.replace('value="0.4"', 'value="${9**9**9**9}"')
    start = time.perf_counter()
    one_line_error(write(tmp_path, text, "slow.xacro"), "9**9**9**9", "larger than 2**1024")
    assert time.perf_counter() - start < 5.0  # unbounded work would never end: a wide margin


@needs_xacro
def test_an_expression_that_never_ends_meets_the_time_limit(tmp_path, monkeypatch):
    monkeypatch.setattr(xacro_module, "XACRO_TIME_LIMIT", 1.5)
    text = XACRO.replace('value="0.4"', 'value="${9**9**9**9}"')
    start = time.perf_counter()
    one_line_error(write(tmp_path, text, "slow.xacro"), "within 1.5 s", trust_xacro=True)
    assert time.perf_counter() - start < 5.0


def test_the_time_limit_holds_for_our_expander(tmp_path, monkeypatch):
    monkeypatch.setattr(xacro_module, "XACRO_TIME_LIMIT", 0.0)
    one_line_error(write(tmp_path, CHAIN, "chain.xacro"), "time limit")


def test_string_growth_and_output_size_are_bounded(tmp_path):
    # a string that doubles 28 times (256 MB): refused past a million characters
    doubling = "\n".join(
        f'<xacro:property name="s{k}" value="${{s{k - 1} + s{k - 1}}}"/>' for k in range(1, 29)
    )
    text = XACRO.replace(
        '<xacro:property name="len" value="0.4"/>',
        '<xacro:property name="len" value="0.4"/>\n<xacro:property name="s0" value="xx"/>\n'
        + doubling
        + '\n<link name="${s28}"/>',
    )
    one_line_error(write(tmp_path, text, "big.xacro"), "longer than 1,000,000", "refused")
    path = write(tmp_path, XACRO, "arm.xacro")
    size = len(xacro_module.xacro_to_urdf(path, max_bytes=URDF_MAX_BYTES))
    with pytest.raises(km.RobotFileError, match=f"larger than the limit of {size - 1} bytes"):
        read_urdf(path, max_bytes=size - 1)
    assert len(read_urdf(path, max_bytes=size).joints) == 2


@needs_xacro
def test_memory_and_output_limits(tmp_path, monkeypatch):
    # a string that doubles 28 times (256 MB) against a memory limit of 200 MB
    doubling = "\n".join(
        f'<xacro:property name="s{k}" value="${{s{k - 1} + s{k - 1}}}"/>' for k in range(1, 29)
    )
    text = XACRO.replace(
        '<xacro:property name="len" value="0.4"/>',
        '<xacro:property name="len" value="0.4"/>\n<xacro:property name="s0" value="xx"/>\n'
        + doubling
        + '\n<link name="${s28}"/>',
    )
    monkeypatch.setattr(xacro_module, "XACRO_MAX_MEMORY", 200 * 2**20)
    one_line_error(write(tmp_path, text, "big.xacro"), "memory", trust_xacro=True)
    # the expansion (about 900 bytes) is refused under a limit its file (560 bytes) is within
    path = write(tmp_path, XACRO, "arm.xacro")
    size = len(expand_xacro(path, max_bytes=URDF_MAX_BYTES))
    assert size > len(XACRO) + 100
    with pytest.raises(km.RobotFileError, match=f"larger than the limit of {size - 1} bytes"):
        read_urdf(path, max_bytes=size - 1, trust_xacro=True)
    assert len(read_urdf(path, max_bytes=size, trust_xacro=True).joints) == 2


def test_without_the_package_only_the_trusted_path_needs_it(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "xacro", None)  # as if not installed
    path = write(tmp_path, XACRO, "arm.xacro")
    one_line_error(path, "pip install 'kinematica[xacro]'", "trust_xacro", trust_xacro=True)
    assert km.load(path).dof == 2  # kinematica's expander needs no package
    one_line_error(write(tmp_path, XACRO, "arm.urdf"), "xacro elements", "xacro=True")
    with pytest.raises(km.RobotFileError, match="xacro substitutions"):
        parse_urdf(ARM.replace('xyz="0.1 0 0"', 'xyz="${a} 0 0"'))


@BOTH
def test_xacro_errors_and_hostile_xml_give_one_line(tmp_path, trust):
    text = XACRO.replace(
        '<link name="base"/>', '<xacro:include filename="$(find some_ros_package)/urdf/x.xacro"/>'
    )
    path = write(tmp_path, text, "arm.xacro")
    one_line_error(path, "'some_ros_package'", "--package some_ros_package=DIR", trust_xacro=trust)
    one_line_error(write(tmp_path, BOMB, "bomb.xacro"), "declares an entity", trust_xacro=trust)


@needs_xacro
def test_nothing_from_the_files_folder_is_imported(tmp_path):
    # the child runs isolated: a module named like xacro's beside the file is not run
    (tmp_path / "xacro.py").write_text("raise SystemExit('imported from the folder')\n")
    assert km.load(write(tmp_path, XACRO, "arm.xacro"), trust_xacro=True).dof == 2


RECURSION = (
    '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
    '<xacro:macro name="m" params="i"><xacro:if value="${{i &lt; {levels}}}">'
    '<xacro:m i="${{i + 1}}"/></xacro:if></xacro:macro><link name="base"/><xacro:m i="0"/></robot>'
)


def test_macro_recursion_stops_at_the_depth_limit(tmp_path):
    # 118 nested calls are within MAX_DEPTH (the root element counts too), 119 are not
    assert MAX_DEPTH == 120
    read_urdf(write(tmp_path, RECURSION.format(levels=118), "ok.xacro"))
    one_line_error(
        write(tmp_path, RECURSION.format(levels=119), "deep.xacro"), "nested deeper than 120"
    )
    endless = RECURSION.replace("${{i &lt; {levels}}}", "true").format()
    one_line_error(write(tmp_path, endless, "endless.xacro"), "nested deeper than 120")


def test_the_number_of_files_is_bounded(tmp_path, monkeypatch):
    # a chain of includes: 3 files are read under a limit of 3, not under a limit of 2
    import kinematica.io.xacro_subst as subst

    for k in (1, 2):
        write(
            tmp_path,
            f'<robot xmlns:xacro="http://www.ros.org/wiki/xacro">'
            f'<xacro:include filename="f{k + 1}.xacro"/></robot>',
            f"f{k}.xacro",
        )
    write(tmp_path, '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"/>', "f3.xacro")
    text = XACRO.replace(
        '<link name="base"/>', '<link name="base"/><xacro:include filename="f1.xacro"/>'
    )
    path = write(tmp_path, text, "top.xacro")
    monkeypatch.setattr(subst, "MAX_FILES", 4)
    assert km.load(path).dof == 2
    monkeypatch.setattr(subst, "MAX_FILES", 3)
    one_line_error(path, "more than 3 files")


def test_a_default_that_never_ends_is_refused_at_once(tmp_path):
    # xacro's own pattern for macro defaults backtracks exponentially on this (2**k ways to
    # read k "${x}"); kinematica's reads each piece one way only, and bounds the params
    params = "a:=" + "${x}" * 2000 + "'"
    text = XACRO.replace('params="i parent"', f'params="{params}"')
    start = time.perf_counter()
    one_line_error(write(tmp_path, text, "redos.xacro"), "is not a name")
    assert time.perf_counter() - start < 5.0  # unbounded work would never end: a wide margin
    long = XACRO.replace('params="i parent"', f'params="i parent {"x " * 5000}"')
    one_line_error(write(tmp_path, long, "long.xacro"), "at most 10,000 are read")
