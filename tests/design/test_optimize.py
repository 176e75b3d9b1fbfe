"""Design runs on problems whose optimum is derived by hand; objectives; bad input."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import kinematica as km
from kinematica.design import (
    DesignTemplate,
    Objective,
    Task,
    evaluate_design,
    load_template,
    optimize,
)
from kinematica.errors import KinematicaError, RobotFileError

SUM_ONE = """
name: planar 2R, l1 + l2 = 1
convention: standard
parameters:
  l1: {value: 0.3, min: 0.1, max: 0.9}
  l2: 1 - l1
joints:
  - {theta: q1, d: 0, a: l1, alpha: 0}
  - {theta: q2, d: 0, a: l2, alpha: 0}
"""

FREE = """
name: planar 2R, both lengths free
convention: modified
parameters:
  l1: {value: 0.5, min: 0.1, max: 1.0}
  l2: {value: 0.5, min: 0.1, max: 1.0}
joints:
  - {theta: q1, d: 0, a: 0, alpha: 0}
  - {theta: q2, d: 0, a: l1, alpha: 0}
tool: {xyz: [l2, 0, 0]}
"""


@pytest.fixture
def sum_one(tmp_path: Path) -> Path:
    path = tmp_path / "sum_one.yaml"
    path.write_text(SUM_ONE)
    return path


@pytest.fixture
def free(tmp_path: Path) -> Path:
    path = tmp_path / "free.yaml"
    path.write_text(FREE)
    return path


def test_ring_worst_manipulability_is_best_with_equal_links(sum_one: Path) -> None:
    # By hand: on a ring of radius r every target has cos q2 = (r² - l1² - l2²) / (2 l1 l2)
    # and w = l1 l2 |sin q2|, so with p = l1 l2 and l1 + l2 = 1 (l1² + l2² = 1 - 2p):
    #   w² = p² - (r² - 1 + 2p)² / 4 = p² - (p - 0.32)² = 0.64 p - 0.1024   (r = 0.6),
    # increasing in p = l1 (1 - l1): the optimum is l1 = l2 = 1/2, w = sqrt(0.0576) = 0.24.
    res = optimize(sum_one, Task.ring(0.6, 24), "min_manipulability", budget=150, seed=3)
    assert res.feasible
    assert abs(res.best_params["l1"] - 0.5) < 0.005  # to 1 %
    l1 = res.best_params["l1"]
    assert math.isclose(res.best_value, math.sqrt(0.64 * l1 * (1 - l1) - 0.1024), rel_tol=1e-9)
    assert math.isclose(res.best_value, 0.24, rel_tol=1e-4)
    np.testing.assert_allclose([lk.a for lk in res.best_robot.links], [l1, 1 - l1], rtol=1e-15)
    # the template's own value (l1 = 0.3) is the first candidate and is worse
    assert res.history[0].params == {"l1": 0.3}
    assert math.isclose(
        res.history[0].measures["min_manipulability"], math.sqrt(0.64 * 0.21 - 0.1024), rel_tol=1e-9
    )
    assert len(res.history) <= 150 and res.evaluated <= len(res.history)


def test_isotropic_2r_minimises_the_condition_number(free: Path) -> None:
    # By hand (Salisbury & Craig): in link 2's frame J = [[l1 s2, 0], [l1 c2 + l2, l2]].
    # JᵀJ ∝ I needs l1 c2 = -l2 and l1 |s2| = l2: q2 = ±135°, l2 = l1/√2, and the tip is
    # then at r² = l1² + l2² + 2 l1 l2 c2 = l2². So on a ring of radius r = 0.3 the only
    # design with κ = 1 at every target is l2 = r = 0.3, l1 = √2 r ≈ 0.4243.
    res = optimize(free, Task.ring(0.3, 16), "worst_condition", budget=300, seed=1)
    assert abs(res.best_params["l1"] - math.sqrt(2) * 0.3) < 0.01 * 0.4243
    assert abs(res.best_params["l2"] - 0.3) < 0.01 * 0.3
    assert 1.0 <= res.best_value < 1.01


def test_weighted_sum_of_length_and_manipulability(free: Path) -> None:
    # By hand: for l1 + l2 = s > r the worst manipulability on the ring is largest at
    # l1 = l2 = s/2, where w = (r/2) sqrt(s² - r²). Minimising s - w:
    #   1 = (r/2) s / sqrt(s² - r²)  =>  s = r / sqrt(1 - r²/4),  r = 0.6: s = 0.62897.
    s_star = 0.6 / math.sqrt(1 - 0.09)
    res = optimize(
        free,
        Task.ring(0.6, 16),
        {"total_length": 1.0, "min_manipulability": 1.0},
        budget=300,
        seed=0,
    )
    assert abs(res.best_params["l1"] - s_star / 2) < 0.01 * s_star / 2
    assert abs(res.best_params["l2"] - s_star / 2) < 0.01 * s_star / 2
    w = 0.3 * math.sqrt(s_star**2 - 0.36)
    assert math.isclose(res.best_value, s_star - w, rel_tol=1e-4)
    assert res.objective.weighted


def test_pareto_front_of_length_and_manipulability(free: Path) -> None:
    # The front, by hand (see above): w(L) = (r/2) sqrt(L² - r²) at l1 = l2 = L/2.
    r = 0.3
    res = optimize(
        free, Task.ring(r, 12), ["total_length", "min_manipulability"], budget=7 * 60, seed=2
    )
    assert res.front is not None and len(res.front) >= 10
    L = np.array([ev.measures["total_length"] for ev in res.front])
    w = np.array([ev.measures["min_manipulability"] for ev in res.front])
    true = (r / 2) * np.sqrt(np.maximum(L**2 - r**2, 0.0))
    assert np.all(w <= true + 1e-9)  # nothing beats the true front
    assert np.all(np.diff(L) > 0) and np.all(np.diff(w) > 0)  # sorted, non-dominated
    assert L[0] < 1.1 * r and L[-1] > 1.8  # both ends: shortest arm, longest arm
    assert np.median(true - w) < 0.01 * np.max(w)  # most points on the true front
    # the chosen knee is on the front, and on the true front to 1 %
    assert any(ev.x == res.best.x for ev in res.front)
    Lb, wb = res.best.measures["total_length"], res.best.measures["min_manipulability"]
    assert wb > 0.99 * (r / 2) * math.sqrt(Lb**2 - r**2)
    assert 0 <= res.best_value <= 1 + 2e-3
    assert res.progress().shape == (len(res.history), 2)


def test_reaching_every_target_is_a_hard_constraint(sum_one: Path) -> None:
    # r = 0.3 needs |l1 - l2| = |2 l1 - 1| <= 0.3: the template (l1 = 0.3) reaches nothing.
    # Maximising the total length cannot help (it is 1 for every l1): any feasible l1 wins.
    res = optimize(sum_one, Task.ring(0.3, 8), "total_length", budget=60, seed=0)
    assert res.history[0].measures["reached"] == 0.0 and not res.history[0].feasible
    assert res.feasible and 0.35 <= res.best_params["l1"] <= 0.65
    # targets out of every design's reach: no answer, said so, the least-violating design kept
    res = optimize(sum_one, Task.ring(1.5, 8), "min_manipulability", budget=30, seed=0)
    assert not res.feasible and math.isnan(res.best_value)
    assert "no design reached every target" in res.message
    assert res.best.violation == min(ev.violation for ev in res.history)


def test_same_seed_same_result_other_seed_other_path(sum_one: Path) -> None:
    task = Task.ring(0.6, 8)
    a = optimize(sum_one, task, budget=40, seed=7)
    b = optimize(sum_one, task, budget=40, seed=7)
    c = optimize(sum_one, task, budget=40, seed=8)
    assert [ev.x for ev in a.history] == [ev.x for ev in b.history]
    assert a.best_params == b.best_params and a.best_value == b.best_value
    assert [ev.x for ev in a.history] != [ev.x for ev in c.history]
    d = optimize(sum_one, task, budget=40)  # a random seed, kept for a replay
    assert optimize(sum_one, task, budget=40, seed=d.seed).best_params == d.best_params


def test_progress_is_the_best_so_far(sum_one: Path) -> None:
    res = optimize(sum_one, Task.ring(0.6, 8), budget=40, seed=1)
    prog = res.progress()
    values = [ev.measures["min_manipulability"] for ev in res.history]
    assert prog.shape == (len(res.history),)
    assert np.all(np.diff(prog) >= 0)
    assert prog[-1] == res.best_value == max(values)


def test_best_robot_file_loads_as_the_best_robot(sum_one: Path, tmp_path: Path) -> None:
    res = optimize(sum_one, Task.ring(0.6, 8), budget=30, seed=1)
    for suffix in (".yaml", ".json", ".toml"):
        res.write_robot(tmp_path / f"best{suffix}")
        again = km.load(tmp_path / f"best{suffix}")
        q = np.random.default_rng(0).uniform(-3, 3, (5, 2))
        np.testing.assert_allclose(again.fk(q), res.best_robot.fk(q), atol=1e-15)
    text = (tmp_path / "best.yaml").read_text()
    assert "a: l1" in text and "min:" not in text  # the table as written; no bounds


def test_evaluate_design_is_the_measure_of_the_rebuilt_robot(sum_one: Path) -> None:
    tmpl = load_template(sum_one)
    ev = evaluate_design(tmpl, Task.ring(0.6, 4), [0.4])
    assert ev.params == {"l1": 0.4} and ev.feasible and ev.x == (0.4,)
    assert math.isclose(ev.measures["min_manipulability"], math.sqrt(0.64 * 0.24 - 0.1024))
    assert ev.measures["total_length"] == 1.0


def test_template_accessors(sum_one: Path) -> None:
    tmpl = load_template(sum_one)
    assert load_template(tmpl) is tmpl
    assert load_template(tmpl.spec).names == ("l1",)
    assert tmpl.nominal == {"l1": 0.3}
    assert tmpl.lower.tolist() == [0.1] and tmpl.upper.tolist() == [0.9]
    assert tmpl.vector({}).tolist() == [0.3]
    assert tmpl.robot_at({"l1": 0.2}).links[1].a == 0.8
    with pytest.raises(KinematicaError, match="'l2' is not a design variable"):
        tmpl.vector({"l2": 0.5})
    with pytest.raises(KinematicaError, match=r"expected 1 values \(l1\)"):
        tmpl.params([0.1, 0.2])
    with pytest.raises(RobotFileError, match=r"outside its bounds \[0.1, 0.9\]"):
        tmpl.robot_at([0.95])


def test_a_template_needs_bounded_parameters(tmp_path: Path) -> None:
    path = tmp_path / "plain.yaml"
    path.write_text(SUM_ONE.replace("{value: 0.3, min: 0.1, max: 0.9}", "0.3"))
    with pytest.raises(RobotFileError, match=r"plain\.yaml: a design template needs at least one"):
        optimize(path, Task.ring(0.6, 4), budget=10)
    with pytest.raises(RobotFileError, match="must be read from a robot file"):
        DesignTemplate(km.spec_from_robot(km.load("puma560")))


@pytest.mark.parametrize(
    ("objective", "match"),
    [
        ("max_reach", r"unknown objective 'max_reach'; expected one of: min_manipulability"),
        (["total_length"] * 2, "two different objectives"),
        (["total_length", "worst_condition", "min_manipulability"], "exactly two objectives"),
        ({"total_length": -1}, "weight of total_length must be a positive number"),
        ({"total_length": math.inf}, "positive number"),
        ({}, "at least one measure"),
    ],
)
def test_bad_objectives(sum_one: Path, objective: object, match: str) -> None:
    with pytest.raises(KinematicaError, match=match):
        optimize(sum_one, Task.ring(0.6, 4), objective, budget=10)  # type: ignore[arg-type]


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"budget": 0}, "budget must be a positive whole number"),
        ({"budget": 4}, "below one generation of 5 candidates"),
        ({"budget": 20.0}, "budget must be a positive whole number"),
        ({"seed": -1}, "seed must be a non-negative whole number"),
        ({"workers": 0}, "workers must be a positive whole number"),
        ({"workers": 2, "scheduler": "tcp://127.0.0.1:1"}, "use scheduler='local'"),
        ({"scheduler": 42}, "scheduler must be None, 'local', an address"),
        ({"objective": ["total_length", "min_manipulability"], "front_size": 1}, "front_size"),
        (
            {"objective": ["total_length", "min_manipulability"], "budget": 34},
            "a Pareto front of 7 subproblems needs a budget of at least 35 evaluations, got 34",
        ),
    ],
)
def test_bad_run_settings(sum_one: Path, kwargs: dict[str, object], match: str) -> None:
    with pytest.raises(KinematicaError, match=match):
        optimize(sum_one, Task.ring(0.6, 4), **kwargs)  # type: ignore[arg-type]


def test_objective_descriptions_and_values() -> None:
    one = Objective.parse("worst_condition")
    assert one.describe() == "minimise worst_condition" and not one.weighted
    assert Objective.parse(["mean_manipulability"]) == Objective.parse("mean_manipulability")
    both = Objective.parse({"total_length": 2, "min_manipulability": 0.5})
    measures = {"total_length": 1.5, "min_manipulability": 0.2}
    assert both.value(measures) == 2 * 1.5 - 0.5 * 0.2
    assert both.describe() == "minimise 2·total_length + 0.5·-min_manipulability"
    pair = Objective.parse(("total_length", "singularity_clearance"))
    assert pair.pareto and math.isnan(pair.value(measures))
    assert pair.signed({"total_length": 1.0, "singularity_clearance": 0.1}) == (1.0, -0.1)


def test_progress_bar_counts_every_evaluation(
    sum_one: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    res = optimize(sum_one, Task.ring(0.6, 4), budget=20, seed=0, progress=True)
    err = capsys.readouterr().err
    assert "design: 100%" in err and f"{len(res.history)}/20" in err
    optimize(sum_one, Task.ring(0.6, 4), budget=20, seed=0, progress=False)
    assert capsys.readouterr().err == ""


def test_heavy_dependencies_are_imported_only_when_used() -> None:
    import subprocess
    import sys

    code = (
        "import sys\n"
        "before = set(sys.modules)\n"
        "import kinematica, kinematica.design, kinematica.design.report, kinematica.cli.main\n"
        "heavy = ('scipy', 'dask', 'distributed', 'matplotlib', 'tqdm')\n"
        "print([m for m in heavy if m in sys.modules and m not in before])"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


def test_candidates_a_rounding_outside_the_bounds_are_clipped(sum_one: Path) -> None:
    from kinematica.design.runner import Runner

    tmpl = load_template(sum_one)
    with Runner(tmpl, Task.ring(0.6, 4)) as runner:
        over, under = np.nextafter(0.9, 1.0), np.nextafter(0.1, 0.0)
        evs = runner.evaluate(np.array([[over], [under], [0.9]]))
    assert [ev.params["l1"] for ev in evs] == [0.9, 0.1, 0.9]
    assert runner.evaluated == 2  # the clipped 0.9 and the plain 0.9 are one candidate
