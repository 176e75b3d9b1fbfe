"""The symbolic geometric Jacobian against the numeric one (lambdify) and by hand."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from support.helpers import PROPERTY, RobotSpec, random_q, robot_specs, seeds

import kinematica as km
from kinematica import symbolic
from kinematica.symbolic.model import numeric_model, symbolic_robot


@settings(PROPERTY, max_examples=6)
@given(spec=robot_specs(max_dof=4), seed=seeds)
def test_symbolic_jacobian_equals_the_numeric_one(spec: RobotSpec, seed: int) -> None:
    robot = spec.build()
    model = numeric_model(robot)
    J = symbolic.jacobian(model, simplify=False)
    f = sp.lambdify(model.q, J, modules="numpy")
    q = random_q(spec, np.random.default_rng(seed))
    got = np.array(f(*q), dtype=float)
    want = robot.jacobian(q)
    assert np.allclose(got, want, atol=1e-12 * (1.0 + np.abs(want).max()))


def test_anthropomorphic_arm_by_hand() -> None:
    """Seed 002: p = (c1 (L2 c2 + L3 c23), s1 (L2 c2 + L3 c23), L1 + L2 s2 + L3 s23)."""
    J = symbolic.jacobian("anthropomorphic-3r")
    q1, q2, q3 = sp.symbols("q1 q2 q3", real=True)
    L1, L2, L3 = sp.symbols("L1 L2 L3", real=True)
    r = L2 * sp.cos(q2) + L3 * sp.cos(q2 + q3)
    p = sp.Matrix([sp.cos(q1) * r, sp.sin(q1) * r, L1 + L2 * sp.sin(q2) + L3 * sp.sin(q2 + q3)])
    names = {s.name: s for s in J.free_symbols}
    J = J.xreplace({names[k]: v for k, v in {"q1": q1, "q2": q2, "q3": q3}.items() if k in names})
    J = J.xreplace({names[k]: v for k, v in {"L1": L1, "L2": L2, "L3": L3}.items() if k in names})
    assert sp.simplify(J[:3, :] - p.jacobian([q1, q2, q3])) == sp.zeros(3, 3)
    # the rotation rows: z0 = (0, 0, 1), z1 = z2 = (s1, -c1, 0)
    assert sp.simplify(J[3:, 0] - sp.Matrix([0, 0, 1])) == sp.zeros(3, 1)
    assert sp.simplify(J[3:, 1] - sp.Matrix([sp.sin(q1), -sp.cos(q1), 0])) == sp.zeros(3, 1)


def test_puma_jacobian_in_the_modified_convention() -> None:
    puma = km.load("puma560").to_convention("modified")
    J = symbolic.jacobian(numeric_model(puma), simplify=False)
    f = sp.lambdify(numeric_model(puma).q, J, modules="numpy")
    q = np.radians([10, -20, 30, 40, 50, 60])
    assert np.allclose(np.array(f(*q), dtype=float), puma.jacobian(q), atol=1e-12)


@pytest.mark.parametrize("name", ["anthropomorphic-3r", "stanford", "scara"])
def test_textbook_form_equals_the_numeric_jacobian(name: str) -> None:
    model = symbolic_robot(name)
    J = symbolic.jacobian(model).xreplace({s: sp.Float(v) for s, v in model.values.items()})
    f = sp.lambdify(model.q, J, modules="numpy")
    for q in model.robot.random_q(3, seed=2):
        got = np.array(f(*q), dtype=float)
        assert np.allclose(got, model.robot.jacobian(q), atol=1e-12)


def test_report_has_the_jacobian_in_both_languages() -> None:
    en = symbolic.report("anthropomorphic-3r", format="markdown", lang="en")
    es = symbolic.report("anthropomorphic-3r", format="markdown", lang="es")
    assert "## Geometric Jacobian" in en and "## Jacobiano geométrico" in es
    assert "J_{3} &=" in en and "L_{3} c_{23}" in en
