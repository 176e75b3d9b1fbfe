"""The symbolic DH table: parameters stay symbols, exact angles, units, sources, errors."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import kinematica as km

sp = pytest.importorskip("sympy")
from kinematica import symbolic  # noqa: E402
from kinematica.symbolic import model as sm  # noqa: E402


def test_builtin_keeps_parameters_and_exact_degrees() -> None:
    m = symbolic.symbolic_robot("arm6-dh")
    q2, l1, l2 = (sp.Symbol(n) for n in ("q2", "l1", "l2"))
    assert m.rows[0].d == l1 and m.rows[0].alpha == sp.pi / 2
    assert m.rows[1].theta == q2 + sp.pi / 2  # "q2 + 90" -> pi/2, never 1.5708
    assert m.rows[1].a == l2
    assert m.rows[2].alpha == -sp.pi / 2
    assert {s.name for s in m.values} == {"l1", "l2", "l3", "l4"}
    assert m.values[l1] == pytest.approx(0.5)
    assert m.q == tuple(sp.Symbol(f"q{i}") for i in range(1, 7))


def test_robot_keeps_numbers_and_snaps_angles() -> None:
    robot = km.Robot.from_dh(
        [
            km.Revolute(d=0.25, a=1.0, alpha=math.radians(90), offset=math.radians(-15)),
            km.Prismatic(theta=math.pi, alpha=0.3, offset=0.1),
        ],
        convention="standard",
    )
    m = symbolic.symbolic_robot(robot)
    q1, q2 = m.q
    assert m.rows[0].alpha == sp.pi / 2
    assert m.rows[0].theta == q1 - sp.pi / 12
    assert m.rows[0].a == 1 and isinstance(m.rows[0].a, sp.Integer)
    assert m.rows[0].d == sp.Float(0.25)
    assert m.rows[1].theta == sp.pi and m.rows[1].d == q2 + sp.Float(0.1)
    assert m.rows[1].alpha == sp.Float(0.3)  # not a multiple of pi/12: a number
    assert m.values == {}


def test_angle_snap_tolerance_both_sides() -> None:
    tol = sm.ANGLE_SNAP_TOL
    assert sm.exact_angle(math.pi / 2 + 0.5 * tol) == sp.pi / 2
    assert sm.exact_angle(math.pi / 2 + 50 * tol) != sp.pi / 2
    assert sm.exact_angle(1e-10) == sp.Float(1e-10)  # an offset of 1e-10 stays
    assert sm.exact_angle(-5 * math.pi / 12) == -5 * sp.pi / 12


def test_entry_snap_tolerance_both_sides() -> None:
    tol = sm.ENTRY_SNAP_TOL
    T = np.eye(4)
    c = math.sqrt(2) / 2
    T[:2, :2] = [[c, -c], [c, c]]
    T[0, 0] += 0.5 * tol
    M = sm.exact_matrix(T)
    assert M[0, 0] == sp.sqrt(2) / 2 and M[1, 0] == sp.sqrt(2) / 2
    T[0, 0] += 50 * tol
    assert sm.exact_matrix(T)[0, 0] != sp.sqrt(2) / 2


def test_base_rpy_is_exact() -> None:
    # planar-pr's base is rpy (-90, 0, -90) degrees: every entry exactly 0 or ±1.
    base = symbolic.symbolic_robot("planar-pr").base
    assert all(e in (0, 1, -1) for e in base)
    np.testing.assert_allclose(np.array(base, dtype=float), km.load("planar-pr").base, atol=1e-15)


def test_file_in_millimetres_and_parameter_expressions(tmp_path: Path) -> None:
    path = tmp_path / "arm.json"
    path.write_text(
        '{"convention": "standard", "units": {"angle": "deg", "length": "mm"},'
        ' "parameters": {"L": 400, "half": "L/2"},'
        ' "joints": [{"theta": "q1", "d": 290, "a": "0.5*L", "alpha": 90},'
        '            {"theta": 0, "d": "q2 + half", "a": 0, "alpha": 0},'
        '            {"theta": "q3 - 22.5", "d": 0, "a": "L", "alpha": 0}]}'
    )
    m = symbolic.symbolic_robot(path)
    L, half, q2, q3 = (sp.Symbol(n) for n in ("L", "half", "q2", "q3"))
    assert m.rows[0].d == sp.Float(0.29)  # 290 mm, in metres
    assert m.rows[0].a == L / 2  # 0.5*L keeps its symbol; L means metres
    assert m.rows[1].d == q2 + half
    assert m.rows[2].theta == q3 - sp.pi / 8
    assert m.values[L] == pytest.approx(0.4) and m.values[half] == pytest.approx(0.2)
    robot = km.load(path)
    q = np.array([0.3, 0.05, -0.7])
    np.testing.assert_allclose(symbolic.lambdify(path)(q), robot.fk(q), atol=1e-12)


def test_parameter_in_angles_and_lengths_uses_its_number(tmp_path: Path) -> None:
    # A parameter used as an angle (deg) and as a length (m) has no single SI value.
    path = tmp_path / "odd.yaml"
    path.write_text(
        "convention: modified\nparameters: {k: 30}\n"
        "joints:\n  - {theta: q1, d: 0, a: k, alpha: k}\n  - {theta: q2, d: 0, a: 1, alpha: 0}\n"
    )
    m = symbolic.symbolic_robot(path)
    assert m.rows[0].alpha == sp.pi / 6 and m.rows[0].a == 30
    q = np.array([0.4, -1.1])
    np.testing.assert_allclose(symbolic.lambdify(path)(q), km.load(path).fk(q), atol=1e-12)


def test_bad_sources() -> None:
    with pytest.raises(km.UnknownRobotError, match="no such robot file"):
        symbolic.symbolic_robot("missing.yaml")
    with pytest.raises(km.UnknownRobotError, match="did you mean 'puma560'"):
        symbolic.position("puma56")
    with pytest.raises(symbolic.SymbolicError, match="expected a Robot"):
        symbolic.fk(42)  # type: ignore[arg-type]


def test_bad_file_says_where(tmp_path: Path) -> None:
    path = tmp_path / "bad.yaml"
    path.write_text("convention: standard\njoints:\n  - {theta: q1, d: 0, a: 0, alfa: 0}\n")
    with pytest.raises(km.RobotFileError, match="joint 1"):
        symbolic.report(path)


def test_near_exact_twist_snaps_in_report_but_not_in_lambdify() -> None:
    # alpha = pi/2 + 5e-13 with a 2 m lever: shown as pi/2, compiled as it is.
    robot = km.Robot.from_dh(
        [km.Revolute(alpha=math.pi / 2 + 5e-13), km.Revolute(d=2.0, a=2.0)],
        base=np.array([[1, 0, 0, 0], [0, 0, -1, 0], [0, 1 + 4e-13, 0, 0], [0, 0, 0, 1.0]]),
        convention="standard",
    )
    assert symbolic.symbolic_robot(robot).rows[0].alpha == sp.pi / 2
    q = np.array([[0.3, 1.2], [-2.0, 0.4]])
    exact = robot.fk(q)
    np.testing.assert_allclose(symbolic.lambdify(robot)(q), exact, rtol=0, atol=1e-14)
    snapped = sp.lambdify(symbolic.symbolic_robot(robot).q, symbolic.fk(robot), "numpy")
    assert np.abs(snapped(*q[0]) - exact[0]).max() > 1e-13  # what snapping alone would give


def test_expression_fold_rebuilds_the_tree() -> None:
    expr = km.io.parse_expression("-(q2 + 90) * 2 / l1 - .5")
    text = expr.fold(
        number=lambda v: f"{v:g}",
        name=str,
        unary=lambda op, x: f"({op}{x})",
        binary=lambda op, a, b: f"({a} {op} {b})",
    )
    assert text == "((((-(q2 + 90)) * 2) / l1) - 0.5)"
