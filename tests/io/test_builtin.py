"""Built-in models: they parse, match the shared reference data, the seeds'
formulas and the makers' URDFs.

The robot layer is not used here: a small DH product written in this file
computes forward kinematics (a later test re-checks through the real Robot).
"""

from __future__ import annotations

import json
import math
from collections.abc import Sequence
from typing import Any

import numpy as np
import pytest
from support import DATA

import kinematica as km
from kinematica.errors import UnknownRobotError
from kinematica.io import RobotSpec, builtin_names, builtin_path, read_builtin

REFERENCE = DATA / "reference" / "fk_reference.json"
ATOL = 1e-12  # agreement of two forward-kinematics computations, m and rad
RNG_SEED = 20240531

EXPECTED = {
    "anthropomorphic-3r",
    "arm6-dh",
    "cylindrical-4dof",
    "iiwa14",
    "irb120",
    "kr6",
    "panda",
    "planar-3r",
    "planar-pr",
    "planar-prr",
    "puma560",
    "rrr-geometric",
    "scara",
    "stanford",
    "ur5",
    "ur10",
}
INDUSTRIAL = {"iiwa14", "irb120", "kr6", "panda", "puma560", "scara", "stanford", "ur5", "ur10"}


# --- a tiny forward kinematics, for these tests only ---------------------------


def _rotz(t: float) -> np.ndarray:
    c, s = math.cos(t), math.sin(t)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])


def _rotx(t: float) -> np.ndarray:
    c, s = math.cos(t), math.sin(t)
    return np.array([[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1.0]])


def _trans(x: float, y: float, z: float) -> np.ndarray:
    T = np.eye(4)
    T[:3, 3] = (x, y, z)
    return T


def _axis_angle(axis: Sequence[float], t: float) -> np.ndarray:
    k = np.asarray(axis, dtype=float)
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    T = np.eye(4)
    T[:3, :3] = np.eye(3) + math.sin(t) * K + (1 - math.cos(t)) * K @ K
    return T


def _rpy(r: float, p: float, y: float) -> np.ndarray:
    return _axis_angle((0, 0, 1), y) @ _axis_angle((0, 1, 0), p) @ _axis_angle((1, 0, 0), r)


def fk(spec: RobotSpec, q: Sequence[float]) -> np.ndarray:
    """base @ A1(q1) @ ... @ An(qn) @ tool, standard or modified DH."""
    T = spec.base.as_matrix() if spec.base is not None else np.eye(4)
    for j, qi in zip(spec.joints, q, strict=True):
        theta = j.theta + (qi if j.kind == "R" else 0.0)
        d = j.d + (qi if j.kind == "P" else 0.0)
        if spec.convention == "standard":  # Rz(theta) Tz(d) Tx(a) Rx(alpha)
            T = T @ _rotz(theta) @ _trans(0, 0, d) @ _trans(j.a, 0, 0) @ _rotx(j.alpha)
        else:  # Rx(alpha) Tx(a) Rz(theta) Tz(d)
            T = T @ _rotx(j.alpha) @ _trans(j.a, 0, 0) @ _rotz(theta) @ _trans(0, 0, d)
    if spec.tool is not None:
        T = T @ spec.tool.as_matrix()
    return T


def _random_q(spec: RobotSpec, n: int) -> np.ndarray:
    rng = np.random.default_rng(RNG_SEED)
    return rng.uniform(-math.pi, math.pi, size=(n, spec.dof))


# --- names, files, errors ----------------------------------------------------------


def test_builtin_names_are_sorted_and_complete() -> None:
    names = builtin_names()
    assert names == sorted(names)
    assert set(names) == EXPECTED


@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_every_builtin_parses_and_cites_its_source(name: str) -> None:
    spec = read_builtin(name)
    assert spec.source == f"builtin:{name}"
    assert spec.name and spec.description and spec.reference
    text = builtin_path(name).read_text(encoding="utf-8")
    assert text.startswith("# "), "each model file opens with a comment giving its source"
    assert "Source" in text or "Seed" in text
    if name in INDUSTRIAL:
        assert all(j.qlim is not None for j in spec.joints), "limits from the datasheet"
        assert "limits" in text.lower()


@pytest.mark.parametrize("name", ["PUMA560", " puma560 ", "planar_pr", "Planar-PR"])
def test_names_ignore_case_and_underscores(name: str) -> None:
    assert read_builtin(name).source in ("builtin:puma560", "builtin:planar-pr")


def test_unknown_name_lists_the_builtins_and_suggests_one() -> None:
    with pytest.raises(UnknownRobotError, match=r"'puma' \(did you mean 'puma560'\?\)") as info:
        read_builtin("puma")
    for name in EXPECTED:
        assert name in str(info.value)
    with pytest.raises(UnknownRobotError, match="no built-in robot named 'xyzzy'; built-in"):
        builtin_path("xyzzy")
    with pytest.raises(LookupError):
        read_builtin("")


# --- the shared reference data -------------------------------------------------


def _reference_arms() -> list[dict]:
    return json.loads(REFERENCE.read_text(encoding="utf-8"))["arms"]


@pytest.mark.parametrize("arm", _reference_arms(), ids=lambda arm: arm["name"])
def test_reference_arms_have_the_published_numbers(arm: dict) -> None:
    spec = read_builtin(arm["name"])
    assert spec.convention == arm["convention"]
    assert spec.dof == len(arm["joints"])
    for j, ref in zip(spec.joints, arm["joints"], strict=True):
        assert j.kind == ref["type"]
        np.testing.assert_allclose(
            [j.theta, j.d, j.a, j.alpha],
            [ref["theta"], ref["d"], ref["a"], ref["alpha"]],
            rtol=0,
            atol=1e-15,
        )
    tool = spec.tool.as_matrix() if spec.tool is not None else np.eye(4)
    np.testing.assert_allclose(tool, arm["tool"], rtol=0, atol=1e-15)
    assert spec.base is None


@pytest.mark.parametrize("arm", _reference_arms(), ids=lambda arm: arm["name"])
def test_reference_arms_reproduce_the_reference_poses(arm: dict) -> None:
    spec = read_builtin(arm["name"])
    assert len(arm["samples"]) >= 25
    for sample in arm["samples"]:
        np.testing.assert_allclose(fk(spec, sample["q"]), sample["T"], rtol=0, atol=ATOL)


# --- the seeds' worked examples ---------------------------------------------------


def _position(spec: RobotSpec, q: Sequence[float]) -> np.ndarray:
    return fk(spec, q)[:3, 3]


def test_planar_pr_seed_formula() -> None:
    spec = read_builtin("planar-pr")
    l1, l2 = spec.parameters["l1"], spec.parameters["l2"]
    assert [j.kind for j in spec.joints] == ["P", "R"]
    for q1, q2 in _random_q(spec, 50):
        x = q1 + l1 + l2 * math.cos(q2)
        y = l2 * math.sin(q2)
        np.testing.assert_allclose(_position(spec, (q1, q2)), [x, y, 0.0], atol=ATOL)


def test_planar_prr_seed_formula() -> None:
    spec = read_builtin("planar-prr")
    p = spec.parameters
    assert [j.kind for j in spec.joints] == ["P", "R", "R"]
    for q1, q2, q3 in _random_q(spec, 50):
        z = q1 + p["l1"] + p["l3"] * math.cos(q2) + p["l4"] * math.cos(q2 + q3)
        x = p["l2"] + p["l3"] * math.sin(q2) + p["l4"] * math.sin(q2 + q3)
        np.testing.assert_allclose(_position(spec, (q1, q2, q3)), [x, 0.0, z], atol=ATOL)


def test_rrr_geometric_seed_formula() -> None:
    spec = read_builtin("rrr-geometric")
    l1, l2, l3 = (spec.parameters[k] for k in ("l1", "l2", "l3"))
    for q1, q2, q3 in _random_q(spec, 50):
        r = l2 * math.cos(q2) + l3 * math.cos(q2 + q3)
        x = l1 + l2 * math.sin(q2) + l3 * math.sin(q2 + q3)
        expected = [x, r * math.cos(q1), r * math.sin(q1)]
        np.testing.assert_allclose(_position(spec, (q1, q2, q3)), expected, atol=ATOL)


def test_arm6_dh_is_the_seed_table() -> None:
    spec = read_builtin("arm6-dh")
    l1, l2, l3, l4 = (spec.parameters[k] for k in ("l1", "l2", "l3", "l4"))
    rows = [
        (0, l1, 0, 90),
        (90, 0, l2, 0),
        (-90, 0, 0, -90),
        (-90, l3, 0, -90),
        (0, 0, 0, 90),
        (0, l4, 0, 0),
    ]
    deg = math.pi / 180
    for j, (theta, d, a, alpha) in zip(spec.joints, rows, strict=True):
        assert (j.kind, j.theta, j.d, j.a, j.alpha) == ("R", theta * deg, d, a, alpha * deg)
    # The offsets make q = 0 the upright pose: every link stacked along z0.
    T0 = fk(spec, [0.0] * 6)
    np.testing.assert_allclose(T0[:3, 3], [0.0, 0.0, l1 + l2 + l3 + l4], atol=ATOL)

    def slide_matrix(theta: float, d: float, a: float, alpha: float) -> np.ndarray:
        """The link matrix exactly as the seed's slide (rule 14) writes it."""
        ct, st, ca, sa = math.cos(theta), math.sin(theta), math.cos(alpha), math.sin(alpha)
        return np.array(
            [
                [ct, -ca * st, sa * st, a * ct],
                [st, ca * ct, -sa * ct, a * st],
                [0, sa, ca, d],
                [0, 0, 0, 1],
            ]
        )

    for q in _random_q(spec, 20):
        T = np.eye(4)
        for (theta, d, a, alpha), qi in zip(rows, q, strict=True):
            T = T @ slide_matrix(theta * deg + qi, d, a, alpha * deg)
        np.testing.assert_allclose(fk(spec, q), T, atol=ATOL)


def test_planar_3r_seed_formula() -> None:
    spec = read_builtin("planar-3r")
    l1, l2, l3 = (spec.parameters[k] for k in ("l1", "l2", "l3"))
    for q1, q2, q3 in _random_q(spec, 50):
        x = l1 * math.cos(q1) + l2 * math.cos(q1 + q2) + l3 * math.cos(q1 + q2 + q3)
        y = l1 * math.sin(q1) + l2 * math.sin(q1 + q2) + l3 * math.sin(q1 + q2 + q3)
        T = fk(spec, (q1, q2, q3))
        np.testing.assert_allclose(T[:3, 3], [x, y, 0.0], atol=ATOL)
        phi = q1 + q2 + q3
        np.testing.assert_allclose(T[:2, 0], [math.cos(phi), math.sin(phi)], atol=ATOL)


def test_cylindrical_4dof_reconstruction_formula() -> None:
    spec = read_builtin("cylindrical-4dof")
    l1, l4 = spec.parameters["l1"], spec.parameters["l4"]
    assert [j.kind for j in spec.joints] == ["R", "P", "P", "R"]
    for q1, q2, q3, q4 in _random_q(spec, 50):
        expected = [(q3 + l4) * math.cos(q1), (q3 + l4) * math.sin(q1), l1 + q2]
        T = fk(spec, (q1, q2, q3, q4))
        np.testing.assert_allclose(T[:3, 3], expected, atol=ATOL)
        np.testing.assert_allclose(T[:3, 2], [math.cos(q1), math.sin(q1), 0.0], atol=ATOL)


def test_anthropomorphic_3r_seed_formula() -> None:
    spec = read_builtin("anthropomorphic-3r")
    L1, L2, L3 = (spec.parameters[k] for k in ("L1", "L2", "L3"))
    assert L2 != L3, "the seed's table repeats L2 for a3; the model uses a distinct L3"
    for q1, q2, q3 in _random_q(spec, 50):
        reach = L2 * math.cos(q2) + L3 * math.cos(q2 + q3)
        expected = [
            math.cos(q1) * reach,
            math.sin(q1) * reach,
            L2 * math.sin(q2) + L3 * math.sin(q2 + q3) + L1,
        ]
        np.testing.assert_allclose(_position(spec, (q1, q2, q3)), expected, atol=ATOL)


def test_scara_formula() -> None:
    spec = read_builtin("scara")
    p = spec.parameters
    for q1, q2, q3, q4 in _random_q(spec, 50):
        T = fk(spec, (q1, q2, q3, q4))
        expected = [
            p["a1"] * math.cos(q1) + p["a2"] * math.cos(q1 + q2),
            p["a1"] * math.sin(q1) + p["a2"] * math.sin(q1 + q2),
            p["h"] - q3,
        ]
        np.testing.assert_allclose(T[:3, 3], expected, atol=ATOL)
        np.testing.assert_allclose(T[:3, 2], [0.0, 0.0, -1.0], atol=ATOL)


# --- the makers' URDFs ---------------------------------------------------------------
#
# Joint origins (xyz, rpy) and axes of the ROS URDFs named in each model file's
# comment; the DH models must give the URDF's flange frame for every q.

_URDF: dict[str, Any] = {
    "irb120": (  # ROS-Industrial abb_irb120_support, irb120_3_58_macro.xacro; tool0
        [
            ((0, 0, 0), (0, 0, 0), (0, 0, 1)),
            ((0, 0, 0.29), (0, 0, 0), (0, 1, 0)),
            ((0, 0, 0.27), (0, 0, 0), (0, 1, 0)),
            ((0, 0, 0.07), (0, 0, 0), (1, 0, 0)),
            ((0.302, 0, 0), (0, 0, 0), (0, 1, 0)),
            ((0.072, 0, 0), (0, 0, 0), (1, 0, 0)),
        ],
        ((0, 0, 0), (0, math.pi / 2, 0)),
    ),
    "kr6": (  # ROS-Industrial kuka_experimental, kr6r900sixx_macro.xacro; tool0
        [
            ((0, 0, 0.4), (0, 0, 0), (0, 0, -1)),
            ((0.025, 0, 0), (0, 0, 0), (0, 1, 0)),
            ((0.455, 0, 0), (0, 0, 0), (0, 1, 0)),
            ((0, 0, 0.035), (0, 0, 0), (-1, 0, 0)),
            ((0.42, 0, 0), (0, 0, 0), (0, 1, 0)),
            ((0.08, 0, 0), (0, 0, 0), (-1, 0, 0)),
        ],
        ((0, 0, 0), (0, math.pi / 2, 0)),
    ),
    "iiwa14": (  # iiwa_stack iiwa_description/urdf/iiwa14.xacro; link_7 + 0.045 m
        [
            ((0, 0, 0.1575), (0, 0, 0), (0, 0, 1)),
            ((0, 0, 0.2025), (math.pi / 2, 0, math.pi), (0, 0, 1)),
            ((0, 0.2045, 0), (math.pi / 2, 0, math.pi), (0, 0, 1)),
            ((0, 0, 0.2155), (math.pi / 2, 0, 0), (0, 0, 1)),
            ((0, 0.1845, 0), (-math.pi / 2, math.pi, 0), (0, 0, 1)),
            ((0, 0, 0.2155), (math.pi / 2, 0, 0), (0, 0, 1)),
            ((0, 0.081, 0), (-math.pi / 2, math.pi, 0), (0, 0, 1)),
        ],
        ((0, 0, 0.045), (0, 0, 0)),
    ),
}


@pytest.mark.parametrize("name", sorted(_URDF))
def test_industrial_models_match_the_urdf_joint_by_joint(name: str) -> None:
    spec = read_builtin(name)
    joints, (tail_xyz, tail_rpy) = _URDF[name]
    lo = np.array([j.qlim[0] for j in spec.joints if j.qlim is not None])
    hi = np.array([j.qlim[1] for j in spec.joints if j.qlim is not None])
    rng = np.random.default_rng(RNG_SEED)
    for q in rng.uniform(lo, hi, size=(30, spec.dof)):
        T = np.eye(4)
        for (xyz, rpy, axis), qi in zip(joints, q, strict=True):
            T = T @ _trans(*xyz) @ _rpy(*rpy) @ _axis_angle(axis, qi)
        T = T @ _trans(*tail_xyz) @ _rpy(*tail_rpy)
        np.testing.assert_allclose(fk(spec, q), T, atol=ATOL)


def test_irb120_and_kr6_limits_are_the_datasheet_values() -> None:
    deg = math.pi / 180
    irb = [(-165, 165), (-110, 110), (-110, 70), (-160, 160), (-120, 120), (-400, 400)]
    kr6 = [(-170, 170), (-190, 45), (-120, 156), (-185, 185), (-120, 120), (-350, 350)]
    iiwa = [(-170, 170), (-120, 120)] * 3 + [(-175, 175)]
    for name, limits in (("irb120", irb), ("kr6", kr6), ("iiwa14", iiwa)):
        got = [j.qlim for j in read_builtin(name).joints]
        assert got == [(lo * deg, hi * deg) for lo, hi in limits], name


def test_ur10_is_example_robot_data_s_ur10_flange() -> None:
    # Issue 35, item 9: km.load("ur10") suggested "irb120". The built-in is UR's published
    # table; example-robot-data 6.0.0's URDF (tests/data/urdf, PROVENANCE.md) is the
    # independent reference: its base_link is the DH base turned by 180° about z, its tool0
    # a fixed frame on DH frame 6. Its rpy are printed to 10 digits (1.570796325): 1e-10.
    import warnings

    dh = km.load("ur10")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", km.KinematicaWarning)  # the tool0 choice, said
        urdf = km.load(DATA / "urdf" / "ur10_robot.urdf", tip="tool0")
    B = np.diag([-1.0, -1.0, 1.0, 1.0])  # Rz(180°)
    E = np.linalg.inv(B @ dh.fk(np.zeros(6))) @ urdf.fk(np.zeros(6))
    q = np.random.default_rng(RNG_SEED).uniform(-3, 3, (50, 6))
    assert np.abs(B @ dh.fk(q) @ E - urdf.fk(q)).max() < 1e-10
    assert km.classify(dh).kind == km.classify(urdf).kind
