"""robot.ik's one door: a request read once, found again by its settings, and its plan.

:class:`~kinematica.ik.request.IKRequest` is what ``robot.ik`` solves with, whether
the settings came as keywords or as ``options=``; requests of hashable settings are
kept and found again (``MEMO``), each plan is kept by the chain (``PLANS``). A kept
request must never stand for other settings: ``True`` is not ``1``, a dict changed
after a call is read again, a Generator seed is drawn from on every call.
"""

from __future__ import annotations

import numpy as np
import pytest

import kinematica as km
from kinematica.errors import KinematicaError
from kinematica.ik import IKOptions, Tolerance
from kinematica.ik.request import KEYS, MEMO, IKRequest, settings_key
from kinematica.ik.solvers import PLANS, plan_of


def test_keywords_and_options_give_one_request_and_the_same_answer() -> None:
    robot = km.load("puma560")
    T = robot.fk(np.full(6, 0.3))
    given = {"tol": (1e-9, 1e-8), "respect_limits": False, "method": "analytic"}
    by_keywords = IKRequest.parse(**given)  # type: ignore[arg-type]
    assert IKRequest.parse(**given) is by_keywords  # type: ignore[arg-type]  # found again
    by_options = IKRequest.parse(options=IKOptions(**given))  # type: ignore[arg-type]
    assert by_options is by_keywords
    assert by_keywords.tolerance == Tolerance(1e-9, 1e-8) and by_keywords.tol == Tolerance(
        1e-9, 1e-8
    )
    a, b = robot.ik(T, **given), robot.ik(T, options=IKOptions(**given))  # type: ignore[arg-type]
    assert a.status == b.status == "ok" and a.method == b.method
    np.testing.assert_array_equal(a.solutions, b.solutions)


def test_a_kept_request_never_stands_for_a_setting_that_only_compares_equal() -> None:
    robot = km.load("puma560")
    T = robot.fk(np.full(6, 0.3))
    robot.ik(T, respect_limits=True, tol=1, seed=1, workers=1)
    for bad in ({"respect_limits": 1}, {"tol": True}, {"seed": True}, {"workers": True}):
        with pytest.raises(KinematicaError):
            robot.ik(T, **bad)  # type: ignore[arg-type]
    assert robot.ik(T, seed=1).status == "ok"
    iiwa = km.load("iiwa14")
    P = iiwa.fk(np.array([0.3, 0.5, 0.3, -1.2, 0.3, 0.8, 0.3]))
    assert iiwa.ik(P, arm_angle=1).parameter == ("arm angle", 1.0)
    with pytest.raises(KinematicaError, match="must be a number"):
        iiwa.ik(P, arm_angle=True)
    assert iiwa.ik(P, fixed={6: 1}).parameter == ("q7", 1.0)
    with pytest.raises(KinematicaError, match="must be a number"):
        iiwa.ik(P, fixed={6: True})


def test_a_fixed_dict_changed_after_a_call_is_read_again() -> None:
    robot = km.load("iiwa14")
    q = np.array([0.3, 0.5, 0.3, -1.2, 0.3, 0.8, 0.3])
    T = robot.fk(q)
    fixed = {6: 0.3}
    first = robot.ik(T, fixed=fixed)
    fixed[6] = -0.2  # the caller's dict, changed
    second = robot.ik(T, fixed=fixed)
    assert first.parameter == ("q7", 0.3) and second.parameter == ("q7", -0.2)
    assert np.all(second.solutions[:, 6] == -0.2)
    assert first.parameter == ("q7", 0.3)  # the first answer is untouched


def test_a_generator_seed_is_drawn_from_every_call_and_no_plan_is_kept() -> None:
    robot = km.load("panda")
    T = robot.fk(np.array([0.2, 0.2, 0.2, -1.2, 0.2, 1.2, 0.2]))
    request = IKRequest.parse(method="numeric", seed=np.random.default_rng(3))
    assert request.key is None

    def plans() -> int:
        return sum(type(k) is int for k in robot.chain.memo)

    before = plans()
    plan_of(robot.chain, "pose", request)
    assert plans() == before  # made for the call, not kept
    rng = np.random.default_rng(3)
    res = robot.ik(T, method="numeric", seed=rng)
    assert res.success
    assert IKRequest.parse(method="numeric", seed=rng) is not IKRequest.parse(
        method="numeric", seed=rng
    )


def test_requests_are_kept_up_to_memo_then_made_again_with_the_same_keys() -> None:
    tols = [1e-6 * (1 + i) for i in range(MEMO + 5)]
    first = [IKRequest.parse(tol=t) for t in tols]
    again = [IKRequest.parse(tol=t) for t in tols]  # the table was emptied on the way
    assert {a.key for a in first} == {b.key for b in again}
    assert len({a.key for a in first}) == len(tols)  # distinct settings, distinct keys
    assert all(a.tolerance == b.tolerance for a, b in zip(first, again, strict=True))


def test_settings_keys_are_never_given_to_other_settings_after_the_table_is_emptied() -> None:
    first = settings_key(("auto", 0.5, 0.5, True, None, None))
    for i in range(KEYS + 1):  # the table fills and is emptied
        settings_key(("auto", float(i), 1.0, True, None, None))
    again = settings_key(("auto", 0.5, 0.5, True, None, None))
    other = settings_key(("auto", 0.25, 0.5, True, None, None))
    assert again != other
    assert first != other  # a number once given stays with its settings


def test_a_chain_keeps_at_most_plans_plans() -> None:
    robot = km.load("ur5")
    T = robot.fk(np.full(6, 0.3))
    for i in range(PLANS + 3):
        assert robot.ik(T, tol=1e-9 * (1 + i)).status == "ok"
    plans = [k for k in robot.chain.memo if type(k) is int]
    assert len(plans) == PLANS
    # the plan of the defaults, made again after it went, answers as it did
    assert robot.ik(T).status == "ok"


def test_options_must_be_ikoptions_and_not_given_with_keywords() -> None:
    robot = km.load("puma560")
    T = robot.fk(np.full(6, 0.3))
    with pytest.raises(KinematicaError, match="IKOptions") as bad:
        robot.ik(T, options={"tol": 1e-9})  # type: ignore[arg-type]
    assert bad.value.arg == "options"
    with pytest.raises(KinematicaError, match="not both"):
        robot.ik(T, tol=1e-9, options=IKOptions())
