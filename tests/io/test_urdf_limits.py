"""Large and extreme URDFs: loading is linear in the file's size; numbers that are not finite
or beyond what a URDF describes are RobotFileErrors naming the file, the joint and the key."""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np
import pytest
from support.urdf import broken, one_line_error, write

import kinematica as km
from kinematica.io import parse_urdf, read_urdf
from kinematica.io._parse import MAX_JOINTS
from kinematica.io.urdf import URDF_AXIS_SCALE, URDF_MAX_ANGLE, URDF_MAX_LENGTH


def chain_text(links: int, movable_every: int = 1) -> str:
    """A serial chain of ``links`` joints, 0.1 m apart along z; every ``movable_every``-th
    joint revolute about z, the others fixed."""
    parts = ['<?xml version="1.0"?>\n<robot name="long">']
    parts += [f'<link name="l{i}"/>' for i in range(links + 1)]
    for i in range(1, links + 1):
        kind = "revolute" if i % movable_every == 0 else "fixed"
        parts.append(
            f'<joint name="j{i}" type="{kind}"><parent link="l{i - 1}"/><child link="l{i}"/>'
            '<origin xyz="0 0 0.1" rpy="0 0 0"/><axis xyz="0 0 1"/>'
            '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
        )
    return "\n".join([*parts, "</robot>"])


def star_text(arms: int) -> str:
    """``arms`` revolute joints all hanging from the root link."""
    parts = ['<robot name="star"><link name="hub"/>']
    parts += [f'<link name="s{i}"/>' for i in range(arms)]
    parts += [
        f'<joint name="r{i}" type="revolute"><parent link="hub"/><child link="s{i}"/>'
        f'<origin xyz="{i * 1e-3} 0 0"/><axis xyz="0 0 1"/>'
        '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
        for i in range(arms)
    ]
    return "".join([*parts, "</robot>"])


def cpu_seconds_to_load(path: Path, links: int, dof: int) -> float:
    start = time.process_time()
    robot = km.load(path)
    spent = time.process_time() - start
    assert robot.dof == dof
    # links 0.1 m apart along z, every joint about z: the tip is 0.1 m per link up at any q
    q = np.linspace(-1.0, 1.0, dof)
    np.testing.assert_allclose(robot.fk(q)[:3, 3], [0.0, 0.0, 0.1 * links], atol=1e-6)
    return spent


def test_loading_a_long_chain_is_linear(tmp_path):
    # quadratic before: 20,000 links took 4.4 s, 40,000 links 20.6 s. Four times the
    # links: linear 4x, quadratic 16x; 5,000 and 20,000 tell them apart as 10,000 and
    # 40,000 did (a quadratic 20,000 took 4.4 s). The bound sits between the two: a
    # linear load read up to 8.0x on a busy 2-core machine (the small file's time is the
    # shorter of two loads, its noise being the larger share of it).
    small = write(tmp_path, chain_text(5_000, movable_every=1_250), "small.urdf")
    big = write(tmp_path, chain_text(20_000, movable_every=4_000), "big.urdf")
    t_small = min(cpu_seconds_to_load(small, 5_000, 4) for _ in range(2))
    t_big = cpu_seconds_to_load(big, 20_000, 5)
    assert t_big < 5.0
    assert t_big < 10.0 * t_small


def test_a_star_of_30000_joints_names_its_leaves_or_loads_one_arm():
    model = parse_urdf(star_text(30_000))
    with pytest.raises(km.RobotFileError, match=r"30000 leaf links below 'hub'.*30000 in all"):
        model.chain()
    chain = model.chain(tip="s29999")
    assert [j.name for j in chain.joints] == ["r29999"]
    assert chain.joints[0].origin.xyz == (29999 * 1e-3, 0.0, 0.0)


def test_a_loop_of_many_links_is_named_briefly():
    n = 20_000
    text = "".join(
        ['<robot name="loop">']
        + [f'<link name="a{i}"/>' for i in range(n)]
        + [
            f'<joint name="j{i}" type="fixed"><parent link="a{i}"/>'
            f'<child link="a{(i + 1) % n}"/></joint>'
            for i in range(n)
        ]
        + ["</robot>"]
    )
    start = time.process_time()
    with pytest.raises(km.RobotFileError, match=f"loop: .* <- ... \\({n} links in the loop\\)"):
        parse_urdf(text)
    assert time.process_time() - start < 5.0


def test_at_most_max_joints_movable_joints_on_the_chain(tmp_path):
    assert km.load(write(tmp_path, chain_text(MAX_JOINTS))).dof == MAX_JOINTS
    one_line_error(
        write(tmp_path, chain_text(MAX_JOINTS + 1)),
        f"{MAX_JOINTS + 1} movable joints",
        f"at most {MAX_JOINTS}",
    )


# ------------------------------------------------------------------ numbers
ORIGIN = 'xyz="0.1 0 0"'  # joint j2's origin
RPY = 'rpy="1.5707963267948966 0 0"'
AXIS = '<axis xyz="1 0 0"/>'  # joint j2's axis (prismatic)
LIMIT = 'lower="0" upper="0.5"'  # joint j2's limits (prismatic, metres)
REVOLUTE_LIMIT = 'lower="-2" upper="2"'  # joint j1's (revolute, radians)


@pytest.mark.parametrize(
    ("old", "new", "joint", "key"),
    [
        (ORIGIN, 'xyz="1e154 1e154 0"', "j2", "origin xyz"),  # a ValueError before
        (AXIS, '<axis xyz="1e200 1e200 0"/>', "j2", "axis xyz"),  # an AssertionError before
        (ORIGIN, 'xyz="0.1 0 1e400"', "j2", "origin xyz"),  # overflows to inf when read
        (ORIGIN, 'xyz="0.1 -inf 0"', "j2", "origin xyz"),
        (RPY, 'rpy="0 1e300 0"', "j2", "origin rpy"),
        (RPY, 'rpy="0 0 nan"', "j2", "origin rpy"),
        (AXIS, '<axis xyz="inf 0 0"/>', "j2", "axis xyz"),
        (AXIS, '<axis xyz="1e-200 1e-200 0"/>', "j2", "axis xyz"),
        (AXIS, '<axis xyz="0 0 0"/>', "j2", "zero axis"),
        (AXIS, '<axis xyz="-0.0 0 0"/>', "j2", "zero axis"),
        (LIMIT, 'lower="-1e308" upper="1e308"', "j2", "limit lower"),
        (LIMIT, 'lower="0" upper="1e309"', "j2", "limit upper"),
        (REVOLUTE_LIMIT, 'lower="-1e16" upper="1e16"', "j1", "limit lower"),
        (REVOLUTE_LIMIT, 'lower="nan" upper="2"', "j1", "limit lower"),
    ],
)
def test_numbers_out_of_range_name_the_file_joint_and_key(tmp_path, old, new, joint, key):
    path = write(tmp_path, broken(old, new))
    one_line_error(path, f"joint '{joint}'", key)
    with pytest.raises(km.RobotFileError):  # the reader alone, too
        read_urdf(path)


def _tool_x(robot: km.Robot) -> float:
    return float(robot.fk([0.0, 0.0])[0, 3])


def _tool_yz(robot: km.Robot) -> list[float]:
    return robot.fk([0.0, 0.0])[1:3, 3].tolist()


A = URDF_MAX_ANGLE


@pytest.mark.parametrize(
    ("old", "template", "bound", "joint", "key", "measure", "expected"),
    [
        # j2's origin at x = bound: the tool at x = bound
        (ORIGIN, 'xyz="{} 0 0"', URDF_MAX_LENGTH, "j2", "origin xyz", _tool_x, URDF_MAX_LENGTH),
        # j2's roll at the bound turns the tool's 0.05 m offset to that angle in the y-z plane
        (
            RPY,
            'rpy="{} 0 0"',
            A,
            "j2",
            "origin rpy",
            _tool_yz,
            [-0.05 * np.sin(A), 0.3 + 0.05 * np.cos(A)],
        ),
        (
            LIMIT,
            'lower="0" upper="{}"',
            URDF_MAX_LENGTH,
            "j2",
            "limit upper",
            lambda r: r.qlim[1, 1],
            URDF_MAX_LENGTH,
        ),
        (
            REVOLUTE_LIMIT,
            'lower="-2" upper="{}"',
            A,
            "j1",
            "limit upper",
            lambda r: r.qlim[0, 1],
            A,
        ),
    ],
)
def test_bounds_on_both_sides(tmp_path, old, template, bound, joint, key, measure, expected):
    inside = km.load(write(tmp_path, broken(old, template.format(repr(bound)))))
    np.testing.assert_allclose(measure(inside), expected, rtol=1e-12, atol=1e-12)
    outside = write(tmp_path, broken(old, template.format(repr(bound * (1 + 1e-9)))))
    one_line_error(outside, f"joint '{joint}'", key, f"±{bound:g}")


def test_axis_scale_on_both_sides(tmp_path):
    s = URDF_AXIS_SCALE
    for inside in (f"{s!r} 0 0", f"{1 / s!r} 0 0", f"0 {s!r} {s!r}"):
        robot = km.load(write(tmp_path, broken(AXIS, f'<axis xyz="{inside}"/>')))
        axis = np.array([float(v) for v in inside.split()])
        chain = read_urdf(write(tmp_path, broken(AXIS, f'<axis xyz="{inside}"/>'))).chain()
        np.testing.assert_allclose(chain.joints[1].axis, axis / np.linalg.norm(axis), atol=1e-15)
        assert robot.dof == 2
    for outside in (f"{s * (1 + 1e-9)!r} 0 0", f"{1 / s * (1 - 1e-9)!r} 0 0"):
        one_line_error(
            write(tmp_path, broken(AXIS, f'<axis xyz="{outside}"/>')), "joint 'j2'", "axis xyz"
        )
