"""Step-by-step closed-form IK: the derived formulas give exactly robot.ik's solutions."""

from __future__ import annotations

import dataclasses
import itertools

import numpy as np
import pytest

import kinematica as km

sp = pytest.importorskip("sympy")
from kinematica import symbolic  # noqa: E402
from kinematica.symbolic import inverse, trig  # noqa: E402

TEXTBOOK = {
    "anthropomorphic-3r": 4,
    "rrr-geometric": 4,
    "planar-3r": 2,
    "planar-pr": 2,
    "planar-prr": 2,
    "scara": 2,
    "arm6-dh": 8,
    "puma560": 8,
    "irb120": 8,
    "kr6": 8,
}


def solutions(
    d: inverse.InverseDerivation, model: symbolic.SymbolicRobot, T: np.ndarray
) -> np.ndarray:
    """Every finite branch of the derived formulas at the world pose T, evaluated here."""
    p, R = inverse.target_symbols()
    env = {s: float(v) for s, v in model.values.items()}
    env.update({s: float(T[i, 3]) for i, s in enumerate(p)})
    env.update({R[i, j]: float(T[i, j]) for i in range(3) for j in range(3)})
    out = []
    for choice in itertools.product(*(range(len(a.branches)) for a in d.plan)):
        vals = dict(env)
        for a, c in zip(d.plan, choice, strict=True):
            e = a.branches[c]
            args = sorted(e.free_symbols, key=str)
            with np.errstate(all="ignore"):  # acos(1.2) is NaN: no such branch
                vals[a.symbol] = float(sp.lambdify(args, e, "numpy")(*(vals[s] for s in args)))
        q = np.array([vals[s] for s in model.q])
        if np.all(np.isfinite(q)):
            out.append(q)
    return np.array(out)


def same_sets(a: np.ndarray, b: np.ndarray, prismatic: np.ndarray) -> bool:
    def key(q: np.ndarray) -> tuple[float, ...]:
        w = np.where(prismatic, q, np.angle(np.exp(1j * q)))
        return tuple(np.round(w, 6))

    return sorted(map(key, a)) == sorted(map(key, b))


def check_against_ik(source: object, robot: km.Robot, pose: bool, seed: int = 3) -> int:
    model = symbolic.symbolic_robot(source)  # type: ignore[arg-type]
    d = inverse.derive_inverse(model)
    assert d is not None
    rng = np.random.default_rng(seed)
    for _ in range(3):
        q = rng.uniform(-np.pi, np.pi, robot.dof)
        q[robot.is_prismatic] = rng.uniform(0.05, 0.4, int(robot.is_prismatic.sum()))
        T = robot.fk(q)
        ours = solutions(d, model, T)
        target = T if pose else T[:3, 3]
        ref = robot.ik(target, respect_limits=False).solutions
        assert len(ours) == len(ref)
        assert same_sets(ours, ref, robot.is_prismatic)
    return d.solutions


@pytest.mark.parametrize("name", sorted(TEXTBOOK))
def test_derived_solutions_are_robot_ik_solutions(name: str) -> None:
    robot = km.load(name)
    pose = name not in ("anthropomorphic-3r", "rrr-geometric", "planar-pr")
    assert check_against_ik(name, robot, pose) == TEXTBOOK[name]


@pytest.mark.parametrize("name", ["ur5", "panda", "stanford", "cylindrical-4dof"])
def test_no_textbook_class_no_derivation(name: str) -> None:
    assert inverse.derive_inverse(symbolic.symbolic_robot(name)) is None


def test_report_without_textbook_derivation_says_so() -> None:
    text = symbolic.report("ur5", lang="en")
    assert "no textbook closed-form derivation" in text and "three parallel axes" in text


def test_report_of_a_spherical_shoulder_says_its_method() -> None:
    # the Panda's joints 1-6 (q7 locked at 0: the flange's frame 7 is its tool)
    panda = km.load("panda")
    arm = km.Robot.from_dh(panda.links[:6], convention="modified", name="panda, q7 = 0")
    text = symbolic.report(arm, lang="en")
    assert "(6R, spherical shoulder: T⁻¹, the joints in reverse order" in text
    assert "(method analytic (spherical-shoulder-6R))" in text
    assert "no textbook closed-form derivation" not in text


def test_class_not_example_modified_base_tool_offsets() -> None:
    # The same classes written differently: Craig's convention, a base, a tool, offsets.
    arm = km.load("anthropomorphic-3r").to_convention("modified")
    base = np.eye(4)
    base[:3, :3] = [[0, -1, 0], [1, 0, 0], [0, 0, 1]]
    base[:3, 3] = [0.1, -0.2, 0.3]
    arm = arm.with_base(base)
    assert km.classify(arm).kind == "anthropomorphic-3R"
    check_against_ik(arm, arm, pose=False)
    elbow = km.Robot.from_dh(
        [
            km.Revolute(d=0.4, a=0.1, alpha=-np.pi / 2, offset=0.3),
            km.Revolute(d=0.12, a=0.35, offset=-np.pi / 2),
            km.Revolute(a=0.3, alpha=np.pi / 2, offset=0.2),
        ],
        tool=np.array([[1, 0, 0, 0.05], [0, 1, 0, 0.02], [0, 0, 1, 0.1], [0, 0, 0, 1.0]]),
        convention="standard",
    )
    assert km.classify(elbow).kind == "elbow-3R"
    check_against_ik(elbow, elbow, pose=False)
    puma = km.load("puma560").to_convention("modified")
    tool = np.eye(4)
    tool[:3, 3] = [0.0, 0.0, 0.12]
    puma = puma.with_tool(tool)
    assert check_against_ik(puma, puma, pose=True) == 8


def test_check_tolerance_both_sides() -> None:
    # A formula off by far less than CHECK_TOL still passes; off by far more, it fails.
    model = symbolic.symbolic_robot("planar-3r")
    ctx = inverse._context(model)
    inverse._build(ctx, "planar-3R")
    assert inverse._check(ctx, ctx.plan, pose=True)
    last = ctx.plan[-1]
    for delta, ok in ((inverse.CHECK_TOL * 1e-2, True), (inverse.CHECK_TOL * 1e2, False)):
        bent = [*ctx.plan[:-1], dataclasses.replace(last, branches=(last.branches[0] + delta,))]
        assert inverse._check(ctx, bent, pose=True) is ok


def test_coefficient_tolerance_both_sides() -> None:
    q = sp.Symbol("q")
    tiny = trig.COEFF_TOL * 1e-2
    assert trig.linear_cs(2 * sp.cos(q) + tiny * sp.cos(q) ** 2 * sp.sin(q), q) is not None
    big = trig.COEFF_TOL * 1e2
    assert trig.linear_cs(2 * sp.cos(q) + big * sp.cos(q) ** 2 * sp.sin(q), q) is None


def test_linear_cs_and_single_solution_forms() -> None:
    q, a, b, v = sp.symbols("q a b v")
    eq = trig.linear_cs(a * sp.cos(q + sp.pi / 2) + b + sp.sin(q) ** 2 + sp.cos(q) ** 2, q)
    assert eq is not None and eq.A == 0 and -a == eq.B and b + 1 == eq.K
    s = trig.solve_single(trig.Linear(sp.Integer(0), a, sp.Integer(0)), v)
    assert s == [sp.asin(v / a), sp.pi - sp.asin(v / a)]  # seed 000: q2 = asin(y/l2), pi - asin
    assert trig.linear_cs(sp.cos(q) * sp.sin(q), q) is None


def test_report_ik_vocabulary_es() -> None:
    text = symbolic.report("anthropomorphic-3r", lang="es")
    assert "codo arriba / codo abajo" in text
    assert "dos soluciones para $q_{1}$" in text
    wrist = symbolic.report("arm6-dh", lang="es")
    assert "muñeca esférica" in wrist and "Desacoplo cinemático" in wrist
    assert "{}^{3}R_{6}" in wrist and "Singularidad de la muñeca" in wrist


def test_report_of_a_general_6r_arm_names_the_elimination() -> None:
    # right-angle twists keep sympy quick; the offsets fit no special family
    rows = [
        km.Revolute(d=d, a=a, alpha=alpha)
        for d, a, alpha in [
            (0.3, 0.1, np.pi / 2), (0.05, 0.4, 0.0), (0.1, 0.05, np.pi / 2),
            (0.35, 0.02, -np.pi / 2), (0.04, 0.03, np.pi / 2), (0.1, 0.0, 0.0),
        ]
    ]  # fmt: skip
    robot = km.Robot.from_dh(rows, name="general", convention="standard")
    assert robot.ik(robot.fk(np.full(6, 0.3))).method == "analytic:general-6R"
    text = symbolic.report(robot, lang="en")
    assert "Raghavan-Roth elimination to a 12x12 quadratic eigenproblem" in text
    assert "analytic (general-6R)" in text and "16x16" in text
