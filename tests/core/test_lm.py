"""The core's Levenberg-Marquardt search (``lm.hpp``): what its counts say of each target.

``internals.lm_stats`` runs the search as ``robot.ik`` does (default first guess,
then the restarts in order) and returns, per target, the configurations evaluated,
the attempts made and whether one converged. The facts checked are independent of
the search's tuning: a first guess that is a solution costs one evaluation, a
target beyond the reach bound none, a target that no configuration reaches every
restart, and "converged" is exactly what the shared check then calls ``ok``.
"""

from __future__ import annotations

import numpy as np
from kinematica._core_testing import internals
from kinematica._core_testing.internals import STALL_WINDOW

import kinematica as km
from kinematica.ik.numeric import NumericSetup, numeric_setup


def setup_of(robot: km.Robot, weights: tuple[float, ...] = (1.0,) * 6) -> NumericSetup:
    return numeric_setup(
        robot.chain,
        respect_limits=True,
        tol_position=1e-10,
        tol_rotation=1e-10,
        seed=None,
        weights=weights,
    )


def stats(setup: NumericSetup, robot: km.Robot, T: np.ndarray) -> tuple[np.ndarray, ...]:
    """(evaluations, attempts, converged), each (N,), of the search of targets T (N, 4, 4)."""
    return tuple(internals.lm_stats(setup.solver, robot.chain.core, T))


def test_a_first_guess_that_is_a_solution_costs_one_evaluation() -> None:
    robot = km.load("panda")
    setup = setup_of(robot)
    evaluations, attempts, converged = stats(setup, robot, robot.fk(setup.middle)[None])
    assert (evaluations[0], attempts[0], converged[0]) == (1, 1, True)


def test_a_target_beyond_the_reach_bound_is_not_searched() -> None:
    robot = km.load("panda")
    T = np.eye(4)
    T[:3, 3] = [3.0, 0.0, 0.5]
    evaluations, attempts, converged = stats(setup_of(robot), robot, T[None])
    assert (evaluations[0], attempts[0], converged[0]) == (0, 0, False)


def planar_2r() -> km.Robot:
    return km.Robot.from_dh(
        [km.Revolute(a=1.0), km.Revolute(a=0.7)], name="planar 2R", convention="standard"
    )


def test_a_target_in_the_hole_uses_every_restart_and_stalls_early() -> None:
    # The 2R arm reaches no point within 0.3 m of its base; (0.1, 0, 0) is inside the
    # reach bound, so every restart is tried. Each attempt slides to the rim, the
    # nearest reachable point 0.2 m away, a local minimum of the error: it can stop
    # only after STALL_WINDOW steps (evaluations >= 1 + STALL_WINDOW per attempt), and
    # the stall test stops it soon after (the step budget is 60).
    T = np.eye(4)
    T[0, 3] = 0.1
    robot = planar_2r()
    setup = setup_of(robot, (1.0,) * 3 + (0.0,) * 3)
    evaluations, attempts, converged = stats(setup, robot, T[None])
    assert not converged[0]
    assert attempts[0] == setup.solver.restarts + 1
    per_attempt = evaluations[0] / attempts[0]
    assert 1 + STALL_WINDOW < per_attempt <= 1 + 3 * STALL_WINDOW, per_attempt


def test_converged_is_what_the_check_calls_ok() -> None:
    robot = km.load("iiwa14")
    q = np.random.default_rng(3).uniform(*robot.qlim.T, (40, robot.dof))
    T = robot.fk(q)
    T[5, :3, 3] = [0.05, 0.0, 0.36]  # at the shoulder, the tool's rotation kept: not found
    evaluations, attempts, converged = stats(setup_of(robot), robot, T)
    res = robot.ik(T, method="numeric")
    assert res.status[5] == "not_found" and (res.status == "ok").sum() == 39
    np.testing.assert_array_equal(converged, res.status == "ok")
    assert np.all(evaluations >= attempts) and np.all(attempts >= 1)


def test_the_search_after_the_first_guess_starts_at_the_restarts() -> None:
    # The first guess (the middle) solves this target exactly: the search from it alone
    # returns it, the search robot.ik runs next (skip_first) never tries it again and
    # ends where the first restart leads, elsewhere on the Panda's self-motion.
    robot = km.load("panda")
    setup = setup_of(robot)
    T = robot.fk(setup.middle)
    assert setup.solver.skip_first and not setup.quick.skip_first
    first = setup.quick.candidates(robot.chain.core, T)[0][0]
    after = setup.solver.candidates(robot.chain.core, T)[0][0]
    np.testing.assert_allclose(first, setup.middle, atol=1e-12)
    assert np.max(np.abs(after - setup.middle)) > 1e-3
    np.testing.assert_allclose(robot.fk(after), T, atol=1e-9)
