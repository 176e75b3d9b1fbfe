"""Symbolic forward kinematics against the seeds' hand-derived formulas and robot.fk."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import kinematica as km

sp = pytest.importorskip("sympy")
from support.helpers import assert_transform_close, random_q, robot_specs  # noqa: E402

from kinematica import symbolic  # noqa: E402

#: lambdify must equal robot.fk to this (the issue's figure).
LAMBDIFY_TOL = 1e-12


def sym(*names: str) -> list[sp.Symbol]:
    # Plain symbols, as anyone would write them: the derivation's symbols are too.
    return list(sp.symbols(names))


def is_zero(expr: sp.Expr) -> bool:
    return sp.simplify(expr) == 0


# ----------------------------------------------------------- seeds' formulas
def test_planar_pr_seed_000() -> None:
    # Seed 000, 2-DOF prismatic-rotational: x = q1 + l1 + l2 cos q2, y = l2 sin q2.
    q1, q2, l1, l2 = sym("q1", "q2", "l1", "l2")
    x, y, z = symbolic.position("planar-pr")
    assert is_zero(x - (q1 + l1 + l2 * sp.cos(q2)))
    assert is_zero(y - l2 * sp.sin(q2))
    assert z == 0


def test_anthropomorphic_3r_seed_002() -> None:
    # Seed 002: px = c1 (a2 c2 + a3 c23), py = s1 (...), pz = a2 s2 + a3 s23 + d1.
    q1, q2, q3, L1, L2, L3 = sym("q1", "q2", "q3", "L1", "L2", "L3")
    reach = L2 * sp.cos(q2) + L3 * sp.cos(q2 + q3)
    px, py, pz = symbolic.position("anthropomorphic-3r")
    assert is_zero(px - sp.cos(q1) * reach)
    assert is_zero(py - sp.sin(q1) * reach)
    assert is_zero(pz - (L2 * sp.sin(q2) + L3 * sp.sin(q2 + q3) + L1))
    # ... and in the textbook form itself, not just equal to it.
    assert str(symbolic.short(px)) == "c1*(L2*c2 + L3*c23)"


def test_rrr_geometric_seed_000() -> None:
    # Seed 000, geometric example 2: x = l1 + l2 s2 + l3 s23, y = r c1, z = r s1.
    q1, q2, q3, l1, l2, l3 = sym("q1", "q2", "q3", "l1", "l2", "l3")
    r = l2 * sp.cos(q2) + l3 * sp.cos(q2 + q3)
    x, y, z = symbolic.position("rrr-geometric")
    assert is_zero(x - (l1 + l2 * sp.sin(q2) + l3 * sp.sin(q2 + q3)))
    assert is_zero(y - r * sp.cos(q1))
    assert is_zero(z - r * sp.sin(q1))


def test_planar_3r_seed_001() -> None:
    # Seed 001, DH example 1 (with sines in y: the seed's typo corrected).
    q1, q2, q3, l1, l2, l3 = sym("q1", "q2", "q3", "l1", "l2", "l3")
    x, y, z = symbolic.position("planar-3r")
    assert is_zero(x - (l1 * sp.cos(q1) + l2 * sp.cos(q1 + q2) + l3 * sp.cos(q1 + q2 + q3)))
    assert is_zero(y - (l1 * sp.sin(q1) + l2 * sp.sin(q1 + q2) + l3 * sp.sin(q1 + q2 + q3)))
    assert z == 0
    assert str(symbolic.short(x)) == "c1*l1 + c12*l2 + c123*l3"


def test_planar_prr_seed_000() -> None:
    # Seed 000, geometric example 1: z = q1 + l1 + l3 c2 + l4 c23, x = l2 + l3 s2 + l4 s23.
    q1, q2, q3, l1, l2, l3, l4 = sym("q1", "q2", "q3", "l1", "l2", "l3", "l4")
    x, y, z = symbolic.position("planar-prr")
    assert is_zero(z - (q1 + l1 + l3 * sp.cos(q2) + l4 * sp.cos(q2 + q3)))
    assert is_zero(x - (l2 + l3 * sp.sin(q2) + l4 * sp.sin(q2 + q3)))
    assert y == 0


def test_arm6_dh_at_zero_seed_000() -> None:
    # By hand from seed 000's table at q = 0: z1 = -y0, then joint 2's +90° turns
    # x2 up, joints 3 and 4 (-90°, -90° twists) bring z3 = z5 = +z0: the arm
    # stands straight up, p = (0, 0, l1 + l2 + l3 + l4), x6 = -y0, y6 = +x0.
    l1, l2, l3, l4 = sym("l1", "l2", "l3", "l4")
    T = symbolic.fk("arm6-dh").xreplace({q: 0 for q in sym(*(f"q{i}" for i in range(1, 7)))})
    expected = sp.Matrix([[0, 1, 0, 0], [-1, 0, 0, 0], [0, 0, 1, l1 + l2 + l3 + l4], [0, 0, 0, 1]])
    assert sp.simplify(T - expected) == sp.zeros(4, 4)


# ------------------------------------------------------------- link matrices
def test_link_factors_standard_order_and_product() -> None:
    # Seed 003: Rot(z, θ)·Tras(z, d)·Tras(x, a)·Rot(x, α), product = seed 000's matrix.
    q2, l2 = sym("q2", "l2")
    Rz, Tz, Tx, Rx = symbolic.link_factors("arm6-dh", 2)
    assert Rz[:3, :3] == sp.Matrix(
        [[-sp.sin(q2), -sp.cos(q2), 0], [sp.cos(q2), -sp.sin(q2), 0], [0, 0, 1]]
    )
    assert Tz == sp.eye(4) and Rx == sp.eye(4)
    assert Tx[0, 3] == l2
    theta, alpha, d, a = q2 + sp.pi / 2, 0, 0, l2
    seed = sp.Matrix(
        [
            [
                sp.cos(theta),
                -sp.cos(alpha) * sp.sin(theta),
                sp.sin(alpha) * sp.sin(theta),
                a * sp.cos(theta),
            ],
            [
                sp.sin(theta),
                sp.cos(alpha) * sp.cos(theta),
                -sp.sin(alpha) * sp.cos(theta),
                a * sp.sin(theta),
            ],
            [0, sp.sin(alpha), sp.cos(alpha), d],
            [0, 0, 0, 1],
        ]
    )
    assert sp.simplify(symbolic.link_matrices("arm6-dh")[1] - seed) == sp.zeros(4, 4)


def test_link_factors_modified_order() -> None:
    # Craig: Rot(x, α(i-1))·Tras(x, a(i-1))·Rot(z, θi)·Tras(z, di).
    robot = km.Robot.from_dh(
        [km.Revolute(d=0.3, a=0.2, alpha=np.pi / 2), km.Revolute(a=0.5)], convention="modified"
    )
    Rx, Tx, Rz, Tz = symbolic.link_factors(robot, 1)
    q1 = sym("q1")[0]
    assert Rx[1, 2] == -1  # alpha0 = 90°, exact
    assert Tx[0, 3] == sp.Float(0.2)
    assert Rz[0, 0] == sp.cos(q1)
    assert Tz[2, 3] == sp.Float(0.3)
    assert [f.kind + f.axis for f in symbolic.factors(robot, 1)] == [
        "Rotx",
        "Trasx",
        "Rotz",
        "Trasz",
    ]


@pytest.mark.parametrize("row", [0, 4, -1, 1.0, True])
def test_link_factors_bad_row(row: object) -> None:
    with pytest.raises(symbolic.SymbolicError, match="rows 1 to 3"):
        symbolic.link_factors("planar-3r", row)  # type: ignore[arg-type]


def test_frames_layout_matches_robot_fk_all_frames() -> None:
    robot = km.load("planar-pr")
    f = symbolic.lambdify("planar-pr", all_frames=True)
    q = np.array([0.2, 0.7])
    assert_transform_close(f(q), robot.fk(q, all_frames=True), atol=LAMBDIFY_TOL)
    assert len(symbolic.frames("planar-pr")) == robot.dof + 1


# ------------------------------------------------------------------ lambdify
@pytest.mark.parametrize("name", km.builtin_names())
def test_lambdify_equals_fk_for_every_builtin(name: str) -> None:
    robot = km.load(name)
    f = symbolic.lambdify(name)
    rng = np.random.default_rng(7)
    for batch in [(), (1,), (3, 2)]:
        q = rng.uniform(-np.pi, np.pi, (*batch, robot.dof))
        q[..., robot.is_prismatic] = rng.uniform(0.0, 0.5, q[..., robot.is_prismatic].shape)
        out = f(q)
        assert out.shape == (*batch, 4, 4)
        assert_transform_close(out, robot.fk(q), atol=LAMBDIFY_TOL)


def test_lambdify_from_robot_keeps_numbers() -> None:
    robot = km.load("puma560")
    assert symbolic.fk(robot).free_symbols == set(sym(*(f"q{i}" for i in range(1, 7))))
    q = np.random.default_rng(1).uniform(-3, 3, (5, 6))
    assert_transform_close(symbolic.lambdify(robot)(q), robot.fk(q), atol=LAMBDIFY_TOL)


def test_lambdify_parameter_values_and_errors() -> None:
    f = symbolic.lambdify("planar-pr", values={"l2": 1.0})
    T = f([0.0, 0.0])
    assert T[0, 3] == pytest.approx(0.5 + 1.0)  # x = q1 + l1 + l2 cos q2
    with pytest.raises(symbolic.SymbolicError, match="unknown parameter 'l9'"):
        symbolic.lambdify("planar-pr", values={"l9": 1.0})
    with pytest.raises(km.DimensionError, match="2 joint values"):
        symbolic.lambdify("planar-pr")(np.zeros(3))


@settings(max_examples=15, deadline=None, database=None)
@given(spec=robot_specs(max_dof=7), seed=st.integers(0, 2**16))
def test_lambdify_random_robots(spec, seed: int) -> None:  # type: ignore[no-untyped-def]
    # Both conventions, prismatic joints, offsets, base, tool, degenerate values;
    # the reference is the slides' product of four elementary matrices per row.
    robot = spec.build()
    q = random_q(spec, np.random.default_rng(seed), (3,))
    ref = np.array([spec.ref_fk(x) for x in q])
    assert_transform_close(symbolic.lambdify(robot, simplify=False)(q), ref, atol=LAMBDIFY_TOL)


@settings(max_examples=8, deadline=None, database=None)
@given(spec=robot_specs(max_dof=3), seed=st.integers(0, 2**16))
def test_simplified_fk_random_robots(spec, seed: int) -> None:  # type: ignore[no-untyped-def]
    # The textbook form (sums folded, terms collected) is the same function.
    robot = spec.build()
    q = random_q(spec, np.random.default_rng(seed), (2,))
    ref = np.array([spec.ref_frames(x) for x in q])
    assert_transform_close(symbolic.lambdify(robot, all_frames=True)(q), ref, atol=LAMBDIFY_TOL)


# ------------------------------------------------------------- short notation
def test_short_notation() -> None:
    q1, q2, q3, q4, a = sym("q1", "q2", "q3", "q4", "a")
    expr = sp.cos(q1) * (a * sp.sin(q2 + q3)) + sp.cos(q2 + q3 + q4) + sp.cos(q2 - q3)
    out = symbolic.short(expr)
    c1, s23, c234 = sym("c1", "s23", "c234")
    assert out == c1 * a * s23 + c234 + sp.cos(q2 - q3)
    assert symbolic.short(sp.Matrix([[sp.sin(q1)]])) == sp.Matrix([[sym("s1")[0]]])
    assert symbolic.short(sp.cos(q1 + sp.pi / 7)) == sp.cos(q1 + sp.pi / 7)


# ------------------------------------------------------------------ lazy import
def test_import_and_fk_do_not_import_sympy(tmp_path: Path) -> None:
    code = (
        "import sys\n"
        "import kinematica\n"
        "from kinematica.cli.main import main\n"
        "assert main(['fk', 'puma560', '--q', '0', '10', '20', '0', '0', '0']) == 0\n"
        "assert 'sympy' not in sys.modules, 'sympy was imported'\n"
    )
    proc = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path, check=False
    )
    assert proc.returncode == 0, proc.stderr
