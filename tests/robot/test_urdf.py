"""URDF files published by robot makers: FK equal to independent URDF implementations.

Files and provenance: tests/data/urdf/PROVENANCE.md. References: a hand-written
URDF chain product (tests/support/urdf.py, scipy rotations) and Pinocchio 4.1.0
(tests/data/urdf/pinocchio_fk.json, computed once by make_pinocchio_reference.py).
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from support.helpers import assert_transform_close
from support.urdf import URDF_DIR, random_joint_values, reference_file

import kinematica as km

#: FK of a loaded URDF equals the URDF's own to this (m; unitless for rotations).
URDF_FK_ATOL = 1e-12


PINOCCHIO = json.loads((URDF_DIR / "pinocchio_fk.json").read_text())
CASES = [(c["file"], c["base"], c["tip"]) for c in PINOCCHIO["cases"]]
IDS = [c[0].removesuffix(".urdf") for c in CASES]


@pytest.mark.parametrize("convention", ["standard", "modified"])
@pytest.mark.parametrize(("name", "base", "tip"), CASES, ids=IDS)
def test_fk_equals_hand_written_urdf_reference(name, base, tip, convention):
    robot = km.load(URDF_DIR / name, base=base, tip=tip, convention=convention)
    ref = reference_file(name, base, tip)
    assert robot.dof == ref.dof
    assert robot.joint_types == "".join(
        "P" if j.get("type") == "prismatic" else "R" for j in ref.movable
    )
    rng = np.random.default_rng(7)
    for batch in [(), (1,), (3, 2)]:
        q = random_joint_values(ref, rng, batch)
        assert_transform_close(robot.fk(q), ref.fk_batch(q), atol=URDF_FK_ATOL)
    assert_transform_close(robot.fk(np.zeros(robot.dof)), ref.fk(np.zeros(ref.dof)), atol=1e-15)


@pytest.mark.parametrize("case", PINOCCHIO["cases"], ids=IDS)
def test_fk_equals_pinocchio(case):
    for convention in ("standard", "modified"):
        ext = km.urdf_to_dh(
            URDF_DIR / case["file"], base=case["base"], tip=case["tip"], convention=convention
        )
        assert [link.name for link in ext.robot.links] == case["joints"]
        for sample in case["samples"]:
            assert_transform_close(ext.robot.fk(sample["q"]), sample["T"], atol=URDF_FK_ATOL)


#: Files whose axes are parallel only to round-off of their numbers (π written with
#: 10 digits): a DH table describes them to about the angle by which they miss.
APPROXIMATE_DH = {"lynxmotion_al5d.urdf": 1e-9}


@pytest.mark.parametrize(("name", "base", "tip"), CASES, ids=IDS)
def test_extracted_table_alone_reproduces_fk(name, base, tip):
    # The DH rows, base and tool, rebuilt from the printed numbers alone.
    ext = km.urdf_to_dh(URDF_DIR / name, base=base, tip=tip)
    expected = APPROXIMATE_DH.get(name, 1e-13)
    assert ext.fk_error < expected
    r = ext.robot
    rebuilt = km.Robot.from_dh(
        [
            km.Revolute(d=d, a=a, alpha=al, offset=th)
            if t == "R"
            else km.Prismatic(theta=th, a=a, alpha=al, offset=d)
            for (th, d, a, al), t in zip(r.dh_table(), r.joint_types, strict=True)
        ],
        base=r.base,
        tool=r.tool,
        convention="standard",
    )
    ref = reference_file(name, base, tip)
    q = random_joint_values(ref, np.random.default_rng(3), (20,))
    assert_transform_close(rebuilt.fk(q), ref.fk_batch(q), atol=max(1e-10, 10 * expected))
    assert len(ext.rules) == r.dof + 1
    assert [rule.frame for rule in ext.rules] == list(range(r.dof + 1))


def _table_alone(robot: km.Robot) -> km.Robot:
    """The robot's DH rows, base and tool, computing without the file's transforms."""
    return km.Robot.from_dh(
        robot.links, convention=robot.convention, base=robot.base, tool=robot.tool
    )


def _largest_entry_difference(model: km.Robot, table: km.Robot) -> float:
    """Independent of the extraction's check: 2000 random q within the model's limits."""
    q = model.random_q(2000, seed=19)
    return float(np.abs(model.fk(q) - table.fk(q)).max())


@pytest.mark.parametrize("convention", ["standard", "modified"])
@pytest.mark.parametrize(("name", "base", "tip"), CASES, ids=IDS)
def test_fk_error_is_the_tables_distance_from_the_loaded_file(name, base, tip, convention):
    # robot.to_dh() measured its table against the robot's own DH rows, so the AL5D
    # reported 4.4e-16 while the table misses the file's FK by 5.9e-10.
    robot = km.load(URDF_DIR / name, base=base, tip=tip, convention=convention)
    other = "modified" if convention == "standard" else "standard"
    loaded = km.urdf_to_dh(URDF_DIR / name, base=base, tip=tip, convention=convention)
    for ext in (loaded, robot.to_dh(convention), robot.to_dh(other)):
        measured = _largest_entry_difference(robot, _table_alone(ext.robot))
        if name in APPROXIMATE_DH:  # 5.9e-10: the AL5D's axes miss parallel by that
            assert ext.fk_error > 1e-10
            assert ext.fk_error == pytest.approx(measured, rel=1e-3)
        else:
            assert ext.fk_error < 1e-12
            assert measured < 1e-12


def test_limits_names_and_continuous_joints_are_kept():
    kr16 = km.load(URDF_DIR / "kuka_kr16_2.urdf")
    assert [link.name for link in kr16.links] == [f"joint_a{i}" for i in range(1, 7)]
    assert kr16.has_limits.all()
    np.testing.assert_allclose(kr16.qlim[0], [-3.22885911619, 3.22885911619], rtol=0, atol=0)
    np.testing.assert_allclose(kr16.qlim[1], [-2.70526034059, 0.610865238198], rtol=0, atol=0)
    kinova = km.load(
        URDF_DIR / "kinova_j2s6s200.urdf", tip="j2s6s200_end_effector"
    )  # joints 1, 4 and 6 are continuous: the limits in their <limit> are ignored
    assert kinova.has_limits.tolist() == [False, True, True, False, True, False]
    assert kinova.qlim[0].tolist() == [-math.pi, math.pi]


@pytest.mark.parametrize(
    ("name", "tip", "kind"),
    [
        ("kuka_kr16_2.urdf", "tool0", "spherical-wrist-6R"),
        ("kuka_kr210l150.urdf", "tool0", "spherical-wrist-6R"),
        ("puma560_robot.urdf", "link7", "spherical-wrist-6R"),
        ("kinova_j2s6s200.urdf", "j2s6s200_end_effector", "spherical-wrist-6R"),
        ("ur5_robot.urdf", "tool0", "three-parallel-6R"),
        ("ur10_robot.urdf", "ee_link", "three-parallel-6R"),
    ],
)
@pytest.mark.parametrize("convention", ["standard", "modified"])
def test_structure_and_closed_form_ik_on_urdf_arms(name, tip, kind, convention):
    robot = km.load(URDF_DIR / name, tip=tip, convention=convention)
    assert km.classify(robot).kind == kind
    ref = reference_file(name, None, tip)
    rng = np.random.default_rng(11)
    lo, hi = robot.qlim[:, 0], robot.qlim[:, 1]
    for _ in range(3):
        q = rng.uniform(np.maximum(lo, -3.0), np.minimum(hi, 3.0))
        target = ref.fk(q)
        res = robot.ik(target)
        assert res.status == "ok", res.message
        assert res.method.startswith("analytic:")
        assert res.count >= 1
        for sol in res.solutions:  # every solution, checked by the URDF's own FK
            assert_transform_close(ref.fk(sol), target, atol=1e-9)
        assert np.min(np.abs(np.angle(np.exp(1j * (res.solutions - q)))).max(axis=1)) < 1e-6
