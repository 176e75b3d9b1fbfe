"""One pose of a redundant arm at one parameter value, straight to the core (ik/direct.py).

``robot.ik(T, fixed={k: v})``, ``robot.ik(T, arm_angle=psi)`` and ``robot.ik(T)`` of a
7-joint arm take :class:`DirectParameter`'s path for one rigid pose with every other
default; ``robot.ik(T, options=IKOptions(...))`` asks the same through the general
path (:func:`kinematica.ik.redundancy.solve_arm`). Every field of both answers, the
message and the parameter must be identical, on poses made at the value (reachable,
some outside the limits), random poses (the lock finds nothing: unreachable, not
found, or ``auto``'s numeric search over every joint), singular ones and poses beyond
reach; what the direct path leaves (None) the general path answers.
"""

from __future__ import annotations

from collections import Counter
from typing import Any

import numpy as np
import pytest
from support.helpers import assert_same_result

import kinematica as km
import kinematica.ik.redundancy as redundancy_module
from kinematica.errors import KinematicaError
from kinematica.ik import IKOptions, IKResult
from kinematica.ik.direct import HELD_CACHE, DirectParameter

#: Poses per case: made at the held value, at random, singular, beyond reach.
AT_VALUE, RANDOM, SINGULAR, FAR = 90, 40, 30, 15


def _same(a: IKResult, b: IKResult) -> None:
    """Identical answers, the parameter's value a float on both sides."""
    assert_same_result(a, b)
    if a.parameter is not None:
        assert type(a.parameter[1]) is float


def _poses(robot: km.Robot, joint: int | None, value: float, seed: int) -> list[np.ndarray]:
    """Poses made with ``joint`` at ``value``, random, singular (elbow or wrist), far."""
    rng = np.random.default_rng(seed)
    lo, hi = robot.qlim.T
    q = rng.uniform(lo, hi, size=(AT_VALUE + RANDOM + SINGULAR, robot.dof))
    if joint is not None:
        q[:AT_VALUE, joint] = value
    singular = q[AT_VALUE + RANDOM :]
    singular[: SINGULAR // 2, 3] = np.clip(0.0, lo[3], hi[3])  # elbow stretched (or its limit)
    singular[SINGULAR // 2 :, 5] = 0.0  # wrist axes 5 and 7 aligned
    T = robot.fk(q)
    far = T[:FAR].copy()
    far[:, :3, 3] += rng.normal(size=(FAR, 3)) * 3.0  # beyond the arm's reach
    return list(np.ascontiguousarray(np.concatenate([T, far])))


def _robot(name: str) -> km.Robot:
    """A built-in arm, or ``"puma+1"``: a joint before the PUMA 560, which ``auto`` holds."""
    if name != "puma+1":
        return km.load(name)
    puma = km.load("puma560")
    rows = [km.Revolute(d=0.3, a=0.1, alpha=np.pi / 2), *puma.links]
    return km.Robot.from_dh(rows, convention=puma.convention, tool=puma.tool)


def _direct(d: DirectParameter, T: np.ndarray, kwargs: dict[str, Any]) -> IKResult | None:
    if "fixed" in kwargs:
        return d.fixed(T, kwargs["fixed"])
    if "arm_angle" in kwargs:
        return d.arm_angle(T, kwargs["arm_angle"])
    return d.auto(T)


CASES = [  # robot, keywords, the joint the poses are made at and its value (None: auto's)
    ("panda", {}, 6, 0.0),  # auto: q7 held at the middle of its limits, spherical shoulder
    ("panda", {"fixed": {6: 0.3}}, 6, 0.3),
    ("panda", {"fixed": {0: 0.3}}, 0, 0.3),  # the general 6R locked there: not direct
    ("iiwa14", {}, None, 0.0),  # auto: the arm angle at 0
    ("iiwa14", {"arm_angle": 0.3}, None, 0.0),
    ("iiwa14", {"arm_angle": 0}, None, 0.0),  # an int: the parameter comes out a float
    ("iiwa14", {"fixed": {0: 0.3}}, 0, 0.3),  # the target moved (the first joint)
    ("iiwa14", {"fixed": {"q7": -0.3}}, 6, -0.3),  # by name
    ("iiwa14", {"fixed": {4: -1.0}}, 4, -1.0),  # a middle joint (q4 held: a continuum)
    ("puma+1", {}, 0, 0.0),  # auto: q1 held at 0 (no limits), the target moved
]


@pytest.mark.parametrize(("name", "kwargs", "joint", "value"), CASES)
def test_one_pose_at_a_parameter_matches_the_general_path(
    name: str, kwargs: dict[str, Any], joint: int | None, value: float
) -> None:
    robot = _robot(name)
    direct = DirectParameter(robot.chain, robot.joint_names)
    general = IKOptions(**kwargs)
    statuses: Counter[str] = Counter()
    methods: Counter[str] = Counter()
    answered = 0
    with np.errstate(all="ignore"):
        for T in _poses(robot, joint, value, seed=len(str(kwargs)) + len(name)):
            slow = robot.ik(T, options=general)
            assert isinstance(slow, IKResult)
            _same(robot.ik(T, **kwargs), slow)
            fast = _direct(direct, T, kwargs)
            if fast is not None:
                _same(fast, slow)
                answered += 1
            statuses[str(slow.status)] += 1
            methods[slow.method] += 1
    # the direct path answered every pose at the value, and the cases below were met
    if name == "panda" and kwargs == {"fixed": {0: 0.3}}:
        # the general 6R: answered directly too (a target it proves nothing for is
        # not_found, which the direct path hands to the general one, which searches)
        assert methods["analytic:general-6R"] > 0
    assert answered >= AT_VALUE
    assert {"ok", "unreachable"} <= set(statuses)
    if name == "iiwa14" and "fixed" not in kwargs:
        assert statuses["singular"] >= SINGULAR // 3  # the elbow stretched: no arm angle
    if not kwargs and name == "panda":
        assert methods["numeric:lm"] > 0  # no solution at the lock: every joint searched


@pytest.mark.parametrize(
    "kwargs", [{}, {"fixed": {6: 0.3}}, {"fixed": {0: 0.3}}, {"arm_angle": 0.3}]
)
def test_one_reachable_pose_does_not_take_the_general_path(
    kwargs: dict[str, Any], monkeypatch: pytest.MonkeyPatch
) -> None:
    robot = km.load("iiwa14")
    q = np.array([0.3, 0.5, 0.3, -1.2, 0.3, 0.8, 0.3])
    T = robot.fk(q)
    expected = robot.ik(T, options=IKOptions(**kwargs))

    def general(*args: object, **kw: object) -> None:
        raise AssertionError("the general path was taken")

    monkeypatch.setattr(redundancy_module, "solve_arm", general)  # robot.ik's general path
    res = robot.ik(T, **kwargs)
    assert res.status == "ok" and res.count >= 1
    _same(res, expected)
    # the configuration that made the pose is among the solutions where it holds the value
    if kwargs.get("fixed") == {6: 0.3} or kwargs.get("fixed") == {0: 0.3}:
        assert np.min(np.abs(res.solutions - q).max(axis=1)) < 1e-9


def test_what_the_direct_path_leaves_the_general_path_explains() -> None:
    robot = km.load("iiwa14")
    direct = DirectParameter(robot.chain, robot.joint_names)
    T = robot.fk(np.array([0.3, 0.5, 0.3, -1.2, 0.3, 0.8, 0.3]))
    skewed = T.copy()
    skewed[:3, :3] *= 1.0 + 1e-6  # not rigid to round-off: projected, with a note
    for kwargs in ({}, {"fixed": {0: 0.3}}, {"fixed": {6: 0.3}}, {"arm_angle": 0.3}):
        assert _direct(direct, skewed, kwargs) is None
        res = robot.ik(skewed, **kwargs)
        assert res.status == "ok" and "projected" in res.message
        _same(res, robot.ik(skewed, options=IKOptions(**kwargs)))
    # a view the core does not read as it is (Fortran order, strided): copied, same answer
    wide = np.zeros((8, 8))
    wide[::2, ::2] = T
    for view in (np.asfortranarray(T), wide[::2, ::2]):
        for kwargs in ({}, {"fixed": {6: 0.3}}, {"arm_angle": 0.3}):
            _same(robot.ik(view, **kwargs), robot.ik(T, options=IKOptions(**kwargs)))
        puma = km.load("puma560")
        P = puma.fk(np.full(6, 0.3))
        _same(puma.ik(np.asfortranarray(P)), puma.ik(P))


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"fixed": {True: 0.3}}, "0-based index or a name"),  # True == 1, never joint 1
        ({"fixed": {7: 0.3}}, "out of range"),
        ({"fixed": {"elbow": 0.3}}, "no joint is named"),
        ({"fixed": {6: 5.0}}, "outside its limits"),
        ({"fixed": {6: float("nan")}}, "finite"),
        ({"fixed": {6: "0.3"}}, "must be a number"),
        ({"fixed": {6: 0.3, 5: 0.1}}, "one joint"),
        ({"arm_angle": float("inf")}, "finite"),
        ({"arm_angle": True}, "must be a number"),
        ({"fixed": {6: 0.3}, "arm_angle": 0.3}, "not both"),
    ],
)
def test_bad_parameters_say_what_is_wrong_as_the_general_path_does(
    kwargs: dict[str, Any], match: str
) -> None:
    robot = km.load("iiwa14")
    T = robot.fk(np.array([0.3, 0.5, 0.3, -1.2, 0.3, 0.8, 0.3]))
    robot.ik(T, fixed={1: 0.5})  # joint 1 known to the direct path: True must not find it
    with pytest.raises(KinematicaError, match=match) as fast:
        robot.ik(T, **kwargs)
    with pytest.raises(KinematicaError, match=match) as slow:
        robot.ik(T, options=IKOptions(**kwargs))
    assert str(fast.value) == str(slow.value) and fast.value.arg == slow.value.arg


@pytest.mark.parametrize("joint", [0, 6])
def test_a_sweep_past_the_cache_answers_as_the_general_path(joint: int) -> None:
    robot = km.load("iiwa14")
    direct = DirectParameter(robot.chain, robot.joint_names)
    T = robot.fk(np.array([0.3, 0.5, 0.3, -1.2, 0.3, 0.8, 0.3]))
    values = np.linspace(-1.0, 1.0, HELD_CACHE + 3).tolist()
    for _ in range(2):  # the second pass: values made again after the cache let them go
        answered = 0
        for v in values:
            slow = robot.ik(T, options=IKOptions(fixed={joint: v}))
            fast = direct.fixed(T, {joint: v})
            if fast is not None:
                assert fast.parameter == (f"q{joint + 1}", v)
                _same(fast, slow)
                answered += 1
        assert answered >= len(values) // 2
